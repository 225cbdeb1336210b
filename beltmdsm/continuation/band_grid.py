"""A band's edges from its evaluated neighbours: classified, merged, cut into ranges.

Between two values of `beltmdsm.continuation.band.floquet_band` whose evaluations
differ, the change is an `Edge` (a multiplier crossing, or a grazing where the switch
structure changes); edges closer than the band's tolerance merge into one
(`_merge_close`), and the evaluated values between edges become the band's ranges
(`_runs`).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..periodic.closed_form import largest_sliding_velocity
from .band_result import Edge
from .edges import multiplier_kind

#: Which edge of a group closer than the tolerance names the group: an exact grazing
#: point, then an end of the response, then a multiplier crossing.
_MERGE_ORDER = (
    "grazing",
    "tangency",
    "fold",
    "existence",
    "unclassified",
    "period_doubling",
    "neimark_sacker",
)


def _merge_close(edges, tol):
    """Edges closer than ``tol`` to the first of their group, merged into one.

    At that tolerance they cannot be told apart. The merged edge takes the outer
    sides (below from the first, above from the last), the union of the brackets and
    the value, kind and frequency of the first of the group in `_MERGE_ORDER`; its
    accuracy covers the union.

    Returns
    -------
    edges : list of Edge
    hidden : list of (lo, hi)
        The merged brackets: the values evaluated strictly inside do not enter the
        ranges (their changes are below the resolution).
    """
    groups = []
    for e in edges:
        if groups and e.value - groups[-1][0].value <= tol:
            groups[-1].append(e)
        else:
            groups.append([e])
    out, hidden = [], []
    for group in groups:
        if len(group) == 1:
            out.append(group[0])
            continue
        lead = min(group, key=lambda e: _MERGE_ORDER.index(e.kind))
        bracket = (min(e.bracket[0] for e in group), max(e.bracket[1] for e in group))
        others = ", ".join(f"{e.kind} at {e.value:.9g}" for e in group if e is not lead)
        out.append(
            dataclasses.replace(
                lead,
                bracket=bracket,
                accuracy=max(lead.value - bracket[0], bracket[1] - lead.value),
                unstable_below=group[0].unstable_below,
                unstable_above=group[-1].unstable_above,
                detail="; ".join(
                    filter(None, [lead.detail, f"with {others}, closer than tol = {tol:g}"])
                ),
            )
        )
        hidden.append(bracket)
    return out, hidden


def _same_structure(fa, fb):
    return (
        fa is not None
        and fb is not None
        and fa.stable is not None
        and fb.stable is not None
        and (fa.n_reversals, fa.n_sticks) == (fb.n_reversals, fb.n_sticks)
    )


def _multiplier_step(a, fa, b, fb, tol):
    """The next value for ``|mu| = 1`` within one structure: the secant of ``log|mu|``.

    ``log|mu|`` is smooth there (it is ``k T`` times the growth rate), so the secant
    converges in a few steps; kept inside the bracket, a tolerance away from its ends
    so that the bracket shrinks.
    """
    ga, gb = math.log(fa.max_abs_multiplier), math.log(fb.max_abs_multiplier)
    if ga == gb:
        return None
    m = a - ga * (b - a) / (gb - ga)
    return min(max(m, a + tol / 3), b - tol / 3)


def _state(f):
    """What a value's evaluation says: not found, or (structure, verdict)."""
    return None if f is None else (f.n_reversals, f.n_sticks, f.verdict)


def _band_kind(old_kind, fa, fb):
    """The bifurcation of an edge between two responses, from the band's classification.

    A ``multiplier`` edge takes the kind of the critical multiplier of the unstable
    side (the largest in modulus); a change of structure is a grazing.
    """
    if old_kind != "multiplier":
        return "grazing", None
    unstable = fa if fa.stable is False else fb
    mu = unstable.multipliers[int(np.argmax(np.abs(unstable.multipliers)))]
    return multiplier_kind(mu, unstable.period)


def _edge(a, fa, b, fb, kind=None, accuracy=None):
    """The change between two responses closer than the tolerance, classified.

    ``kind``: the old kind, ``multiplier`` or ``grazing`` (found from the structures
    where not given); the new one by `_band_kind`. ``accuracy``: where the value is
    known better than the bracket says.
    """
    if kind is None:
        # a response that grazes has no multipliers (`Floquet.stable` None): the change
        # next to it is the grazing, never a multiplier's crossing
        same = (fa.n_reversals, fa.n_sticks) == (fb.n_reversals, fb.n_sticks)
        kind = "multiplier" if same and None not in (fa.stable, fb.stable) else "grazing"
    new_kind, frequency = _band_kind(kind, fa, fb)
    return Edge(
        0.5 * (a + b),
        new_kind,
        kind,
        (a, b),
        0.5 * (b - a) if accuracy is None else accuracy,
        frequency,
        fa is None or fa.stable is False,
        fb is None or fb.stable is False,
    )


def _unclassified_edge(a, fa, b, fb, why):
    """The end of a response between ``a`` and ``b`` (closer than the tolerance, found on
    one side only) that no continuation could classify: kind ``unclassified``."""
    return Edge(
        0.5 * (a + b),
        "unclassified",
        "existence",
        (a, b),
        0.5 * (b - a),
        None,
        fa is None or fa.stable is False,
        fb is None or fb.stable is False,
        f"the response ends between {a:.9g} and {b:.9g}; its continuation stops there "
        f"without classifying the end ({why})",
    )


def _runs(points, edges, flag, lo, hi):
    """Maximal ranges of the evaluated values where ``flag`` holds, cut at the edges."""
    out, start, previous = [], None, None
    cuts = sorted(e.value for e in edges)
    for v, f in points:
        if flag(f) and start is None:
            inside = [c for c in cuts if previous is not None and previous < c < v]
            start = inside[-1] if inside else (lo if previous is None else v)
        elif not flag(f) and start is not None:
            inside = [c for c in cuts if previous < c < v]
            out.append([start, inside[0] if inside else previous])
            start = None
        previous = v
    if start is not None:
        out.append([start, hi])
    return out


def _sliding_grazing(param, fa, fb):
    """The grazing point of the backward-sliding response between ``a`` and ``b``, or None.

    Where the side above slides backwards throughout (no switch in contact) and the
    side below does not, the sliding response stops at the belt speed equal to its
    largest velocity in contact; on the closed-form path it does not depend on ``Vb``.
    Only for ``param = "Vb"`` on that path; other parameters, and the general path
    (where the friction depends on the velocity), are bisected.
    """
    if (
        param != "Vb"
        or fb is None
        or fb.engine != "closed_form"
        or (fb.n_reversals, fb.n_sticks) != (0, 0)
        or (fa is not None and (fa.n_reversals, fa.n_sticks) == (0, 0))
    ):
        return None
    return largest_sliding_velocity(fb.response._engine)
