"""``continue_branch`` of the paper's model from a point of its branch (issue 39: it took a
periodic response only; another model's branch point continued already).

A forced `Branch`'s point (`beltmdsm.continuation.forced.BranchPoint`) carries the model
at its value and its ``k``: ``continue_branch(b.points[-1], ...)`` continues ``b`` from
its end, ``continue_branch(b.point_near(s.value), ...)`` from a special point. Two
pieces must be the one branch: their special points the whole's, each within the
locating accuracies, and every point of theirs a response of the whole branch.

The error model of the last: each point is the period map's fixed point to the
corrector's residual ``NEWTON_TOL`` of its scale ``1 + max|x|``, its map integrated to
`beltmdsm.periodic.base.RTOL`; the response solved again at the point's value from
the whole branch's nearest point has as much error; the states differ by at most twice
the sum over the smallest singular value of ``dP/dx - I`` (the conditioning of the
fixed point).
"""

from dataclasses import replace

import numpy as np
import pytest

from beltmdsm import Model, branch, periodic_response
from beltmdsm.branches import continue_branch
from beltmdsm.continuation.settings import CYCLE_SETTINGS, ContinuationSettings
from beltmdsm.periodic.base import RTOL
from beltmdsm.periodic.cycle import cycle
from beltmdsm.periodic.family import MapFamily
from beltmdsm.periodic.newton import NEWTON_TOL, fixed_point

#: The docstring's branch (`beltmdsm.branches.branch`): a Neimark-Sacker point at Vb = 5.44991
MODEL = dict(beta1=0.3, Vb=5.4)
#: Long steps (about ten points a piece): the test's cost
COARSE = ContinuationSettings(step_first=0.1, step_max=1.0)


@pytest.fixture(scope="module")
def whole():
    return branch(Model(**MODEL), lo=5.4, hi=5.5, settings=COARSE)


def test_two_pieces_from_a_branch_point_are_the_whole_branch(whole):
    m = Model(**MODEL)
    first = branch(m, lo=5.4, hi=5.43, settings=COARSE)
    more = continue_branch(first.points[-1], "Vb", 5.43, 5.5, settings=COARSE)
    assert more.kind == "forced" and more.model["Vb"] == 5.43 and more.periods == 1
    assert more.value_range() == [5.43, 5.5]
    # the special points of the pieces, less the joint's range ends, are the whole's
    joined = first.special[:-1] + more.special[1:]
    assert [s.kind for s in joined] == [s.kind for s in whole.special]
    assert [s.kind for s in whole.special] == ["range", "neimark_sacker", "range"]
    for a, b in zip(joined, whole.special):
        assert abs(a.value - b.value) <= a.accuracy + b.accuracy + 1e-12
    # every point of the pieces lies on the whole branch (module docstring)
    family = MapFamily(m, "Vb")
    for q in first.points + more.points:
        at = fixed_point(family(q.value), whole.point_near(q.value).state)
        scale = 1.0 + float(np.max(np.abs(q.state)))
        sigma = np.linalg.svd(at.image.jacobian - np.eye(q.state.size), compute_uv=False)[-1]
        tol = 2 * (NEWTON_TOL + RTOL) * scale / sigma
        assert np.max(np.abs(at.state - q.state)) <= tol, (q.value, at.state - q.state, tol)
    assert whole.points[-1].value == more.points[-1].value == 5.5
    assert whole.points[-1].state == pytest.approx(more.points[-1].state, abs=1e-9)


def test_a_branch_continues_from_its_point_near_a_special_point(whole):
    ns = whole.special[1]
    near = whole.point_near(ns.value)
    again = continue_branch(near, "Vb", 5.4, 5.5, settings=COARSE)
    assert again.model["Vb"] == near.value
    assert [s.kind for s in again.special] == ["range", "neimark_sacker", "range"]
    assert abs(again.special[1].value - ns.value) <= again.special[1].accuracy + ns.accuracy


def test_a_branch_of_cycles_continues_from_its_end():
    """A point of a branch of self-excited cycles (`beltmdsm.cycles.continuation.CyclePoint`)
    carries its model too: its cycle is shot again there and continued. Stribeck's
    stick-slip cycle at Vb = 1.5 (the docstring of `beltmdsm.branches.continue_branch`):
    every point of the second piece is the cycle shot at its value from the whole
    branch's nearest point, to twice the shooting's residual and integration over the
    distance of its nontrivial multipliers from 1 (the fixed point's conditioning)."""
    coarse = replace(CYCLE_SETTINGS, step_first=0.1, step_max=1.0)
    m = Model(friction="stribeck", alpha=0.0, Vb=1.5)
    start = periodic_response(m)
    whole = continue_branch(start, "Vb", 1.5, 1.52, settings=coarse)
    first = continue_branch(start, "Vb", 1.5, 1.51, settings=coarse)
    more = continue_branch(first.points[-1], "Vb", 1.51, 1.52, settings=coarse)
    assert more.kind == "cycle" and more.model["Vb"] == 1.51
    assert more.value_range() == [1.51, 1.52]
    assert [s.kind for s in more.special] == ["range", "range"]
    for q in more.points:
        near = whole.point_near(q.value)
        ref = cycle(m.replace(Vb=q.value), guess=near.state, period=near.period)
        scale = 1.0 + float(np.max(np.abs(q.state)))
        tol = 2 * (NEWTON_TOL + RTOL) * scale / float(np.min(np.abs(1.0 - q.multipliers)))
        assert np.max(np.abs(ref.state - q.state)) <= tol, (q.value, ref.state - q.state, tol)
        assert abs(ref.period - q.period) <= tol
