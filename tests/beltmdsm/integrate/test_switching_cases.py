"""Switching cases the robustness study pins (issue 11, item 3): short runs, both solvers.

Each case runs 100 s with the default settings (DOP853, rtol = atol = 1e-10) under
both integrators (`beltmdsm.events`, `beltmdsm.superposition`) and both tension laws,
and must finish with status ``done``, close its energy balance to 1e-8 and give the
same run from both solvers: the same sequence of events (kind and new mode) at the
same times, and the same states.

Error model of the agreement. DOP853 keeps each step's local error below
``tol (1 + |y|)`` with tol = 1e-10. The tangential oscillator forgets an error over
its decay time ``1 / (beta1 omega1)`` <= 10 s, about 500 steps, so each solver's
global error stays below ~500 tol (1 + |y|) = 5e-8 (1 + |y|); a switch carries a
state error on multiplied by its saltation factor (at most ~10 here), so the two
solvers may differ by 2 x 5e-8 x 10 = 1e-6 (1 + max |y|) (`STATE_TOL`). A switch
time moves by the state error divided by the rate at which the switching function
crosses zero; the slowest crossing in these runs is 0.22 m/s^2 (the Fig. 15 point),
so 1e-6 x (1 + |y| ~ 2 near Vr = 0) / 0.22 < 1e-5 s (`TIME_TOL`). Measured: states
within 3.3e-8, switch times within 1.1e-9 s.
"""

import warnings

import numpy as np
import pytest

from beltmdsm.generated import dynamics
from beltmdsm.integrate.switching import TIE_ULPS, Mode, Switching
from beltmdsm.simulation import simulate

T_END = 100.0
STATE_TOL = 1e-6
TIME_TOL = 1e-5
RESIDUAL = 1e-8

CASES = {
    # the paper's Vb = 0 from rest: |a_free| = mu_s Fn to one ulp at t = 0
    "Vb=0": dict(Vb=0.0),
    # Fig. 15 (two excitation frequencies, Fig. 14b) and the phase-shifted excitation
    "fig15": dict(Vb=14.5, alpha_t=2.0, Omega_t=6.0, alpha_n=2.0, Omega_n=4.0),
    "phase_t=pi/2": dict(Vb=14.5, phase_t=np.pi / 2),
    # Fig. 20c, omega1 = 12: the stick chatter region at small Vb
    "omega1=12,Vb=0.5": dict(omega1=12.0, Vb=0.5),
    "omega1=12,Vb=1": dict(omega1=12.0, Vb=1.0),
    "omega1=12,Vb=1.5": dict(omega1=12.0, Vb=1.5),
    # Fig. 19c, Omega = 10: stick-slip
    "Omega=10,Vb=5": dict(Omega=10.0, Vb=5.0),
}
TENSIONS = ("allowed", "clipped")
SOLVERS = ("superposition", "events")


@pytest.fixture(scope="module")
def runs():
    out = {}
    with warnings.catch_warnings():
        # the 100 s runs may not resolve the omega1 peak; that is not the question here
        warnings.simplefilter("ignore", RuntimeWarning)
        for name, params in CASES.items():
            for tension in TENSIONS:
                for solver in SOLVERS:
                    out[name, tension, solver] = simulate(
                        {**params, "tension": tension}, solver=solver, t_end=T_END
                    )
    return out


@pytest.mark.parametrize("tension", TENSIONS)
@pytest.mark.parametrize("name", list(CASES))
def test_every_case_is_done_closes_its_energy_and_stops_no_zeno(runs, name, tension):
    for solver in SOLVERS:
        sim = runs[name, tension, solver]
        assert sim.status == "done", (solver, sim.message)
        assert sim.trajectory.t_end == T_END
        assert sim.solver_used == solver  # superposition never fell back
        assert sim.summary.energy_residual < RESIDUAL, solver


@pytest.mark.parametrize("tension", TENSIONS)
@pytest.mark.parametrize("name", list(CASES))
def test_both_solvers_give_the_same_run(runs, name, tension):
    a, b = (runs[name, tension, s] for s in SOLVERS)
    assert [(k, int(m)) for _, k, m in a.events] == [(k, int(m)) for _, k, m in b.events]
    np.testing.assert_allclose(
        [t for t, _, _ in a.events], [t for t, _, _ in b.events], rtol=0, atol=TIME_TOL
    )
    scale = 1 + np.abs(b.y).max(axis=1, keepdims=True)
    assert np.all(np.abs(a.y - b.y) <= STATE_TOL * scale)
    assert a.summary.n_zeno == b.summary.n_zeno
    assert a.summary.regime == b.summary.regime


@pytest.mark.parametrize("tension", TENSIONS)
def test_vb0_from_rest_sticks_at_the_one_ulp_tie(runs, tension):
    sim = runs["Vb=0", tension, "superposition"]
    p = sim.params
    y0 = sim.y[:, 0]
    # the tie: at the equilibrium of Eq. (9) the spring holds mu_s g, the friction limit,
    # up to the rounding of the Hertz power (Fn = 9.809999999999995: 5 ulps of mu_s Fn
    # here; 16 allows another libm), well inside the switching tie of TIE_ULPS ulps of
    # the surface's scale, where the rate decides
    Fn = float(dynamics.normal_force(y0[2], y0[3], tension=tension, **p))
    a_free = float(dynamics.free_acceleration(0.0, y0[0], y0[1], **p))
    assert abs(abs(a_free) - p["mu_s"] * Fn) <= 16 * np.spacing(p["mu_s"] * Fn)
    h, tol = Switching(sim.model).ties(0.0, y0)
    assert abs(h[2]) <= tol[2] and tol[2] <= 4 * TIE_ULPS * np.spacing(p["mu_s"] * Fn)
    for solver in SOLVERS:
        s = runs["Vb=0", tension, solver]
        first = s.trajectory.segments[0]
        assert first.mode == Mode.STICK and first.t1 > 0, solver
        assert s.events[0][1] == "unstick"
        assert s.summary.n_zeno == 0


@pytest.mark.parametrize("tension", TENSIONS)
@pytest.mark.parametrize("vb", ["0.5", "1", "1.5"])
def test_omega1_12_in_the_stick_chatter_region_never_stops_on_zeno(runs, vb, tension):
    for solver in SOLVERS:
        sim = runs[f"omega1=12,Vb={vb}", tension, solver]
        assert sim.status != "zeno" and sim.summary.n_zeno == 0, sim.message


def test_omega10_at_vb5_is_stick_slip(runs):
    for solver in SOLVERS:
        sim = runs["Omega=10,Vb=5", "allowed", solver]
        assert sim.summary.regime == "stick_slip"
        assert sim.summary.n_sticks > 0


def _reference_run(p, y0, t_end, tol=1e-11):
    """Eq. (4) by scipy's solve_ivp with events, on the fields typed by hand in
    tests/hand_eq4.py (Coulomb friction, Hertz-Damp contact, the contact kept): slip
    until ``Vr = 0``, there stick where ``|a_free| <= mu_s F`` (both stick limits >= 0)
    or slip on in the direction of ``a_free``; stick until a stick limit falls through
    zero. Returns the switches ``(t, mode before, mode after)``."""
    import hand_eq4 as H
    from scipy.integrate import solve_ivp

    Vb, contact = p["Vb"], "hertz_damp"
    t, y, switches = 0.0, np.array(y0, dtype=float), []
    mode = int(np.sign(y[1] - Vb))
    assert mode != 0  # the start slips (at rest, on a moving belt)

    def limit(k):
        def event(t, x):
            return H.surfaces(t, x, p, contact)[k]

        event.terminal, event.direction = True, -1
        return event

    def penetration(t, x):
        return x[2]

    penetration.terminal = True
    while True:

        def vr(t, x):
            return x[1] - Vb

        vr.terminal, vr.direction = True, -mode
        events = (vr, penetration) if mode else (limit(1), limit(2), penetration)
        sol = solve_ivp(
            lambda t, x: H.field(mode, t, x, p, contact), (t, t_end), y,
            method="DOP853", rtol=tol, atol=tol, events=events,
        )  # fmt: skip
        if sol.status == 0:
            return switches
        k = next(i for i, te in enumerate(sol.t_events) if len(te))
        assert events[k] is not penetration, "the reference keeps the contact"
        t, y = float(sol.t_events[k][0]), np.array(sol.y_events[k][0])
        if mode:
            y[1] = Vb
            h = H.surfaces(t, y, p, contact)
            new = 0 if min(h[1], h[2]) >= 0 else (1 if h[1] < 0 else -1)
        else:
            new = 1 if k == 0 else -1
        switches.append((t, mode, new))
        mode = new


def test_the_chattering_case_at_loose_tolerances_is_the_motion_of_a_reference():
    """Issue 17, bounded work, and issue 36 item 11: omega1 = 12, Vb = 0.5 at rtol = atol
    = 1e-3, 300 s, both solvers.

    At t = 252.97 s the superposition once entered stick, left it at once and
    chattered again at the same time, for ever (10 GB within minutes); then it stopped
    there as ``zeno`` (the guard is tested on its own below). Neither was the motion:
    its normal steps grew without bound and amplified the rounding of a mass at rest in
    the normal direction. The mass leaves stick there and slips forward until Vr = 0 at
    253.311 s, as an event-driven solve_ivp of the equations typed by hand says
    (`_reference_run`). Run in a process of its own with a time limit, so that a
    regression fails instead of hanging.

    Error model: rtol = 1e-3 allows each step an error of 1e-3 of the state; the stick
    phases reset X1' to Vb, so errors do not grow over the run, and a switch time moves
    by the state error over the rate of its switching function (>= 0.2 m/s^2 here):
    1e-2 s bounds both solvers (measured: events 6e-4 s; the superposition 3e-8 s, its
    tangential motion in closed form and its normal steps bounded by 1 / omega1).
    """
    import json
    import subprocess
    import sys
    from pathlib import Path

    code = (
        "import json, warnings\n"
        "warnings.simplefilter('ignore')\n"
        "from beltmdsm import Model\n"
        "from beltmdsm.simulation import simulate\n"
        "out = {}\n"
        "for solver in ('superposition', 'events'):\n"
        "    s = simulate(Model(Vb=0.5, omega1=12.0), t_end=300.0, rtol=1e-3, atol=1e-3,\n"
        "                 solver=solver)\n"
        "    out[solver] = dict(status=s.status, message=s.message, n_zeno=s.summary.n_zeno,\n"
        "        y0=s.trajectory.state([0.0]).ravel().tolist(),\n"
        "        events=[(float(t), int(new)) for t, kind, new in s.events])\n"
        "print(json.dumps(out))\n"
    )
    root = Path(__file__).resolve().parents[3]
    r = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=root, timeout=120
    )
    assert r.returncode == 0, r.stderr
    runs = json.loads(r.stdout)
    from beltmdsm.model import Model

    p = dict(Model(Vb=0.5, omega1=12.0).params)
    reference = _reference_run(p, runs["events"]["y0"], 300.0)
    assert len(reference) == 573 and sum(new == 0 for *_, new in reference) == 191
    # where the superposition stopped: the stick ends, the mass slips forward
    there = np.array([s for s in reference if 252.9 < s[0] < 253.4])
    np.testing.assert_allclose(there, [(252.9699954, 0, 1), (253.3113850, 1, -1)], atol=1e-6)
    for solver, run in runs.items():
        assert run["status"] == "done" and run["n_zeno"] == 0, (solver, run["message"])
        assert [new for _, new in run["events"]] == [new for *_, new in reference], solver
        gap = max(abs(t - ref[0]) for (t, _), ref in zip(run["events"], reference))
        assert gap < 1e-2, (solver, gap)


def test_a_stick_that_ends_where_it_was_entered_and_chatters_again_stops():
    """The bounded-work guard of issue 17 (`Zeno.after`): chattering on Vr = 0 inside
    the friction cone enters stick once; chattering again at that time stops the run
    with a message instead of entering and leaving stick for ever."""
    from beltmdsm.excitation import initial_state
    from beltmdsm.integrate.zeno import ZENO_SWITCHES, Zeno
    from beltmdsm.model import Model

    model = Model(Vb=0.0, alpha=0.0)
    y = initial_state(model)
    zeno = Zeno(Switching(model))

    def chatter(t0):
        return [
            zeno.after(t0 + k * 1e-12, "vr_zero", "relative_velocity", y, Mode.SLIP_BACK)
            for k in range(ZENO_SWITCHES)
        ][-1]

    assert chatter(1.0) == Mode.STICK and zeno.entered == 1
    said = chatter(1.0 + ZENO_SWITCHES * 1e-12)
    assert isinstance(said, str) and "again right after the stick entered there ended" in said
    # later, a fresh accumulation is a new stick, not a stop
    assert chatter(2.0) == Mode.STICK and zeno.entered == 2
