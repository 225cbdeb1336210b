"""Floquet bands (beltmdsm.analysis.band): edges located, labelled, against independent references.

References: `floquet()` from scratch on either side of an edge; the sliding orbit's
largest velocity sampled on its run; for an existence edge, the T-periodic response
computed on the event-driven integrator (`beltmdsm.integrate.events`, Newton's method
with central differences of its flow, not the superposition's closed forms and
saltation matrices), the rate of its reversal's crossing from that run, and the zero
of the rate's fit against the belt speed.
"""

import numpy as np
import pytest

from beltmdsm.analysis import floquet as F
from beltmdsm.analysis.band import Band, floquet_band
from beltmdsm.integrate.events import integrate_events
from beltmdsm.integrate.switching import SURFACE_INDEX, Mode, Switching
from beltmdsm.model import Model
from beltmdsm.settings import SolverSettings

# The tangency of the T-periodic response at the base set: where its reversal from
# sliding back to sliding forward becomes tangential (beltmdsm.analysis.edges.locate_end).
TANGENCY = 6.164352


@pytest.fixture(scope="module")
def base_band() -> Band:
    return floquet_band("Vb", 1.0, 9.0, points=17, tol=1e-3)


def test_band_edges_are_located_and_match_pointwise_verdicts(base_band):
    band = base_band
    assert len(band.unstable) == 1
    lo, hi = band.unstable[0]
    for e in band.edges:
        assert e.bracket[1] - e.bracket[0] <= 1e-3
    # the lower edge is a multiplier crossing: |mu| - 1 changes sign across it
    below, above = F.floquet(Vb=lo - 2e-3), F.floquet(Vb=lo + 2e-3)
    assert below.stable and not above.stable
    # the upper edge is the grazing point of the sliding orbit: its largest velocity
    # equals Vb there (the sliding orbit does not depend on Vb)
    sliding = F.periodic_response(Vb=12.0)
    t = np.linspace(0, sliding.period, 4001)
    run = sliding._engine.engine.run(0.0, *sliding.state0[:2], sliding.period)
    vmax = run.segments(t, np.zeros(t.size, dtype=int))[1].max()
    assert hi == pytest.approx(vmax, abs=2e-3)
    assert band.no_periodic_response
    assert band.no_periodic_response[0][1] == pytest.approx(hi, abs=1e-9)


def test_every_edge_is_labelled_with_its_bifurcation_and_the_kind_of_before(base_band):
    kinds = [(e.kind, e.old_kind) for e in base_band.edges]
    assert kinds == [
        ("neimark_sacker", "multiplier"),
        ("tangency", "existence"),
        ("grazing", "grazing"),
    ]
    ns = base_band.edges[0]
    # the critical pair of the unstable side, near omega1 = 1 (modulo Omega = 4)
    assert ns.frequency == pytest.approx(F.floquet(Vb=ns.value + 1e-3).frequency, rel=1e-3)
    assert 0.9 < ns.frequency < 1.1
    out = base_band.as_dict()
    assert set(out) == {
        "param",
        "unstable",
        "edges",
        "grazing_points",
        "no_periodic_response",
        "grid",
        "failed",
        "tension",
        "contact",
        "friction",
        "engine",
    }
    assert set(out["edges"][0]) == {
        "value",
        "kind",
        "old_kind",
        "bracket",
        "accuracy",
        "frequency",
        "unstable_below",
        "unstable_above",
        "detail",
    }
    assert {"value", "stable", "max_abs_multiplier", "state0"} <= set(out["grid"][0])


def _events_orbit(model, state0):
    """The T-periodic response on the event-driven integrator: Newton's method, central
    differences of its flow for the Jacobian, from ``state0``."""
    T = 2 * np.pi / model["Omega"]
    normal = state0[2:]
    settings = SolverSettings(t_end=T, rtol=1e-13, atol=1e-13, dt=T / 100)

    def flow(x):
        run = integrate_events(model, settings, y0=np.concatenate([x, normal]))
        assert run.status == "done"
        return run, run.trajectory.state(np.array([T]))[:2, 0]

    x = np.array(state0[:2], dtype=float)
    for _ in range(8):
        r = flow(x)[1] - x
        if np.abs(r).max() < 1e-11:
            break
        J = np.empty((2, 2))
        for j in range(2):
            e = np.zeros(2)
            e[j] = 1e-7
            J[:, j] = (flow(x + e)[1] - flow(x - e)[1]) / 2e-7
        x = x - np.linalg.solve(J - np.eye(2), r)
    return flow(x)[0]


def _reversal_rate(model, run):
    """The rate of Vr along sliding back at the reversal to sliding forward, over its scale."""
    sw = Switching(model)
    (t,) = [t for t, kind, new in run.events if kind == "vr_zero" and new == Mode.SLIP_FORWARD]
    state = run.trajectory.state(np.array([t]))[:, 0]
    rate = sw.rates(t, *state, float(Mode.SLIP_BACK))[SURFACE_INDEX["relative_velocity"]]
    return abs(rate) / sw.scales(t, *state)[SURFACE_INDEX["stick_forward"]]


def test_the_existence_edge_is_the_tangency_of_the_events_orbit(base_band):
    values, rates = [6.149, 6.153, 6.157, 6.161], []
    guess = F.periodic_response(Vb=6.14)
    for vb in values:
        guess = F.periodic_response(Vb=vb, guess=guess)
        rates.append(_reversal_rate(guess.model, _events_orbit(guess.model, guess.state0)))
    # the belt speed against the rate is smooth up to the tangency: the cubic's value at
    # zero rate, with the quadratic's distance to it as the reference's error bound
    reference = np.polyval(np.polyfit(rates, values, 3), 0.0)
    bound = abs(reference - np.polyval(np.polyfit(rates[1:], values[1:], 2), 0.0))
    assert bound < 1e-5
    (edge,) = [e for e in base_band.edges if e.kind == "tangency"]
    assert edge.old_kind == "existence"
    # issue 20: to 1e-4 (the bisection of before was 2.5e-4 to 1.3e-3 low)
    assert abs(edge.value - reference) < 1e-4
    assert edge.value == pytest.approx(TANGENCY, abs=1e-6)
    assert edge.accuracy < 1e-5
    assert base_band.no_periodic_response[0][0] == pytest.approx(edge.value, abs=1e-12)


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match="param"):
        floquet_band("Vbelt", 1.0, 2.0)
    with pytest.raises(ValueError, match="lo < hi"):
        floquet_band("Vb", 2.0, 1.0)
    with pytest.raises(ValueError, match=r"leaves the domain: Vb must be >= 0"):
        floquet_band("Vb", -1.0, 9.0)
    with pytest.raises(ValueError, match=r"leaves the domain: omega1 must be > 0"):
        floquet_band("omega1", 0.0, 9.0)
    with pytest.raises(ValueError, match="tension"):
        floquet_band("Vb", 1.0, 2.0, Model(), tension="loose")
