"""beltmdsm.generated.hybrid: modes, switching surfaces, guards and saltation matrices of Eq. (4).

References, all independent of the generated code: the fields, surfaces and the
saltation formula typed by hand (tests/hand_eq4.py) and evaluated with mpmath at 30
digits; time derivatives along trajectories integrated by scipy; and, for the saltation
matrices, central differences of the simulated flow across the switch.

Error model of the comparisons with the hand formulas: each generated entry is a sum of
at most ~8 terms, each a product of at most ~6 rounded factors and at most one
elementary function (sin, cos, pow, sqrt: < 1 ulp each), so it is within ~16 ulps of
the sum of the absolute values of its terms (its *scale*), which hand_eq4 computes
alongside each value. A quotient adds the relative error of its denominator, scaled by
the quotient.
"""

import itertools

import hand_eq4 as H
import mpmath
import numpy as np
import pytest
from conftest import random_params
from scipy.integrate import solve_ivp

from beltmdsm.generated import dynamics, hybrid
from beltmdsm.generated.mp import hybrid as mp_hybrid
from beltmdsm.generated.parameters import BASE

EPS = H.EPS
ULPS = 16
SURFACES = ("relative_velocity", "stick_forward", "stick_back", "penetration", "contact_force")
MODE_NAMES = tuple(H.MODES)


def hybrid_params(rng):
    """Random parameters with a per-direction excitation (each direction its own)."""
    p = random_params(rng)
    p.update(
        alpha_n=p["alpha"] * rng.uniform(0.3, 2),
        Omega_n=p["Omega"] * rng.uniform(0.5, 2),
        phase_t=rng.uniform(-3, 3),
        phase_n=rng.uniform(-3, 3),
    )
    return p


def random_state(rng, contact=True):
    X2 = rng.uniform(0.05, 3.0) if contact else -rng.uniform(0.05, 2.0)
    return rng.uniform(-5, 5), np.array([rng.normal() * 2, rng.normal() * 3, X2, rng.normal() * 2])


def mp_args(t, x, p):
    mpf = mpmath.mpf
    return mpf(t), [mpf(v) for v in x], {k: mpf(v) for k, v in p.items()}


def flat(values):
    """Entries of a number, sequence or mpmath matrix, as a flat list."""
    if isinstance(values, mpmath.matrix):
        values = values.tolist()
    if isinstance(values, (list, tuple)):
        return [v for item in values for v in flat(item)]
    return [values]


def assert_within(got, ref, bound, what=""):
    got = np.asarray(got, dtype=float).ravel()
    ref = np.array([float(r) for r in flat(ref)])
    bound = np.asarray(bound, dtype=float).ravel()
    err = np.abs(got - ref)
    assert np.all(err <= bound), f"{what}: error {err} > bound {bound} (got {got}, ref {ref})"


# Constants and guards ------------------------------------------------------------------


def test_mode_codes_fields_and_surface_order():
    assert hybrid.MODE_CODES == {
        "slip_back": -1,
        "stick": 0,
        "slip_forward": 1,
        "flight": 2,
        "separated": 3,
    }
    assert hybrid.FIELDS == {
        "slip_back": "slip_back",
        "stick": "stick",
        "slip_forward": "slip_forward",
        "flight": "free",
        "separated": "free",
    }
    assert hybrid.SURFACES == SURFACES
    for name in (
        "MODE_CODES",
        "FIELDS",
        "SURFACES",
        "DECIDE_SLIP",
        "DECIDE_CONTACT",
        "GUARDS",
        "TRANSITIONS",
    ):
        assert getattr(mp_hybrid, name) == getattr(hybrid, name), name


def test_guards_of_the_allowed_law_have_no_separation():
    allowed = hybrid.GUARDS["allowed"]
    assert set(allowed) == {"slip_back", "slip_forward", "stick", "flight"}
    surfaces = {s for guards in allowed.values() for s, _, _ in guards}
    assert "contact_force" not in surfaces
    targets = {target for guards in allowed.values() for _, _, target in guards}
    assert "separated" not in targets
    assert set(hybrid.GUARDS["clipped"]) == set(H.MODES)


def test_every_guard_names_a_surface_a_direction_and_a_target():
    targets = set(H.MODES) | {hybrid.DECIDE_SLIP, hybrid.DECIDE_CONTACT}
    for tension, table in hybrid.GUARDS.items():
        for mode, guards in table.items():
            assert mode in H.MODES
            for surface, direction, target in guards:
                assert surface in hybrid.SURFACES, (tension, mode, surface)
                assert direction in (-1, 1), (tension, mode, surface)
                assert target in targets and target != mode, (tension, mode, target)


def expand(tension, before, target):
    """The modes a guard target can choose (derive/hybrid.py's docstring)."""
    if target == hybrid.DECIDE_SLIP:
        return ["stick", "slip_forward" if before == "slip_back" else "slip_back"]
    if target == hybrid.DECIDE_CONTACT:
        after = ["slip_back", "slip_forward", "stick"]
        if tension == "clipped" and before != "separated":
            after.append("separated")
        return after
    return [target]


def test_transitions_are_exactly_the_switches_the_guards_reach_and_all_have_saltation():
    reached = {
        (before, after, surface)
        for tension, table in hybrid.GUARDS.items()
        for before, guards in table.items()
        for surface, _, target in guards
        for after in expand(tension, before, target)
    }
    assert reached == set(hybrid.TRANSITIONS)
    t, x = 0.3, (0.1, 2.0, 1.3, 0.4)
    for (before, after, surface), contact in itertools.product(reached, H.CONTACTS):
        S = hybrid.saltation(
            t, *x, before=before, after=after, surface=surface, contact=contact, **BASE
        )
        assert S.shape == (4, 4) and np.all(np.isfinite(S)), (before, after, surface)
        hybrid.bind_saltation(
            before=before, after=after, surface=surface, contact=contact, backend="python", **BASE
        )


def test_a_switch_no_run_takes_is_rejected_by_name():
    with pytest.raises(
        ValueError,
        match="no variant for .*before='flight', after='stick', surface='relative_velocity'",
    ):
        hybrid.saltation(
            0.0,
            0.0,
            0.0,
            1.0,
            0.0,
            before="flight",
            after="stick",
            surface="relative_velocity",
            **BASE,
        )
    with pytest.raises(ValueError, match="no variant"):
        hybrid.bind_saltation(
            before="slip_back", after="slip_forward", surface="penetration", **BASE
        )
    with pytest.raises(ValueError, match="no variant"):
        mp_hybrid.saltation(
            0.0, 0.0, 0.0, 1.0, 0.0, before="stick", after="stick", surface="stick_back", **BASE
        )
    with pytest.raises(ValueError, match="before"):
        hybrid.saltation(0.0, 0.0, 0.0, 1.0, 0.0, before="hover", **BASE)
    with pytest.raises(ValueError, match="contact"):
        hybrid.surfaces(0.0, 0.0, 0.0, 1.0, 0.0, contact="hertz", **BASE)


def state_in_mode(mode, rng, p, contact):
    """A state (t, x) satisfying the mode's invariant: slip_back Y1 < Vb, slip_forward
    Y1 > Vb (both in contact, F > 0), stick Y1 = Vb with |a_free| < mu F, flight X2 < 0,
    separated X2 > 0 with F < 0."""
    while True:
        t, x = random_state(rng, contact=mode != "flight")
        if mode == "slip_back":
            x[1] = p["Vb"] - abs(x[1]) - 0.1
        elif mode == "slip_forward":
            x[1] = p["Vb"] + abs(x[1]) + 0.1
        elif mode == "stick":
            x[1] = p["Vb"]
            F = H.force(x[2], x[3], p, contact)
            target = rng.uniform(-0.9, 0.9) * p["mu_s"] * F  # a_free inside the cone
            x[0] = (H.a_free(t, 0.0, x[1], p) - target) / p["omega1"] ** 2
        elif mode == "separated":
            x[3] = -abs(x[3]) - p["omega2"] * (1 if contact == "hertz_damp" else x[2]) / (
                2 * p["beta2"]
            )
        F = H.force(x[2], x[3], p, contact)
        if mode == "separated" and F < 0 or mode == "flight" or F > 0:
            return t, x


@pytest.mark.parametrize("tension", H.TENSIONS)
@pytest.mark.parametrize("contact", H.CONTACTS)
def test_guard_directions_leave_the_mode(rng, tension, contact):
    """In a state of the mode each guard's h has the sign opposite to its crossing
    direction: crossing it (h through 0 in that direction) leaves the mode."""
    for mode, guards in hybrid.GUARDS[tension].items():
        for _ in range(10):
            p = hybrid_params(rng)
            t, x = state_in_mode(mode, rng, p, contact)
            h = hybrid.surfaces(t, *x, contact=contact, **p)
            for surface, direction, _ in guards:
                value = h[SURFACES.index(surface)]
                assert np.sign(value) == -direction, (mode, surface, value)


# Vector fields, surfaces, scales, rates -------------------------------------------------


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_vector_field_of_each_mode_is_the_hand_field(rng, contact):
    for _ in range(20):
        p = hybrid_params(rng)
        t, x = random_state(rng, contact=rng.uniform() < 0.7)
        for name, code in H.MODES.items():
            got = hybrid.vector_field(t, *x, code, contact=contact, **p)
            with mpmath.workdps(30):
                ref = H.field(name, *mp_args(t, x, p)[:2], mp_args(t, x, p)[2], contact, m=mpmath)
            scale = H.field_scale(name, t, x, p, contact)
            assert_within(got, ref, ULPS * EPS * np.array(scale), f"{name} {contact}")


def law_params(rng):
    """`hybrid_params` with Stribeck's and Hunt-Crossley's parameters drawn as well."""
    p = hybrid_params(rng)
    p.update(
        mu_k=p["mu_s"] * rng.uniform(0.1, 1.5), v_s=rng.uniform(0.2, 3), n_h=rng.uniform(1, 2.5)
    )
    return p


def scale_params(p):
    """``p`` for the scales: the friction coefficient is at most max(mu_s, mu_k)."""
    return {**p, "mu_s": max(p["mu_s"], p["mu_k"])}


@pytest.mark.parametrize("friction", H.FRICTIONS)
@pytest.mark.parametrize("contact", H.ALL_CONTACTS)
def test_vector_field_of_every_law_is_the_hand_field(rng, contact, friction):
    """Each mode's field for every friction and contact law against hand_eq4 (the law's
    coefficient at the speed sgn Vr, one more rounded exp in Stribeck's: within the scale)."""
    for _ in range(10):
        p = law_params(rng)
        t, x = random_state(rng, contact=rng.uniform() < 0.7)
        for name, code in H.MODES.items():
            got = hybrid.vector_field(t, *x, code, contact=contact, friction=friction, **p)
            with mpmath.workdps(30):
                T, X, P = mp_args(t, x, p)
                ref = H.field(name, T, X, P, contact, m=mpmath, friction=friction)
            scale = H.field_scale(name, t, x, p, contact, friction=friction)
            assert_within(got, ref, ULPS * EPS * np.array(scale), f"{name} {contact} {friction}")


@pytest.mark.parametrize("friction", H.FRICTIONS)
@pytest.mark.parametrize("contact", H.ALL_CONTACTS)
def test_mode_jacobian_is_the_hand_derivative_of_each_field(rng, contact, friction):
    """hybrid.mode_jacobian against the derivative typed by hand (Stribeck: the slip
    modes' damping gains mu'(|Vr|) F), within ULPS of each entry's terms' scale; its
    mpmath twin against mpmath's central differences of the mpmath field (30 digits,
    step 1e-12: truncation ~1e-24, rounding ~1e-18 of the field's size)."""
    for _ in range(8):
        p = law_params(rng)
        t, x = random_state(rng, contact=rng.uniform() < 0.7)
        for name, code in H.MODES.items():
            got = hybrid.mode_jacobian(t, *x, code, contact=contact, friction=friction, **p)
            with mpmath.workdps(30):
                T, X, P = mp_args(t, x, p)
                ref = H.mode_jacobian(name, T, X, P, contact, m=mpmath, friction=friction)
            scale = H.mode_jacobian_scale(name, t, x, scale_params(p), contact, friction)
            assert_within(got, ref, ULPS * EPS * np.array(scale), f"{name} {contact} {friction}")
    x = [x[0], x[1], abs(x[2]) + 0.1, x[3]]  # in contact: the fields are smooth there
    with mpmath.workdps(30):
        T, X, P = mp_args(t, x, p)
        step = mpmath.mpf(10) ** -12
        for code in H.MODES.values():
            J = mp_hybrid.mode_jacobian(T, *X, code, contact=contact, friction=friction, **P)
            for j in range(4):
                shifted = [
                    [v + (h if k == j else 0) for k, v in enumerate(X)] for h in (step, -step)
                ]
                plus, minus = (
                    mp_hybrid.vector_field(T, *Y, code, contact=contact, friction=friction, **P)
                    for Y in shifted
                )
                for i in range(4):
                    fd = (plus[i] - minus[i]) / (2 * step)
                    assert abs(J[i, j] - fd) <= mpmath.mpf(10) ** -16 * (1 + abs(fd)), (code, i, j)


def test_vector_field_broadcasts_over_mode_codes_and_flight_equals_separated(rng):
    p = hybrid_params(rng)
    t, x = random_state(rng)
    codes = np.array([-1, 0, 1, 2, 3])
    rows = hybrid.vector_field(t, *x, codes, **p)
    assert rows.shape == (5, 4)
    for code, row in zip(codes, rows):
        np.testing.assert_array_equal(row, hybrid.vector_field(t, *x, code, **p))
    np.testing.assert_array_equal(rows[3], rows[4])


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_response_field_is_the_hand_field_and_its_twin_agrees(rng, contact):
    """(z', z'', X2', Y2') with z'' = F_m - 2 b1 w1 z' - w1^2 z and the normal equation,
    F_m the extended Eq. (1) in the contact modes and 0 in flight and separation; its
    normal rows are vector_field's. References: hand (30 digits) and the mpmath twin."""
    for _ in range(20):
        p = hybrid_params(rng)
        t, x = random_state(rng, contact=rng.uniform() < 0.7)
        y = np.array([rng.normal() * 2, rng.normal() * 3, x[2], x[3]])
        for name, code in H.MODES.items():
            got = hybrid.response_field(t, *y, code, contact=contact, **p)
            with mpmath.workdps(30):
                tm, ym, pm = mp_args(t, y, p)
                ref = H.response_field(name, tm, ym, pm, contact, m=mpmath)
            scale = ULPS * EPS * np.array(H.response_field_scale(name, t, y, p, contact))
            assert_within(got, ref, scale, f"{name} {contact}")
            with mpmath.workdps(50):
                twin = mp_hybrid.response_field(t, *y, code, contact=contact, **p)
            assert_within(got, twin, scale, f"twin {name} {contact}")
            field = hybrid.vector_field(t, *x, code, contact=contact, **p)
            assert_within(got[2:], list(field[2:]), scale[2:], "normal rows")


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_surfaces_are_the_hand_switching_functions(rng, contact):
    for _ in range(40):
        p = hybrid_params(rng)
        t, x = random_state(rng, contact=rng.uniform() < 0.7)
        got = hybrid.surfaces(t, *x, contact=contact, **p)
        assert isinstance(got, tuple) and len(got) == 5
        with mpmath.workdps(30):
            ref = H.surfaces(*mp_args(t, x, p)[:2], mp_args(t, x, p)[2], contact, m=mpmath)
        scale = H.surface_scales(t, x, p, contact)
        assert_within(got, ref, ULPS * EPS * np.array(scale), contact)


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_contact_force_surface_has_the_sign_of_the_force(rng, contact):
    """h = F / (positive factor): Hertz-Damp F = h omega2 X2^(3/2), Kelvin-Voigt
    F = h omega2; so h < 0 exactly where Eq. (1) pulls (states on both sides)."""
    pulls = 0
    for _ in range(60):
        p = hybrid_params(rng)
        t, x = random_state(rng)
        x[3] = rng.uniform(-3, 1) * p["omega2"] / (2 * p["beta2"])
        h = hybrid.surfaces(t, *x, contact=contact, **p)[4]
        F = H.force(x[2], x[3], p, contact)
        factor = p["omega2"] * (x[2] ** 1.5 if contact == "hertz_damp" else 1.0)
        # F and h factor: each a few ulps of the force's terms' scale
        assert abs(h * factor - F) <= ULPS * EPS * H.force_scale(x[2], x[3], p, contact)
        if abs(F) > 1e-8 * H.force_scale(x[2], x[3], p, contact):
            assert np.sign(h) == np.sign(F)
        pulls += F < 0
    assert 10 < pulls < 50


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_surface_scales_are_the_sums_of_absolute_terms(rng, contact):
    """scale >= |h|, scale = the hand sum of the absolute values of h's terms plus the
    rounding of the excitation's argument (hand_eq4.excitation_scale), and a computed h
    is within a few ulps of that scale of the exact h."""
    for _ in range(40):
        p = hybrid_params(rng)
        t, x = random_state(rng, contact=rng.uniform() < 0.7)
        scale = np.array(hybrid.surface_scales(t, *x, contact=contact, **p))
        h = np.array(hybrid.surfaces(t, *x, contact=contact, **p))
        # equal when all terms have one sign; the two sums round differently by <= 8 ulps
        assert np.all(scale >= np.abs(h) * (1 - 8 * EPS))
        # both are sums of |terms| of at most 6 terms (the rounding of the excitation's
        # argument included): 8 ulps of each other
        np.testing.assert_allclose(scale, H.surface_scales(t, x, p, contact), rtol=8 * EPS)
        with mpmath.workdps(30):
            exact = H.surfaces(*mp_args(t, x, p)[:2], mp_args(t, x, p)[2], contact, m=mpmath)
        assert_within(
            h,
            exact,
            4 * EPS * np.array(H.surface_scales(t, x, p, contact)),
            "h against its scale with the argument's rounding",
        )
    # one case by hand: Hertz-Damp or Kelvin-Voigt at a state in contact
    p = dict(BASE, phase_t=0.5)
    t, X1, Y1, X2, Y2 = 0.2, -1.5, 2.5, 4.0, -0.5
    b1, w1, b2, w2, mu, a, W = 0.1, 1.0, 0.15, 0.5, 0.4, 2.0, 4.0
    F_terms = (
        w2**2 * 8 + 2 * b2 * w2 * 0.5 * 8
        if contact == "hertz_damp"
        else w2**2 * 4 + 2 * b2 * w2 * 0.5
    )
    stick = (
        a * W**2 * (abs(np.sin(W * t + 0.5)) + (W * t + 0.5) * abs(np.cos(W * t + 0.5)))
        + 2 * b1 * w1 * 2.5
        + w1**2 * 1.5
        + mu * F_terms
    )
    sign_F = w2 + 2 * b2 * 0.5 if contact == "hertz_damp" else w2 * 4 + 2 * b2 * 0.5
    np.testing.assert_allclose(
        hybrid.surface_scales(t, X1, Y1, X2, Y2, contact=contact, **p),
        (2.5 + 4.0, stick, stick, 4.0, sign_F),
        rtol=8 * EPS,
    )


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_surface_scales_bound_the_rounding_of_h_at_late_times(rng, contact):
    """surface_scales' docstring: "a computed h is within a few ulps of this scale of the
    exact one". At t ~ 1000 (a long run) the argument Omega_t t is rounded to
    ~eps Omega_t t before the sine, an error in f_t of ~1e-13 alpha_t Omega_t^2 that the
    sum of the terms' absolute values does not contain."""
    worst = 0.0
    for _ in range(20):
        p = hybrid_params(rng)
        t, x = random_state(rng)
        t += 1000.0
        scale = np.array(hybrid.surface_scales(t, *x, contact=contact, **p))
        h = np.array(hybrid.surfaces(t, *x, contact=contact, **p))
        with mpmath.workdps(30):
            exact = H.surfaces(*mp_args(t, x, p)[:2], mp_args(t, x, p)[2], contact, m=mpmath)
        err = np.abs(h - np.array([float(v) for v in exact]))
        worst = max(worst, float(np.max(err / (EPS * scale))))
    assert worst <= 8, f"h off by {worst:.0f} ulps of its scale"


rate_scale = H.rate_scale


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_surface_rates_are_the_chain_rule_with_hand_derivatives(rng, contact):
    for _ in range(20):
        p = hybrid_params(rng)
        t, x = random_state(rng, contact=rng.uniform() < 0.7)
        for name, code in H.MODES.items():
            got = hybrid.surface_rates(t, *x, code, contact=contact, **p)
            with mpmath.workdps(30):
                tm, xm, pm = mp_args(t, x, p)
                f = H.field(name, tm, xm, pm, contact, m=mpmath)
                ref = [
                    ht + sum(ni * fi for ni, fi in zip(n, f))
                    for ht, n in H.surface_gradients(tm, xm, pm, contact, m=mpmath)
                ]
            # the rate multiplies entries of the field by entries of the gradient,
            # each a few ulps of its scale: 2 x ULPS
            assert_within(
                got, ref, 2 * ULPS * EPS * rate_scale(name, t, x, p, contact), f"{name} {contact}"
            )


@pytest.mark.parametrize("contact", H.CONTACTS)
@pytest.mark.parametrize("mode", MODE_NAMES)
def test_surface_rates_are_time_derivatives_along_the_integrated_field(rng, mode, contact):
    """dh/dt at t0 by the 4th-order central difference of h(t, x(t)) along the mode's
    field (hand-typed) integrated by DOP853 at rtol = atol = 1e-13 from x(t0).

    Error model: truncation C d^4 and noise (rounding of h, integration error ~1e-13
    of h's scale) times 3 / (2 d). With d = 1e-3 / W (W the fastest frequency) and
    d / 2, the truncation of the finer one is |D(d) - D(d/2)| / 15; tolerance
    |D(d) - D(d/2)| (15x that) + 1e-10 of the rate's terms' scale (the noise, ~1e-12
    of it). The tolerance is asserted to stay below 1e-7 of that scale.
    """
    for _ in range(4):
        p = hybrid_params(rng)
        d = 1e-3 / max(1.0, p["Omega"], p["Omega_n"])
        t0, x0 = random_state(rng, contact=mode != "flight")
        x0[2] = abs(x0[2]) + 0.5 if mode != "flight" else -abs(x0[2]) - 0.5  # off the kink

        def derivative(d):
            hs = {}
            for sign in (1, -1):
                sol = solve_ivp(
                    lambda t, x: H.field(mode, t, x, p, contact),
                    (t0, t0 + sign * 2 * d),
                    x0,
                    method="DOP853",
                    rtol=1e-13,
                    atol=1e-13,
                    t_eval=[t0 + sign * d, t0 + sign * 2 * d],
                )
                for k, (tk, xk) in enumerate(zip(sol.t, sol.y.T), start=1):
                    hs[sign * k] = np.array(H.surfaces(tk, xk, p, contact))
            return (8 * (hs[1] - hs[-1]) - (hs[2] - hs[-2])) / (12 * d)

        coarse, fine = derivative(d), derivative(d / 2)
        got = np.array(hybrid.surface_rates(t0, *x0, H.MODES[mode], contact=contact, **p))
        scale = rate_scale(mode, t0, x0, p, contact)
        tol = np.abs(coarse - fine) + 1e-10 * scale
        assert np.all(tol <= 1e-7 * scale)
        assert np.all(np.abs(got - fine) <= tol), (got, fine)


# Saltation matrices -----------------------------------------------------------------------


def saltation_bound(before, after, surface, t, x, p, contact, S_ref, rate):
    """ULPS ulps of each entry's rounding scale (hand_eq4.saltation_scale)."""
    return (
        ULPS * EPS * H.saltation_scale(before, after, surface, t, x, p, contact, S_ref, rate)
        + 1e-300
    )


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_saltation_is_the_hand_formula_for_every_transition(rng, contact):
    for before, after, surface in hybrid.TRANSITIONS:
        for _ in range(3):
            p = hybrid_params(rng)
            t, x = random_state(rng, contact=rng.uniform() < 0.8)
            with mpmath.workdps(30):
                tm, xm, pm = mp_args(t, x, p)
                S_ref, rate = H.saltation(before, after, surface, tm, xm, pm, contact, m=mpmath)
            if abs(rate) < 1e-3 * rate_scale(before, t, x, p, contact)[SURFACES.index(surface)]:
                continue  # next to grazing: S is ill-conditioned
            got = hybrid.saltation(
                t, *x, before=before, after=after, surface=surface, contact=contact, **p
            )
            bound = saltation_bound(before, after, surface, t, x, p, contact, S_ref, rate)
            assert_within(got, S_ref, bound, f"{before}->{after} at {surface}, {contact}")


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_saltation_of_a_reversal_scales_the_velocity_perturbation(rng, contact):
    """slip s -> slip -s at Y1 = Vb: only S[1,1] differs from I, and it is
    a_after / a_before with a_s = a_free - mu s F."""
    for before, after in (("slip_back", "slip_forward"), ("slip_forward", "slip_back")):
        for _ in range(10):
            p = hybrid_params(rng)
            t, x = random_state(rng)
            s_b, s_a = H.MODES[before], H.MODES[after]
            with mpmath.workdps(30):
                tm, xm, pm = mp_args(t, x, p)
                a = H.a_free(tm, xm[0], xm[1], pm, m=mpmath)
                F = H.force(xm[2], xm[3], pm, contact)
                a_b, a_a = a - pm["mu_s"] * s_b * F, a - pm["mu_s"] * s_a * F
            S = hybrid.saltation(
                t, *x, before=before, after=after, surface="relative_velocity", contact=contact, **p
            )
            expected = np.eye(4)
            expected[1, 1] = float(a_a / a_b)
            scale = H.a_free_scale(t, *x[:2], p) + p["mu_s"] * H.force_scale(x[2], x[3], p, contact)
            # numerator and denominator each within ULPS eps of scale
            tol = ULPS * EPS * scale / abs(float(a_b)) * (1 + abs(expected[1, 1]))
            off = np.ones((4, 4), bool)
            off[1, 1] = False
            assert np.all(S[off] == expected[off])
            assert abs(S[1, 1] - expected[1, 1]) <= tol


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_saltation_of_stick_onset_removes_the_velocity_perturbation(rng, contact):
    """slip s -> stick at Y1 = Vb: row 1 is zero (stick holds Y1 = Vb), S[0,1] is
    (Vb - Y1) / a_before (zero on the surface), the rest is I."""
    for before in ("slip_back", "slip_forward"):
        for _ in range(10):
            p = hybrid_params(rng)
            t, x = random_state(rng)
            s = H.MODES[before]
            a_b = H.a_free(t, x[0], x[1], p) - p["mu_s"] * s * H.force(x[2], x[3], p, contact)
            S = hybrid.saltation(
                t,
                *x,
                before=before,
                after="stick",
                surface="relative_velocity",
                contact=contact,
                **p,
            )
            scale = H.a_free_scale(t, *x[:2], p) + p["mu_s"] * H.force_scale(x[2], x[3], p, contact)
            rel = ULPS * EPS * scale / abs(a_b)  # relative error of a_before
            expected = np.eye(4)
            expected[1, 1] = 0.0
            expected[0, 1] = (p["Vb"] - x[1]) / a_b
            assert np.all(np.abs(S - expected) <= rel * (np.abs(expected) + np.eye(4)))
            x_on = x.copy()
            x_on[1] = p["Vb"]
            S_on = hybrid.saltation(
                t,
                *x_on,
                before=before,
                after="stick",
                surface="relative_velocity",
                contact=contact,
                **p,
            )
            assert S_on[0, 1] == 0 and np.all(np.abs(S_on[1]) <= rel)


def test_saltation_of_kelvin_voigt_lift_off(rng):
    """Kelvin-Voigt at X2 = 0 still has its damping force 2 b2 w2 Y2, which the flight
    field drops: S[1,2] = mu s F / Y2 = 2 mu s b2 w2 and S[3,2] = F / Y2 = 2 b2 w2 (the
    signs flip on entering contact)."""
    for _ in range(10):
        p = hybrid_params(rng)
        t, x = random_state(rng)
        x[2] = 0.0
        for s in (-1, 1):
            mode = "slip_back" if s < 0 else "slip_forward"
            for before, after, sign in ((mode, "flight", 1), ("flight", mode, -1)):
                S = hybrid.saltation(
                    t,
                    *x,
                    before=before,
                    after=after,
                    surface="penetration",
                    contact="kelvin_voigt",
                    **p,
                )
                expected = np.eye(4)
                expected[1, 2] = sign * 2 * p["mu_s"] * s * p["beta2"] * p["omega2"]
                expected[3, 2] = sign * 2 * p["beta2"] * p["omega2"]
                # F / Y2 with F = 2 b2 w2 Y2: a few ulps
                np.testing.assert_allclose(S, expected, rtol=8 * EPS, atol=0)


def on_surface(kind, rng, p, contact):
    """A state on a surface where the fields of the switch agree (to rounding)."""
    t, x = random_state(rng)
    if kind in ("stick_forward", "stick_back"):
        x[1] = p["Vb"]
        muF = p["mu_s"] * H.force(x[2], x[3], p, contact)
        a_target = muF if kind == "stick_forward" else -muF
        x[0] = (H.a_free(t, 0.0, x[1], p) - a_target) / p["omega1"] ** 2
    elif kind == "contact_force":
        x[3] = -p["omega2"] * (1 if contact == "hertz_damp" else x[2]) / (2 * p["beta2"])
    elif kind == "penetration":
        x[2] = 0.0
    return t, x


IDENTITY_SWITCHES = [
    ("stick", "slip_forward", "stick_forward", H.CONTACTS),
    ("stick", "slip_back", "stick_back", H.CONTACTS),
    ("slip_back", "separated", "contact_force", H.CONTACTS),
    ("slip_forward", "separated", "contact_force", H.CONTACTS),
    ("separated", "slip_back", "contact_force", H.CONTACTS),
    ("separated", "slip_forward", "contact_force", H.CONTACTS),
    ("slip_back", "flight", "penetration", ("hertz_damp",)),
    ("slip_forward", "flight", "penetration", ("hertz_damp",)),
    ("flight", "slip_back", "penetration", ("hertz_damp",)),
    ("flight", "slip_forward", "penetration", ("hertz_damp",)),
    ("flight", "separated", "penetration", H.CONTACTS),
    ("separated", "flight", "penetration", H.CONTACTS),
]


@pytest.mark.parametrize("before,after,surface,contacts", IDENTITY_SWITCHES)
def test_saltation_is_identity_where_the_fields_agree_on_the_surface(
    rng, before, after, surface, contacts
):
    """On the surface f+ = f-, so S = I: up to the rounding of the constructed state's
    h (a few ulps of its scale), which enters f+ - f- and is divided by the rate."""
    for contact in contacts:
        for _ in range(10):
            p = hybrid_params(rng)
            t, x = on_surface(surface, rng, p, contact)
            S = hybrid.saltation(
                t, *x, before=before, after=after, surface=surface, contact=contact, **p
            )
            S_ref, rate = H.saltation(before, after, surface, t, x, p, contact)
            h_scale = H.surface_scales(t, x, p, contact)[SURFACES.index(surface)]
            n = np.array(
                H.surface_gradients(t, x, p, contact, absolute=True)[SURFACES.index(surface)][1]
            )
            Fs = p["mu_s"] * H.force_scale(x[2], x[3], p, contact)
            jump_scale = (h_scale + Fs) * (1 + p["mu_s"])  # |f+ - f-| on the surface
            tol = ULPS * EPS * jump_scale * n / abs(rate)
            assert np.all(np.abs(S - np.eye(4)) <= tol[None, :]), (contact, S)


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_saltation_mpmath_twin_agrees(rng, mp50, contact):
    for before, after, surface in hybrid.TRANSITIONS:
        p = hybrid_params(rng)
        t, x = random_state(rng)
        kw = dict(before=before, after=after, surface=surface, contact=contact)
        S_ref = mp_hybrid.saltation(t, *x, **kw, **p)
        _, rate = H.saltation(before, after, surface, t, x, p, contact)
        if abs(rate) < 1e-3 * rate_scale(before, t, x, p, contact)[SURFACES.index(surface)]:
            continue
        got = hybrid.saltation(t, *x, **kw, **p)
        bound = saltation_bound(before, after, surface, t, x, p, contact, S_ref.tolist(), rate)
        assert_within(got, S_ref.tolist(), bound, f"{before}->{after} at {surface}")


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_mpmath_twins_of_fields_surfaces_scales_and_rates_agree(rng, mp50, contact):
    for _ in range(10):
        p = hybrid_params(rng)
        t, x = random_state(rng, contact=rng.uniform() < 0.7)
        for code in H.MODES.values():
            name = MODE_NAMES[list(H.MODES.values()).index(code)]
            got = hybrid.vector_field(t, *x, code, contact=contact, **p)
            ref = mp_hybrid.vector_field(t, *x, code, contact=contact, **p)
            assert_within(got, ref, ULPS * EPS * np.array(H.field_scale(name, t, x, p, contact)))
            got = hybrid.surface_rates(t, *x, code, contact=contact, **p)
            ref = mp_hybrid.surface_rates(t, *x, code, contact=contact, **p)
            assert_within(got, ref, 2 * ULPS * EPS * rate_scale(name, t, x, p, contact))
        scale = np.array(H.surface_scales(t, x, p, contact))
        assert_within(
            hybrid.surfaces(t, *x, contact=contact, **p),
            mp_hybrid.surfaces(t, *x, contact=contact, **p),
            ULPS * EPS * scale,
        )
        # the scale holds |cos| of the rounded argument theta = Omega_t t + phase_t times
        # the argument's own scale: its rounding moves it by eps theta_scale^2 times the
        # amplitude (stick surfaces only)
        q = H.full(p)
        theta = abs(q["Omega_t"] * t) + abs(q["phase_t"])
        argument = EPS * q["alpha_t"] * q["Omega_t"] ** 2 * theta**2 * np.array([0, 1, 1, 0, 0])
        assert_within(
            hybrid.surface_scales(t, *x, contact=contact, **p),
            mp_hybrid.surface_scales(t, *x, contact=contact, **p),
            8 * EPS * scale + argument,
        )


# Saltation against the simulated flow ----------------------------------------------------

ODE = dict(method="DOP853", rtol=1e-13, atol=1e-13)


def run_mode(mode, contact, p, t0, t1, x0, stop=None):
    """Integrate the hand-typed field of ``mode``; with ``stop = (surface, direction)``
    until that surface is crossed, returning the crossing (t_s, x_s)."""

    def f(t, x):
        return H.field(mode, t, x, p, contact)

    if stop is None:
        return solve_ivp(f, (t0, t1), x0, **ODE).y[:, -1]
    k, direction = SURFACES.index(stop[0]), stop[1]

    def event(t, x):
        return H.surfaces(t, x, p, contact)[k]

    event.terminal, event.direction = True, direction
    sol = solve_ivp(f, (t0, t1), x0, events=event, **ODE)
    assert sol.status == 1, "the run does not reach the surface"
    return sol.t_events[0][0], sol.y_events[0][0]


def mode_jacobian(mode, t, x, p, contact):
    """Jacobian of the mode's field: the generated jacobian_branch (slip: sgn = s in
    contact; flight and separated: the contact-free branch) and normal_jacobian (stick)."""
    code = H.MODES[mode]
    if code in (-1, 1):
        # the run may end a rounding error (~1e-12) past X2 = 0: the contact branch
        x = (x[0], x[1], max(x[2], np.finfo(float).tiny), x[3])
        return dynamics.jacobian_branch(t, *x, code, contact=contact, **p)
    if code == 0:
        J = np.zeros((4, 4))
        J[2:, 2:] = dynamics.normal_jacobian(t, x[2], x[3], contact=contact, **p)
        return J
    return dynamics.jacobian_branch(t, x[0], x[1], -1.0, x[3], 0, contact=contact, **p)


def variational(mode, contact, p, t0, t1, x0):
    """Phi(t1, t0) of the mode's field, from the variational equation."""

    def f(t, z):
        x, Phi = z[:4], z[4:].reshape(4, 4)
        return np.concatenate(
            [H.field(mode, t, x, p, contact), (mode_jacobian(mode, t, x, p, contact) @ Phi).ravel()]
        )

    z = solve_ivp(f, (t0, t1), np.concatenate([x0, np.eye(4).ravel()]), **ODE).y[:, -1]
    return z[4:].reshape(4, 4)


def switch_case(name):
    """(before, after, surface, direction, contact, params, t0, t1, x0) of a switch
    that the run from x0 crosses transversally between t0 and t1."""
    t0 = 0.2
    p = dict(BASE, alpha=0.1)
    X2e = (p["g"] / p["omega2"] ** 2) ** (2 / 3)  # Eq. (9)
    Vb = p["Vb"]

    def X1_for(a_free, Y1):  # X1 with that a_free at t0
        return (H.a_free(t0, 0.0, Y1, p) - a_free) / p["omega1"] ** 2

    if name.startswith("reversal"):
        # a_free ~ 10 > mu F ~ 4.6: both slip accelerations positive, so slip_back
        # reaches Vr = 0 and slip_forward leaves it (transversal reversal)
        contact = name.split("-")[1]
        x0 = [X1_for(10.0, Vb - 0.05), Vb - 0.05, X2e, 0.3]
        return "slip_back", "slip_forward", "relative_velocity", 1, contact, p, t0, t0 + 0.5, x0
    if name == "stick_onset":
        # a_free = 1 inside the cone |a_free| < mu F: slip_back arrives, stick holds
        x0 = [X1_for(1.0, Vb - 0.05), Vb - 0.05, X2e, 0.3]
        return "slip_back", "stick", "relative_velocity", 1, "hertz_damp", p, t0, t0 + 0.5, x0
    if name == "stick_end":
        # stick with a_free just inside -mu F and falling (f_t' - omega1^2 Vb ~ -8 at
        # t0 = 1): it leaves the cone into slip_back
        t0 = 1.0
        muF = p["mu_s"] * H.force(X2e, 0.0, p, "hertz_damp")
        x0 = [X1_for(-muF + 0.2, Vb), Vb, X2e, 0.0]
        return "stick", "slip_back", "stick_back", -1, "hertz_damp", p, t0, t0 + 0.3, x0
    if name.startswith("lift_off"):
        contact = name.split("-")[1]
        q = dict(p, beta2=1.0)  # Kelvin-Voigt: F = 2 b2 w2 Y2 = -2 at X2 = 0
        return (
            "slip_back",
            "flight",
            "penetration",
            -1,
            contact,
            q,
            t0,
            t0 + 0.2,
            [0.5, 0.0, 0.02, -2.0],
        )
    if name == "separation":
        # Hertz-Damp, clipped law: F = 0 where Y2 = -omega2 / (2 beta2) = -5/3; a strong
        # normal excitation (f_n ~ -31 at t0) drives Y2 down through it
        q = dict(BASE)
        return (
            "slip_back",
            "separated",
            "contact_force",
            -1,
            "hertz_damp",
            q,
            0.35,
            0.45,
            [0.0, 0.0, 1.0, -1.5],
        )
    raise KeyError(name)


def composite_flow(x0, case):
    before, after, surface, direction, contact, p, t0, t1 = case[:8]
    t_s, x_s = run_mode(before, contact, p, t0, t1, x0, stop=(surface, direction))
    return run_mode(after, contact, p, t_s, t1, x_s), t_s, x_s


SWITCHES = [
    "reversal-hertz_damp",
    "reversal-kelvin_voigt",
    "stick_onset",
    "stick_end",
    "lift_off-kelvin_voigt",
    "lift_off-hertz_damp",
    "separation",
]


@pytest.mark.parametrize("name", SWITCHES)
def test_saltation_matches_finite_differences_of_the_simulated_flow(name):
    """The derivative of the flow map across a switch is Phi_after(t1, t_s) S
    Phi_before(t_s, t0), with S = saltation(x(t_s)) (Leine and Nijmeijer 2004).

    The flow map runs mode ``before`` from t0 until the surface is crossed (scipy event,
    located by brentq to ~4 eps), then mode ``after`` to t1; its Jacobian is taken by
    central differences with step h = 1e-4. Error model: truncation h^2 |phi'''| / 6
    (measured: the difference falls as h^2 from h = 1e-3, where it is <= 8e-7 in these
    cases, so <= 8e-9 at h = 1e-4) plus integration noise delta / h, delta ~ 1e-12
    (DOP853 at rtol = atol = 1e-13; the step pattern changes with the perturbation):
    <= 1e-8. Tolerance 1e-7 of max(1, |J|). Where S != I its effect on J is >= 0.16
    here, so the same comparison with S dropped must fail by a factor > 1e5 (asserted).
    """
    case = switch_case(name)
    before, after, surface, direction, contact, p, t0, t1, x0 = case
    x0 = np.array(x0, dtype=float)
    x1, t_s, x_s = composite_flow(x0, case)
    assert t0 < t_s < t1
    h = 1e-4
    J = np.empty((4, 4))
    for k in range(4):
        e = np.zeros(4)
        e[k] = h
        J[:, k] = (composite_flow(x0 + e, case)[0] - composite_flow(x0 - e, case)[0]) / (2 * h)
    Phi_before = variational(before, contact, p, t0, t_s, x0)
    Phi_after = variational(after, contact, p, t_s, t1, x_s)
    S = hybrid.saltation(
        t_s, *x_s, before=before, after=after, surface=surface, contact=contact, **p
    )
    tol = 1e-7 * max(1.0, np.abs(J).max())
    predicted = Phi_after @ S @ Phi_before
    assert np.abs(J - predicted).max() <= tol, (J, predicted)
    without = Phi_after @ Phi_before
    if np.abs(S - np.eye(4)).max() > 1e-6:
        assert np.abs(J - without).max() > 1e5 * tol
    else:
        assert name in ("stick_end", "lift_off-hertz_damp", "separation")
