"""The lines of a bifurcation diagram, drawn alike for every model's branch.

`beltmdsm.plotting.branch` (a `beltmdsm.continuation.branch_result.Branch`) and
another model's branch (`beltmdsm.continuation.oscillator_branch.OscillatorBranch.plot`)
draw a branch with `draw_branch`: one line per run of equal stability
(`stability_runs`), stable solid, unstable dashed, grazing dotted (`STYLES`), each with
the ``gid`` ``branch:<stability>:<n>``; each special point inside the range marked at
the branch's nearest point in its kind's colour (`KIND_COLOURS`), with its label
(`beltmdsm._display.LABELS`). The axes' words stay with each caller. matplotlib is
imported only where `new_axes` makes axes.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._display import LABELS

__all__ = ["KIND_COLOURS", "STYLES", "new_axes", "stability_runs", "draw_branch"]

#: The colour of each kind of special point or boundary curve.
KIND_COLOURS = {
    "neimark_sacker": "tab:red",
    "period_doubling": "tab:purple",
    "fold": "tab:orange",
    "grazing": "tab:green",
    "tangency": "k",
    "branch_point": "tab:brown",
    "hopf": "tab:pink",
    "stick_onset": "tab:cyan",
}
#: Line styles of a branch by stability: stable, unstable, grazing (no multiplier).
STYLES = {True: "-", False: "--", None: ":"}


def new_axes(ax: Any) -> Any:
    """``ax``, or new matplotlib axes where it is None.

    See Also
    --------
    draw_branch : draws on them.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> ax = new_axes(None)
    >>> new_axes(ax) is ax
    True
    """
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.subplots()[1]


def stability_runs(stable: list) -> list[tuple[int, int, Any]]:
    """``(start, stop, stable)`` of the runs of equal stability; consecutive runs share
    their boundary point, so that the drawn line is unbroken.

    See Also
    --------
    draw_branch : one line per run.

    Examples
    --------
    >>> stability_runs([True, True, False, None])
    [(0, 3, True), (2, 4, False), (3, 4, None)]
    """
    runs, start = [], 0
    for i in range(1, len(stable) + 1):
        if i == len(stable) or stable[i] != stable[start]:
            runs.append((start, min(i + 1, len(stable)), stable[start]))
            start = i
    return runs


def draw_branch(
    ax: Any, x: Any, y: Any, stable: list, special: Any, *, labels: bool = True,
    colour: str = "tab:blue", name: str | None = None,
) -> None:  # fmt: skip
    """Draw a branch's ``y`` against ``x`` on ``ax`` (module docstring).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    x, y : array_like (k,)
        The parameter and the observable at the branch's points.
    stable : list of bool or None
        Each point's stability (None: grazing).
    special : list of SpecialPoint
        The branch's special points; those of a kind without a label (the range's
        ends) are not marked.
    labels : bool
        Whether to write the special points' labels.
    colour : str
        The lines' colour.
    name : str, optional
        The response's name, before each line's label.

    See Also
    --------
    beltmdsm.plotting.branch : the paper's branch, its axes named.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from types import SimpleNamespace
    >>> ax = new_axes(None)
    >>> ns = SimpleNamespace(kind="neimark_sacker", value=1.5)
    >>> draw_branch(ax, [1.0, 1.5, 2.0], [0.1, 0.2, 0.3], [True, False, False], [ns])
    >>> [(line.get_gid(), line.get_linestyle()) for line in ax.lines]
    [('branch:stable:0', '-'), ('branch:unstable:1', '--'), (None, 'None')]
    >>> [t.get_text() for t in ax.texts]
    ['NS']
    """
    for n, (a, b, s) in enumerate(stability_runs(stable)):
        tag = {True: "stable", False: "unstable", None: "grazing"}[s]
        ax.plot(x[a:b], y[a:b], STYLES[s], color=colour,
                label=f"{name} {tag}" if name else tag, gid=f"branch:{tag}:{n}")  # fmt: skip
    for s in special:
        if s.kind not in LABELS or not len(x):
            continue
        i = int(np.argmin(np.abs(np.asarray(x) - s.value)))
        mark = KIND_COLOURS.get(s.kind, "0.3")
        ax.plot([s.value], [y[i]], "o", color=mark, ms=5, zorder=3)
        if labels:
            ax.annotate(LABELS[s.kind], (s.value, y[i]), xytext=(3, 3),
                        textcoords="offset points", fontsize=8, color=mark)  # fmt: skip
