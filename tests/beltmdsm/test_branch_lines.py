"""The lines of a bifurcation diagram have one home (issue 39: another model's
``Branch.plot`` imported beltmdsm.plotting's private helpers, ``_STYLES``, ``_axes``,
``_special_markers``, ``_stability_runs``): `beltmdsm.branch_lines`, which both
`beltmdsm.plotting.branch` and `beltmdsm.continuation.oscillator_branch` use.

Every ``from ... import`` in beltmdsm/ is read (module level or inside a function);
none takes an underscore name from beltmdsm.plotting or beltmdsm.branch_lines. The
figures themselves are those of before (their lines, styles, colours, labels and
markers: tests/beltmdsm/test_plotting.py and test_oscillator_forced_branch.py).
"""

import ast
from pathlib import Path

import matplotlib
import pytest

import beltmdsm
from beltmdsm import branch_lines, plotting

ROOT = Path(beltmdsm.__file__).parent
HOMES = ("beltmdsm.plotting", "beltmdsm.branch_lines")


def _imported_from(path: Path, node: ast.ImportFrom) -> str:
    """The absolute module of a ``from ... import`` in ``path``."""
    if not node.level:
        return node.module or ""
    package = path.relative_to(ROOT.parent).with_suffix("").parts[: -node.level]
    return ".".join([*package, *([node.module] if node.module else [])])


def test_no_module_imports_a_private_name_of_the_plot_helpers():
    private = []
    for path in sorted(ROOT.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and _imported_from(path, node) in HOMES:
                private += [f"{path}: {a.name}" for a in node.names if a.name.startswith("_")]
    assert private == []


def test_the_helpers_have_one_home():
    # plotting re-exports the public colours (a public name keeps its path)
    assert plotting.KIND_COLOURS is branch_lines.KIND_COLOURS
    assert not hasattr(plotting, "_STYLES") and not hasattr(plotting, "_special_markers")


def test_draw_branch_draws_a_line_per_run_of_stability_and_marks_special_points():
    matplotlib.use("Agg")
    from types import SimpleNamespace

    ax = branch_lines.new_axes(None)
    special = [SimpleNamespace(kind="range", value=0.0), SimpleNamespace(kind="fold", value=2.1)]
    x, y = [0.0, 1.0, 2.0, 3.0], [1.0, 2.0, 3.0, 4.0]
    branch_lines.draw_branch(ax, x, y, [True, None, False, False], special, name="T")
    lines = ax.get_lines()
    assert [(ln.get_gid(), ln.get_linestyle(), ln.get_label()) for ln in lines[:3]] == [
        ("branch:stable:0", "-", "T stable"),
        ("branch:grazing:1", ":", "T grazing"),
        ("branch:unstable:2", "--", "T unstable"),
    ]
    # consecutive runs share their boundary point: the line is unbroken
    assert [list(ln.get_xdata()) for ln in lines[:3]] == [[0.0, 1.0], [1.0, 2.0], [2.0, 3.0]]
    # the fold marked at the nearest point (x = 2), the range's end not marked
    (marker,) = lines[3:]
    assert list(marker.get_xdata()) == [2.1] and list(marker.get_ydata()) == [3.0]
    assert marker.get_color() == branch_lines.KIND_COLOURS["fold"]
    assert [t.get_text() for t in ax.texts] == ["LP"]


@pytest.mark.parametrize("stable", [[], [True]])
def test_stability_runs_of_short_branches(stable):
    assert branch_lines.stability_runs(stable) == ([(0, 1, True)] if stable else [])
