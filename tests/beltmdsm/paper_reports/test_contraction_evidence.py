"""Two tangential motions under one normal motion (derive/contraction.py).

Symbolic: the derived energy of the difference and its rate against formulas typed
here from Eq. (4), and every sign case of the set-valued Sgn. Numerical: two runs of
the simulation (beltmdsm/) at the base set with one normal motion and different
tangential initial states.

Error model of the numerical checks. The runs integrate with rtol = atol = TOL, so a
sampled state component ``y`` is within about ``TOL (1 + |y|)`` of the exact one;
``K = 10`` allows for the accumulation over a run (measured: the energy balance of
the difference closes to 0.2-0.4 TOL of its scale at TOL = 1e-8 and 1e-10). With
component errors ``dx, dv`` of each run the sampled ``E_d = e'^2/2 + k1 e^2/2`` is
within ``|e'| (dv_a + dv_b) + k1 |e| (dx_a + dx_b) + (dv_a + dv_b)^2/2 + k1 (dx_a +
dx_b)^2/2`` of the exact value, and an integrated work within ``K TOL`` times the
integral of the absolute powers.
"""

import numpy as np
import pytest
import sympy as sp

from beltmdsm.derive import contraction as C
from beltmdsm.derive import contraction_energy as CE
from beltmdsm.derive import contraction_sign as CS
from beltmdsm.derive.model import CONTACT_LAWS, FRICTION_LAWS, TENSION_LAWS, X2, Y2, P, normal_force
from beltmdsm.paper_reports import contraction_evidence as S

TOL = 1e-10
K = 10.0
T_END = 200.0
SHIFT = (5.0, -3.0)
b1, w1, b2, w2, mu = (P[k] for k in ("beta1", "omega1", "beta2", "omega2", "mu_s"))


# Symbolic ------------------------------------------------------------------------------


def test_difference_energy_is_the_tangential_oscillator_energy():
    assert sp.expand(CE.difference_energy() - (CE.ep**2 / 2 + w1**2 * CE.e**2 / 2)) == 0


@pytest.mark.parametrize(
    "contact, F",
    [
        ("hertz_damp", (w2**2 + 2 * b2 * w2 * Y2) * X2 ** sp.Rational(3, 2)),
        ("kelvin_voigt", w2**2 * X2 + 2 * b2 * w2 * Y2),
    ],
)
def test_difference_power_against_the_hand_typed_formula(contact, F):
    de = CE.Ya - CE.Yb
    hand = -2 * b1 * w1 * de**2 - mu * (CE.sa - CE.sb) * F * de
    split = CE.power_split(contact, "allowed")
    assert sp.expand(CE.difference_power(contact, "allowed") - hand) == 0
    assert split.exact and sp.expand(split.c1 - 2 * b1 * w1) == 0
    assert sp.expand(split.friction - (hand + 2 * b1 * w1 * de**2)) == 0


def test_clipped_difference_power_has_the_clipped_force():
    """max(F, 0) of Eq. (1): equal to the hand-typed form where F > 0 and where F < 0."""
    F = (w2**2 + 2 * b2 * w2 * Y2) * X2 ** sp.Rational(3, 2)
    de = CE.Ya - CE.Yb
    split = CE.power_split("hertz_damp", "clipped")
    assert split.exact
    base = {
        b1: sp.Rational(1, 10),
        w1: 1,
        b2: sp.Rational(3, 20),
        w2: sp.Rational(1, 2),
        mu: sp.Rational(2, 5),
        X2: 2,
        CE.Ya: 3,
        CE.Yb: -1,
        CE.sa: 1,
        CE.sb: -1,
    }
    for y2, clipped in ((sp.Integer(1), F), (sp.Integer(-5), 0)):  # F > 0, F < 0
        point = {**base, Y2: y2}
        assert (F.subs(point) > 0) == (clipped != 0)
        hand = (-2 * b1 * w1 * de**2 - mu * (CE.sa - CE.sb) * clipped * de).subs(point)
        assert sp.simplify(split.total.subs(point) - hand) == 0


def test_every_sign_case_is_proved_and_covers_the_graph_of_sgn():
    cases = CS.friction_power_sign_cases()
    assert len(cases) == 25  # (1 + 3 + 1)^2: stick at -1, inside, +1
    assert {(c.state_a, c.state_b) for c in cases} == {(a, b) for a in CS.STATES for b in CS.STATES}
    assert all(c.proved and c.sign in ("= 0", "> 0", ">= 0") for c in cases)
    by = {(c.state_a, c.state_b, str(c.s_a), str(c.s_b)): c for c in cases}
    opposite = by[("slip_forward", "slip_back", "1", "-1")]
    ua, ub = sp.symbols("u_a u_b", positive=True)
    assert sp.expand(opposite.product - 2 * (ua + ub)) == 0 and opposite.sign == "> 0"
    assert by[("slip_back", "slip_back", "-1", "-1")].sign == "= 0"
    assert all(c.sign == "= 0" for c in cases if c.state_a == c.state_b == "stick")


def test_the_sign_decision_fails_for_an_anti_monotone_law():
    """Negative control: with s = -sgn(Vr) the product is negative and is not proved."""
    ua, ub = sp.symbols("u_a u_b", positive=True)
    sign, proved = CS._decide((-1 - 1) * (ua + ub))
    assert not proved and sign == "undecided"


def test_couplings_stick_and_clipped_force():
    coupling = CE.one_way_coupling()
    assert all(coupling.values()) and len(coupling) == len(CONTACT_LAWS) * len(TENSION_LAWS)
    for contact in CONTACT_LAWS:
        for friction in FRICTION_LAWS:
            assert CE.stick_is_set_valued(contact, friction), (contact, friction)
        assert CS.clipped_force_nonnegative(contact)
    # the law as printed is not: Eq. (1) at X2 = 1, X2' = -10 (base set) pulls
    pull = normal_force().subs({X2: 1, Y2: -10, b2: sp.Rational(3, 20), w2: sp.Rational(1, 2)})
    assert pull < 0


def test_signs_conclusion_and_converse():
    signs = CS.sign_of_friction_power()
    assert all(signs.values()) and len(signs) == 6


def test_the_conditions_are_needed():
    breaks = C.breaking_conditions()
    assert set(breaks) == {"falling friction", "beta1 = 0", "two-way coupling"}
    assert all(ok for ok, _ in breaks.values())


def test_the_claim_says_which_steps_sympy_proved():
    claim = C.claim()
    assert claim.proved_by_sympy
    how = {s.name: s.how for s in claim.steps}
    assert how["convergence"] == "words"
    assert sum(h == "SymPy" for h in how.values()) == 8
    assert any("beta1 > 0" in c for c in claim.conditions)
    assert any("one-way" in c for c in claim.conditions)
    assert "F < 0" in claim.converse


# Numerical -----------------------------------------------------------------------------


def _sample_error(run):
    """Bound on |E_d(sampled) - E_d(exact)| at each sample (module docstring)."""
    k1 = run.a.params["omega1"] ** 2
    dx = K * TOL * (2 + np.abs(run.a.y[0]) + np.abs(run.b.y[0]))
    dv = K * TOL * (2 + np.abs(run.a.y[1]) + np.abs(run.b.y[1]))
    e, ep = run.a.y[0] - run.b.y[0], run.a.y[1] - run.b.y[1]
    return np.abs(ep) * dv + k1 * np.abs(e) * dx + dv**2 / 2 + k1 * dx**2 / 2


def _sampled_power(run):
    """dE_d/dt at the samples: -c1 e'^2 + (f_a - f_b) e' (the runtime's friction forces)."""
    p = run.a.params
    ep = run.a.y[1] - run.b.y[1]
    c1 = 2 * p["beta1"] * p["omega1"]
    fric = (run.a.friction - run.b.friction) * ep
    bound = K * TOL * (np.abs(run.a.friction) + np.abs(run.b.friction) + 1) * (np.abs(ep) + 1)
    return -c1 * ep**2 + fric, fric, bound


@pytest.fixture(scope="module")
def clipped():
    return S.difference_runs(SHIFT, tension="clipped", t_end=T_END, Vb=4.0, rtol=TOL, atol=TOL)


@pytest.fixture(scope="module")
def allowed():
    return S.difference_runs(SHIFT, tension="allowed", t_end=T_END, Vb=4.0, rtol=TOL, atol=TOL)


def test_the_two_runs_share_the_normal_motion(clipped, allowed):
    for run in (clipped, allowed):
        assert np.array_equal(run.a.y[2:], run.b.y[2:])
        assert not np.allclose(run.a.y[:2, 0], run.b.y[:2, 0])


def test_clipped_difference_energy_never_increases_and_decays(clipped):
    E = clipped.energy
    err = _sample_error(clipped)
    assert np.all(np.diff(E) <= err[:-1] + err[1:])
    assert E[0] == pytest.approx(0.5 * SHIFT[1] ** 2 + 0.5 * SHIFT[0] ** 2)  # omega1 = 1
    assert E[-1] <= 1e-12 * E[0]
    # after the transient both runs slide backward without reversal: no friction term,
    # and E_d decays at the dashpot's mean rate c1 = 2 beta1 omega1 (ripple ~ beta1)
    i, j = np.searchsorted(clipped.t, [50.0, 150.0])
    rate = np.log(E[i] / E[j]) / (clipped.t[j] - clipped.t[i])
    p = clipped.a.params
    assert rate == pytest.approx(2 * p["beta1"] * p["omega1"], rel=0.01)


def test_clipped_friction_never_adds_energy(clipped):
    assert clipped.a.normal_force.min() >= 0
    power, fric, bound = _sampled_power(clipped)
    assert np.all(fric <= bound)
    w = S.difference_works(clipped)
    assert w["work_friction_pull"] == 0.0
    assert w["work_friction_push"] <= K * TOL * w["scale"]
    assert w["work_friction_push"] < -0.1  # the transient's reversals: not vacuous
    assert abs(w["imbalance"]) <= K * TOL * w["scale"]
    assert w["energy_change"] == pytest.approx(-clipped.energy[0], rel=1e-9)


def test_allowed_difference_energy_gains_only_while_the_contact_pulls(allowed):
    E = allowed.energy
    err = _sample_error(allowed)
    rises = np.diff(E) > err[:-1] + err[1:]
    assert rises.sum() > 100 and np.max(np.diff(E)) > 0.1
    F = allowed.a.normal_force
    assert np.all((F[:-1] < 0) | (F[1:] < 0) | ~rises)
    power, fric, bound = _sampled_power(allowed)
    gain = power > bound
    assert gain.sum() > 100 and np.all(F[gain] < 0)
    assert np.all(fric[F >= 0] <= bound[F >= 0])


def test_allowed_energy_balance_of_the_difference(allowed):
    w = S.difference_works(allowed)
    assert abs(w["imbalance"]) <= K * TOL * w["scale"]
    assert w["work_friction_push"] <= K * TOL * w["scale"]
    assert w["work_friction_pull"] > 0.4 * w["scale"]
    assert w["energy_change"] > 0  # the runs do not converge (E_d: 17 -> 24)


def test_reversals_by_force_sign(allowed, clipped):
    """At Vb = 4 (Eq. 1 as printed) every reversal to forward sliding sees a pulling contact."""
    rev = S.reversals_by_force_sign(allowed.a)
    assert rev["slip_forward"][0] > 50 and rev["slip_forward"][1] == 0
    assert rev["slip_back"][0] == 0 and rev["slip_back"][1] > 50
    quiet = S.reversals_by_force_sign(clipped.a, t0=50.0)
    assert quiet == {"slip_forward": (0, 0), "slip_back": (0, 0)}


# Every figure case (slow) ------------------------------------------------------------------


def _figure_cases():
    from beltmdsm.paper_reports.validation import CASES

    cases = [(f"{c.figure} {c.name}", dict(c.overrides), "hertz_damp") for c in CASES]
    return cases + [
        ("Fig. 14a Omega=4.5", {"Omega": 4.5}, "hertz_damp"),
        ("Fig. 14b Omega_t=6, Omega_n=4", {"Omega_t": 6.0, "Omega_n": 4.0}, "hertz_damp"),
        ("Fig. 15 phase_t=pi/2", {"phase_t": np.pi / 2}, "hertz_damp"),
        ("Fig. 16b linear contact", {"omega2": 0.5, "beta2": 3.0}, "kelvin_voigt"),
    ]


def _forced_line_in_band(p, band):
    """Whether a combination m Omega_t + n Omega_n (|m|, |n| <= 6) lies in the omega1 band.

    There the periodic (forced) response itself has a line that the peak reader counts.
    """
    lines = {abs(m * p["Omega_t"] + n * p["Omega_n"]) for m in range(-6, 7) for n in range(-6, 7)}
    return any(band[0] <= w <= band[1] for w in lines)


@pytest.mark.slow
@pytest.mark.parametrize(
    "name, overrides, contact", _figure_cases(), ids=[c[0] for c in _figure_cases()]
)
def test_clipped_motions_converge_in_every_figure_case(name, overrides, contact):
    """Fig. 2b and Figs. 14-21 with tension clipped, Vb from 1 to 16 m/s (400 s runs)."""
    from beltmdsm.run.summary import PEAK_PRESENT_RATIO, omega1_band

    for Vb in np.arange(1.0, 16.1, 1.5):
        run = S.difference_runs(
            SHIFT,
            tension="clipped",
            contact=contact,
            t_end=400.0,
            Vb=float(Vb),
            rtol=TOL,
            atol=TOL,
            **overrides,
        )
        E, err = run.energy, _sample_error(run)
        assert np.all(np.diff(E) <= err[:-1] + err[1:]), (name, Vb)
        assert E[-1] <= 1e-6 * E[0], (name, Vb)
        s, p = run.a.summary, run.a.params
        if not _forced_line_in_band(p, omega1_band(p)):
            assert s.peak_omega1 < PEAK_PRESENT_RATIO * s.peak_Omega, (name, Vb)


def test_monotonicity_of_each_friction_law():
    """Coulomb's law is proved non-decreasing; Stribeck's falls at every |Vr| > 0 where
    mu_k < mu_s, and the claim says so (not proved for it)."""
    coulomb, stribeck = CS.monotonicity("coulomb"), CS.monotonicity("stribeck")
    assert coulomb.holds and coulomb.slope == 0
    assert not stribeck.holds
    assert stribeck.falls == "every |Vr| > 0 (0 < |Vr| < oo) where mu_k < mu_s"
    mu_s, mu_k, v_s = P["mu_s"], P["mu_k"], P["v_s"]
    speed = sp.Symbol("speed", nonnegative=True)
    assert sp.simplify(stribeck.slope + (mu_s - mu_k) / v_s * sp.exp(-speed / v_s)) == 0
    assert C.claim("coulomb").proved_by_sympy
    failed = [s for s in C.claim("stribeck").steps if not s.proved]
    assert [s.name for s in failed] == ["friction law non-decreasing"]
    assert "mu_k < mu_s" in failed[0].detail
    # static above kinetic: constant in slip, but the static bound falls to mu_k at Vr = 0
    jump = CS.monotonicity("static_kinetic")
    assert not jump.holds and jump.slope == 0
    assert jump.falls == "Vr = 0, where mu_k < mu_s"
    failed = [s for s in C.claim("static_kinetic").steps if not s.proved]
    assert [s.name for s in failed] == ["friction law non-decreasing"]
    assert "falling jump at Vr = 0" in failed[0].detail


def test_the_power_split_holds_for_every_law():
    """dE_d/dt = -c1 e'^2 - (f_a - f_b) F e' with the law's signed coefficient per run."""
    for friction in FRICTION_LAWS:
        for contact in CONTACT_LAWS:
            assert CE.power_split(contact, "clipped", friction).exact, (friction, contact)
