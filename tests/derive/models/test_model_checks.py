"""Derivation-level checks of the registered models (issue 39 items 1, 2, 5).

Each against a reference typed or computed independently here: the 1-DOF model's
Stribeck Hopf point in closed form, Hoffmann's flutter threshold (the undamped 2 x 2
problem's discriminant, worked by hand below; numpy eigenvalues of a Jacobian typed
here with damping), the derived holding force against the constrained equations solved
by numpy, a 4-DOF (8-state) model with no closed-form equilibrium, and the one-line
refusals of `register`.
"""

import math
import re
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from beltmdsm.derive.models import Contact, Excitation, Oscillator, get, register
from beltmdsm.derive.models.render import PAPER_PIECES, render_entry
from beltmdsm.derive.models.steady import NUMERIC
from beltmdsm.derive.parameters import MODEL, Parameter
from beltmdsm.generated.models import load

ROW = {p.name: p for p in MODEL}


def _p(module, law, **values):
    return np.array([values.get(n, module.DEFAULTS[n]) for n in module.PARAMETERS[law]])


def _module(entry):
    """The module that `python -m derive` would write for ``entry``, imported."""
    namespace = {"__name__": f"user_{entry.name}"}
    exec(compile(render_entry(entry), entry.name, "exec"), namespace)
    return namespace


# --------------------------------------------------------------------------- belt_1dof


@pytest.mark.parametrize("seed", range(5))
def test_belt_1dof_stribeck_hopf_point(seed):
    """H_1 = 2 beta omega - g (mu_s - mu_k)/v_s exp(-Vb/v_s) vanishes (and steady sliding
    loses stability as Vb falls) at Vb* = v_s ln(g (mu_s - mu_k) / (2 beta omega v_s))."""
    rng = np.random.default_rng(seed)
    m = load("belt_1dof")
    k = m.kernels("stribeck")
    v = dict(
        beta1=rng.uniform(0.01, 0.1),
        omega1=rng.uniform(0.5, 2.0),
        g=rng.uniform(5.0, 15.0),
        mu_s=rng.uniform(0.3, 0.6),
        v_s=rng.uniform(0.2, 2.0),
    )
    v["mu_k"] = v["mu_s"] * rng.uniform(0.2, 0.8)
    typed = v["v_s"] * math.log(
        v["g"] * (v["mu_s"] - v["mu_k"]) / (2 * v["beta1"] * v["omega1"] * v["v_s"])
    )
    assert typed > 0

    def H1(Vb):
        return k.hurwitz(_p(m, "stribeck", Vb=Vb, **v))[0]

    found = brentq(H1, 1e-6, 60 * v["v_s"], xtol=1e-15, rtol=1e-15)
    assert abs(found - typed) <= 1e-12 * typed
    assert H1(0.9 * typed) < 0 < H1(1.1 * typed)
    H = k.hurwitz(_p(m, "stribeck", Vb=found, **v))
    assert abs(H[1]) <= 1e-12  # H_2 = a_1 a_2 vanishes with it


# --------------------------------------------------------------------------- hoffmann


def _hoffmann(rng, damped):
    v = dict(
        m=rng.uniform(0.5, 2.0),
        k1=rng.uniform(0.5, 2.0),
        k2=rng.uniform(0.2, 1.0),
        k3=rng.uniform(0.5, 2.0),
        k_c=rng.uniform(0.5, 2.0),
        F_pre=rng.uniform(0.5, 2.0),
        c1=rng.uniform(0.01, 0.1) if damped else 0.0,
        c2=rng.uniform(0.01, 0.1) if damped else 0.0,
        Vb=1.0,
    )
    return v


def _undamped_threshold(v):
    """By hand: with Lambda = m w^2, det(K_eff - Lambda I) = 0 for K_eff =
    [[k11, k12 - mu k_c], [k21, k22 + k_c]] (k11 = k1 + k3/2, k12 = k21 = k3/2,
    k22 = k2 + k3/2) is Lambda^2 - (k11 + k22')Lambda + k11 k22' - k21 (k12 - mu k_c) = 0;
    its discriminant (k11 - k22')^2 + 4 k21 k12 - 4 mu k21 k_c turns negative (a complex
    pair: flutter) above mu = ((k11 - k22')^2 + 4 k12 k21) / (4 k21 k_c)."""
    k11 = v["k1"] + v["k3"] / 2
    k22 = v["k2"] + v["k3"] / 2 + v["k_c"]
    k12 = k21 = v["k3"] / 2
    return ((k11 - k22) ** 2 + 4 * k12 * k21) / (4 * k21 * v["k_c"])


def _growth(k, m, v, mu):
    p = _p(m, "coulomb", mu_s=mu, **v)
    J = k.jacobian(0.0, k.equilibrium(p), p, -1)
    return np.max(np.linalg.eigvals(J).real)


@pytest.mark.parametrize("seed", range(4))
def test_hoffmann_undamped_flutter_threshold(seed):
    rng = np.random.default_rng(seed)
    m = load("hoffmann")
    k = m.kernels("coulomb")
    v = _hoffmann(rng, damped=False)
    typed = _undamped_threshold(v)
    # numpy eigenvalues of the derived Jacobian: imaginary below, a growing pair above
    assert _growth(k, m, v, typed * (1 - 1e-6)) <= 1e-12
    assert _growth(k, m, v, typed * (1 + 1e-6)) > 1e-6
    lo, hi = 0.5 * typed, 2 * typed
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if _growth(k, m, v, mid) <= 1e-9 else (lo, mid)
    assert abs(hi - typed) <= 1e-8 * typed


def _typed_jacobian(v, mu):
    """The linearised equations typed here: y = (x, y, x', y'), M = m I."""
    K = np.array(
        [
            [v["k1"] + v["k3"] / 2, v["k3"] / 2 - mu * v["k_c"]],
            [v["k3"] / 2, v["k2"] + v["k3"] / 2 + v["k_c"]],
        ]
    )
    C = np.diag([v["c1"], v["c2"]])
    return np.block([[np.zeros((2, 2)), np.eye(2)], [-K / v["m"], -C / v["m"]]])


@pytest.mark.parametrize("seed", range(4))
def test_hoffmann_damped_threshold_from_hurwitz(seed):
    rng = np.random.default_rng(10 + seed)
    m = load("hoffmann")
    k = m.kernels("coulomb")
    v = _hoffmann(rng, damped=True)

    def H3(mu):
        return k.hurwitz(_p(m, "coulomb", mu_s=mu, **v))[2]

    def typed_growth(mu):
        return np.max(np.linalg.eigvals(_typed_jacobian(v, mu)).real)

    hi = 5 * _undamped_threshold(v)
    assert H3(0.0) > 0 > H3(hi)
    from_hurwitz = brentq(H3, 0.0, hi, xtol=1e-14, rtol=1e-14)
    from_eigenvalues = brentq(typed_growth, 0.0, hi, xtol=1e-14, rtol=1e-14)
    assert abs(from_hurwitz - from_eigenvalues) <= 1e-9 * from_eigenvalues
    # the Hurwitz verdict matches the eigenvalues on either side
    for mu in (0.9 * from_hurwitz, 1.1 * from_hurwitz):
        stable = all(h > 0 for h in k.hurwitz(_p(m, "coulomb", mu_s=mu, **v)))
        assert stable == (typed_growth(mu) < 0)


# --------------------------------------------------------------------------- stick


#: A model the holding force cannot be read off: a non-diagonal mass matrix and a
#: contact whose slip velocity mixes both rates (a lever arm r), a bilateral load.
LEVER = Oscillator(
    "lever",
    "A sliding mass with a pendulum: the contact on the pendulum's arm",
    "Test model.",
    ("u", "phi"),
    (
        Parameter("m1", "kg", 1.0, "positive", "cart mass"),
        Parameter("m2", "kg", 0.7, "positive", "pendulum mass"),
        Parameter("r", "m", 0.6, "positive", "arm"),
        Parameter("k1", "N/m", 2.0, "positive", "cart spring"),
        Parameter("k2", "N m", 1.5, "positive", "pendulum spring"),
        Parameter("c1", "N s/m", 0.1, "nonnegative", "cart damper"),
        Parameter("N0", "N", 3.0, "positive", "load"),
        Parameter("kn", "N", 1.0, "nonnegative", "load per rotation"),
        ROW["Vb"],
        Parameter("A", "m", 0.3, "nonnegative", "excitation amplitude"),
        Parameter("W", "rad/s", 2.0, "nonnegative", "excitation frequency"),
        ROW["phase_t"],
    ),
    Contact(
        slip=lambda P: {"u": 1, "phi": P["r"]},
        normal=lambda P, q, v, t: P["N0"] + P["kn"] * q["phi"],
    ),
    mass=lambda P: [
        [P["m1"] + P["m2"], P["m2"] * P["r"]],
        [P["m2"] * P["r"], P["m2"] * P["r"] ** 2],
    ],
    damping=lambda P: [[P["c1"], 0], [0, 0]],
    stiffness=lambda P: [[P["k1"], 0], [0, P["k2"]]],
    excitation=(Excitation("u", "A", "W", "phase_t"),),
    friction_laws=("stribeck",),
)


def test_holding_force_against_the_constrained_equations():
    """lambda and the stick accelerations against numpy.linalg on the constrained
    equations [[M, -d], [w^T, 0]] (q'', lambda) = (Q0, 0), Q0 typed here."""
    mod = _module(LEVER)
    k = mod["kernels"]("stribeck")
    names = mod["PARAMETERS"]["stribeck"]
    rng = np.random.default_rng(3)
    for _ in range(20):
        v = {n: rng.uniform(0.2, 2.0) for n in names}
        p = np.array([v[n] for n in names])
        t = rng.uniform(0, 10)
        u, phi, du, dphi = rng.normal(0, 1, 4)
        y = np.array([u, phi, du, dphi])
        M = np.array(
            [[v["m1"] + v["m2"], v["m2"] * v["r"]], [v["m2"] * v["r"], v["m2"] * v["r"] ** 2]]
        )
        exc = v["A"] * v["W"] ** 2 * math.sin(v["W"] * t + v["phase_t"])
        Q0 = np.array([-v["c1"] * du - v["k1"] * u + exc, -v["k2"] * phi])
        w = np.array([1.0, v["r"]])
        A = np.block([[M, -w[:, None]], [w[None, :], np.zeros((1, 1))]])
        solved = np.linalg.solve(A, np.append(Q0, 0.0))
        lam = k.holding_force(t, y, p)
        assert abs(lam - solved[2]) <= 1e-12 * (abs(solved[2]) + np.max(np.abs(Q0)))
        f = k.field(t, y, p, 0)
        assert np.allclose(f[2:], solved[:2], rtol=1e-12, atol=1e-12 * np.max(np.abs(Q0)))
        assert abs(k.slip_acceleration(t, y, p, 0)) <= 1e-12 * np.max(np.abs(Q0))
        assert k.friction_force(t, y, p, 0) == lam
        N = v["N0"] + v["kn"] * phi
        assert k.stick_limit(t, y, p) == pytest.approx(v["mu_s"] * N, rel=1e-15)


def test_paper_holding_force_is_minus_the_free_acceleration():
    m = load("paper")
    k = m.kernels("coulomb")
    p = _p(m, "coulomb")
    d = m.DEFAULTS
    y = np.array([0.3, d["Vb"], 11.0, 0.1])
    t = 0.7
    a_free = (
        d["alpha_t"] * d["Omega_t"] ** 2 * math.sin(d["Omega_t"] * t + d["phase_t"])
        - 2 * d["beta1"] * d["omega1"] * y[1]
        - d["omega1"] ** 2 * y[0]
    )
    assert k.holding_force(t, y, p) == pytest.approx(-a_free, rel=1e-14)


# --------------------------------------------------------------------------- 8 states


CHAIN = Oscillator(
    "chain4",
    "Four masses in a chain, a hardening spring on the first, the belt under the first",
    "Test model: 8 states, no closed-form equilibrium.",
    ("q1", "q2", "q3", "q4"),
    (
        Parameter("kc", "N/m", 1.0, "positive", "chain springs"),
        Parameter("knl", "N/m^3", 0.5, "positive", "hardening"),
        Parameter("cc", "N s/m", 0.05, "nonnegative", "dampers"),
        ROW["g"],
        ROW["Vb"],
    ),
    Contact(slip=lambda P: {"q1": 1}, normal=lambda P, q, v, t: P["g"]),
    damping=lambda P: [[P["cc"] if i == j else 0 for j in range(4)] for i in range(4)],
    stiffness=lambda P: [
        [2 * P["kc"], -P["kc"], 0, 0],
        [-P["kc"], 2 * P["kc"], -P["kc"], 0],
        [0, -P["kc"], 2 * P["kc"], -P["kc"]],
        [0, 0, -P["kc"], P["kc"]],
    ],
    forces=lambda P, q, v, t: {"q1": -P["knl"] * q["q1"] ** 3, "q2": -P["knl"] * q["q2"] ** 3},
    friction_laws=("coulomb",),
)


def test_eight_states_numeric_equilibrium_and_hurwitz():
    mod = _module(CHAIN)
    assert mod["EQUILIBRIUM"] == {"coulomb": NUMERIC}
    k = mod["kernels"]("coulomb")
    p = np.array([mod["DEFAULTS"][n] for n in mod["PARAMETERS"]["coulomb"]])
    y = k.equilibrium(p)
    assert np.max(np.abs(k.field(0.0, y, p, -1))) <= 1e-12
    J = k.jacobian(0.0, y, p, -1)
    a = k.characteristic(p)
    assert a.shape == (9,)
    assert np.allclose(a, np.poly(J), rtol=1e-9, atol=1e-12)
    H = k.hurwitz(p)
    assert H.shape == (8,)
    hm = np.array(
        [[a[2 * j - i] if 0 <= 2 * j - i <= 8 else 0 for j in range(1, 9)] for i in range(1, 9)]
    )
    for n in range(1, 9):
        ref = np.linalg.det(hm[:n, :n])
        assert abs(H[n - 1] - ref) <= 1e-9 * max(abs(ref), 1e-300) + 1e-14
    # damped chain sliding on Coulomb friction: stable, every determinant positive
    assert np.all(H > 0) and np.max(np.linalg.eigvals(J).real) < 0


# --------------------------------------------------------------------------- registry


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (dict(name="belt 1dof"), "Python identifier"),
        (dict(coordinates=()), "at least one generalized coordinate"),
        (dict(parameters=(ROW["beta1"], ROW["omega1"], ROW["g"])), "Vb is missing"),
        (dict(stiffness=lambda P: [[P["omega1"] ** 2, 0]]), "stiffness: a 1 x 1 matrix"),
        (dict(mass=lambda P: [[0]]), "mass: the matrix is singular"),
        (
            dict(contact=Contact(slip=lambda P: {"z": 1}, normal=lambda P, q, v, t: 1)),
            "contact.slip: ['z'] are not coordinates",
        ),
        (dict(contact=Contact(slip=lambda P: {"x": 1}, normal="z")), "contact.normal: 'z'"),
        (dict(damping=lambda P: [[P["zeta"]]]), "'zeta' is neither a parameter"),
        (dict(excitation=(Excitation("x", "A", "W", "phase_t"),)), "'A' is not one of"),
        (dict(friction_laws=("lugre",)), "'lugre' is not a registered friction law"),
        (dict(coordinates=("t",)), "'t' is not a free identifier"),
    ],
)
def test_register_refuses_in_one_line(change, message):
    entry = replace(get("belt_1dof"), **{"name": "belt_copy", **change})
    with pytest.raises(ValueError, match=re.escape(message)) as err:
        register("model", entry)
    assert "\n" not in str(err.value) and str(err.value).startswith(f"model {entry.name!r}")


def test_register_refuses_a_taken_name():
    with pytest.raises(ValueError, match="registered already"):
        register("model", get("hoffmann"))


def test_other_models_name_the_paper_pieces_absent():
    assert load("paper").ABSENT == {}
    for name in ("belt_1dof", "hoffmann"):
        absent = load(name).ABSENT
        assert (
            set(absent) == set(PAPER_PIECES) == {"cubic_fit", "mdsm", "correlation", "paper_check"}
        )
        assert all("paper's model" in why for why in absent.values())


def test_generated_text_independent_of_hash_seed():
    code = (
        "from beltmdsm.derive.models.render import render_model; import hashlib; "
        "print(hashlib.sha256(render_model('hoffmann').encode()).hexdigest())"
    )
    out = {
        subprocess.run(
            [sys.executable, "-c", code],
            capture_output=True,
            text=True,
            check=True,
            env={**__import__("os").environ, "PYTHONHASHSEED": seed},
        ).stdout
        for seed in ("0", "1")
    }
    assert len(out) == 1


# --------------------------------------------------------------------------- finite differences


def _fd(f, x, h):
    """Central differences of ``f`` at ``x``, one column per entry of ``x``."""
    cols = []
    for i in range(len(x)):
        e = np.zeros_like(x)
        e[i] = h * max(1.0, abs(x[i]))
        cols.append((np.asarray(f(x + e)) - np.asarray(f(x - e))) / (2 * e[i]))
    return np.array(cols).T


@pytest.mark.parametrize("name", ["belt_1dof", "hoffmann", "paper"])
def test_jacobians_and_saltation_against_finite_differences(name):
    """Each mode's Jacobian against central differences of its field, and each switch's
    saltation matrix assembled here from the fields and the switching function's
    finite-difference gradient and time rate: I + (f+ - f-) n^T / (h_t + n . f-)."""
    m = load(name)
    law = m.FRICTION_LAWS[1]
    k = m.kernels(law)
    p = _p(m, law, alpha_t=0.5, alpha_n=0.2) if name != "hoffmann" else _p(m, law)
    rng = np.random.default_rng(5)
    index = {s: i for i, s in enumerate(m.SURFACES)}
    for _ in range(3):
        t = rng.uniform(0, 5)
        y = k.equilibrium(p) + rng.normal(0, 0.3, len(m.STATES))
        for mode in m.MODES.values():
            J = k.jacobian(t, y, p, mode)
            ref = _fd(lambda z: k.field(t, z, p, mode), y, 1e-6)
            assert np.allclose(J, ref, rtol=1e-6, atol=1e-6 * np.max(np.abs(ref))), mode
        for (before, after), surface in m.SWITCHES.items():
            i = index[surface]
            n = _fd(lambda z: [k.surfaces(t, z, p)[i]], y, 1e-6)[0]
            dt = 1e-6 * max(1.0, t)
            h_t = (k.surfaces(t + dt, y, p)[i] - k.surfaces(t - dt, y, p)[i]) / (2 * dt)
            f_minus, f_plus = k.field(t, y, p, before), k.field(t, y, p, after)
            S = np.eye(len(y)) + np.outer(f_plus - f_minus, n) / (h_t + n @ f_minus)
            got = k.saltation(t, y, p, before, after)
            assert np.allclose(got, S, rtol=1e-5, atol=1e-5 * np.max(np.abs(S))), (before, after)
            rate = k.surface_rates(t, y, p, before)[i]
            assert rate == pytest.approx(h_t + n @ f_minus, rel=1e-5, abs=1e-8)


@pytest.mark.parametrize("law", ["coulomb", "stribeck", "static_kinetic"])
def test_belt_1dof_is_the_paper_with_its_normal_direction_at_rest(law):
    """With no normal excitation the paper's normal motion stays at its equilibrium
    (F = g), and its tangential equation is belt_1dof's: the fields, holding forces and
    stick limits agree there, in every mode of contact."""
    paper, belt = load("paper"), load("belt_1dof")
    kp, kb = paper.kernels(law), belt.kernels(law)
    rng = np.random.default_rng(9)
    for _ in range(10):
        v = {
            n: rng.uniform(0.2, 2.0) for n in set(paper.PARAMETERS[law]) | set(belt.PARAMETERS[law])
        }
        v["alpha_n"] = 0.0
        v["mu_k"] = v["mu_s"] * 0.6
        pp = np.array([v[n] for n in paper.PARAMETERS[law]])
        pb = np.array([v[n] for n in belt.PARAMETERS[law]])
        X2 = kp.equilibrium(pp)[2]
        t, x, xd = rng.uniform(0, 5), rng.normal(), rng.normal()
        yp, yb = np.array([x, xd, X2, 0.0]), np.array([x, xd])
        assert kp.normal_force(t, yp, pp) == pytest.approx(v["g"], rel=1e-14)
        for mode in (1, -1, 0):
            fp, fb = kp.field(t, yp, pp, mode), kb.field(t, yb, pb, mode)
            np.testing.assert_allclose(fp[:2], fb, rtol=1e-13, atol=1e-13 * np.max(np.abs(fb)))
            assert abs(fp[3]) <= 1e-13 * v["g"]  # the normal direction stays at rest
        assert kp.holding_force(t, yp, pp) == pytest.approx(kb.holding_force(t, yb, pb), rel=1e-13)
        assert kp.stick_limit(t, yp, pp) == pytest.approx(kb.stick_limit(t, yb, pb), rel=1e-13)
