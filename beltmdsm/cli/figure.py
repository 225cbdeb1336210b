"""The figures the commands draw (``--png FILE``): matplotlib, imported when drawing.

The drawing is the results' own (`beltmdsm.plotting`, the ``plot`` methods); here a
figure is made, drawn on, titled and written to a PNG.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .. import plotting
from ..continuation.map_result import FloquetMap
from ..plotting import KIND_COLOURS

__all__ = ["floquet_map", "draw_floquet_map", "KIND_COLOURS", "save"]


def save(
    draw: Callable[[Any], Any], path: str, title: str, panels: int = 1, size: tuple = (7, 4.5)
) -> None:
    """Call ``draw(ax)`` on new axes (``draw(axes)``, a list, for ``panels > 1`` side by
    side), add a legend to each that labels something, the title, and write the figure
    to the PNG ``path`` (Agg backend: no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, panels, figsize=(size[0] * (1 + 0.6 * (panels - 1)), size[1]))
    try:
        draw(axes if panels == 1 else list(axes))
        for ax in [axes] if panels == 1 else axes:
            if ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=7, loc="best")
        fig.suptitle(title, fontsize=9)
        fig.tight_layout()
        fig.savefig(path, dpi=120)
    finally:
        plt.close(fig)


def draw_floquet_map(ax: Any, result: FloquetMap, linear: bool = True) -> None:
    """Draw a map on matplotlib axes ``ax`` (`beltmdsm.plotting.floquet_map`, which
    ``FloquetMap.plot`` calls; kept here, with its arguments in this order, for the
    notebooks that call it)."""
    plotting.floquet_map(result, ax, linear)


def floquet_map(result: FloquetMap, path: str) -> None:
    """Draw a map to a PNG (`beltmdsm.plotting.floquet_map`, with a legend and a title)."""
    save(
        lambda ax: plotting.floquet_map(result, ax),
        path,
        f"Floquet map ({result.model.contact}, tension {result.model.tension})",
    )
