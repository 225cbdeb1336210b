"""Floquet bands (beltmdsm.continuation.band): edges located, labelled, against references.

References: `floquet()` from scratch on either side of an edge; the sliding orbit's
largest velocity sampled on its run; for an existence edge, the T-periodic response
computed on the event-driven integrator (`beltmdsm.integrate.events`, Newton's method
with central differences of its flow, not the superposition's closed forms and
saltation matrices), the rate of its reversal's crossing from that run, and the zero
of the rate's fit against the belt speed.
"""

import numpy as np
import pytest
from scipy import optimize

from beltmdsm.continuation.band import floquet_band
from beltmdsm.continuation.band_result import Band
from beltmdsm.integrate.events import integrate_events
from beltmdsm.integrate.switching import SURFACE_INDEX, Mode, Switching
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet
from beltmdsm.periodic.shooting import periodic_response
from beltmdsm.settings import SolverSettings

# The tangency of the T-periodic response at the base set: where its reversal from
# sliding back to sliding forward becomes tangential (beltmdsm.continuation.edges.locate_end).
TANGENCY = 6.164352


@pytest.fixture(scope="module")
def base_band() -> Band:
    return floquet_band(None, "Vb", 1.0, 9.0, points=17, tol=1e-3)


def test_band_edges_are_located_and_match_pointwise_verdicts(base_band):
    band = base_band
    assert len(band.unstable) == 1
    lo, hi = band.unstable[0]
    for e in band.edges:
        assert e.bracket[1] - e.bracket[0] <= 1e-3
    # the lower edge is a multiplier crossing: |mu| - 1 changes sign across it
    below, above = floquet(Model(Vb=lo - 2e-3)), floquet(Model(Vb=lo + 2e-3))
    assert below.stable and not above.stable
    # the upper edge is the grazing point of the sliding orbit: its largest velocity
    # equals Vb there (the sliding orbit does not depend on Vb)
    sliding = periodic_response(Model(Vb=12.0))
    t = np.linspace(0, sliding.period, 4001)
    run = sliding._engine.engine.run(0.0, *sliding.state0[:2], sliding.period)
    vmax = run.segments(t, np.zeros(t.size, dtype=int))[1].max()
    assert hi == pytest.approx(vmax, abs=2e-3)
    assert band.no_periodic_response
    assert band.no_periodic_response[0][1] == pytest.approx(hi, abs=1e-9)


def test_the_sliding_grazing_point_is_exact_where_the_grid_finds_nothing_below_it():
    # on [0.5, 12] the grid point 6.25 (between the tangency and the grazing) finds no
    # response: the edge above it is still the sliding response's largest velocity
    band = floquet_band(None, "Vb", 0.5, 12.0)
    assert any(f.value == 6.25 for f in band.failed)
    (edge,) = [e for e in band.edges if e.kind == "grazing"]
    sliding = periodic_response(Model(Vb=12.0))
    run = sliding._engine.engine.run(0.0, *sliding.state0[:2], sliding.period)

    def velocity(t):
        return float(run.segments(np.array([t]), np.zeros(1, dtype=int))[1][0])

    t = np.linspace(0, sliding.period, 4001)
    k = int(np.argmax([velocity(s) for s in t]))
    top = optimize.minimize_scalar(
        lambda s: -velocity(s),
        bounds=(t[max(k - 1, 0)], t[min(k + 1, t.size - 1)]),
        method="bounded",
        options={"xatol": 1e-12},
    )
    # the maximum is quadratic in t: a bounded search to 1e-12 s gives it to rounding
    assert edge.value == pytest.approx(-top.fun, abs=1e-10)
    assert edge.accuracy <= 1e-12
    assert band.no_periodic_response[-1][1] == edge.value


def test_every_edge_is_labelled_with_its_bifurcation_and_the_kind_of_before(base_band):
    kinds = [(e.kind, e.old_kind) for e in base_band.edges]
    assert kinds == [
        ("neimark_sacker", "multiplier"),
        ("tangency", "existence"),
        ("grazing", "grazing"),
    ]
    ns = base_band.edges[0]
    # the critical pair of the unstable side, near omega1 = 1 (modulo Omega = 4)
    assert ns.frequency == pytest.approx(floquet(Model(Vb=ns.value + 1e-3)).frequency, rel=1e-3)
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
        "tol",
        "merged_away",
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
    guess = periodic_response(Model(Vb=6.14))
    for vb in values:
        guess = periodic_response(Model(Vb=vb), guess=guess)
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
        floquet_band(None, "Vbelt", 1.0, 2.0)
    with pytest.raises(ValueError, match="lo < hi"):
        floquet_band(None, "Vb", 2.0, 1.0)
    with pytest.raises(ValueError, match=r"leaves the domain: Vb must be >= 0"):
        floquet_band(None, "Vb", -1.0, 9.0)
    with pytest.raises(ValueError, match=r"leaves the domain: omega1 must be > 0"):
        floquet_band(None, "omega1", 0.0, 9.0)
    with pytest.raises(ValueError, match="tension"):
        floquet_band(Model(tension="loose"), "Vb", 1.0, 2.0)


# ------------------------------------------- issue 17, items 6 and 8: the text agrees


def _inside(ranges, x):
    return any(lo <= x <= hi for lo, hi in ranges)


def _check_consistent(band, lo, hi):
    """The edges' sides agree with the ranges, and every end of a range is an edge."""
    tol = band.tol
    values = [e.value for e in band.edges]
    assert all(b - a > tol for a, b in zip(values, values[1:])), values
    for e in band.edges:
        a, b = e.bracket
        # to tol, or, for an end located by extrapolation, to its stated accuracy; an
        # end's bracket is value -+ accuracy, each end rounded to half an ulp of value
        rounding = 2 * np.spacing(abs(e.value))
        assert a <= e.value <= b and b - a <= 2 * max(tol, e.accuracy) + rounding
        assert e.accuracy <= max(tol, 1e-6)
        below, above = e.value - tol / 2, e.value + tol / 2  # edges are > tol apart
        assert e.unstable_below == _inside(band.unstable, below), e
        assert e.unstable_above == _inside(band.unstable, above), e
    for ranges in (band.unstable, band.no_periodic_response):
        for r_lo, r_hi in ranges:
            for end in (r_lo, r_hi):
                assert end in (lo, hi) or end in values, (end, values)
    for r_lo, r_hi in band.no_periodic_response:
        assert any(u_lo <= r_lo and r_hi <= u_hi for u_lo, u_hi in band.unstable)


def test_the_band_text_agrees_with_itself_at_every_tolerance():
    """``--tol 1e-6`` added "edge at 6.4154 (grazing; stable on both sides)" beside
    "no periodic response in [6.1637, 6.4154]"; at 1e-7 a "stable window" 2.9e-7 wide
    appeared below the grazing point: the sliding response, whose crossing of the belt
    speed the integrators stepped over (tests/beltmdsm/integrate/test_shallow_crossings.py).
    Every tolerance now gives the same three edges, the finer ones closer."""
    from beltmdsm.cli import text

    previous = None
    for tol in (1e-3, 1e-4, 1e-6, 1e-7, 1e-9):
        band = floquet_band(None, "Vb", 1.0, 9.0, tol=tol)
        _check_consistent(band, 1.0, 9.0)
        printed = text.band(band, 1.0, 9.0)
        at = [line.split()[2] for line in printed.splitlines() if "edge at" in line]
        assert len(set(at)) == len(at), printed
        assert [(e.kind, e.unstable_below, e.unstable_above) for e in band.edges] == [
            ("neimark_sacker", False, True),
            ("tangency", True, True),
            ("grazing", True, False),
        ]
        if previous is not None:  # the multiplier edge within the coarser tolerance
            assert abs(band.edges[0].value - previous.edges[0].value) <= previous.tol
        previous = band


def test_edges_closer_than_tol_are_one_with_the_outer_sides():
    from beltmdsm.continuation.band_grid import _merge_close
    from beltmdsm.continuation.band_result import Edge

    def edge(v, kind, below, above):
        return Edge(v, kind, "x", (v - 1e-9, v + 1e-9), 1e-9, None, below, above)

    merged, hidden = _merge_close(
        [edge(1.0, "tangency", False, True), edge(1.0 + 5e-4, "grazing", True, False)], 1e-3
    )
    (e,) = merged
    sides = (e.unstable_below, e.unstable_above)
    assert (e.kind, e.value, sides) == ("grazing", 1.0005, (False, False))
    assert hidden == [(1.0 - 1e-9, 1.0005 + 1e-9)] and e.accuracy == pytest.approx(5e-4 + 1e-9)
    apart, hidden = _merge_close(
        [edge(1.0, "tangency", False, True), edge(1.002, "grazing", True, False)], 1e-3
    )
    assert len(apart) == 2 and hidden == []


def test_the_clipped_band_stays_consistent():
    band = floquet_band(Model(tension="clipped"), "Vb", 0.5, 16.0)
    _check_consistent(band, 0.5, 16.0)


def test_a_tolerance_below_the_rounding_of_the_range_is_refused():
    from beltmdsm.errors import Refused
    from beltmdsm.settings import MAX_BAND_POINTS, MIN_TOL_ULPS

    # the report: RecursionError
    with pytest.raises(Refused, match="below what the rounding of the range") as err:
        floquet_band(None, "Vb", 1.0, 9.0, tol=1e-15)
    assert err.value.names == ("tol",)
    # at the finest tolerance the refinement still ends, consistent
    band = floquet_band(None, "Vb", 1.0, 9.0, tol=2 * MIN_TOL_ULPS * np.spacing(9.0))
    _check_consistent(band, 1.0, 9.0)
    with pytest.raises(Refused, match="MAX_BAND_POINTS") as err:
        floquet_band(None, "Vb", 1.0, 9.0, points=MAX_BAND_POINTS + 1)
    assert err.value.names == ("points",)
