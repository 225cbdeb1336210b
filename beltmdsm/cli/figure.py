"""The figures the commands draw: ``floquet-map --png`` (matplotlib, imported when drawing)."""

from __future__ import annotations

from typing import Any

from ..analysis.floquet_map import FloquetMap

__all__ = ["floquet_map", "draw_floquet_map", "KIND_COLOURS"]

#: The colour of each kind of boundary curve (`beltmdsm.analysis.edges.KINDS`).
KIND_COLOURS = {
    "neimark_sacker": "tab:red",
    "period_doubling": "tab:purple",
    "fold": "tab:orange",
    "grazing": "tab:green",
    "tangency": "k",
}


def draw_floquet_map(ax: Any, result: FloquetMap, linear: bool = True) -> None:
    """Draw a map on matplotlib axes ``ax`` (typed Any: matplotlib is imported only when
    drawing): the exact unstable region and its curves by kind.

    Shaded: where no stable periodic response is found, row by row; lines: the boundary
    curves, coloured by kind (`KIND_COLOURS`); hatched blue (``linear``): where the paper's
    linear analysis says unstable on the same rows.
    """
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
        label = c.kind if c.kind not in seen else None
        seen.add(c.kind)
        ax.plot(c.x, c.y, ".-", color=KIND_COLOURS.get(c.kind, "0.3"), lw=1.4, ms=3, label=label)
    ax.fill_between([], [], color="0.8", label="no stable periodic response")
    ax.set_xlim(*result.x_range)
    ax.set_ylim(*result.y_range)
    ax.set_xlabel(result.x)
    ax.set_ylabel(result.y)


def floquet_map(result: FloquetMap, path: str) -> None:
    """Draw a map to a PNG (`draw_floquet_map`, with a legend and a title)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    draw_floquet_map(ax, result)
    ax.legend(fontsize=7, loc="best")
    ax.set_title(
        f"Floquet map ({result.model.contact}, tension {result.model.tension})", fontsize=9
    )
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
