"""The textbook laws of issue 29 derive completely, with the default budgets (slow).

Three one-entry friction laws a user would write, registered in a fresh process with
`beltmdsm.derive.laws.register` and derived with ``python -m derive --out DIR`` (every module):

* rational velocity weakening ``mu_s / (1 + delta_l s)`` (Risch's algorithm ran for
  minutes into tens of GB before the budgets);
* cubic ``mu_s - c_1 s + c_3 s^3`` (`sympy.solve` on its forced damping ran for hours);
* exponential ``mu_d + (mu_s - mu_d) exp(-s / v_e)`` (Stribeck-like).

The derivation must finish (exit 0) and print one line per module as it goes; what it
decides is checked against references written here: the unforced equilibrium and
critical belt speed against their closed forms typed by hand, the effective friction of
Eq. (23) against an mpmath quadrature of the law at 30 digits (whichever path the budget
left, closed form or quadrature), and the capability facts against the generated code.
The time and peak memory of the derivation are printed (the per-law figures of the
issue's report: one law each, ``/usr/bin/time -v``).
"""

import json
import math
import os
import re
import resource
import subprocess
import sys
import time
from pathlib import Path

import mpmath
import pytest
from checkout import as_checkout

from beltmdsm.generated.parameters import BASE

ROOT = Path(__file__).resolve().parents[2]

REGISTER = """
import sys
import sympy as sp
from beltmdsm.derive import laws
from beltmdsm.derive.parameters import Parameter

def law(name, summary, parameters, coefficient):
    laws.register("friction", laws.FrictionLaw(
        name, summary, "A law of tests/derive/test_user_laws.py.", "none", parameters,
        coefficient=coefficient))

law("rational", "mu_s / (1 + delta_l |Vr|)",
    (Parameter("delta_l", "s/m", 3.0, "nonnegative", "fall rate of mu"),),
    lambda P, s: P["mu_s"] / (1 + P["delta_l"] * s))
law("cubic", "mu_s - c_1 |Vr| + c_3 |Vr|^3",
    (Parameter("c_1", "s/m", 0.3, "nonnegative", "linear fall of mu"),
     Parameter("c_3", "s^3/m^3", 0.1, "positive", "cubic rise of mu")),
    lambda P, s: P["mu_s"] - P["c_1"] * s + P["c_3"] * s**3)
law("exponential", "mu_d + (mu_s - mu_d) exp(-|Vr|/v_e)",
    (Parameter("mu_d", "1", 0.2, "nonnegative", "kinetic coefficient"),
     Parameter("v_e", "m/s", 0.5, "positive", "decay speed")),
    lambda P, s: P["mu_d"] + (P["mu_s"] - P["mu_d"]) * sp.exp(-s / P["v_e"]))
from beltmdsm.cli import main
sys.exit(main(["--out", sys.argv[1]]))
"""

CHECK = """
import json, sys
sys.path.insert(0, sys.argv[1])
import mpmath
from beltmdsm.generated import capabilities, friction, unforced
from beltmdsm.generated.mp import friction as mp_friction
from beltmdsm.generated.parameters import BASE
out = {}
cases = [(-0.3, 0.8), (0.5, 0.8), (2.0, 0.8), (-1.5, 0.4)]
for law in ("rational", "cubic", "exponential"):
    with mpmath.workdps(30):
        mp = [str(mp_friction.mu_bar(mpmath.mpf(v), mpmath.mpf(h), friction=law, **BASE))
              for v, h in cases]
    out[law] = dict(
        facts=capabilities.CAPABILITIES[(law, "hertz_damp", "allowed")],
        numpy=[float(friction.mu_bar(v, h, friction=law, **BASE)) for v, h in cases],
        mp=mp,
        X1=[float(unforced.equilibrium(friction=law, **{**BASE, "Vb": vb})[0])
            for vb in (0.2, 1.0, 3.0)],
        critical=float(unforced.critical_belt_speed(friction=law, **BASE)),
    )
print(json.dumps(dict(cases=cases, laws=out)))
"""

b1, w1, g, mu_s = BASE["beta1"], BASE["omega1"], BASE["g"], BASE["mu_s"]
#: The laws at their base values, as the generated code receives them: the binary
#: doubles nearest 0.3, 0.1, 0.2 (mpmath.mpf of a float is exact).
c_1, c_3, mu_d = mpmath.mpf(0.3), mpmath.mpf(0.1), mpmath.mpf(0.2)
LAWS = {
    "rational": lambda s: mpmath.mpf(mu_s) / (1 + 3 * s),
    "cubic": lambda s: mpmath.mpf(mu_s) - c_1 * s + c_3 * s**3,
    "exponential": lambda s: mu_d + (mpmath.mpf(mu_s) - mu_d) * mpmath.exp(-2 * s),
}


def _critical(law):
    """The nonnegative root of 2 beta1 omega1 + g mu'(Vb), typed by hand (NaN: none)."""
    d = 2 * b1 * w1
    if law == "rational":  # mu' = -mu_s delta / (1 + delta Vb)^2
        root = (math.sqrt(g * mu_s * 3.0 / d) - 1) / 3.0
    elif law == "cubic":  # mu' = -c_1 + 3 c_3 Vb^2
        root = math.sqrt((0.3 * g - d) / (3 * 0.1 * g)) if 0.3 * g > d else math.nan
    else:  # mu' = -(mu_s - mu_d) / v_e exp(-Vb / v_e)
        root = 0.5 * math.log(g * (mu_s - 0.2) / (0.5 * d))
    return root if root > 0 else math.nan


def _mu_bar(mu, Vr, Vhat):
    """(1/2pi) int_0^2pi sgn(v) mu(|v|) dphi, v = Vr + Vhat sin(phi), split at the reversals."""
    Vr, Vhat = mpmath.mpf(Vr), mpmath.mpf(Vhat)

    def f(phi):
        v = Vr + Vhat * mpmath.sin(phi)
        return mpmath.sign(v) * mu(abs(v))

    cuts = [mpmath.mpf(0), 2 * mpmath.pi]
    if abs(Vr) < Vhat:
        a = mpmath.asin(-Vr / Vhat)
        cuts += [a % (2 * mpmath.pi), (mpmath.pi - a) % (2 * mpmath.pi)]
    return mpmath.quad(f, sorted(cuts)) / (2 * mpmath.pi)


@pytest.fixture(scope="module")
def derived(tmp_path_factory):
    root = tmp_path_factory.mktemp("user_laws")
    env = {**os.environ, "PYTHONHASHSEED": "0", "PYTHONPATH": str(ROOT)}
    start = time.perf_counter()
    made = subprocess.run(
        [sys.executable, "-c", REGISTER, str(root / "generated")],
        cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800,
    )  # fmt: skip
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    print(f"derived the three laws in {time.perf_counter() - start:.0f} s, peak {peak:.0f} MB")
    assert made.returncode == 0, made.stdout + made.stderr
    return as_checkout(root), made  # its generated/ is beltmdsm.generated there


@pytest.mark.slow
def test_the_derivation_finishes_and_reports_each_module(derived):
    root, made = derived
    lines = [x for x in made.stderr.splitlines() if x.startswith("derived generated/")]
    assert len(lines) == 11 and all(x.endswith(" s") for x in lines), made.stderr
    # every file written, the record of the budgeted steps (_budget.py) among them
    assert re.search(r"wrote (\d+) changed file\(s\) of \1\.", made.stdout)
    assert (root / "generated" / "_budget.py").is_file()


@pytest.mark.slow
def test_the_laws_values_against_closed_forms_and_mpmath(derived):
    root, _ = derived
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONDONTWRITEBYTECODE": "1"}
    out = subprocess.run(
        [sys.executable, "-c", CHECK, str(root)], cwd=ROOT, env=env, capture_output=True,
        text=True,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    got = json.loads(out.stdout)
    source = (root / "generated" / "friction.py").read_text()
    for law, mu in LAWS.items():
        res = got["laws"][law]
        # the unforced equilibrium X1 = mu(Vb) g / omega1^2: a few ulps
        for vb, x1 in zip((0.2, 1.0, 3.0), res["X1"]):
            assert x1 == pytest.approx(float(mu(mpmath.mpf(vb))) * g / w1**2, rel=1e-14), law
        assert res["critical"] == pytest.approx(_critical(law), rel=1e-13, nan_ok=True), law
        holds, why = res["facts"]["closed_form_average"]
        body = source[source.index(f"def _mu_bar__{law}") :].split("\n\n\n")[0]
        assert ("_support.quad(" in body) == (not holds), (law, why)
        assert holds or "quadrature" in why, (law, why)
        with mpmath.workdps(30):
            for (Vr, Vh), np_value, mp_value in zip(got["cases"], res["numpy"], res["mp"]):
                ref = _mu_bar(mu, Vr, Vh)
                assert abs(mpmath.mpf(mp_value) - ref) <= mpmath.mpf("1e-24"), (law, Vr, Vh)
                # a closed form or the Gauss-Legendre rule on smooth pieces, terms of order
                # mu_s: a few ulps, plus the rounding of the arc-sine limits
                assert abs(np_value - float(ref)) <= 1e-13, (law, Vr, Vh, np_value)
