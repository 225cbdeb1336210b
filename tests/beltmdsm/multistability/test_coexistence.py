"""Exact coexistence (beltmdsm.multistability.coexistence) against the runs and the band.

References: runs of `beltmdsm.simulation.simulate` started on each coexisting response
(a stable response keeps a run started on it), and the Floquet band
(`beltmdsm.continuation.band`), found by another method, for the T-periodic response's edges.
"""

import numpy as np
import pytest

from beltmdsm.continuation.band import floquet_band
from beltmdsm.multistability.coexistence import coexistence
from beltmdsm.periodic.floquet import floquet
from beltmdsm.simulation import simulate


def test_the_base_set_coexistence_is_two_ranges_with_their_bifurcations():
    found = coexistence(None, "Vb", 0.5, 12.0)
    names = {r.name: r for r in found.responses}
    assert sorted(names) == ["4T", "T#1", "T#2"]
    ranges = [(c.range, sorted(c.responses), c.lower, c.upper) for c in found.ranges]
    assert len(ranges) == 2
    (r1, who1, lo1, hi1), (r2, who2, lo2, hi2) = ranges
    # below the band: the 4T orbit appears at a grazing, the periodic one loses stability
    # at a Neimark-Sacker point; above it: the sliding response grazes, the 4T orbit folds
    assert (who1, lo1, hi1) == (["4T", "T#1"], "grazing", "neimark_sacker")
    assert (who2, lo2, hi2) == (["4T", "T#2"], "grazing", "fold")
    assert r1 == pytest.approx([3.869919, 4.057609], abs=1e-5)
    assert r2 == pytest.approx([6.415415, 7.673801], abs=1e-5)
    # the Floquet band's edges are the T-responses' (the same bifurcations, found apart)
    band = floquet_band(None, "Vb", 0.5, 12.0)
    lower, upper = band.unstable[0]
    assert abs(lower - r1[1]) < 2e-4 and abs(upper - r2[0]) < 1e-9
    # just below, the run from rest is not locked: listed, not explained by a response
    assert any(abs(u.value - 3.5) < 1e-9 for u in found.unlocked)
    out = found.as_dict()
    assert set(out["coexistence"][0]) == {"range", "responses", "lower", "upper"}


@pytest.mark.parametrize("vb", [4.0, 7.0])
def test_a_run_started_on_each_coexisting_response_stays_on_it(vb):
    found = coexistence(None, "Vb", vb - 0.5, vb + 0.5, points=3)
    coexisting = [c for c in found.ranges if c.range[0] < vb < c.range[1]]
    assert coexisting
    for r in found.responses:
        if r.name not in coexisting[0].responses:
            continue
        point = r.branch.point_near(vb)
        model = r.branch.model.replace(Vb=point.value)
        f = floquet(model, guess=point.state, periods=r.branch.periods)
        assert f.stable
        T = f.period / r.branch.periods
        sim = simulate(model, y0=f.response.state0, t_end=60 * T)
        end = sim.trajectory.state(np.array([60 * T]))[:2, 0]
        assert np.abs(end - f.response.state0[:2]).max() < 1e-6 * (1 + np.abs(end).max())


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="param"):
        coexistence(None, "Vbelt", 1.0, 2.0)
    with pytest.raises(ValueError, match="lo < hi"):
        coexistence(None, "Vb", 2.0, 2.0)
    with pytest.raises(ValueError, match="points = 2 leaves no seed"):
        coexistence(None, "Vb", 1.0, 2.0, points=2)
