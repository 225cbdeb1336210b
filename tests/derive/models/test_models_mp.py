"""The mpmath twins of the model modules (generated/mp/models/, issue 39).

For every registered model and friction law, on random points inside the parameters'
domains, at 50 digits:

* each twin's kernel is the derivation's SymPy expression (derive/models/), evaluated
  here by walking the expression itself (rounding_bound.evaluate): a check of the
  printing, to 1e-40 of the expression's rounding scale;
* each numpy kernel (generated/models/) is within ``EPS * E`` of the twin, ``E`` the
  first-order rounding bound of the same expression (rounding_bound's error model: the
  hand-typed one of tests/generated/test_hybrid.py, made mechanical);
* the independent references, each computed here from the twin's field, gradient and
  Jacobian alone: the characteristic coefficients against the Faddeev-LeVerrier
  recurrence on the Jacobian at the equilibrium (itself a zero of the field); the
  Hurwitz determinants against mpmath determinants of the Hurwitz matrix; the
  saltation matrices against ``I + (f+ - f-) n^T / (dh/dt)-`` with ``n`` and ``dh/dt``
  by mpmath's differentiation of the switching function; the holding force against the
  Lagrange multiplier solved from ``M q'' = Q0 + d lambda, w . q'' = 0`` (``M^-1 d`` and
  ``M^-1 Q0`` read from the two slip fields and their friction forces).
"""

from __future__ import annotations

import itertools
import os
import subprocess
import sys
from dataclasses import replace

import mpmath
import numpy as np
import pytest
import sympy as sp
from rounding_bound import EPS, evaluate

from beltmdsm.derive.codegen import stale
from beltmdsm.derive.model import t as T
from beltmdsm.derive.models import MODELS as ENTRIES
from beltmdsm.derive.models import Contact, Oscillator
from beltmdsm.derive.models import hybrid as hy
from beltmdsm.derive.models.render import files, render_entry
from beltmdsm.derive.models.steady import NUMERIC, coefficient_symbols, hurwitz, steady
from beltmdsm.derive.models.system import system
from beltmdsm.derive.parameters import MODEL, Parameter
from beltmdsm.generated.models import MODELS, load
from beltmdsm.generated.mp import models as mp_models

POINTS = 3
CASES = [(name, law) for name in MODELS for law in load(name).FRICTION_LAWS]
#: The twin's printing: the walked expression's value to this fraction of its scale.
PRINTED = mpmath.mpf(10) ** -40


def random_params(rng, M, law):
    """Each parameter drawn around its default, inside its domain."""
    out = []
    for name in M.PARAMETERS[law]:
        default, domain = M.DEFAULTS[name], M.DOMAINS[name]
        if domain == "real":
            out.append(rng.uniform(-3, 3))
        elif default > 0:
            out.append(default * float(np.exp(rng.uniform(-0.7, 0.7))))
        else:  # nonnegative, 0 by default (an amplitude)
            out.append(rng.uniform(0, 1))
    return np.array(out)


def random_state(rng, s, contact=True):
    y = rng.normal(size=len(s.state)) * 2
    if s.gap is not None:
        k = s.state.index(-s.gap)
        y[k] = rng.uniform(0.05, 3.0) if contact else -rng.uniform(0.05, 2.0)
    return y


def env_of(s, t, y, p):
    exact = mpmath.mpf(0)
    env = {T: (t, exact)}
    env.update({x: (v, exact) for x, v in zip(s.state, y)})
    env.update({x: (v, exact) for x, v in zip(s.params, p)})
    return env


def flat(value):
    if isinstance(value, mpmath.matrix):
        return [value[i, j] for i in range(value.rows) for j in range(value.cols)]
    if isinstance(value, (list, tuple, np.ndarray)):
        return list(np.ravel(np.asarray(value, dtype=object)))
    return [value]


class Worst:
    """The largest error seen, as a fraction of its bound (reported by -s)."""

    ratio = 0.0


def check(got, twin, exprs, env, memo, what):
    """The twin is the expressions (to PRINTED of their scale) and numpy within EPS * E."""
    twin, got = flat(twin), np.ravel(np.asarray(got, dtype=float))
    assert len(twin) == len(got) == len(exprs), what
    for k, (g, w, e) in enumerate(zip(got, twin, exprs)):
        v, err = evaluate(e, env, memo)
        assert abs(w - v) <= PRINTED * (err + abs(v)), (what, k, w, v)
        bound = EPS * err
        assert abs(mpmath.mpf(float(g)) - v) <= bound, (what, k, float(g), v, float(bound))
        if bound:
            Worst.ratio = max(Worst.ratio, float(abs(mpmath.mpf(float(g)) - v) / bound))


def kernels(name, law):
    return load(name).kernels(law), mp_models.load(name).kernels(law), system(ENTRIES[name], law)


@pytest.mark.parametrize("name,law", CASES)
def test_state_kernels_are_the_derived_expressions_and_numpy_is_within_rounding(
    rng, mp50, name, law
):
    k, km, s = kernels(name, law)
    M = load(name)
    modes = sorted(s.fields)
    grad = [hy.d(s.slip, x) for x in s.state]
    surf = list(hy.surfaces(s).values())
    for i in range(POINTS):
        p = random_params(rng, M, law)
        t, y = rng.uniform(-5, 5), random_state(rng, s, contact=i < POINTS - 1)
        env, memo = env_of(s, t, y, p), {}
        args = (t, y, p)
        for kernel, exprs in (
            ("slip_velocity", [s.slip]),
            ("slip_gradient", grad),
            ("normal_force", [s.normal]),
            ("holding_force", [s.holding]),
            ("stick_limit", [s.limit]),
            ("surfaces", surf),
        ) + ((("gap", [s.gap]),) if s.gap is not None else ()):
            got, twin = getattr(k, kernel)(*args), getattr(km, kernel)(*args)
            check(got, twin, exprs, env, memo, (kernel, i))
        for m in modes:
            for kernel, exprs in (
                ("field", list(s.fields[m])),
                ("jacobian", list(hy.jacobian(s, m))),
                ("slip_acceleration", [hy.rate(s, s.slip, m)]),
                ("friction_force", [s.friction[m]]),
                ("surface_rates", [hy.rate(s, h, m) for h in surf]),
            ):
                got, twin = getattr(k, kernel)(*args, m), getattr(km, kernel)(*args, m)
                check(got, twin, exprs, env, memo, (kernel, m, i))
        for before, after in hy.switches(s):
            got = k.saltation(*args, before, after)
            twin = km.saltation(*args, before, after)
            check(got, twin, list(hy.saltation(s, before, after)), env, memo, (before, after))


def steady_layers(s, p):
    """(value, E) of the equilibrium, the Jacobian entries and the coefficients, each
    layer reading the previous one's rounded values."""
    st = steady(s)
    env = env_of(s, 0.0, [0.0] * len(s.state), p)
    state = [evaluate(st.solution.get(x, sp.Integer(0)), env) for x in s.state]
    env.update(zip(s.state, state))
    entries = {sym: evaluate(e, env) for sym, e in st.entries.items()}
    coefficients = [evaluate(c, entries) for c in st.coefficients]
    a = dict(zip(coefficient_symbols(len(s.state)), coefficients[1:]))
    determinants = [evaluate(h, a) for h in hurwitz(len(s.state))]
    return state, coefficients, determinants


@pytest.mark.parametrize("name,law", CASES)
def test_steady_kernels_are_the_derived_expressions_and_numpy_is_within_rounding(
    rng, mp50, name, law
):
    k, km, s = kernels(name, law)
    M = load(name)
    assert M.EQUILIBRIUM[law] == "closed form"  # the numeric path: test_numeric_path_*
    for _ in range(POINTS):
        p = random_params(rng, M, law)
        layers = steady_layers(s, [mpmath.mpf(v) for v in p])
        for kernel, values in zip(("equilibrium", "characteristic", "hurwitz"), layers):
            got, twin = np.ravel(getattr(k, kernel)(p)), flat(getattr(km, kernel)(p))
            for g, w, (v, err) in zip(got, twin, values, strict=True):
                assert abs(w - v) <= PRINTED * (err + abs(v)), (kernel, w, v)
                assert abs(mpmath.mpf(float(g)) - v) <= EPS * err, (kernel, float(g), v)


def unforced(M, law, p):
    """``p`` with every excitation amplitude 0."""
    names = M.PARAMETERS[law]
    q = list(p)
    for _, amplitude, _, _ in M.EXCITATION:
        q[names.index(amplitude)] = 0
    return q


def faddeev_leverrier(J):
    """1, c_1 .. c_n of det(lambda I - J), by the Faddeev-LeVerrier recurrence."""
    n = J.rows
    eye, Mk, c = mpmath.eye(n), mpmath.zeros(n, n), [mpmath.mpf(1)]
    for k in range(1, n + 1):
        Mk = J * Mk + c[-1] * eye
        c.append(-sum((J * Mk)[i, i] for i in range(n)) / k)
    return c


def hurwitz_matrix_minors(a):
    """H_1 .. H_n of lambda^n + a_1 lambda^(n-1) + ... + a_n: leading minors of the
    Hurwitz matrix h_ij = a_(2j - i)."""
    n = len(a) - 1
    H = mpmath.matrix(n, n)
    for i, j in itertools.product(range(1, n + 1), repeat=2):
        m = 2 * j - i
        H[i - 1, j - 1] = a[m] if 0 <= m <= n else 0
    return [mpmath.det(H[:r, :r]) for r in range(1, n + 1)]


@pytest.mark.parametrize("name,law", CASES)
def test_characteristic_and_hurwitz_against_independent_mpmath(rng, mp50, name, law):
    M = load(name)
    km = mp_models.load(name).kernels(law)
    for _ in range(POINTS):
        p = random_params(rng, M, law)
        y0 = km.equilibrium(p)
        q = unforced(M, law, p)
        f = km.field(0.0, y0, q, -1)
        scale = 1 + max(abs(x) for x in km.jacobian(0.0, y0, q, -1))
        assert max(abs(x) for x in f) <= mpmath.mpf(10) ** -40 * scale * (1 + max(map(abs, y0)))
        assert km.slip_velocity(0.0, y0, q) < 0  # steady sliding is mode -1
        J = km.jacobian(0.0, y0, q, -1)
        a = faddeev_leverrier(J)
        got = km.characteristic(p)
        for k, (x, r) in enumerate(zip(got, a, strict=True)):
            assert abs(x - r) <= mpmath.mpf(10) ** -40 * scale ** (k + 1), (k, x, r)
        H = hurwitz_matrix_minors(got)
        for k, (x, r) in enumerate(zip(km.hurwitz(p), H, strict=True)):
            size = (1 + max(abs(c) for c in got)) ** (k + 2)
            assert abs(x - r) <= mpmath.mpf(10) ** -40 * size, (k, x, r)


@pytest.mark.parametrize("name,law", CASES)
def test_saltation_is_its_definition_from_the_twins_field_and_surface(rng, mp50, name, law):
    M = load(name)
    km = mp_models.load(name).kernels(law)
    s = system(ENTRIES[name], law)
    for _ in range(POINTS):
        p = random_params(rng, M, law)
        t, y = rng.uniform(-5, 5), random_state(rng, s)
        y = [mpmath.mpf(v) for v in y]
        for (before, after), surface in M.SWITCHES.items():
            h_index = M.SURFACES.index(surface)

            def h(tt, *state, h_index=h_index):
                return km.surfaces(tt, list(state), p)[h_index]

            n = [
                mpmath.diff(h, [t, *y], tuple(int(j == k) for j in range(len(y) + 1)))
                for k in range(1, len(y) + 1)
            ]
            h_t = mpmath.diff(h, [t, *y], (1,) + (0,) * len(y))
            f_minus = km.field(t, y, p, before)
            f_plus = km.field(t, y, p, after)
            rate = h_t + sum(a * b for a, b in zip(n, f_minus))
            S = km.saltation(t, y, p, before, after)
            size = 1 + max(abs(x) for x in f_minus + f_plus) * max(map(abs, n)) / abs(rate)
            for r, c in itertools.product(range(len(y)), repeat=2):
                ref = int(r == c) + (f_plus[r] - f_minus[r]) * n[c] / rate
                assert abs(S[r, c] - ref) <= mpmath.mpf(10) ** -25 * size, (before, after, r, c)


@pytest.mark.parametrize("name,law", CASES)
def test_holding_force_is_the_lagrange_multiplier_of_the_constraint(rng, mp50, name, law):
    M = load(name)
    km = mp_models.load(name).kernels(law)
    s = system(ENTRIES[name], law)
    rates = [s.state.index(v) for v in s.v]  # the rows of q' in the state
    for _ in range(POINTS):
        p = random_params(rng, M, law)
        t, y = rng.uniform(-5, 5), random_state(rng, s)
        w = [km.slip_gradient(t, y, p)[i] for i in rates]  # v_r = w . q' - Vb
        f1 = [km.field(t, y, p, 1)[i] for i in rates]
        f2 = [km.field(t, y, p, -1)[i] for i in rates]
        F1, F2 = km.friction_force(t, y, p, 1), km.friction_force(t, y, p, -1)
        assert F1 != F2  # in contact, mu > 0: the friction direction is seen
        Minv_d = [(a - b) / (F1 - F2) for a, b in zip(f1, f2)]
        free = [a - m * F1 for a, m in zip(f1, Minv_d)]  # M^-1 Q0
        lam = -sum(a * b for a, b in zip(w, free)) / sum(a * b for a, b in zip(w, Minv_d))
        got = km.holding_force(t, y, p)
        assert abs(got - lam) <= mpmath.mpf(10) ** -35 * (1 + abs(lam)), (got, lam)
        assert km.friction_force(t, y, p, 0) == got
        # the stick field keeps v_r: d v_r / dt = 0 along it
        assert abs(km.slip_acceleration(t, y, p, 0)) <= mpmath.mpf(10) ** -35 * (1 + abs(lam))


def test_twins_list_the_models_and_compute_at_the_working_precision():
    assert mp_models.MODELS == MODELS
    with pytest.raises(ValueError, match="model must be one of"):
        mp_models.load("nope")
    M = load("belt_1dof")
    km = mp_models.load("belt_1dof").kernels("coulomb")
    names = M.PARAMETERS["coulomb"]
    p = np.array([M.DEFAULTS[x] for x in names]) * 1.1  # 0.44 * 10.791 is not a double
    with mpmath.workdps(60):
        x = km.equilibrium(p)[0]
        # friction opposes v_r = -Vb: x = mu_s g / omega1^2, typed here
        mu_s, g, omega1 = (mpmath.mpf(p[names.index(k)]) for k in ("mu_s", "g", "omega1"))
        exact = mu_s * g / omega1**2
    assert abs(x - exact) < mpmath.mpf(10) ** -58 * exact
    assert abs(x - float(exact)) > mpmath.mpf(10) ** -25  # not a double's value


# --------------------------------------------------------------------------- numeric path

ROW = {p.name: p for p in MODEL}
#: A model whose equilibrium has no closed form (two roots of a quadratic: SymPy cannot
#: pick the admissible one): q'' = -k q - k2 q^2 - F0 + friction, a bilateral load g.
WELL = Oscillator(
    "well",
    "A mass on a softening spring with a constant pull",
    "Test model: the numeric equilibrium path.",
    ("q",),
    (
        Parameter("k", "N/m", 1.0, "positive", "linear spring"),
        Parameter("k2", "N/m^2", 0.5, "positive", "quadratic spring"),
        Parameter("F0", "N", 0.5, "nonnegative", "constant pull"),
        ROW["g"],
        ROW["Vb"],
    ),
    Contact(slip=lambda P: {"q": 1}, normal=lambda P, q, v, t: P["g"]),
    stiffness=lambda P: [[P["k"]]],
    forces=lambda P, q, v, t: {"q": -P["k2"] * q["q"] ** 2 - P["F0"]},
    friction_laws=("coulomb",),
)


#: WELL with a second coordinate after one named ``q`` (the Newton step reads ``q[1]``).
WELL2 = replace(
    WELL,
    name="well2",
    coordinates=("q", "r"),
    stiffness=lambda P: [[P["k"], 0], [0, P["k"]]],
    forces=lambda P, q, v, t: {"q": -P["k2"] * q["q"] ** 2 - P["F0"], "r": -P["k2"] * q["r"] ** 2},
)


def module_of(entry, mp):
    namespace = {"__name__": f"user_{entry.name}{'_mp' if mp else ''}"}
    exec(compile(render_entry(entry, mp=mp), entry.name, "exec"), namespace)
    return namespace


def test_numeric_path_twin_solves_at_the_working_precision_or_refuses_by_name(mp50):
    numpy_module, twin = module_of(WELL, False), module_of(WELL, True)
    assert numpy_module["EQUILIBRIUM"] == twin["EQUILIBRIUM"] == {"coulomb": NUMERIC}
    k, km = numpy_module["kernels"]("coulomb"), twin["kernels"]("coulomb")
    names = numpy_module["PARAMETERS"]["coulomb"]
    v = dict(numpy_module["DEFAULTS"])
    p = np.array([v[n] for n in names])
    y = km.equilibrium(p)
    # the root Newton reaches from q = 0, typed: k2 q^2 + k q + F0 - mu_s g = 0
    k_, k2, F0, mu, g = (mpmath.mpf(v[n]) for n in ("k", "k2", "F0", "mu_s", "g"))
    root = (-k_ + mpmath.sqrt(k_**2 - 4 * k2 * (F0 - mu * g))) / (2 * k2)
    assert abs(y[0] - root) <= mpmath.mpf(10) ** -45 * abs(root) and y[1] == 0
    assert max(abs(x) for x in km.field(0.0, y, p, -1)) <= mpmath.mpf(10) ** -45
    # numpy's Newton stops at steps of 1e-14 (1 + |q|); its rounding is a few ulps of the
    # residual's terms over the slope (the slope k + 2 k2 q is about 3.7 here)
    assert abs(k.equilibrium(p)[0] - root) <= 1e-14 * (1 + abs(root))
    a = km.characteristic(p)
    assert faddeev_leverrier(km.jacobian(0.0, y, p, -1)) == pytest.approx(a, abs=1e-45)
    # a second coordinate read after the one named q: the same root, r = 0
    two = (
        module_of(WELL2, False)["kernels"]("coulomb"),
        module_of(WELL2, True)["kernels"]("coulomb"),
    )
    for kernels_ in two:
        assert [float(x) for x in kernels_.equilibrium(p)] == pytest.approx([float(root), 0, 0, 0])
    # a pull the friction cannot balance: no equilibrium, and both paths say so by name
    v["F0"] = 10.0
    p = np.array([v[n] for n in names])
    for kernels_ in (k, km):
        with pytest.raises(ArithmeticError, match="equilibrium did not converge: numeric"):
            kernels_.equilibrium(p)


# --------------------------------------------------------------------------- generation


def test_twins_are_up_to_date_and_an_edit_is_stale(tmp_path):
    """``python -m derive --check``'s comparison covers generated/mp/models/."""
    rendered = files()
    assert {f"mp/models/{n}.py" for n in MODELS} | {"mp/models/__init__.py"} <= set(rendered)
    differ = {rel: diff for rel, diff in stale(rendered).items() if rel.startswith("mp/models/")}
    assert differ == {}, "\n".join(differ.values())[:3000]
    for rel, text in rendered.items():
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text(text)
    edited = tmp_path / "mp/models/hoffmann.py"
    edited.write_text(edited.read_text().replace("mpmath.mpf(2)", "mpmath.mpf(3)", 1))
    assert set(stale(rendered, tmp_path)) == {"mp/models/hoffmann.py"}


def test_twin_text_is_independent_of_the_hash_seed():
    code = (
        "from beltmdsm.derive.models.render import render_model; import hashlib; "
        "print(hashlib.sha256(render_model('paper', mp=True).encode()).hexdigest())"
    )
    out = {
        subprocess.run(
            [sys.executable, "-c", code],
            capture_output=True,
            text=True,
            check=True,
            env={**os.environ, "PYTHONHASHSEED": seed},
        ).stdout
        for seed in ("0", "7")
    }
    assert len(out) == 1 and len(next(iter(out)).strip()) == 64


def test_importing_the_twins_never_imports_sympy():
    code = (
        "import sys; from beltmdsm.generated.mp import models; "
        "[models.load(n) for n in models.MODELS]; print('sympy' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
