"""The paper's linear verdict on the rows of a Floquet map, for comparison.

`beltmdsm.continuation.floquet_map.floquet_map` evaluates `beltmdsm.generated.stability.is_stable`
(the options of the paper) on each row over `LINEAR_POINTS` values of ``x``, many rows
in one call.
"""

from __future__ import annotations

import numpy as np

from beltmdsm.generated import stability
from beltmdsm.generated._support import CHECKED

from ..intervals import runs as true_intervals

#: Points of ``x`` on which the linear analysis is evaluated per row.
LINEAR_POINTS = 2001
#: Rows of the linear analysis evaluated at once.
_LINEAR_BLOCK = 64


def _linear(rows, x, xs):
    """Per row, where the paper's linear analysis says unstable (`beltmdsm.generated.stability`).

    One evaluation for `_LINEAR_BLOCK` rows at a time: a call costs about as much as
    its 2001 points (0.15 ms), which for a 100-row map is 4 % of its time.
    """
    out = []
    for first in range(0, len(rows), _LINEAR_BLOCK):
        args = [row.arguments(stability.is_stable) for row in rows[first : first + _LINEAR_BLOCK]]
        block = {
            k: v if isinstance(v, str) else np.array([a[k] for a in args])[:, None]
            for k, v in args[0].items()
            if k != CHECKED  # the rows' values are stacked here: checked as a block
        }
        stable = np.asarray(stability.is_stable(**{**block, x: xs[None, :]}), bool)
        out += [[[float(a), float(b)] for a, b in true_intervals(xs, ~s)] for s in stable]
    return out
