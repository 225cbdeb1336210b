"""Figures of the results: matplotlib, imported only when a figure is drawn.

Each function draws one result on matplotlib axes (new ones where ``ax`` is None) and
returns the axes; the results' ``plot`` methods call them. Every axis names its
quantity and its unit (the parameter table's units, ``beltmdsm.generated.parameters``,
with the units each contact law gives, ``LAW_UNITS``); each symbol has one spelling: a
state as the model's tables name it (`beltmdsm.state_names`: the paper's ``X1'`` its
tangential velocity, ``Vr = X1' - Vb`` the relative one; belt_1dof's ``x_dot``). Special points
carry the labels of the continuation literature (`beltmdsm._display.LABELS`: NS, PD,
LP, GR, BP, HB, SL), each kind in a colour of its own (`KIND_COLOURS`); every figure
has a legend and a title saying which response or run it draws and at which point of
the model; a multiplier's modulus is drawn on a log scale. The lines drawn are the
result's own arrays (tests/beltmdsm/test_plotting.py reads them back), so a figure
shows what the result holds and nothing recomputed.

The labels' text is `beltmdsm.plot_labels` (re-exported here); a branch's lines and
special points, which another model's branch draws too, `beltmdsm.branch_lines`
(``KIND_COLOURS`` re-exported here).

The results are taken as they are (typed ``Any``): this module sits below the analyses
in the layers of the package (tests/test_layers.py) and imports none of them.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from . import state_names
from ._display import LABELS
from .branch_lines import KIND_COLOURS, draw_branch, new_axes
from .plot_labels import (
    STATE,
    _model_of,
    _state_rows,
    axis_label,
    observable_label,
    response_name,
    unit,
)

__all__ = [
    "unit",
    "axis_label",
    "simulation",
    "band",
    "branch",
    "coexistence",
    "floquet_map",
    "basins",
    "observable_label",
    "response_name",
    "KIND_COLOURS",
    "STATE",
]


def simulation(sim: Any, ax: Any = None, kind: str = "time", variable: str | None = None) -> Any:
    """A run (`beltmdsm.simulation.Simulation`, or another model's
    `beltmdsm.oscillator.hybrid.Trajectory`).

    ``kind="time"``: ``variable`` (a state of the run's model, named as its tables name
    it, `beltmdsm.state_names.columns`, e.g. ``X1``, ``X1'``, ``X2``, ``X2'`` of the
    paper's, or as the model names it; or, for a run of the paper's model,
    ``friction`` or ``normal_force``, the forces per unit mass) against time, the samples
    of the run. ``kind="friction"`` (the paper's model): the friction loop (Fig. 3b),
    friction per unit mass against ``Vr = X1' - Vb``, over the steady window
    (``sim.window``).

    Parameters
    ----------
    sim : beltmdsm.simulation.Simulation or beltmdsm.oscillator.hybrid.Trajectory
        the run
    ax : matplotlib.axes.Axes, optional
        where to draw; new axes where None
    kind : {"time", "friction"}
    variable : str, optional
        what ``kind="time"`` draws; default the rate of the model's first coordinate
        (``X1'`` of the paper's)

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ValueError
        if ``kind`` or ``variable`` is none of the above.

    See Also
    --------
    beltmdsm.simulation.simulate

    Examples
    --------
    One line holding every sample of the run, axes named with their units:

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from beltmdsm import Model, simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> ax = simulation(sim)
    >>> ax.get_xlabel(), ax.get_ylabel(), len(ax.lines)
    ('t [s]', "X1' [m/s]", 1)
    >>> bool(len(ax.lines[0].get_xdata()) == sim.t.size)
    True
    >>> simulation(sim, kind="friction").get_xlabel()
    "Vr = X1' - Vb [m/s]"
    """
    model = _model_of(sim)
    rows = _state_rows(model)
    forces = [f for f in ("friction", "normal_force") if hasattr(sim, f)]
    rate = state_names.rate_column(model)
    ax = new_axes(ax)
    if kind == "time":
        variable = rate if variable is None else variable
        if variable in forces:
            u, y = "m/s^2", getattr(sim, variable)
        else:
            try:
                i = state_names.index(model, variable)
            except ValueError:
                raise ValueError(
                    f"variable must be one of {', '.join([*rows, *forces])}; got {variable!r}"
                ) from None
            variable = state_names.columns(model)[i]
            u, y = rows[variable][0], sim.y[i]
        ax.plot(sim.t, y, lw=0.8, label=variable)
        ax.set_xlabel(axis_label("t", "s"))
        ax.set_ylabel(axis_label(variable, u))
    elif kind == "friction" and "friction" in forces:
        w = sim.window
        ax.plot(sim.y[rows[rate][1]][w] - sim.params["Vb"], sim.friction[w], lw=0.6,
                label="friction loop, steady window")  # fmt: skip
        ax.set_xlabel(axis_label(f"Vr = {rate} - Vb", "m/s"))
        ax.set_ylabel(axis_label("friction per unit mass", "m/s^2"))
    elif kind == "friction":
        raise ValueError("kind='friction' needs a run that holds its friction force")
    else:
        raise ValueError(f"kind must be 'time' or 'friction'; got {kind!r}")
    t_end = sim.settings.t_end if hasattr(sim, "settings") else sim.t[-1]
    ax.set_title(f"a run to t = {t_end:g} s: {model!r}", fontsize=8)
    ax.legend(loc="best", fontsize="small")
    return ax


def band(result: Any, ax: Any = None) -> Any:
    """A Floquet band (`beltmdsm.continuation.band_result.Band`): the largest multiplier's modulus
    at each evaluated value, the unit circle's 1, the unstable ranges shaded and each
    edge marked with its label.

    Parameters
    ----------
    result : beltmdsm.continuation.band_result.Band
        the band
    ax : matplotlib.axes.Axes, optional
        where to draw; new axes where None

    Returns
    -------
    matplotlib.axes.Axes

    See Also
    --------
    beltmdsm.continuation.band.floquet_band

    Examples
    --------
    The band of ``beta1 = 0.3`` over 5.2-5.8 m/s has one edge, a Neimark-Sacker one,
    and one unstable range shaded:

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from beltmdsm import Model, floquet_band
    >>> ax = band(floquet_band(Model(beta1=0.3), "Vb", 5.2, 5.8, points=4))
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('Vb [m/s]', 'max |mu| [-]')
    >>> [t.get_text() for t in ax.texts], len(ax.patches)
    (['NS'], 1)
    """
    ax = new_axes(ax)
    x, y = [], []
    for g in result.grid:
        # the line breaks (NaN) across a range with no periodic response
        if x and any(x[-1] <= a and b <= g.value for a, b in result.no_periodic_response):
            x.append(np.nan), y.append(np.nan)
        x.append(g.value), y.append(g.max_abs_multiplier)
    ax.plot(x, y, ".-", color="tab:blue", label="max |mu|")
    ax.axhline(1.0, color="0.5", lw=0.8)
    for i, (a, b) in enumerate(result.unstable):
        ax.axvspan(a, b, color="0.85", lw=0, label="unstable or absent" if i == 0 else None)
    for e in result.edges:
        ax.axvline(e.value, color=KIND_COLOURS.get(e.kind, "0.3"), lw=1)
        ax.annotate(LABELS.get(e.kind, e.kind), (e.value, 1.0), xytext=(2, 4),
                    textcoords="offset points", fontsize=8)  # fmt: skip
    ax.set_yscale("log")
    ax.set_xlabel(axis_label(result.param, unit(result.param, result.model)))
    ax.set_ylabel(axis_label("max |mu|", "1"))
    ax.set_title(f"the {response_name(result.periods)} response: {result.model!r}", fontsize=8)
    ax.legend(loc="best", fontsize="small")
    return ax


def branch(
    result: Any, ax: Any = None, observable: str | None = None, labels: bool = True,
    colour: str = "tab:blue", name: str | None = None,
) -> Any:  # fmt: skip
    """A bifurcation diagram (`beltmdsm.continuation.branch.Branch`): ``observable`` (a
    column of ``result.observables()``) against the parameter; stable parts solid,
    unstable dashed, grazing dotted; the special points marked with their labels.

    Parameters
    ----------
    result : beltmdsm.continuation.branch.Branch
        the branch
    ax : matplotlib.axes.Axes, optional
        where to draw; new axes where None
    observable : str, optional
        a column of ``result.observables()``; default the amplitude of the rate of the
        model's first coordinate (``X1'_amplitude`` of the paper's)
    labels : bool
        whether to write the special points' labels
    colour : str
        the branch's colour
    name : str, optional
        the response's name, before each line's label

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ValueError
        if ``observable`` is not a column of the branch's observables.

    See Also
    --------
    beltmdsm.continuation.branch.branch, beltmdsm.plotting.observable_label

    Examples
    --------
    The branch of ``beta1 = 0.3`` loses stability at a Neimark-Sacker point: a solid
    line, then a dashed one, and the point marked NS:

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from beltmdsm import Model
    >>> from beltmdsm import branch as continue_
    >>> ax = branch(continue_(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6))
    >>> [(line.get_gid(), line.get_linestyle()) for line in ax.lines[:2]]
    [('branch:stable:0', '-'), ('branch:unstable:1', '--')]
    >>> ax.get_ylabel(), [t.get_text() for t in ax.texts]
    ("X1' amplitude [m/s]", ['NS'])
    """
    ax = new_axes(ax)
    table = result.observables()
    observable = observable or f"{state_names.rate_column(result.model)}_amplitude"
    if observable not in table or observable == result.param:
        raise ValueError(
            f"observable must be one of {', '.join(list(table)[1:])}; got {observable!r}"
        )
    x, y = table[result.param], table[observable]
    stable = [p.stable for p in result.points]
    draw_branch(ax, x, y, stable, result.special, labels=labels, colour=colour, name=name)
    ax.set_xlabel(axis_label(result.param, unit(result.param, result.model)))
    ax.set_ylabel(observable_label(observable, result.model))
    ax.set_title(f"{name or result.response}: {result.model!r}", fontsize=8)
    ax.legend(loc="best", fontsize="small")
    return ax


def coexistence(result: Any, ax: Any = None, observable: str | None = None) -> Any:
    """Where stable responses coexist (`beltmdsm.multistability.coexistence.Coexistence`): each
    response's branch as in `branch`, one colour each, the coexistence ranges shaded.

    Parameters
    ----------
    result : beltmdsm.multistability.coexistence.Coexistence
        the responses found and where they coexist
    ax : matplotlib.axes.Axes, optional
        where to draw; new axes where None
    observable : str, optional
        as in `branch`

    Returns
    -------
    matplotlib.axes.Axes

    See Also
    --------
    beltmdsm.multistability.coexistence.coexistence

    Examples
    --------
    With no response found nothing is drawn, over the result's range:

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from beltmdsm import Model
    >>> from beltmdsm.multistability.coexistence import Coexistence
    >>> ax = coexistence(Coexistence("Vb", 1.0, 2.0, Model(), [], [], [], [], wall_s=0.1))
    >>> len(ax.lines), tuple(float(v) for v in ax.get_xlim())
    (0, (1.0, 2.0))
    """
    ax = new_axes(ax)
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown"]
    for i, r in enumerate(result.responses):
        branch(r.branch, ax, observable, colour=colours[i % len(colours)], name=r.name)
    for i, c in enumerate(result.ranges):
        ax.axvspan(*c.range, color="0.9", lw=0, zorder=0,
                   label="stable responses coexist" if i == 0 else None)  # fmt: skip
    ax.set_xlim(result.lo, result.hi)
    ax.set_title(f"stable responses along {result.param}: {result.model!r}", fontsize=8)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize="small")
    return ax


def floquet_map(result: Any, ax: Any = None, linear: bool = True) -> Any:
    """A Floquet map (`beltmdsm.continuation.map_result.FloquetMap`): shaded where no
    stable periodic response is found, row by row; the boundary curves coloured by kind
    (`KIND_COLOURS`) and labelled; hatched blue (``linear``): where the paper's linear
    analysis says unstable on the same rows.

    Parameters
    ----------
    result : beltmdsm.continuation.map_result.FloquetMap
        the map
    ax : matplotlib.axes.Axes, optional
        where to draw; new axes where None
    linear : bool
        whether to hatch the linear analysis's unstable region

    Returns
    -------
    matplotlib.axes.Axes

    See Also
    --------
    beltmdsm.continuation.floquet_map.floquet_map

    Examples
    --------
    Three rows of ``beta1`` draw one Neimark-Sacker curve through three points:

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from beltmdsm import floquet_map as compute
    >>> ax = floquet_map(compute(None, "Vb", 5.3, 5.7, "beta1", 0.29, 0.31, points=3))
    >>> [(line.get_label(), len(line.get_xdata())) for line in ax.lines]
    [('NS (neimark_sacker)', 3)]
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('Vb [m/s]', 'beta1 [-]')
    """
    ax = new_axes(ax)
    dy = (result.rows[1] - result.rows[0]) if result.rows.size > 1 else 1.0
    for value, intervals in zip(result.rows, result.unstable):
        for a, b in intervals:
            ax.fill_between([a, b], value - dy / 2, value + dy / 2, color="0.8", lw=0)
    if linear:
        # hatched row by row: the hatching is aligned on the canvas, so the rows join
        # into one region whose outline is the linear analysis's boundary
        hatch = {"facecolor": "none", "edgecolor": "tab:blue", "hatch": "////", "lw": 0}
        for value, intervals in zip(result.rows, result.linear):
            for a, b in intervals:
                ax.fill_between([a, b], value - dy / 2, value + dy / 2, alpha=0.5, **hatch)
        ax.fill_between([], [], alpha=0.5, label="paper's linear analysis: unstable", **hatch)
    seen = set()
    for c in result.curves:
        label = f"{LABELS.get(c.kind, c.kind)} ({c.kind})" if c.kind not in seen else None
        seen.add(c.kind)
        ax.plot(c.x, c.y, ".-", color=KIND_COLOURS.get(c.kind, "0.3"), lw=1.4, ms=3, label=label)
    ax.fill_between([], [], color="0.8", label="no stable periodic response")
    ax.set_xlim(*result.x_range)
    ax.set_ylim(*result.y_range)
    ax.set_xlabel(axis_label(result.x, unit(result.x, result.model)))
    ax.set_ylabel(axis_label(result.y, unit(result.y, result.model)))
    ax.set_title(f"where no stable periodic response is: {result.model!r}", fontsize=8)
    ax.legend(loc="best", fontsize="small")
    return ax


def basins(result: Any, ax: Any = None) -> Any:
    """A basin map (`beltmdsm.basin.basins.Basins`, or another model's
    `beltmdsm.oscillator.basins.Basins`): one colour per attractor (grey where none was
    identified), its stroboscopic points (another model's: its state) marked, a legend
    with its kind and share of the starts; the axes are the model's states.

    Parameters
    ----------
    result : beltmdsm.basin.basins.Basins or beltmdsm.oscillator.basins.Basins
        the basin map
    ax : matplotlib.axes.Axes, optional
        where to draw; new axes where None

    Returns
    -------
    matplotlib.axes.Axes

    See Also
    --------
    beltmdsm.basin.basins.basins

    Examples
    --------
    Nine starts at 3.88 m/s land on two attractors, one legend entry each:

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from beltmdsm import Model
    >>> from beltmdsm import basins as compute
    >>> b = compute(Model(Vb=3.88), points=3, x_lo=3.0, x_hi=7.0, y_lo=-8.5, y_hi=-4.5,
    ...             cache_dir=None)
    >>> ax = basins(b)
    >>> [t.get_text() for t in ax.get_legend().get_texts()]
    ['0: periodic 1T, 11.1% of the starts', '1: periodic 4T, 88.9% of the starts']
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('X1 [m]', "X1' [m/s]")
    """
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    ax = new_axes(ax)
    n = max(len(result.attractors), 1)
    colours = plt.get_cmap("tab10")(np.arange(n) % 10)
    cmap = ListedColormap(np.vstack([[0.85, 0.85, 0.85, 1.0], colours]))
    ax.pcolormesh(
        result.xs, result.ys, result.labels + 1, cmap=cmap, vmin=0, vmax=n,
        shading="nearest", alpha=0.5,
    )  # fmt: skip
    model = _model_of(result)
    rows = _state_rows(model)
    # the axes as the model names its states (the paper's Y1 is the column X1')
    x, y = (state_names.column(model, a) for a in (result.x, result.y))
    for a, c in zip(result.attractors, colours):
        # the stroboscopic points; an attractor of another model's map keeps its state
        points = a.points if hasattr(a, "points") else np.atleast_2d(a.state)
        ax.plot(
            points[:, rows[x][1]], points[:, rows[y][1]], "o", ms=6, mec="k", color=c,
            label=repr(a).removeprefix("BasinAttractor(").rstrip(")"),
        )  # fmt: skip
    # the mesh's cells reach half a step past the outer starts: clip to the starts
    ax.set_xlim(result.xs[0], result.xs[-1])
    ax.set_ylim(result.ys[0], result.ys[-1])
    ax.set_xlabel(axis_label(x, rows[x][0]))
    ax.set_ylabel(axis_label(y, rows[y][0]))
    ax.set_title(f"basins at {model!r}", fontsize=8)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize="small")
    return ax
