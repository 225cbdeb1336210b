"""Branches and their bifurcations (beltmdsm.continuation.branch) against independent references.

References: `floquet()` from scratch at the branch's points, the band of
`beltmdsm.continuation.band` (found by another method: a grid, secants and natural
continuation), the multipliers at a fold (a real one is +1 there), and the tangency
the band's (tests/beltmdsm/continuation/test_band.py checks it against the event-driven
integrator).
"""

import numpy as np
import pytest

from beltmdsm.continuation.band import floquet_band
from beltmdsm.continuation.branch import branch, continue_branch
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet
from beltmdsm.periodic.shooting import periodic_response


def test_the_4T_branch_is_stable_from_a_grazing_to_a_fold_and_ends_at_a_tangency():
    b = branch(Model(Vb=5.0), periods=4, param="Vb", lo=2.0, hi=9.0)
    kinds = [s.kind for s in b.special]
    assert kinds == ["grazing", "fold", "tangency"]
    grazing, fold, tangency = b.special
    assert grazing.value == pytest.approx(3.869919, abs=1e-5)
    assert fold.value == pytest.approx(7.673801, abs=1e-5)
    assert tangency.value == pytest.approx(7.375788, abs=1e-5)
    assert all(s.accuracy < 1e-4 for s in b.special)
    # at the fold a real multiplier is +1 (to the location's accuracy)
    assert np.min(np.abs(fold.multipliers - 1.0)) < 1e-3
    ((lo, hi),) = b.stable_ranges()
    assert (lo, hi) == pytest.approx((grazing.value, fold.value), abs=1e-9)
    # the part between the fold and the tangency is unstable, multipliers growing
    unstable = [p for p in b.points if p.value > tangency.value and p.stable is False]
    assert unstable and max(p.max_abs_multiplier for p in unstable) > 10
    # a point of the stable part, solved again from scratch by floquet()
    inside = b.point_near(5.5)
    f = floquet(b.model.replace(Vb=inside.value), guess=inside.state, periods=4)
    assert f.max_abs_multiplier == pytest.approx(inside.max_abs_multiplier, rel=1e-8)
    parts = [(p.start, p.end, p.stable) for p in b.parts()]
    assert parts == [("grazing", "fold", True), ("fold", "tangency", False)]
    assert set(b.as_dict()["parts"][0]) == {"range", "stable", "from", "to", "lower", "upper"}


def test_the_periodic_branch_loses_stability_at_a_neimark_sacker_point_near_omega1():
    b = continue_branch(periodic_response(Model(Vb=3.0)), "Vb", 1.0, 6.3)
    (ns,) = [s for s in b.special if s.kind == "neimark_sacker"]
    assert ns.stable_before is True and ns.stable_after is False
    assert 0.9 < ns.frequency < 1.1  # omega1 = 1, modulo Omega = 4
    band = floquet_band(None, "Vb", 1.0, 9.0)
    (edge,) = [e for e in band.edges if e.kind == "neimark_sacker"]
    assert abs(edge.value - ns.value) <= edge.accuracy + ns.accuracy
    assert edge.frequency == pytest.approx(ns.frequency, rel=1e-3)
    (tangency,) = [e for e in band.edges if e.kind == "tangency"]
    end = b.special[-1]
    assert end.kind == "tangency"
    assert abs(end.value - tangency.value) <= end.accuracy + tangency.accuracy


def test_a_branch_rejects_a_start_outside_its_range():
    with pytest.raises(ValueError, match="outside"):
        continue_branch(periodic_response(Model(Vb=3.0)), "Vb", 4.0, 6.0)
    with pytest.raises(ValueError, match="param"):
        continue_branch(periodic_response(Model(Vb=3.0)), "Vbelt", 1.0, 6.0)
