"""The continuation problem interface and its one driver (issue 38 items 1, 2, 5).

A new problem (steady sliding, `beltmdsm.continuation.equilibrium`) is added by
implementing `beltmdsm.continuation.problem.Problem` alone, and the driver locates its
Hopf points: checked against the closed form of belt_1dof's Stribeck Hopf point
``v_s ln(g (mu_s - mu_k) / (2 beta omega v_s))`` and against the paper model's Hopf point
by the independent scan and Brent's method of `beltmdsm.cycles.hopf.hopf_point`.
"""

import ast
import math
from pathlib import Path

import pytest

from beltmdsm import Model
from beltmdsm.continuation.branch import branch
from beltmdsm.continuation.branch_parts import LOCATE_TOL, Branch
from beltmdsm.continuation.circle import Circle
from beltmdsm.continuation.driver import walk
from beltmdsm.continuation.equilibrium import EquilibriumProblem, equilibrium_branch
from beltmdsm.continuation.problem import Problem
from beltmdsm.continuation.settings import FORCED_SETTINGS, ContinuationSettings
from beltmdsm.cycles.branch import CycleBranch
from beltmdsm.cycles.hopf import hopf_point
from beltmdsm.oscillator.system import System

ROOT = Path(__file__).resolve().parents[3]


def test_the_equilibrium_problem_fills_in_the_interface_alone():
    """It imports no other problem and the driver knows it by no name."""
    source = ast.parse((ROOT / "beltmdsm/continuation/equilibrium.py").read_text())
    imported = {n.module for n in ast.walk(source) if isinstance(n, ast.ImportFrom)}
    assert not {"forced", "cycles", "cycles.continuation", "arclength"} & imported
    assert issubclass(EquilibriumProblem, Problem)
    driver = (ROOT / "beltmdsm/continuation/driver.py").read_text()
    assert "Equilibrium" not in driver and "Forced" not in driver and "Cycle" not in driver


def test_belt_1dof_hopf_point_against_its_closed_form():
    system = System("belt_1dof", friction="stribeck", Vb=1.5)
    p = system.params
    exact = p["v_s"] * math.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )
    b = equilibrium_branch(system, param="Vb", lo=0.5, hi=4.0)
    hopf = [s for s in b.special if s.kind == "hopf"]
    assert len(hopf) == 1 and b.kind == "equilibrium"
    assert abs(hopf[0].value - exact) <= max(hopf[0].accuracy, LOCATE_TOL)
    # at the Hopf point the pair is +- i omega1: the linear oscillator's frequency
    assert abs(hopf[0].frequency - p["omega1"]) < 1e-5
    assert (hopf[0].stable_before, hopf[0].stable_after) == (False, True)
    assert b.stable_ranges()[0][0] == pytest.approx(exact, abs=1e-6)


def test_paper_model_hopf_point_matches_the_scan():
    model = Model(friction="stribeck", alpha=0.0, Vb=1.5)
    b = equilibrium_branch(model, lo=1.0, hi=3.0)
    reference = hopf_point(model, "Vb", 1.0, 3.0)
    (found,) = [s for s in b.special if s.kind == "hopf"]
    assert abs(found.value - reference.value) <= LOCATE_TOL
    assert found.frequency == pytest.approx(reference.frequency, rel=1e-5)


def test_the_driver_locates_a_fold_of_the_circle():
    circle = Circle(-0.5, 1.5)
    points, special = walk(circle, *circle.start(0.0, direction=1.0))
    assert [s.kind for s in special] == ["fold", "range"]
    assert abs(special[0].value - 1.0) <= LOCATE_TOL and special[1].value == -0.5
    assert all(abs(q.u**2 + q.value**2 - 1) < 1e-12 for q in points)


@pytest.mark.parametrize(
    "kw, word",
    [({"step_min": 0.0}, "step_min"), ({"corrector_iter": 0}, "corrector_iter"),
     ({"step_first": 1.0}, "step bounds"), ({"easy": True}, "easy")],
)  # fmt: skip
def test_settings_are_checked_where_they_enter(kw, word):
    with pytest.raises(ValueError, match=word):
        ContinuationSettings(**kw)
    with pytest.raises(TypeError, match="settings must be a ContinuationSettings"):
        branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6, settings={"step_max": 0.1})


@pytest.mark.parametrize("analysis", ["floquet_band", "coexistence", "floquet_map"])
def test_every_continuation_takes_settings_checked_where_they_enter(analysis):
    import beltmdsm

    call = getattr(beltmdsm, analysis)
    args = ("Vb", 5.3, 5.6, "beta1", 0.3, 0.31) if analysis == "floquet_map" else ("Vb", 5.3, 5.6)
    with pytest.raises(TypeError, match="settings must be a ContinuationSettings"):
        call(Model(beta1=0.3), *args, settings=0.1)


def test_settings_reach_the_driver():
    """Shorter steps: more points, the same Neimark-Sacker point within its accuracy."""
    model = Model(beta1=0.3, Vb=5.3)
    default = branch(model, lo=5.3, hi=5.6)
    fine = branch(model, lo=5.3, hi=5.6, settings=ContinuationSettings(step_max=0.02))
    assert len(fine.points) > 2 * len(default.points)
    assert [s.kind for s in fine.special] == [s.kind for s in default.special]
    assert abs(fine.special[1].value - default.special[1].value) <= 2 * LOCATE_TOL
    assert FORCED_SETTINGS.step_max == 0.25


def test_one_branch_type_with_a_kind():
    circle_kinds = {Branch(param="p", periods=1, model=None, points=[], special=[]).kind}
    assert circle_kinds == {"forced"}
    made = CycleBranch("Vb", 1, None, [], [], None, "subcritical", 0.0)
    assert type(made) is Branch and made.kind == "cycle" and isinstance(made, CycleBranch)
    assert not isinstance(Branch("Vb", 1, None, [], []), CycleBranch)
    assert "issue 38" in CycleBranch.__doc__ and "Branch" in CycleBranch.__doc__
