"""Exact two-parameter maps (beltmdsm.continuation.floquet_map) against bands and verdicts.

References: `beltmdsm.continuation.band.floquet_band` on the map's rows, `floquet()` from
scratch at points of a coarse grid, and the closed-form interval of the paper's linear
analysis (`beltmdsm.generated.stability.unstable_interval`).
"""

import numpy as np
import pytest

from beltmdsm.continuation.band import floquet_band
from beltmdsm.continuation.floquet_map import floquet_map
from beltmdsm.continuation.linear_verdict import LINEAR_POINTS
from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.generated import stability
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet


def test_the_map_rows_are_the_bands_and_the_verdicts_of_floquet():
    result = floquet_map(None, "Vb", 0.5, 12.0, "beta1", 0.05, 0.35, points=4)
    assert {c.kind for c in result.curves} == {"neimark_sacker", "tangency", "grazing"}
    assert all(len(c.y) == 4 for c in result.curves)
    for y, unstable in zip(result.rows, result.unstable):
        band = floquet_band(Model(beta1=float(y)), "Vb", 0.5, 12.0)
        assert len(unstable) == len(band.unstable) == 1
        edges = {e.kind: e for e in band.edges}
        # the map's edges to its accuracy, the band's to theirs
        assert unstable[0][0] == pytest.approx(
            band.unstable[0][0], abs=edges["neimark_sacker"].accuracy + 1e-4
        )
        assert unstable[0][1] == pytest.approx(band.unstable[0][1], abs=1e-6)
        # off the edges, floquet() from scratch says the same
        for x in np.linspace(0.6, 11.9, 12):
            if min(abs(x - v) for v in unstable[0]) < 0.1:
                continue
            try:
                verdict = floquet(Model(Vb=x, beta1=float(y))).stable is not True
            except NoPeriodicResponse:
                verdict = True
            assert verdict == (unstable[0][0] <= x <= unstable[0][1]), (y, x)
    # the paper's linear analysis on the same rows, against its closed-form interval
    # (beltmdsm.generated.stability.unstable_interval), to the map's grid of x
    resolution = (12.0 - 0.5) / (LINEAR_POINTS - 1)
    for y, linear in zip(result.rows, result.linear):
        lower, upper = stability.unstable_interval(**Model(beta1=float(y)).params)
        ((a, b),) = linear
        assert a == pytest.approx(max(float(lower), 0.5), abs=resolution)
        assert b == pytest.approx(float(upper), abs=resolution)
    out = result.as_dict()
    assert set(out["curves"][0]) >= {"kind", "x", "y", "accuracy", "frequency"}
    assert len(out["unstable"]) == len(out["linear"]) == 4


def test_each_neimark_sacker_edge_lies_within_its_accuracy():
    # ten rows followed from one band: the edge extrapolated from the rows before and
    # taken from the secant's last step without a period map of its own. floquet()
    # from scratch on either side, twice the accuracy away (at least 1e-5 m/s, so that
    # |mu| - 1 stands well above the multipliers' rounding), brackets |mu| = 1
    result = floquet_map(None, "Vb", 0.5, 12.0, "beta1", 0.05, 0.35, points=10)
    assert result.band_rows == [0.05]
    ns = next(c for c in result.curves if c.kind == "neimark_sacker")
    assert len(ns.y) == 10
    for y, x, accuracy in zip(ns.y, ns.x, ns.accuracy):
        assert accuracy <= 1e-6 * (12.0 - 0.5)  # the map's EDGE_TOL of the range
        d = max(2 * accuracy, 1e-5)
        below, above = (floquet(Model(Vb=x + s * d, beta1=y)).max_abs_multiplier for s in (-1, 1))
        assert below < 1 < above, (y, x, accuracy)


def test_bad_axes_are_refused():
    with pytest.raises(ValueError, match="differ"):
        floquet_map(None, "Vb", 1.0, 2.0, "Vb", 1.0, 2.0)
    with pytest.raises(ValueError, match="model parameters"):
        floquet_map(None, "Vbelt", 1.0, 2.0, "beta1", 0.1, 0.2)
    with pytest.raises(ValueError, match="points"):
        floquet_map(None, "Vb", 1.0, 2.0, "beta1", 0.1, 0.2, points=1)


def _agrees_with_floquet(result, x, y, points, near):
    """Every point of each row farther than ``near`` from a curve: the map's verdict is that
    of ``floquet()`` from scratch (unstable or absent inside the row's unstable set)."""
    for row, unstable in zip(result.rows, result.unstable):
        edges = [cx for c in result.curves for cy, cx in zip(c.y, c.x) if cy == row]
        for value in points:
            if edges and min(abs(value - e) for e in edges) < near:
                continue
            try:
                verdict = floquet({x: float(value), y: float(row)}).stable is not True
            except NoPeriodicResponse:
                verdict = True
            assert verdict == any(a <= value <= b for a, b in unstable), (row, value)


def test_a_curve_that_changes_kind_goes_on_from_its_edges_history():
    # omega1 from 1 to 2.6: the Neimark-Sacker pair of the base set becomes a multiplier
    # through -1 (period doubling), continued on the next row from the edge's history
    result = floquet_map(None, "Vb", 0.25, 20.0, "omega1", 1.0, 2.6, points=5, check_every=1)
    ns = next(c for c in result.curves if c.kind == "neimark_sacker")
    assert ns.ended.startswith("becomes period_doubling")
    pd = next(c for c in result.curves if c.kind == "period_doubling")
    assert len(pd.y) >= 2
    # the kind, independently: floquet() on both sides of the edge, the unstable side's
    # critical multiplier real and below -1 (on the stable side, a complex pair near -1
    # that meets on the real axis just before the edge)
    y, x = pd.y[-1], pd.x[-1]
    sides = [floquet(Model(Vb=x + d, omega1=y)) for d in (-0.02, 0.02)]
    assert sorted(f.max_abs_multiplier < 1 for f in sides) == [False, True]
    unstable = next(f for f in sides if f.max_abs_multiplier > 1)
    mu = unstable.multipliers[np.argmax(np.abs(unstable.multipliers))]
    assert abs(mu.imag) < 1e-9 and mu.real < -1
    _agrees_with_floquet(result, "Vb", "omega1", np.linspace(0.5, 19.5, 20), 0.5)


def test_a_row_with_a_band_takes_its_unstable_set_beside_a_coexisting_response():
    # beta2 from 0.036 to 0.09: a second periodic response (reversing) goes on past the
    # sliding one's grazing point and loses stability at a Neimark-Sacker point, while
    # the sliding one is stable there: that curve bounds nothing
    result = floquet_map(None, "Vb", 0.25, 16.0, "beta2", 0.036, 0.09, points=3, check_every=1)
    assert result.band_rows == [float(v) for v in result.rows]
    for y, unstable in zip(result.rows, result.unstable):
        band = floquet_band(Model(beta2=float(y)), "Vb", 0.25, 16.0)
        assert unstable == [[float(a), float(b)] for a, b in band.unstable]
    # (farther from every unstable range than the band's tolerance, 1e-3)
    apart = [
        (cy, cx)
        for c in result.curves
        if c.kind == "neimark_sacker"
        for cy, cx in zip(c.y, c.x)
        if not any(
            a - 1e-2 <= cx <= b + 1e-2 for a, b in result.unstable[list(result.rows).index(cy)]
        )
    ]
    assert apart and all(floquet(Model(Vb=cx + 0.1, beta2=cy)).stable for cy, cx in apart)
    _agrees_with_floquet(result, "Vb", "beta2", np.linspace(0.5, 15.5, 16), 0.3)


def test_a_touch_of_the_belt_speed_that_keeps_the_mode_leaves_the_jacobian_smooth():
    # met by the (Vb, omega1) map at omega1 = 6.59: a reversal back to forward sliding
    # 1.6e-5 s before a stick, where the velocity all but touches the belt's. Rounding
    # decides whether the scan also reports a touch that keeps the mode (S = I, which
    # asked for a saltation variant that does not exist) 1e-13 s after the reversal:
    # either way the modes chain and the Jacobian is the map's
    from beltmdsm.periodic.closed_form import TangentialMap

    pmap = TangentialMap(Model(omega1=6.59090909090909, Vb=2.3549836562893516), 1)
    x = np.array([-0.2732120331036181, 2.354983656289352])
    image = pmap(x)
    switches = [s[1:3] for s in image.switches]
    assert all(a[1] == b[0] for a, b in zip(switches, switches[1:]))
    # the X1 direction is smooth here (the velocity direction starts on the stick
    # boundary): the Jacobian's column against central differences of the map
    h = 1e-6
    column = (pmap(x + [h, 0]).state - pmap(x - [h, 0]).state) / (2 * h)
    assert np.allclose(image.jacobian[:, 0], column, rtol=1e-6, atol=1e-9)


def test_a_flat_secant_reports_the_step_that_reached_its_edge(monkeypatch):
    # log max|mu| the same at both points of the secant: no slope to go on with, so the
    # edge is the point reached, its accuracy the step that reached it (not zero)
    from beltmdsm.continuation import map_tracker as module
    from beltmdsm.periodic.family import MapFamily

    model = Model(beta1=0.3)
    state = floquet(model.replace(Vb=5.48)).response.shooting_state
    tracker = module._Tracker(module.Curve("neimark_sacker"), "multiplier", 0.0, ())
    tracker.ys, tracker.xs, tracker.states = [0.3], [5.48], [(state,)]
    monkeypatch.setattr(module, "log_max_multiplier", lambda pmap, point: (0.25, 0.9 + 0.5j))
    kind, x, accuracy, frequency = tracker.step(MapFamily(model, "Vb"), 0.3, 11.5)
    assert kind == "neimark_sacker" and frequency > 0
    assert x == pytest.approx(5.48 + 1e-3 * 11.5, abs=1e-12)
    assert accuracy == pytest.approx(1e-3 * 11.5, rel=1e-9)


def _count_rows_of_one_response(monkeypatch):
    """Per role, the rows where a curve was continued from one response (module docstring)."""
    from beltmdsm.continuation import map_tracker as module

    counts = {"multiplier": 0, "end": 0}
    multiplier, end = module._Tracker._multiplier, module._Tracker._end

    def counted(step, role, measured):
        def wrapper(self, *args):
            before = len(measured(self))
            out = step(self, *args)
            counts[role] += len(measured(self)) == before
            return out

        return wrapper

    monkeypatch.setattr(
        module._Tracker, "_multiplier", counted(multiplier, "multiplier", lambda t: t.slopes)
    )
    monkeypatch.setattr(module._Tracker, "_end", counted(end, "end", lambda t: t.shapes))
    return counts


def test_rows_of_one_response_lie_within_their_accuracy(monkeypatch):
    # twelve close rows: after the first few, the Neimark-Sacker curve takes one response
    # a row (its secant's slope predicted from the rows before), the tangency one too
    # (x against the closing margin, measured by four responses on rows before). The
    # references: floquet() from scratch on either side of each Neimark-Sacker edge,
    # twice its accuracy away, brackets |mu| = 1; the band on each row, which continues
    # the response to its end itself, gives the tangency to its own accuracy
    counts = _count_rows_of_one_response(monkeypatch)
    result = floquet_map(None, "Vb", 0.5, 12.0, "beta1", 0.3, 0.36, points=12)
    assert counts["multiplier"] >= 5 and counts["end"] >= 5, counts
    ns = next(c for c in result.curves if c.kind == "neimark_sacker")
    tangency = next(c for c in result.curves if c.kind == "tangency")
    assert len(ns.y) == len(tangency.y) == 12
    for y, x, accuracy in zip(ns.y, ns.x, ns.accuracy):
        assert accuracy <= 1e-6 * (12.0 - 0.5)
        d = max(2 * accuracy, 1e-5)
        below, above = (floquet(Model(Vb=x + s * d, beta1=y)).max_abs_multiplier for s in (-1, 1))
        assert below < 1 < above, (y, x, accuracy)
    for i, (y, x, accuracy) in enumerate(zip(tangency.y, tangency.x, tangency.accuracy)):
        # (the first row's edge is the band's, located to 1e-4)
        assert i == 0 or accuracy <= 1e-6 * (12.0 - 0.5)
        band = floquet_band(Model(beta1=y), "Vb", 5.8, 6.6)
        (edge,) = (e for e in band.edges if e.kind == "tangency")
        assert abs(x - edge.value) <= accuracy + edge.accuracy, (y, x, edge.value)
