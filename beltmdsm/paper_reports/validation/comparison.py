"""The analyses' unstable ranges against the runs from rest and against the Floquet band.

* `predicted_intervals`: each analysis of `ANALYSES`: the closed form of Eqs. (25),
  (28) for each ``V_hat`` reading and sign convention of Eq. (A4)
  (`beltmdsm.prediction.paper.paper_intervals`), and the consistent MDSM
  (`beltmdsm.prediction.scan.unstable_intervals`);
* `simulated_ranges`: where a sweep from rest shows the omega1 peak of X1' while the
  mass slides (Figs. 2b, 17-21), each edge within half a grid step (`SimulatedRanges`);
* `compare` (against the simulated ranges) and `compare_floquet` (against the exact
  Floquet band): the hulls paired edge by edge (`Edge`), and the length of the belt
  speeds where exactly one side is unstable (`disagreement_length`), as a `Comparison`;
* `summarize_edges`: the mean absolute error of the edges of one analysis' comparisons
  and the counts of misses and false alarms (`EdgeSummary`).

The rules are `DEFINITIONS` and `FLOQUET_DEFINITIONS` (`beltmdsm.paper_reports.validation.cases`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from ... import intervals
from ...continuation.band_result import Band
from ...model import Model
from ...prediction.mdsm import clip_acts
from ...prediction.paper import paper_intervals
from ...prediction.scan import unstable_intervals
from .cases import SLIDING, UNRESOLVED

#: How an analysis' prediction and its reference (the simulation or the Floquet band)
#: compare: both unstable somewhere ("paired"), only the reference ("miss"), only the
#: prediction ("false_alarm"), neither ("both_empty"), or no prediction to compare.
Status = Literal["paired", "miss", "false_alarm", "both_empty", "no_prediction"]


def regime_runs(vb: ArrayLike, regime: ArrayLike) -> list[tuple[str, float, float]]:
    """Runs of consecutive grid points with one label (a regime, or a flag as text).

    Returns ``[(label, first Vb, last Vb), ...]`` (`beltmdsm.intervals.label_runs`).
    """
    return [
        (label, float(vb[i]), float(vb[j]))
        for label, i, j in intervals.label_runs([str(r) for r in regime])
    ]


@dataclass(frozen=True)
class SimulatedRange:
    """One simulated omega1-peak range: a maximal run of sliding grid points with the peak.

    Attributes
    ----------
    first, last : float
        the first and the last grid point that show the peak
    lower, upper : float
        the edge estimates, half a step outside them (each within ± step/2)
    lower_censored, upper_censored : bool
        the edge is not observed: next to an excluded point, or (upper) at the top
        of the grid
    """

    first: float
    last: float
    lower: float
    upper: float
    lower_censored: bool
    upper_censored: bool


@dataclass(frozen=True)
class SimulatedRanges:
    """The simulated omega1-peak ranges of one sweep from rest (`simulated_ranges`).

    Attributes
    ----------
    ranges : list of SimulatedRange
        ascending; empty where no sliding point shows the peak
    excluded : list of (label, first Vb, last Vb)
        the runs of the excluded points: their regime (stick-slip, contact loss) or
        `UNRESOLVED`
    excluded_vb : list of float
        the belt speeds of the excluded points
    top : float
        the last grid point
    sliding_points : int
        how many resolved points slide
    """

    ranges: list[SimulatedRange]
    excluded: list[tuple[str, float, float]]
    excluded_vb: list[float]
    top: float
    sliding_points: int


def simulated_ranges(
    vb: ArrayLike,
    present: ArrayLike,
    regime: ArrayLike,
    step: float,
    resolved: ArrayLike | None = None,
) -> SimulatedRanges:
    """Simulated omega1-peak ranges of a sweep, with their edges (see `DEFINITIONS`).

    Parameters
    ----------
    vb : array_like
        the uniform grid ``step, 2 step, ...`` (ascending)
    present : array_like of bool
        ``omega1_peak_present`` of each point
    regime : array_like of str
        the regime of each point (`beltmdsm.run.summary.REGIMES`)
    step : float
    resolved : array_like of bool, optional
        ``resolved`` of each point (default: all True); an unresolved point is
        excluded like a stick-slip point, with the label `UNRESOLVED`

    Returns
    -------
    SimulatedRanges
    """
    vb = np.asarray(vb, float)
    present = np.asarray(present, bool)
    regime = np.asarray(regime).astype(str)
    if resolved is not None:
        resolved = np.asarray(resolved, bool)
        if resolved.shape != vb.shape:
            raise ValueError(
                f"resolved must hold one flag per grid point; got shape "
                f"{resolved.shape} for {vb.size} points"
            )
        regime = np.where(resolved, regime, UNRESOLVED)
    if vb.ndim != 1 or vb.size == 0 or np.any(np.diff(vb) <= 0):
        raise ValueError("vb must be a non-empty ascending 1-D grid")
    if not np.allclose(np.diff(vb), step, rtol=0, atol=1e-9 * step) or not math.isclose(
        vb[0], step, rel_tol=1e-9
    ):
        raise ValueError(f"vb must be the grid step, 2 step, ... with step = {step}")
    sliding = np.isin(regime, SLIDING)
    shows = present & sliding
    # Below the lowest grid point lies Vb = 0, not an excluded point.
    ranges = [
        SimulatedRange(
            first=float(vb[i]),
            last=float(vb[j]),
            lower=float(vb[i] - step / 2),
            upper=float(vb[j] + step / 2),
            lower_censored=bool(i > 0 and not sliding[i - 1]),
            upper_censored=bool(j == vb.size - 1 or not sliding[j + 1]),
        )
        for i, j in intervals.true_runs(shows)
    ]
    return SimulatedRanges(
        ranges=ranges,
        excluded=[run for run in regime_runs(vb, regime) if run[0] not in SLIDING],
        excluded_vb=[float(v) for v in vb[~sliding]],
        top=float(vb[-1]),
        sliding_points=int(sliding.sum()),
    )


def predicted_intervals(model: Model) -> dict[str, list[tuple[float, float]] | None]:
    """Every analysis' unstable ``Vb`` ranges: ``{key: [(lower, upper), ...] or None}``.

    One entry for each key of `ANALYSES`, in its order. The paper's analysis is the
    closed form of Eqs. (25), (28) for each ``V_hat`` reading and sign convention, or
    its numeric solution where there is none (Stribeck's law;
    `beltmdsm.prediction.paper.paper_intervals`: an empty interval is ``[]``, None
    where ``V_hat`` is 0), the same under both tension laws (a linearisation at the
    equilibrium, where the contact force is positive); the
    consistent MDSM is `beltmdsm.prediction.scan.unstable_intervals`, and None (no
    prediction) under ``tension="clipped"`` where the clip cuts its fast normal force
    (`beltmdsm.prediction.mdsm.clip_acts`).
    """
    paper = {c: paper_intervals(model, convention=c) for c in ("paper", "consistent")}
    out = {
        f"paper_{reading}_{convention}": paper[convention][reading]
        for convention in ("paper", "consistent")
        for reading in ("tangential", "coupled")
    }
    if model.tension == "clipped" and clip_acts(model)[0]:
        out["consistent_mdsm"] = None
    else:
        out["consistent_mdsm"] = [(float(a), float(b)) for a, b in unstable_intervals(model)[0]]
    return out


@dataclass(frozen=True)
class Edge:
    """One paired edge: an analysis' predicted edge against its reference's.

    Attributes
    ----------
    predicted : float
        the edge of the hull of the predicted unstable ranges
    reference : float
        the same edge of the reference: the simulated range (`compare`, known to
        ± step/2) or the Floquet band (`compare_floquet`, exact)
    delta : float
        ``predicted - reference``
    censored : bool
        the reference's edge is not observed; left out of the mean absolute error
    from_zero : bool
        a lower edge predicted at ``Vb = 0`` (unstable from rest); False for an
        upper edge
    """

    predicted: float
    reference: float
    delta: float
    censored: bool
    from_zero: bool

    @classmethod
    def pair(cls, predicted: float, reference: float, censored: bool, lower: bool) -> Edge:
        """The edge ``predicted`` against ``reference``, lower (``lower``) or upper."""
        return cls(
            predicted, reference, predicted - reference, censored, lower and predicted == 0.0
        )


@dataclass(frozen=True)
class Comparison:
    """One analysis against its reference for one case (`compare`, `compare_floquet`).

    Attributes
    ----------
    status : {"paired", "miss", "false_alarm", "both_empty", "no_prediction"}
        see `Status`
    lower, upper : Edge or None
        the paired edges of the hulls; None unless ``status`` is "paired"
    disagreement : float or None
        the length of the belt speeds where exactly one side is unstable (|P Δ S| or
        |P Δ F|); None where the analysis gives no prediction
    """

    status: Status
    lower: Edge | None
    upper: Edge | None
    disagreement: float | None


def _status(predicted, reference) -> Status:
    """Which of the two sides, each a list of ranges, is unstable anywhere."""
    if not predicted and not reference:
        return "both_empty"
    if not predicted:
        return "miss"
    return "false_alarm" if not reference else "paired"


def compare(
    predicted: Sequence[tuple[float, float]] | None, simulated: SimulatedRanges, step: float
) -> Comparison:
    """Pair the edges of one analysis with the simulation's for one case (hull rule).

    Parameters
    ----------
    predicted : list of (lower, upper), or None
        None: the analysis gives no prediction (status "no_prediction")
    simulated : SimulatedRanges
        from `simulated_ranges`
    step : float

    Returns
    -------
    Comparison
        each `Edge` against the simulated edge (``delta`` known to ± step/2),
        ``disagreement`` |P Δ S| (`disagreement_length`).
    """
    if predicted is None:
        return Comparison("no_prediction", None, None, None)
    ranges = simulated.ranges
    status = _status(predicted, ranges)
    lower = upper = None
    if status == "paired":
        lo, hi = intervals.hull(predicted)
        lower = Edge.pair(lo, ranges[0].lower, ranges[0].lower_censored, lower=True)
        upper = Edge.pair(hi, ranges[-1].upper, ranges[-1].upper_censored, lower=False)
    return Comparison(status, lower, upper, disagreement_length(predicted, simulated, step))


def disagreement_length(
    predicted: Sequence[tuple[float, float]], simulated: SimulatedRanges, step: float
) -> float:
    """Length of the belt speeds where prediction and simulation disagree (`DEFINITIONS`).

    Measured within the observed window ``[0, top + step/2]`` minus the cells
    ``[Vb - step/2, Vb + step/2]`` of the excluded (stick-slip, contact-loss) points.
    """
    window_end = simulated.top + step / 2
    observed = intervals.clip(predicted, 0.0, window_end)
    found = [(r.lower, r.upper) for r in simulated.ranges]
    excluded = [
        (max(v - step / 2, 0.0), min(v + step / 2, window_end)) for v in simulated.excluded_vb
    ]
    return intervals.length(
        intervals.difference(intervals.symmetric_difference(observed, found), excluded)
    )


def compare_floquet(
    predicted: Sequence[tuple[float, float]] | None, band: Band, lo: float, hi: float
) -> Comparison:
    """Pair an analysis' unstable ranges with the Floquet band (hull rule, exact edges).

    The Floquet band (``band.unstable`` of `beltmdsm.continuation.band.floquet_band`)
    is computed on ``[lo, hi]``: an edge of it at ``lo`` or ``hi`` (unstable up to the
    end of the range) is not observed and is *censored*. The predicted ranges are
    clipped to ``[lo, hi]`` for the disagreement length.

    Returns
    -------
    Comparison
        each `Edge` against the Floquet edge; ``disagreement``: the length of the
        belt speeds in ``[lo, hi]`` where exactly one of them is unstable.
    """
    if predicted is None:
        return Comparison("no_prediction", None, None, None)
    unstable = [tuple(r) for r in band.unstable]
    status = _status(predicted, unstable)
    lower = upper = None
    if status == "paired":
        p_lo, p_hi = intervals.hull(predicted)
        f_lo, f_hi = intervals.hull(unstable)
        lower = Edge.pair(p_lo, f_lo, math.isclose(f_lo, lo), lower=True)
        upper = Edge.pair(p_hi, f_hi, math.isclose(f_hi, hi), lower=False)
    clipped = intervals.clip(predicted, lo, hi)
    disagreement = intervals.length(intervals.symmetric_difference(clipped, unstable))
    return Comparison(status, lower, upper, disagreement)


@dataclass(frozen=True)
class EdgeSummary:
    """One analysis' comparisons over the cases (`summarize_edges`).

    Attributes
    ----------
    mae : float or None
        the mean |Δ| of the uncensored paired edges; None where there is none
    max_abs_delta : float or None
        the largest of those |Δ|; None where there is none
    n_edges : int
        how many edges the mean is over
    paired, miss, false_alarm, both_empty, no_prediction : int
        how many comparisons have each status
    mean_disagreement : float or None
        the mean disagreement length over the comparisons with a prediction; None
        where there is none
    n_cases : int
        how many comparisons have a prediction
    """

    mae: float | None
    max_abs_delta: float | None
    n_edges: int
    paired: int
    miss: int
    false_alarm: int
    both_empty: int
    no_prediction: int
    mean_disagreement: float | None
    n_cases: int


def summarize_edges(comparisons: Sequence[Comparison]) -> EdgeSummary:
    """MAE and largest |Δ| of the uncensored edges, status counts, mean disagreement
    length of one analysis' comparisons (from `compare` or `compare_floquet`)."""
    deltas, lengths = [], []
    counts = dict.fromkeys(("paired", "miss", "false_alarm", "both_empty", "no_prediction"), 0)
    for comp in comparisons:
        counts[comp.status] += 1
        if comp.status == "no_prediction":
            continue
        lengths.append(comp.disagreement)
        deltas += [
            abs(edge.delta)
            for edge in (comp.lower, comp.upper)
            if edge is not None and not edge.censored
        ]
    return EdgeSummary(
        mae=float(np.mean(deltas)) if deltas else None,
        max_abs_delta=float(np.max(deltas)) if deltas else None,
        n_edges=len(deltas),
        **counts,
        mean_disagreement=float(np.mean(lengths)) if lengths else None,
        n_cases=len(comparisons) - counts["no_prediction"],
    )
