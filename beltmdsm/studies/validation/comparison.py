"""The analyses' unstable ranges against the runs from rest and against the Floquet band.

* `predicted_intervals`: each analysis of `ANALYSES`: the closed form of Eqs. (25),
  (28) for each ``V_hat`` reading and sign convention of Eq. (A4)
  (`beltmdsm.analysis.predict.paper_intervals`), and the consistent MDSM
  (`beltmdsm.analysis.predict.unstable_intervals`);
* `simulated_ranges`: where a sweep from rest shows the omega1 peak of X1' while the
  mass slides (Figs. 2b, 17-21), each edge within half a grid step;
* `compare` (against the simulated ranges) and `compare_floquet` (against the exact
  Floquet band): the hulls paired edge by edge, and the length of the belt speeds
  where exactly one side is unstable (`disagreement_length`);
* `summarize` and `summarize_floquet`: per analysis over the cases, the mean absolute
  error of the edges and the counts of misses and false alarms.

The rules are `DEFINITIONS` and `FLOQUET_DEFINITIONS` (`beltmdsm.studies.validation.cases`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from generated import stability

from ... import intervals
from ...analysis.predict import clip_acts, unstable_intervals
from ...model import Model
from .cases import ANALYSES, SLIDING, UNRESOLVED


def regime_runs(vb: ArrayLike, regime: ArrayLike) -> list[tuple[str, float, float]]:
    """Runs of consecutive grid points with one label (a regime, or a flag as text).

    Returns ``[(label, first Vb, last Vb), ...]`` (`beltmdsm.intervals.label_runs`).
    """
    return [
        (label, float(vb[i]), float(vb[j]))
        for label, i, j in intervals.label_runs([str(r) for r in regime])
    ]


def simulated_ranges(
    vb: ArrayLike,
    present: ArrayLike,
    regime: ArrayLike,
    step: float,
    resolved: ArrayLike | None = None,
) -> dict:
    """Simulated omega1-peak ranges of a sweep, with their edges (see `DEFINITIONS`).

    Parameters
    ----------
    vb : array_like
        the uniform grid ``step, 2 step, ...`` (ascending)
    present : array_like of bool
        ``omega1_peak_present`` of each point
    regime : array_like of str
        the regime of each point (`beltmdsm.simulate.REGIMES`)
    step : float
    resolved : array_like of bool, optional
        ``resolved`` of each point (default: all True); an unresolved point is
        excluded like a stick-slip point, with the label `UNRESOLVED`

    Returns
    -------
    dict
        ``ranges``: list of dicts ``first``, ``last`` (grid points showing the peak),
        ``lower``, ``upper`` (edge estimates, each within ± step/2),
        ``lower_censored``, ``upper_censored``; ``excluded``: the runs of the
        excluded points (regime or `UNRESOLVED`); ``excluded_vb``: their belt
        speeds; ``top``: the last grid point; ``sliding_points``: how many resolved
        points slide.
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
        {
            "first": float(vb[i]),
            "last": float(vb[j]),
            "lower": float(vb[i] - step / 2),
            "upper": float(vb[j] + step / 2),
            "lower_censored": bool(i > 0 and not sliding[i - 1]),
            "upper_censored": bool(j == vb.size - 1 or not sliding[j + 1]),
        }
        for i, j in intervals.true_runs(shows)
    ]
    excluded = [run for run in regime_runs(vb, regime) if run[0] not in SLIDING]
    return {
        "ranges": ranges,
        "excluded": excluded,
        "excluded_vb": [float(v) for v in vb[~sliding]],
        "top": float(vb[-1]),
        "sliding_points": int(sliding.sum()),
    }


def predicted_intervals(model: Model) -> dict[str, list[tuple[float, float]] | None]:
    """Every analysis' unstable ``Vb`` ranges: ``{key: [(lower, upper), ...] or None}``.

    The paper's analysis is the closed form of Eqs. (25), (28)
    (`generated.stability.unstable_interval`; an empty interval, NaN, becomes
    ``[]``), the same under both tension laws (a linearisation at the equilibrium,
    where the contact force is positive); the consistent MDSM is
    `beltmdsm.predict.unstable_intervals`, and None (no prediction) under
    ``tension="clipped"`` where the clip cuts its fast normal force
    (`beltmdsm.predict.clip_acts`).
    """
    out = {}
    for reading in ("tangential", "coupled"):
        for convention in ("paper", "consistent"):
            lower, upper = (
                float(x)
                for x in stability.unstable_interval(
                    vhat_model=reading, convention=convention, contact=model.contact, **model.params
                )
            )
            out[f"paper_{reading}_{convention}"] = [] if math.isnan(lower) else [(lower, upper)]
    if model.tension == "clipped" and clip_acts(model)[0]:
        out["consistent_mdsm"] = None
    else:
        out["consistent_mdsm"] = [(float(a), float(b)) for a, b in unstable_intervals(model)[0]]
    return out


def _edge(predicted, simulated, censored, from_zero=False):
    return {
        "predicted": predicted,
        "simulated": simulated,
        "delta": predicted - simulated,
        "censored": censored,
        "from_zero": from_zero,
    }


def compare(predicted: Sequence[tuple[float, float]] | None, simulated: dict, step: float) -> dict:
    """Pair the edges of one analysis with the simulation's for one case (hull rule).

    Parameters
    ----------
    predicted : list of (lower, upper), or None
        None: the analysis gives no prediction (status "no_prediction")
    simulated : dict from `simulated_ranges`
    step : float

    Returns
    -------
    dict
        ``status``: "paired", "miss" (no unstable range predicted, a simulated
        range), "false_alarm" (a prediction, no simulated range), "both_empty" or
        "no_prediction" (``predicted`` None: nothing is compared, ``disagreement``
        is None);
        ``lower``, ``upper``: None or dicts ``predicted``, ``simulated``, ``delta``
        (predicted − simulated, known to ± step/2), ``censored``, ``from_zero``;
        ``disagreement``: |P Δ S| (`disagreement_length`).
    """
    ranges = simulated["ranges"]
    if predicted is None:
        return {"status": "no_prediction", "lower": None, "upper": None, "disagreement": None}
    out = {
        "status": None,
        "lower": None,
        "upper": None,
        "disagreement": disagreement_length(predicted, simulated, step),
    }
    if not predicted and not ranges:
        out["status"] = "both_empty"
    elif not predicted:
        out["status"] = "miss"
    elif not ranges:
        out["status"] = "false_alarm"
    else:
        out["status"] = "paired"
        lo, hi = intervals.hull(predicted)
        out["lower"] = _edge(lo, ranges[0]["lower"], ranges[0]["lower_censored"], lo == 0.0)
        out["upper"] = _edge(hi, ranges[-1]["upper"], ranges[-1]["upper_censored"])
    return out


def disagreement_length(
    predicted: Sequence[tuple[float, float]], simulated: dict, step: float
) -> float:
    """Length of the belt speeds where prediction and simulation disagree (`DEFINITIONS`).

    Measured within the observed window ``[0, top + step/2]`` minus the cells
    ``[Vb - step/2, Vb + step/2]`` of the excluded (stick-slip, contact-loss) points.
    """
    window_end = simulated["top"] + step / 2
    observed = intervals.clip(predicted, 0.0, window_end)
    found = [(r["lower"], r["upper"]) for r in simulated["ranges"]]
    excluded = [
        (max(v - step / 2, 0.0), min(v + step / 2, window_end)) for v in simulated["excluded_vb"]
    ]
    return intervals.length(
        intervals.difference(intervals.symmetric_difference(observed, found), excluded)
    )


def _summary(comparisons: Sequence[dict]) -> dict:
    """MAE and largest |Δ| of the uncensored edges, status counts, mean disagreement
    length of one analysis' comparisons (from `compare` or `compare_floquet`)."""
    deltas, lengths = [], []
    counts = {"paired": 0, "miss": 0, "false_alarm": 0, "both_empty": 0, "no_prediction": 0}
    for comp in comparisons:
        counts[comp["status"]] += 1
        if comp["status"] == "no_prediction":
            continue
        lengths.append(comp["disagreement"])
        deltas += [
            abs(comp[side]["delta"])
            for side in ("lower", "upper")
            if comp[side] is not None and not comp[side]["censored"]
        ]
    return {
        "mae": float(np.mean(deltas)) if deltas else None,
        "max": float(np.max(deltas)) if deltas else None,
        "n_edges": len(deltas),
        **counts,
        "mean_disagreement": float(np.mean(lengths)) if lengths else None,
        "n_cases": len(comparisons) - counts["no_prediction"],
    }


def summarize(cases: Sequence[dict]) -> dict:
    """Per analysis: the MAE of the edges, counts of the statuses, the mean |P Δ S|.

    ``cases`` are the case results of `validate`; the cases that are not
    comparable are left out (see `DEFINITIONS`).
    """
    comparable = [c for c in cases if c["comparable"]]
    return {key: _summary([c["comparison"][key] for c in comparable]) for key, _, _ in ANALYSES}


def compare_floquet(
    predicted: Sequence[tuple[float, float]] | None, band: Mapping, lo: float, hi: float
) -> dict:
    """Pair an analysis' unstable ranges with the Floquet band (hull rule, exact edges).

    The Floquet band is computed on ``[lo, hi]``: an edge of it at ``lo`` or ``hi``
    (unstable up to the end of the range) is not observed and is *censored*. The
    predicted ranges are clipped to ``[lo, hi]`` for the disagreement length.

    Returns
    -------
    dict
        ``status`` ("paired", "miss", "false_alarm", "both_empty", "no_prediction");
        ``lower``, ``upper``: None or dicts ``predicted``, ``floquet``, ``delta``
        (predicted − Floquet), ``censored``; ``disagreement``: the length of the
        belt speeds in ``[lo, hi]`` where exactly one of them is unstable.
    """
    if predicted is None:
        return {"status": "no_prediction", "lower": None, "upper": None, "disagreement": None}
    unstable = [tuple(r) for r in band["unstable"]]
    clipped = intervals.clip(predicted, lo, hi)
    out = {
        "status": None,
        "lower": None,
        "upper": None,
        "disagreement": intervals.length(intervals.symmetric_difference(clipped, unstable)),
    }
    if not predicted and not unstable:
        out["status"] = "both_empty"
    elif not predicted:
        out["status"] = "miss"
    elif not unstable:
        out["status"] = "false_alarm"
    else:
        out["status"] = "paired"
        p_lo, p_hi = intervals.hull(predicted)
        f_lo, f_hi = intervals.hull(unstable)
        out["lower"] = {
            "predicted": p_lo,
            "floquet": f_lo,
            "delta": p_lo - f_lo,
            "censored": math.isclose(f_lo, lo),
        }
        out["upper"] = {
            "predicted": p_hi,
            "floquet": f_hi,
            "delta": p_hi - f_hi,
            "censored": math.isclose(f_hi, hi),
        }
    return out


def summarize_floquet(cases: Sequence[dict]) -> dict:
    """Per analysis, against Floquet: MAE of the uncensored edges, status counts, mean
    disagreement length; over every case (Floquet needs no comparability rule)."""
    return {key: _summary([c["floquet_comparison"][key] for c in cases]) for key, _, _ in ANALYSES}
