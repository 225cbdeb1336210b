"""The general Floquet path (beltmdsm/periodic/general_map.py `GeneralMap`, on
beltmdsm/periodic/variational.py): the engine the laws' facts choose, its agreement with
the closed-form path where both apply, its monodromy against finite differences of the
simulated period map under Stribeck friction, and the closed-form path's refusal."""

import itertools

import numpy as np
import pytest
from scipy import linalg

from beltmdsm.generated.capabilities import CAPABILITIES
from beltmdsm.integrate.events import integrate_events
from beltmdsm.model import CONTACTS, FRICTIONS, TENSIONS, Model, Unsupported
from beltmdsm.periodic.base import RTOL
from beltmdsm.periodic.closed_form import CLOSED_FORM_FACTS, TangentialMap
from beltmdsm.periodic.engines import engine_of, period_map
from beltmdsm.periodic.floquet import floquet
from beltmdsm.periodic.general_map import GeneralMap
from beltmdsm.periodic.shooting import periodic_response
from beltmdsm.settings import SolverSettings
from beltmdsm.simulation import simulate

#: Coulomb friction, where both paths apply: a point of each switch structure and law.
BOTH = {
    "reversals": dict(Vb=5.0),
    "sliding": dict(Vb=12.0),
    "stick": dict(Vb=0.1, alpha=0.05),
    "clipped": dict(Vb=4.0, tension="clipped"),
    # Fig. 16's linear contact
    "kelvin_voigt": dict(Vb=5.0, contact="kelvin_voigt", omega2=0.5, beta2=3.0),
    "hunt_crossley": dict(Vb=5.0, contact="hunt_crossley", n_h=1.3),
}
#: The two paths find the same fixed point to Newton's tolerance (1e-11 of the state)
#: with integrators at RTOL = 1e-12. The closed-form tangential block is exact to
#: rounding; the variational monodromy carries order-8 stages on the run's own steps,
#: each within RTOL, about 50 of them a period: 5e-11. The multipliers are simple
#: eigenvalues of condition O(1-10) here, so they agree to well below 1e-9 (measured:
#: 5e-13 to 6e-12).
AGREE = 1e-9


def _match(a, b):
    """The largest distance from each of ``a`` to the nearest of ``b``, relative to max(1, |a|)."""
    return max(float(np.min(np.abs(b - z))) / max(1.0, abs(z)) for z in a)


def test_the_engine_follows_the_facts_of_the_laws():
    for friction, contact, tension in itertools.product(FRICTIONS, CONTACTS, TENSIONS):
        facts = CAPABILITIES[(friction, contact, tension)]
        closed = all(facts[f][0] for f in CLOSED_FORM_FACTS)
        model = Model(friction=friction, contact=contact, tension=tension)
        assert engine_of(model) == ("closed_form" if closed else "general")
        assert type(period_map(model)) is (TangentialMap if closed else GeneralMap)
    f = floquet(Model(Vb=3.0, friction="stribeck"))
    assert f.engine == f.as_dict()["engine"] == f.response.engine == "general"
    assert floquet(Model(Vb=3.0)).as_dict()["engine"] == "closed_form"


def test_the_closed_form_path_refuses_stribeck_friction_by_name():
    model = Model(Vb=3.0, friction="stribeck")
    for build in (
        lambda: TangentialMap(model),
        lambda: periodic_response(model, engine="closed_form"),
    ):
        with pytest.raises(Unsupported) as err:
            build()
        text = str(err.value)
        assert "friction='stribeck'" in text and "X1'" in text and "\n" not in text
    with pytest.raises(ValueError, match="engine"):
        period_map(model, engine="numeric")


def test_the_choice_reads_the_facts_not_the_law(monkeypatch):
    # a law whose slip-mode friction depended on the state would be Coulomb's in every
    # other respect: the facts, not the name, send it to the general path
    key = ("coulomb", "hertz_damp", "allowed")
    facts = dict(CAPABILITIES[key])
    facts["slip_friction_state_independent"] = (False, "friction='coulomb': a toy fact")
    monkeypatch.setitem(CAPABILITIES, key, facts)
    model = Model(Vb=5.0)
    assert engine_of(model) == "general" and floquet(model).engine == "general"
    with pytest.raises(Unsupported, match="the closed-form period map: .*a toy fact"):
        TangentialMap(model)
    run = simulate(model, solver="superposition", t_end=20.0)
    assert run.solver_used == "events" and "superposition: friction='coulomb': a toy fact" in (
        run.message
    )


@pytest.mark.parametrize("case", BOTH)
def test_both_paths_agree_where_both_apply(case):
    model = Model(**BOTH[case])
    closed = floquet(model)
    general = floquet(model, engine="general")
    assert (closed.engine, general.engine) == ("closed_form", "general")
    assert [s[1:] for s in closed.response.switches] == [s[1:] for s in general.response.switches]
    assert (closed.n_reversals, closed.n_sticks) == (general.n_reversals, general.n_sticks)
    scale = 1.0 + np.max(np.abs(closed.response.state0))
    assert np.max(np.abs(closed.response.state0 - general.response.state0)) <= AGREE * scale
    assert _match(closed.multipliers, general.multipliers) <= AGREE
    assert _match(general.multipliers, closed.multipliers) <= AGREE
    # the structure the closed form relies on, found by the general path: the normal
    # block free of the tangential state (exactly: the generated Jacobians and saltation
    # matrices have structural zeros there)
    M = general.response.monodromy
    assert np.all(M[2:, :2] == 0.0)
    assert np.max(np.abs(M[:2, :2] - closed.response.monodromy_tangential)) <= AGREE
    assert np.max(np.abs(M[2:, 2:] - closed.response.monodromy_normal)) <= AGREE
    # the general multipliers are the whole monodromy's, largest first
    assert np.all(np.diff(np.abs(general.multipliers)) <= 0)
    # what the band, edges and branches read of the orbit: the same margins and range
    # of X1' (states on the orbit agree to about 1e-10: a dense output of order 7 at
    # RTOL against closed forms)
    a = period_map(model)(closed.response.shooting_state)
    b = period_map(model, engine="general")(general.response.shooting_state)
    assert [(m.kind, m.surface, m.mode) for m in a.margins] == [
        (m.kind, m.surface, m.mode) for m in b.margins
    ]
    for m, n in zip(a.margins, b.margins):
        assert abs(m.t - n.t) <= 1e-8 and abs(m.value - n.value) <= 1e-8
    assert np.allclose(a.velocity_range(), b.velocity_range(), rtol=0, atol=1e-8)


def test_both_paths_agree_on_a_locked_response():
    # the 4T response that the run from rest locks on at Vb = 5 (beltmdsm/periodic/locked.py)
    model = Model(Vb=5.0)
    closed = floquet(model, periods=4)
    general = floquet(model, periods=4, engine="general", guess=closed.response)
    assert general.response.periods == 4 and general.engine == "general"
    assert _match(closed.multipliers, general.multipliers) <= AGREE
    assert _match(general.multipliers, closed.multipliers) <= AGREE


def test_a_tangential_guess_is_completed_by_the_sliding_orbit():
    pmap = GeneralMap(Model(Vb=5.0))
    sliding = pmap.sliding_guess()
    x = pmap.guess([1.0, 2.0])
    assert x.shape == (4,) and np.all(x[:2] == [1.0, 2.0]) and np.all(x[2:] == sliding[2:])
    assert np.all(pmap.guess(np.arange(4.0)) == np.arange(4.0))
    with pytest.raises(ValueError, match="guess"):
        pmap.guess([1.0, 2.0, 3.0])


# ---------------------------------------------------------------- Stribeck friction

#: Stribeck friction (derive/laws.py), mu_k = 0.25, v_s = 1 m/s (issue 19's set), at points
#: of each switch structure: (n_reversals, n_sticks) per period.
STRIBECK = dict(friction="stribeck", mu_k=0.25, v_s=1.0)
FD_CASES = {
    "sliding": (dict(Vb=12.0), (0, 0)),
    "reversals": (dict(Vb=3.0), (2, 0)),
    "reversals_fast": (dict(Vb=5.0), (2, 0)),
    "stick": (dict(Vb=0.1, alpha=0.05), (0, 1)),
    "separation": (dict(Vb=4.0, tension="clipped"), (0, 0)),
}
#: Relative step of the central differences: small enough that the map keeps its switch
#: structure, large enough that the truncation error (estimated) dominates the rounding.
FD_STEP = 1e-4


def _period_map(model, x, T):
    """``P(x)`` by the event-driven integrator at the period maps' tolerance, and its steps."""
    settings = SolverSettings(t_end=T, rtol=RTOL, atol=RTOL, dt=T / 50, t_discard=0.0)
    tr = integrate_events(model, settings, y0=x).trajectory
    return tr.state(np.array([tr.t_end]))[:, 0], tr.evaluator.t_steps.size


def _differences(model, x, T, h):
    D = np.zeros((4, 4))
    for j in range(4):
        e = np.zeros(4)
        e[j] = h * (1.0 + abs(x[j]))
        D[:, j] = (_period_map(model, x + e, T)[0] - _period_map(model, x - e, T)[0]) / (2 * e[j])
    return D


def _fd_bound(model, x, T):
    """Central differences of the simulated period map and their error bound, per entry.

    ``D(h)`` has a truncation error ``c h^2`` and a rounding error below ``2 delta / e``
    (``e`` the step, ``delta`` the integration error of ``P``). With ``D(h/2)`` the
    truncation error of ``D(h/2)`` is ``|D(h) - D(h/2)| / 3`` (taken twice); ``delta``
    is bounded by every step's local error at its tolerance, RTOL (1 + |P|) per step,
    none damped on the way (the flow contracts: a worst case).
    """
    P, steps = _period_map(model, x, T)
    D1 = _differences(model, x, T, FD_STEP)
    D2 = _differences(model, x, T, FD_STEP / 2)
    delta = steps * RTOL * (1.0 + np.max(np.abs(P)))
    e2 = 0.5 * FD_STEP * (1.0 + np.abs(x))
    return D2, 2 * np.abs(D1 - D2) / 3 + 2 * delta / e2[None, :]


@pytest.mark.parametrize("case", FD_CASES)
def test_the_stribeck_monodromy_against_finite_differences(case):
    point, structure = FD_CASES[case]
    f = floquet(Model(**point, **STRIBECK))
    assert f.engine == "general" and (f.n_reversals, f.n_sticks) == structure
    x, T, J = f.response.state0, f.response.period, f.response.monodromy
    D, bound = _fd_bound(f.response.model, x, T)
    assert np.all(np.abs(J - D) <= bound)
    # the multipliers: each within 2 kappa ||D - J|| of one of D's (first order, the 2
    # for the second), kappa = 1 / |y^H x| its condition (unit left and right
    # eigenvectors); a stick makes the small ones ill-conditioned, not the largest
    mu, left, right = linalg.eig(J, left=True, right=True)
    kappa = np.linalg.norm(left, axis=0) * np.linalg.norm(right, axis=0)
    kappa /= np.abs(np.sum(left.conj() * right, axis=0))
    radius = 2 * kappa * np.linalg.norm(bound)
    mu_fd = np.linalg.eigvals(D)
    assert all(np.min(np.abs(mu_fd - z)) <= r for z, r in zip(mu, radius))
    # the check says something: the largest multiplier's radius is far below its size
    assert radius[np.argmax(np.abs(mu))] < 1e-3 * f.max_abs_multiplier


def test_coulombs_multipliers_fail_the_stribeck_check():
    # what the closed-form path returned for Stribeck friction before it was checked
    model = Model(Vb=5.0, **STRIBECK)
    f = floquet(model)
    D, bound = _fd_bound(model, f.response.state0, f.response.period)
    coulomb = floquet(Model(Vb=5.0)).response.monodromy
    assert np.max(np.abs(coulomb - D) - bound) > 1e-3
    assert abs(floquet(Model(Vb=5.0)).max_abs_multiplier - f.max_abs_multiplier) > 0.1
