"""A stick-slip cycle read from its stick end (issue 39): the run over one period ends
there, inside a stick, and its observables hold the stick's exact values.

Before, `beltmdsm.oscillator.orbit.orbit_observables` of such a cycle never returned:
2e-12 s before the period's end the stick ended, and the slip that followed was too short
for a step to enter it, so the modes cycled stick -> slip -> stick at one instant
(`hybrid.flow` now ends the run there, or stops it with status "zeno" where time is
left). The slip velocity's maximum was also refined by a parabola across the stick's
plateau edge, 1.5e-6 m/s above 0.

The reference of the largest x is typed here: from the stick end (closed form, x' = Vb),
the slip x'' = -2 beta omega x' - omega^2 x + mu(|v_r|) g with v_r = x' - Vb < 0, run by
solve_ivp to x' = 0.
"""

import json
import math
import subprocess
import sys

from scipy.integrate import solve_ivp

P = dict(beta1=0.1, omega1=1.0, g=9.81, mu_s=0.4, mu_k=0.25, v_s=1.0, Vb=2.5)

RUN = f"""
import json
import beltmdsm
from beltmdsm.oscillator import orbit
from beltmdsm.oscillator.system import System
m = beltmdsm.Model(model="belt_1dof", friction="stribeck", **{P!r})
state, period = beltmdsm.seed_cycle(m)
c = beltmdsm.cycle(m, guess=state, period=period)
obs = orbit.orbit_observables(System("belt_1dof", friction="stribeck", **{P!r}), c.state, c.period)
print(json.dumps({{"state": list(c.state), "obs": obs}}))
"""


def _largest_x():
    b, w, g, Vb = P["beta1"], P["omega1"], P["g"], P["Vb"]

    def mu(s):
        return P["mu_k"] + (P["mu_s"] - P["mu_k"]) * math.exp(-s / P["v_s"])

    def field(t, z):
        x, v = z
        return [v, -2 * b * w * v - w**2 * x + mu(abs(v - Vb)) * g]

    turn = lambda t, z: z[1]  # noqa: E731
    turn.terminal, turn.direction = True, -1
    x_end = (P["mu_s"] * g - 2 * b * w * Vb) / w**2
    sol = solve_ivp(field, (0, 50), [x_end, Vb], events=turn, rtol=1e-12, atol=1e-12)
    return x_end, float(sol.y_events[0][0][0])


def test_the_observables_of_a_cycle_from_its_stick_end_are_the_sticks_and_the_slips():
    done = subprocess.run(
        [sys.executable, "-c", RUN], capture_output=True, text=True, timeout=300
    )  # the old run never returned
    assert done.returncode == 0, done.stderr[-3000:]
    got = json.loads(done.stdout.splitlines()[-1])
    obs = got["obs"]
    x_end, x_max = _largest_x()
    assert abs(got["state"][0] - x_end) <= 1e-9  # shot from the stick end
    # in stick x' = Vb and v_r = 0 exactly, the largest of either: no overshoot
    assert obs["v_r_max"] == 0.0 and obs["x_dot_max"] == P["Vb"]
    # the largest x is at the slip's turn, sampled (SAMPLES per period) and refined by a
    # parabola: its error is O(h^4) of the curvature, below 1e-8 at these samples
    assert abs(obs["x_max"] - x_max) <= 1e-8, (obs["x_max"], x_max)
