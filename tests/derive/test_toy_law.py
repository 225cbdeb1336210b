"""A friction law registered inside this test reaches every command (issue 19, item 4).

The toy law, ``mu(|Vr|) = mu_s - c_f |Vr|`` (linear falling, one new parameter ``c_f``),
is registered in a fresh process with `beltmdsm.derive.laws.register` (nothing in the package
is edited) and ``python -m derive --out DIR`` writes a complete ``generated/`` for it
into a temporary folder. Each command of the command line (`beltmdsm.cli.tree.COMMANDS`
and ``check-paper``) then runs in a subprocess with that ``generated/`` first on the path
and ``--friction falling``, and either uses the law, its numbers checked against closed
forms typed here or an mpmath reference, or refuses it in one line naming it:

* the unforced equilibrium ``X1 = (mu_s - c_f Vb) g / omega1^2`` and its friction
  (``simulate``, ``sweep`` without excitation), the friction of every slipping sample
  against the law (``simulate``), the superposition solver's refusal naming the law and
  the property it lacks;
* the paper's tangential interval in closed form, ``(sqrt(V_hat^2 - m^2), V_hat]``, its
  coupled reading solved numerically (its ``V_hat`` depends on ``Vb``: no closed form),
  its edges where the pointwise growth rate changes sign, and the consistent MDSM's
  band against Eq. (A1) and the averaged friction integrated by mpmath (``predict``);
* Liouville's formula for the periodic response that slides without reversal: the
  slip-mode friction ``(mu_s - c_f (Vb - X1')) F`` adds ``c_f F`` to the trace, and the
  mean contact force over a period is ``g``, so the tangential pair of multipliers has
  ``|mu|^2 = exp(-(2 beta1 omega1 - c_f g) T)``: the growth rate ``-(2 beta1 omega1 - c_f
  g) / 2`` and a Neimark-Sacker boundary at ``c_f = 2 beta1 omega1 / g`` (``floquet``,
  ``floquet-band``, ``responses``, ``branch``, ``coexistence``, ``floquet-map``; the
  Lyapunov exponents of ``lyapunov`` and the attractor of ``basins`` too);
* ``validate`` (the paper's cases), ``docs`` and ``check-paper`` take no model: they
  refuse ``--friction`` in one line naming it.

Regenerating takes 18-40 s on the shared 2-core machine and the commands about as long
again (numba compiles the toy law's kernels once; 67 s in all): the tests that need the
toy law are marked ``slow`` (``python -m pytest -m slow tests/derive/test_toy_law.py``);
the check that every command has its check here runs by default.
"""

import json
import math
import os
import re
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest
from checkout import as_checkout

from beltmdsm.cli.tree import COMMANDS
from beltmdsm.generated.parameters import BASE, FRICTION_LAWS

ROOT = Path(__file__).resolve().parents[2]
#: The law's name and its parameter's base value (as registered below).
LAW, C_F = "falling", 0.01
F = ["--friction", LAW]

REGISTER = f"""
import sys
from beltmdsm.derive import laws
from beltmdsm.derive.parameters import Parameter

laws.register(
    "friction",
    laws.FrictionLaw(
        {LAW!r},
        "linear falling friction: mu(|Vr|) = mu_s - c_f |Vr|",
        "A toy law of tests/derive/test_toy_law.py: the static coefficient less a part "
        "proportional to the sliding speed.",
        "Eq. (3) for c_f = 0",
        (Parameter("c_f", "s/m", {C_F!r}, "nonnegative", "fall of mu per sliding speed"),),
        coefficient=lambda P, s: P["mu_s"] - P["c_f"] * s,
    ),
)
from beltmdsm.cli import main

sys.exit(main(["--out", sys.argv[1]]))
"""

#: The model's base values (the toy law adds only c_f).
b1, w1, mu_s, g = BASE["beta1"], BASE["omega1"], BASE["mu_s"], BASE["g"]
#: The excitation period at the base set (Omega = 4 in both directions).
T = 2 * math.pi / BASE["Omega"]
#: The tangential damping of the linearisation, 2 beta1 omega1 + g dmu/d|Vr|.
D_TOY = 2 * b1 * w1 - g * C_F
#: Where Liouville's determinant crosses 1: c_f g = 2 beta1 omega1.
C_F_CRITICAL = 2 * b1 * w1 / g


@pytest.fixture(scope="module")
def toy(tmp_path_factory):
    """A folder holding the toy law's complete ``generated/`` (and a numba cache)."""
    root = tmp_path_factory.mktemp("toy")
    env = {**os.environ, "PYTHONHASHSEED": "0", "PYTHONPATH": str(ROOT)}
    start = time.perf_counter()
    made = subprocess.run(
        [sys.executable, "-c", REGISTER, str(root / "generated")],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
    )
    assert made.returncode == 0, made.stdout + made.stderr
    # every file written, the record of the budgeted steps (_budget.py) among them
    assert re.search(r"wrote (\d+) changed file\(s\) of \1\.", made.stdout)
    assert (root / "generated" / "_budget.py").is_file(), made.stdout
    print(f"regenerated with the toy law in {time.perf_counter() - start:.1f} s")
    return as_checkout(root)  # its generated/ is beltmdsm.generated there


def _run(toy, args, **kw):
    args = [str(a) for a in args]
    env = {
        **os.environ,
        "PYTHONPATH": str(toy),
        "BELTMDSM_CACHE": str(toy / "cache"),
        "PYTHONDONTWRITEBYTECODE": "1",
    }
    return subprocess.run(
        [sys.executable, *args], cwd=toy, env=env, capture_output=True, text=True, **kw
    )


def cli(toy, line, *more):
    """``python -m beltmdsm COMMAND --friction falling FLAGS`` (``line`` is ``"COMMAND
    FLAGS"``, ``more`` further arguments) in the toy's folder: it must succeed."""
    command, *flags = line.split()
    out = _run(toy, ["-m", "beltmdsm", command, *F, *flags, *more])
    assert out.returncode == 0, out.stdout + out.stderr
    return out.stdout


def cli_json(toy, line, *more):
    out = json.loads(cli(toy, line, *more, "--json"))
    assert out["friction"] == LAW
    return out


def python(toy, code):
    """Run ``code`` with the toy's ``generated/``; it prints one JSON object."""
    out = _run(toy, ["-c", textwrap.dedent(code)])
    assert out.returncode == 0, out.stdout + out.stderr
    return json.loads(out.stdout)


def _growth(c_f):
    """The growth rate of the tangential pair of a periodic response without reversal."""
    return -(2 * b1 * w1 - c_f * g) / 2


# ---------------------------------------------------------------- the registry


@pytest.mark.slow
def test_the_law_is_an_option_of_every_model_command_and_its_parameter_a_flag(toy):
    facts = python(
        toy,
        """
        import json
        from beltmdsm.generated import capabilities, parameters
        print(json.dumps(dict(
            options=parameters.OPTIONS["friction"],
            owner=parameters.LAW_PARAMETERS[("friction", "falling")],
            facts=capabilities.CAPABILITIES[("falling", "hertz_damp", "allowed")],
        )))
        """,
    )
    assert facts["options"] == [*FRICTION_LAWS, LAW]
    assert facts["owner"] == ["c_f"]
    holds = {k: v[0] for k, v in facts["facts"].items()}
    assert holds == {
        "slip_friction_state_independent": False,
        "one_way_coupling": True,
        "friction_monotone": False,
        "closed_form_average": True,  # a linear law: Risch finds the antiderivative
    }
    for command in COMMANDS:
        if command in WITHOUT_MODEL:
            continue
        text = cli(toy, command, "--help")
        assert ",".join((*FRICTION_LAWS, LAW)) in text and "--c_f" in text, command


# ---------------------------------------------------------------- each command


def check_simulate(toy):
    # unforced: the run stays at the law's equilibrium, X1 = (mu_s - c_f Vb) g / omega1^2
    # (Coulomb's is mu_s g / omega1^2)
    Vb = 3.0
    out = cli_json(
        toy, f"simulate --alpha 0 --Vb {Vb} --t-end 60 --no-progress --save", toy / "rest.npz"
    )
    rest = np.load(toy / "rest.npz")
    mu = mu_s - C_F * Vb
    # (to the integrator's tolerance: the run starts at the generated equilibrium and
    # stays within 4e-9 of it; Coulomb's would be 8 % off)
    np.testing.assert_allclose(rest["X1"], mu * g / w1**2, rtol=1e-7)
    np.testing.assert_allclose(rest["friction"], mu * g, rtol=1e-7)
    assert out["n_switches"] == 0 and out["energy_ok"]
    # forced, with reversals: every slipping sample's friction is the law's,
    # -(mu_s - c_f |Vr|) sgn(Vr) F, typed here
    out = cli_json(toy, "simulate --Vb 4 --t-end 100 --no-progress --save", toy / "run.npz")
    run = np.load(toy / "run.npz")
    Vr = run["Y1"] - 4.0
    slip = np.abs(Vr) > 1e-6
    law = -(mu_s - C_F * np.abs(Vr)) * np.sign(Vr) * run["Fn"]
    np.testing.assert_allclose(run["friction"][slip], law[slip], rtol=1e-9, atol=1e-12)
    assert slip.mean() > 0.99 and (Vr[slip] > 0).any() and (Vr[slip] < 0).any()
    assert out["n_reversals"] > 10 and out["energy_residual"] < out["energy_bound"]
    # the superposition solver needs friction free of the tangential state: it hands
    # the run to the event-driven solver and says why, naming the law and the property
    out = cli_json(toy, "simulate --Vb 4 --t-end 30 --solver superposition")
    assert out["solver"] == "events"
    assert "superposition: friction='falling': the slip-mode friction" in out["message"]
    assert "depends on X1'" in out["message"] and "\n" not in out["message"]


def check_sweep(toy):
    sweep = "sweep --param Vb --values 3 6 --alpha 0 --t-end 60 --no-progress --no-cache"
    out = cli_json(toy, sweep, "--jobs", "1")
    for row in out["rows"]:
        assert row["n_switches"] == 0
        assert row["mean_friction"] == pytest.approx((mu_s - C_F * row["Vb"]) * g, rel=1e-9)


def check_predict(toy):
    out = cli_json(toy, "predict --no-progress")
    # the paper's tangential reading in closed form, typed here: V_hat of the linear
    # tangential response with the damping 2 beta1 omega1 + g dmu/d|Vr|, and the slope
    # of the effective friction 2 mu_s / (pi sqrt(V_hat^2 - Vb^2)) - c_f in the sign of
    # Eq. (A4) as printed (p = 2 beta1 omega1 - g mu_bar')
    W, a = BASE["Omega"], BASE["alpha"]
    vhat = W * a * W**2 / abs(w1**2 - W**2 + 1j * D_TOY * W)
    m = 2 * g * mu_s / (math.pi * (2 * b1 * w1 + g * C_F))
    ((lower, upper),) = out["paper_tangential_vhat"]
    assert upper == pytest.approx(vhat, rel=1e-12)
    assert lower == pytest.approx(math.sqrt(vhat**2 - m**2), rel=1e-10)
    # the coupled reading's V_hat takes mu(Vb) = mu_s - c_f Vb: no closed form, solved
    # numerically from the pointwise growth rate, and the reason says so
    coupled = out["paper_coupled_vhat"]
    assert coupled and all(lo < hi for lo, hi in coupled)
    why = out["reasons"]["paper_coupled_vhat"]
    assert why.startswith("numeric (V_hat depends on Vb under friction='falling'")
    assert "\n" not in why
    text = cli(toy, "predict --no-progress")
    assert any(
        line.strip().startswith("paper_coupled_vhat: unstable Vb in") and why in line
        for line in text.splitlines()
    )
    # the consistent MDSM: its band's edges and points of its grid against Eq. (A1)
    # and the averaged friction of the law typed here, integrated by mpmath
    ((lo, hi),) = out["consistent_mdsm"]
    ref = python(
        toy,
        f"""
        import json
        import mpmath
        from beltmdsm.prediction import mdsm
        from beltmdsm.model import Model
        mpmath.mp.dps = 30

        def average(m, u, V, N1, theta, weight=lambda t: 1):
            def f(t):
                v = u + V * mpmath.sin(t)
                mu = m["mu_s"] - m["c_f"] * abs(v)
                return mpmath.sign(v) * mu * (m["g"] + N1 * mpmath.sin(t + theta)) * weight(t)
            points = {{mpmath.mpf(0), 2 * mpmath.pi}}
            if abs(u) < V:
                a = mpmath.asin(-u / V)
                points |= {{a % (2 * mpmath.pi), (mpmath.pi - a) % (2 * mpmath.pi)}}
            return mpmath.quad(f, sorted(points))

        def reference(m, fast):
            V, phi, N1, psi = (mpmath.mpf(x) for x in (fast.V, fast.phi, fast.N1, fast.psi))
            u, th = -mpmath.mpf(m["Vb"]), psi - phi
            s1 = average(m, u, V, N1, th, mpmath.sin) / mpmath.pi
            c1 = average(m, u, V, N1, th, mpmath.cos) / mpmath.pi
            W = mpmath.mpf(m["Omega_t"])
            q = m["omega1"] ** 2 - W**2 + 2j * m["beta1"] * m["omega1"] * W
            Ft = m["alpha_t"] * W**2 * mpmath.expj(m["phase_t"])
            r = abs(q * V / (1j * W) - Ft * mpmath.expj(-phi) + (s1 + 1j * c1)) / abs(Ft)
            # one-sided (towards larger |u|) where the friction does not reverse: at the
            # onset (|u| = V) the average has a square-root singularity on the other side
            side = 0 if abs(u) < V else -1
            avg = lambda x: average(m, x, V, N1, th) / (2 * mpmath.pi)
            slope = mpmath.diff(avg, u, direction=side)
            return float(r), float(2 * m["beta1"] * m["omega1"] + slope)

        rows = []
        for Vb in (1.0, 4.0, {lo!r}, 6.0, {hi!r}, {hi!r} * 0.999, 9.0):
            m = Model(friction="falling", Vb=Vb)
            fast = mdsm.fast_motion(m)
            r, d = reference(m, fast)
            rows.append((Vb, fast.V, fast.reverses, r, d, mdsm.consistent_mdsm_damping(m, fast)))
        print(json.dumps(rows))
        """,
    )
    for Vb, V, reverses, residual, damping, got in ref:
        assert residual < 1e-12 and reverses == (V > Vb)
        assert got == pytest.approx(damping, rel=1e-10, abs=1e-12), Vb
    by_vb = {row[0]: row for row in ref}
    assert abs(by_vb[lo][4]) < 1e-8  # the lower edge: a root of the damping
    assert not by_vb[hi][2] and by_vb[hi][1] == pytest.approx(hi, rel=1e-10)  # the onset
    assert by_vb[hi * 0.999][2] and by_vb[hi * 0.999][4] < 0  # reversing below it: unstable


def check_floquet(toy):
    # Vb = 12: sliding back throughout, Liouville's closed form (0.05095 below Coulomb's 0.1)
    out = cli_json(toy, "floquet --Vb 12")
    assert out["engine"] == "general" and out["n_reversals"] == out["n_sticks"] == 0
    assert out["growth_rate"] == pytest.approx(_growth(C_F), rel=1e-8)
    pair = [complex(*z) for z in out["multipliers"] if abs(z[1]) > 0]
    assert len(pair) == 2
    assert abs(pair[0] * pair[1]) == pytest.approx(math.exp(-D_TOY * T), rel=1e-8)
    # without excitation, c_f above 2 beta1 omega1 / g: steady sliding is unstable and
    # a self-excited stick-slip cycle is found by shooting (period unknown)
    out = cli_json(toy, "floquet --alpha 0 --c_f 0.03 --Vb 1")
    assert out["autonomous"] and out["stable"] and out["n_sticks"] >= 1
    assert abs(complex(*out["trivial_multiplier"]) - 1) < 1e-8
    # c_f above 2 beta1 omega1 / g: the sliding response is unstable
    out = cli_json(toy, "floquet --alpha 1 --c_f 0.03 --Vb 6")
    assert out["n_reversals"] == 0 and not out["stable"]
    assert out["growth_rate"] == pytest.approx(_growth(0.03), rel=1e-8)


def check_floquet_band(toy):
    band = "floquet-band --alpha 1 --c_f 0.03 --param Vb --from 5 --to 7 --points 3"
    out = cli_json(toy, band, "--no-progress")
    assert out["engine"] == "general" and out["unstable"] == [[5.0, 7.0]]
    for point in out["grid"]:
        assert point["n_reversals"] == 0
        assert point["growth_rate"] == pytest.approx(_growth(0.03), rel=1e-8)


def check_responses(toy):
    out = cli_json(toy, "responses --alpha 1 --c_f 0.03 --Vb 6 --limit 1 --ladder 0 --t-end 200")
    (response,) = out["responses"]
    assert response["periods"] == 1 and response["n_reversals"] == 0
    assert response["growth_rate"] == pytest.approx(_growth(0.03), rel=1e-8)
    assert response["engine"] == "general" and not response["stable"]


def check_branch(toy):
    out = cli_json(toy, "branch --alpha 1 --Vb 6 --c_f 0.01 --param c_f --from 0.01 --to 0.03")
    (ns,) = [p for p in out["special_points"] if p["kind"] == "neimark_sacker"]
    assert abs(ns["value"] - C_F_CRITICAL) <= max(ns["accuracy"], 1e-9)
    assert out["stable_ranges"] == [[0.01, ns["value"]]]
    assert all(p["n_reversals"] == 0 for p in out["points"])
    # without excitation: steady sliding loses stability where its damping
    # 2 beta1 omega1 - c_f g vanishes, the Hopf point of the self-excited cycles
    # (issue 29: cycles under a law a user registers)
    out = cli_json(toy, "branch --alpha 0 --Vb 1 --param c_f --from 0.015 --to 0.03")
    assert out["autonomous"]
    (hopf,) = [p for p in out["special_points"] if p["kind"] == "hopf"]
    assert abs(hopf["value"] - C_F_CRITICAL) < 1e-6


def check_coexistence(toy):
    walk = "coexistence --alpha 1 --Vb 6 --param c_f --from 0.01 --to 0.03 --step 0.01"
    out = cli_json(toy, walk, "--limit", "1")
    assert out["coexistence"] == []
    (periodic,) = [r for r in out["responses"] if r["periods"] == 1]
    ((lo, hi),) = [s["range"] for s in periodic["stable"]]
    assert lo == 0.01 and abs(hi - C_F_CRITICAL) < 1e-6


def check_floquet_map(toy):
    axes = "--x Vb --x-from 5 --x-to 7 --y c_f --y-from 0.01 --y-to 0.03"
    out = cli_json(toy, f"floquet-map --alpha 1 {axes} --rows 3")
    # rows c_f = 0.01, 0.02 (below 2 beta1 omega1 / g = 0.0204) stable, 0.03 unstable
    assert [c < C_F_CRITICAL for c in out["rows"]] == [True, True, False]
    assert out["unstable"] == [[], [], [[5.0, 7.0]]]


def check_lyapunov(toy):
    # on the periodic response that slides back throughout (Vb = 12): the tangential
    # pair's exponents are its Floquet growth rate, their sum Liouville's -D_TOY
    out = cli_json(toy, "lyapunov --Vb 12 --start periodic --perturbation 0 --t-end 400")
    ex, err = out["exponents"], out["error"]
    assert out["collapsed"] == 0
    assert abs(ex[0] - _growth(C_F)) <= err[0] + 1e-6
    assert abs(ex[0] + ex[1] + D_TOY) <= err[0] + err[1] + 1e-6


def check_basins(toy):
    # one attractor, the sliding response: every start reaches it
    line = "basins --Vb 12 --points 2 --jobs 1 --no-cache --t-end 600"
    out = cli_json(toy, line)
    (a,) = out["attractors"]
    assert (a["kind"], a["periods"], a["fraction"]) == ("periodic", 1, 1.0)
    assert abs(a["lyapunov"] - _growth(C_F)) <= a["lyapunov_error"] + 1e-6


def check_basin_stability(toy):
    # without excitation the toy law's steady sliding decays at D_TOY / 2 > 0 at every
    # belt speed (its slope c_f is the same at every Vr): an attractor at each value, no
    # Hopf point in the range, and the shares and the unidentified starts add up to all
    line = (
        "basin-stability --alpha 0 --param Vb --from 2 --to 4 --points 2 --samples 40 "
        "--x-from 0 --x-to 2 --y-from -1 --y-to 1 --no-cache --jobs 1"
    )
    out = json.loads(cli(toy, line, "--json"))
    (sliding,) = [a for a in out["attractors"] if a["name"] == "steady sliding"]
    assert D_TOY > 0 and all(f > 0 for f in sliding["fraction"])
    for k, left in enumerate(out["unidentified"]):
        shares = sum(a["fraction"][k] for a in out["attractors"])
        assert abs(shares + left / 40 - 1) < 1e-12
    assert not [e for e in out["edges"] if e["kind"] == "hopf"]


#: The commands that take no model: they refuse the flag by name.
WITHOUT_MODEL = ("validate", "docs", "check-paper")


def check_without_model(toy, command):
    out = _run(toy, ["-m", "beltmdsm", command, *F])
    assert out.returncode == 2 and out.stdout == ""
    (line,) = out.stderr.strip().splitlines()
    assert "unrecognized arguments: --friction" in line


CHECKS = {
    "simulate": check_simulate,
    "sweep": check_sweep,
    "predict": check_predict,
    "floquet": check_floquet,
    "floquet-band": check_floquet_band,
    "responses": check_responses,
    "branch": check_branch,
    "coexistence": check_coexistence,
    "floquet-map": check_floquet_map,
    "lyapunov": check_lyapunov,
    "basins": check_basins,
    "basin-stability": check_basin_stability,
    **{name: (lambda toy, name=name: check_without_model(toy, name)) for name in WITHOUT_MODEL},
}


def test_every_command_is_checked():
    assert set(CHECKS) == set(COMMANDS) | {"check-paper"}


@pytest.mark.slow
@pytest.mark.parametrize("command", list(CHECKS))
def test_each_command_uses_the_toy_law_or_refuses_it_by_name(toy, command):
    CHECKS[command](toy)
