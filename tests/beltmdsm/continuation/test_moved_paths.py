"""Every module and name issue 38 moved keeps a path that says where it went."""

import importlib
import sys
import warnings
from pathlib import Path

import pytest

from beltmdsm import Model

ROOT = Path(__file__).resolve().parents[3]
MOVED = {
    "beltmdsm.cycles.cycle": "beltmdsm.periodic.cycle",
    "beltmdsm.cycles.flow": "beltmdsm.periodic.cycle_flow",
    "beltmdsm.cycles.returns": "beltmdsm.periodic.cycle_returns",
    "beltmdsm.cycles.seed": "beltmdsm.starts.cycle_seed",
    "beltmdsm.periodic.cycle_seed": "beltmdsm.starts.cycle_seed",
    "beltmdsm.continuation.branch_parts": "beltmdsm.continuation.branch_result",
    "beltmdsm.continuation.map_linear": "beltmdsm.continuation.linear_verdict",
    "beltmdsm.periodic.general": "beltmdsm.periodic.general_map",
    "beltmdsm.periodic.normal": "beltmdsm.periodic.normal_orbit",
    "beltmdsm.periodic.tangential": "beltmdsm.periodic.closed_form",
    "beltmdsm.continuation.arclength": "beltmdsm.continuation.forced",
}


@pytest.mark.parametrize("old, new", sorted(MOVED.items()))
def test_an_old_module_path_is_the_new_module(old, new):
    # one mechanism for every old path, beltmdsm/_moved.py's finder: no file is left
    # at the old path, and the first import names the new one
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=f"{old} moved to {new}"):
        moved = importlib.import_module(old)
    assert moved is importlib.import_module(new)
    assert not ROOT.joinpath(*old.split(".")).with_suffix(".py").exists()


def test_old_names_are_the_new_ones():
    with warnings.catch_warnings():
        # the warning is test_an_old_module_path_is_the_new_module's (once per process)
        warnings.simplefilter("ignore", DeprecationWarning)
        from beltmdsm.continuation.arclength import BranchPoint, _Continuation
        from beltmdsm.periodic.tangential import TangentialMap
    from beltmdsm.continuation.forced import BranchPoint as point
    from beltmdsm.continuation.forced import ForcedProblem
    from beltmdsm.cycles.continuation import Continuation, CycleProblem
    from beltmdsm.periodic.closed_form import ClosedFormMap
    from beltmdsm.periodic.engines import ENGINES

    assert BranchPoint is point and _Continuation is ForcedProblem
    assert Continuation is CycleProblem
    assert TangentialMap is ClosedFormMap is ENGINES["closed_form"]


def test_the_cycle_step_bounds_name_their_new_home():
    import beltmdsm.cycles.continuation as module

    with pytest.warns(DeprecationWarning, match="CYCLE_SETTINGS.step_max"):
        assert module.STEP_MAX == 0.2
    with pytest.raises(AttributeError):
        module.STEP_MIDDLE  # noqa: B018


def test_a_cycle_through_the_forced_entry_names_the_one_that_takes_it():
    from beltmdsm.continuation.branch import branch

    with pytest.raises(ValueError, match="beltmdsm.branches.branch"):
        branch(Model(friction="stribeck", alpha=0.0), lo=1.9, hi=2.1)
