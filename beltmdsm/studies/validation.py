"""Validation: Floquet stability, the simulated omega1 peak and the analyses' predictions.

The paper validates its stability maps (Figs. 6-8) with amplitude spectra of X1'
over a range of belt speeds (Appendix A.5, Figs. 17-21; Fig. 2b for the base set):
where the steady sliding state is unstable, friction-induced vibration shows as a
peak at omega1. The analyses approximate the linear stability of the periodic
response; `beltmdsm.floquet` computes it exactly. For the base set and every case of
Figs. 17-21 this module sets side by side:

* the Floquet band (`beltmdsm.floquet.floquet_band`) and the verdict at each grid
  point (`floquet_verdicts`);
* five runs per grid point (`RUNS`): from rest under each tension law, on the
  periodic response plus a small perturbation, and continued up and down in ``Vb``;
  where the periodic start disagrees with Floquet (`periodic_mismatches`), and where
  a stable periodic response coexists with a self-excited oscillation
  (`coexistence`);
* each analysis' edges against the Floquet band (`compare_floquet`), exact on both
  sides;

and, as before Floquet, against the run from rest:

* the simulated range: the belt speeds ``Vb`` of a sweep (`beltmdsm.sweep.sweep`)
  where the omega1 peak is present (`beltmdsm.simulation.PEAK_PRESENT_RATIO`, fixed
  before any sweep) and the mass slides (stick-slip and contact loss are marked
  and left out, as the paper leaves stick-slip out of Figs. 19b, c; so are the
  runs that cannot tell the peak, ``resolved`` False, which are never "no peak");
* the predicted ranges: the paper's analysis (Eqs. 22-28, closed form in
  `generated.stability.unstable_interval`) for each ``V_hat`` reading and each sign
  convention, and the consistent MDSM (`beltmdsm.predict.unstable_intervals`);
* the differences of the edges, their mean absolute error per analysis and the
  length of the belt-speed set where prediction and simulation disagree.

The simulations use one tension law (``tension=``, docs/modelling.md#tension), named
in the file. The paper's closed forms linearise at the equilibrium and are the same
under both; under ``"clipped"`` the consistent MDSM has no prediction where the clip
cuts its harmonic fast normal force (`beltmdsm.predict.CLIPPED_MDSM`), and its column
says so instead of counting as "predicts nothing".

`render_markdown` writes ``VALIDATION.md``; ``python -m derive validate`` runs it.
The edge rules are stated in `DEFINITIONS` (and in the file): they were fixed
before the numbers were looked at.

Runtime layer: imports ``generated``, ``runtime``, numpy and scipy, never SymPy.
"""

from __future__ import annotations

import concurrent.futures as cf
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from generated import stability

from .. import intervals
from ..analysis.floquet import PERTURBATION, NoPeriodicResponse, floquet, floquet_band
from ..analysis.predict import clip_acts, unstable_intervals
from ..analysis.summary import PEAK_PRESENT_RATIO, TRANSIENT_DECAYED, omega1_band
from ..model import TENSIONS, Model, Tension
from ..settings import SolverSettings
from .sweep import MAX_POINTS, sweep

__all__ = [
    "Case",
    "CASES",
    "ANALYSES",
    "Resolution",
    "FULL",
    "QUICK",
    "SLIDING",
    "UNRESOLVED",
    "DEFINITIONS",
    "vb_grid",
    "regime_runs",
    "simulated_ranges",
    "harmonic_in_band",
    "predicted_intervals",
    "compare",
    "disagreement_length",
    "summarize",
    "RUNS",
    "FLOQUET_SPACING",
    "FLOQUET_TOL",
    "FLOQUET_DEFINITIONS",
    "floquet_verdicts",
    "peak_ranges",
    "periodic_mismatches",
    "coexistence",
    "band_grid_disagreements",
    "compare_floquet",
    "summarize_floquet",
    "summarize_mismatches",
    "validate",
    "render_markdown",
]


@dataclass(frozen=True)
class Case:
    """One parameter set of the paper's numerical validation.

    ``overrides`` changes the base set (Fig. 2, ``generated.parameters.BASE``);
    ``paper`` is what the paper reports for it (Appendix A.5 or Sect. 4.1).
    """

    name: str
    figure: str
    overrides: dict = field(default_factory=dict)
    paper: str = ""


CASES = (
    Case("base", "Fig. 2b", {}, "the omega1 peak vanishes after Vb ≈ 8 m/s"),
    Case("beta1=0.05", "Fig. 17a", {"beta1": 0.05}, "range decreases as beta1 increases"),
    Case("beta1=0.2", "Fig. 17b", {"beta1": 0.2}, "range decreases as beta1 increases"),
    Case("beta1=0.4", "Fig. 17c", {"beta1": 0.4}, "range decreases as beta1 increases"),
    Case("beta2=0.1", "Fig. 18a", {"beta2": 0.1}, "no peak for Vb > 8 m/s"),
    Case(
        "beta2=0.2", "Fig. 18b", {"beta2": 0.2}, "no peak for Vb > 8 m/s; range shrinks at small Vb"
    ),
    Case(
        "beta2=0.3", "Fig. 18c", {"beta2": 0.3}, "no peak for Vb > 8 m/s; range shrinks at small Vb"
    ),
    Case("Omega=6", "Fig. 19a", {"Omega": 6.0}, "good match with the map (Fig. 7)"),
    Case(
        "Omega=8",
        "Fig. 19b",
        {"Omega": 8.0},
        "stick-slip below Vb = 10 m/s; the map underestimates the range",
    ),
    Case(
        "Omega=10",
        "Fig. 19c",
        {"Omega": 10.0},
        "stick-slip below Vb = 15 m/s; the map underestimates the range",
    ),
    Case("omega1=0.3", "Fig. 20a", {"omega1": 0.3}, "wider range than at omega1 = 3"),
    Case("omega1=3", "Fig. 20b", {"omega1": 3.0}, "range narrows"),
    Case("omega1=12", "Fig. 20c", {"omega1": 12.0}, "no peak"),
    Case("omega2=0.4", "Fig. 21a", {"omega2": 0.4}, "good match for Vb > 8 m/s"),
    Case(
        "omega2=0.9",
        "Fig. 21b",
        {"omega2": 0.9},
        "good match for Vb > 8 m/s; smaller range than the map at low Vb",
    ),
    Case(
        "omega2=1.5",
        "Fig. 21c",
        {"omega2": 1.5},
        "good match for Vb > 8 m/s; smaller range than the map at low Vb",
    ),
)

#: (key, short label, description) of each analysis, in table order.
ANALYSES = (
    (
        "paper_tangential_paper",
        "A1",
        "paper's analysis (Eqs. 22-28), V_hat of the tangential oscillator, sign of Eq. (A4) "
        "as printed",
    ),
    (
        "paper_coupled_paper",
        "A2",
        "paper's analysis, V_hat of the coupled linear 2-DOF response, sign as printed",
    ),
    (
        "paper_tangential_consistent",
        "A3",
        "paper's analysis, tangential V_hat, sign consistent with Eq. (4)",
    ),
    (
        "paper_coupled_consistent",
        "A4",
        "paper's analysis, coupled V_hat, sign consistent with Eq. (4)",
    ),
    (
        "consistent_mdsm",
        "MDSM",
        "consistent MDSM with the friction-normal-force correlation (runtime.predict)",
    ),
)

#: Regimes in which the mass slides; the others are marked and left out.
SLIDING = ("continuous_sliding", "sliding_with_reversals")
#: The label of a point whose run cannot tell the omega1 peak (``resolved`` False):
#: excluded like stick-slip, never counted as a point without the peak.
UNRESOLVED = "unresolved"


@dataclass(frozen=True)
class Resolution:
    """Grid and run length of a validation.

    The ``Vb`` grid is ``step, 2 step, ...`` up to the larger of ``min_top`` and
    ``top_factor`` times the largest predicted edge of any analysis (so every
    predicted edge lies inside); it is extended by ``extend_factor`` while its top
    point is not a sliding point without the omega1 peak (so the simulated range
    closes inside), up to ``vb_cap``.
    """

    step: float
    t_end: float
    min_top: float
    top_factor: float = 1.1
    extend_factor: float = 1.25
    vb_cap: float = 40.0
    rtol: float = 1e-7

    @property
    def settings(self) -> SolverSettings:
        """Solver settings of every run (superposition, DOP853; the cache key)."""
        return SolverSettings(rtol=self.rtol, atol=self.rtol, t_end=self.t_end)


# Full: the paper's figures run to Vb = 16 m/s; 0.25 m/s halves their visual step.
# rtol = 1e-7 keeps peak_omega1 within 3e-7 of the reference (README, benchmark).
FULL = Resolution(step=0.25, t_end=1000.0, min_top=16.0)
# Quick: enough for the omega1 peak to settle (the transient decays as
# exp(-beta1 omega1 t), e^-9 at the window start for the base set) on a 1 m/s grid.
QUICK = Resolution(step=1.0, t_end=300.0, min_top=0.0)

DEFINITIONS = """\
* **Simulated range.** A grid point *shows the peak* when the omega1 peak of X1' is at
  least {ratio:g} of the peak at Omega (`beltmdsm.simulation.PEAK_PRESENT_RATIO`, fixed
  before any sweep). Points in stick-slip or contact loss are *excluded* (the stability
  analyses describe steady sliding; the paper leaves stick-slip out of Figs. 19b, c),
  and so are *unresolved* points, whose run cannot tell the peak (a steady window too
  short for the omega1 band, or a transient not yet decayed: `resolved` False in
  `beltmdsm.simulation.summarize`); an unresolved point is never a point without the peak.
  A simulated range is a maximal run of consecutive sliding points that show the peak.
  Its lower edge is taken at the first such point minus h/2 and its upper edge at the
  last plus h/2 (h: the grid step); each lies within ± h/2 of that value, between a
  point without and a point with the peak. The grid starts at Vb = h, so a range that
  starts at the lowest simulated Vb has its lower edge at h/2 (between 0 and h).
* **Censored edges.** An edge next to an excluded point, or at the top of the grid
  (cap {cap:g} m/s reached), is not observed: it is shown with `*` and is not used in
  the mean absolute error.
* **Not comparable.** A case is not comparable when an integer multiple k Omega
  (k >= 2) of the excitation lies in the band where the omega1 peak is read
  (`beltmdsm.simulation.omega1_band`): the forced harmonics of the nonlinear contact
  force are then counted as the omega1 peak whatever the stability. A case with no
  sliding point is not comparable either. Such cases are listed, and left out of
  every mean.
* **Pairing.** For each analysis and case the hull of the predicted unstable ranges
  [lowest lower edge, highest upper edge] is compared with the hull of the simulated
  ranges: lower with lower, upper with upper; Δ = predicted − simulated. A predicted
  lower edge of 0 (unstable from Vb = 0) is paired like any other edge, with the
  simulated lower edge (at or above the lowest simulated Vb = h).
* **No prediction.** Where an analysis gives no prediction (the consistent MDSM under
  the clipped tension law when the clip cuts its harmonic fast normal force:
  `beltmdsm.predict.CLIPPED_MDSM`), its cells read *n/a* and the case counts in none of
  its columns.
* **Mean absolute error (MAE)** of an analysis: the mean of |Δ| over every paired edge
  whose simulated edge is not censored, over all comparable cases (0, 1 or 2 edges per
  case; *n* is their number). A case where the analysis predicts no unstable range
  while the simulation shows one (a *miss*), or the reverse (a *false alarm*),
  contributes no edge; those cases are counted in their own columns.
* **Disagreement length** |P Δ S| of a case: the length of the set of belt speeds
  where exactly one of the predicted unstable set P and the simulated range set S
  holds, within the observed window [0, top of the grid + h/2] without the cells
  [Vb − h/2, Vb + h/2] of excluded points. It covers misses and false alarms; its
  mean is over the comparable cases.
"""


def vb_grid(step: float, top: float, start: float | None = None) -> np.ndarray:
    """Belt speeds ``k step`` for ``k = 1, 2, ...`` up to ``top`` rounded up to the grid.

    ``start`` (a grid value) drops the points below it, so a grid can be extended
    with the new points only. Multiples of the step are computed as ``k * step`` so
    that a value is bit-identical in every sweep (it keys the sweep cache).

    Raises
    ------
    ValueError
        Naming ``step``, ``top`` or ``start``: not finite, ``step <= 0``, ``top < 0``,
        or more than `beltmdsm.sweep.MAX_POINTS` points.
    """
    for name, value in (("step", step), ("top", top), ("start", start)):
        if value is not None and not math.isfinite(value):
            raise ValueError(f"{name} must be finite; got {value!r}")
    if not step > 0 or not top >= 0:
        raise ValueError(f"step must be > 0 and top >= 0; got step = {step!r}, top = {top!r}")
    if top / step > MAX_POINTS:
        raise ValueError(
            f"step = {step!r} up to top = {top!r} is more than MAX_POINTS = "
            f"{MAX_POINTS:.0e} points (runtime/sweep.py)"
        )
    last = math.ceil(top / step - 1e-9)
    first = 1 if start is None else int(round(start / step))
    return step * np.arange(first, last + 1, dtype=float)


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
        the regime of each point (`beltmdsm.simulation.REGIMES`)
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


def harmonic_in_band(p: Mapping[str, float]) -> list[tuple[int, float]]:
    """Harmonics ``k Omega`` (``k >= 2``) of the excitation inside the omega1 band.

    The normal force of Eq. (1) is nonlinear, so the sliding response contains every
    harmonic of the excitation; one inside the band of the omega1 peak
    (`beltmdsm.simulation.omega1_band`) reads as an omega1 peak whatever the
    stability. Returns ``[(k, k Omega), ...]`` (empty when the peak is unambiguous).
    """
    band = omega1_band(p)
    if band is None:
        return []
    found = []
    for line in sorted({p["Omega_t"], p["Omega_n"]}):
        if line <= 0:
            continue
        for k in range(max(2, math.ceil(band[0] / line)), math.floor(band[1] / line) + 1):
            found.append((k, k * line))
    return found


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


# ---------------------------------------------------------------- Floquet and hysteresis

#: The runs of each case (all on the validation grid), in table order: (key, label, how
#: it starts). "rest" uses the file's tension law, "rest_other" the other law.
RUNS = (
    ("rest", "from rest", "from the unforced equilibrium at rest (the file's tension law)"),
    (
        "periodic",
        "periodic start",
        "on the periodic response plus `beltmdsm.simulation.PERTURBATION` in X1",
    ),
    ("up", "up sweep", "continued upwards in Vb, from rest at the lowest point"),
    ("down", "down sweep", "continued downwards in Vb, from rest at the highest point"),
    ("rest_other", "from rest, other law", "from rest under the other tension law"),
)
#: Largest spacing [m/s] of the first grid of `beltmdsm.floquet.floquet_band`: an unstable
#: range narrower than this inside one switch structure could fall between its points.
FLOQUET_SPACING = 0.5
#: Tolerance [m/s] of the Floquet band's edges (issue 13: 1e-3).
FLOQUET_TOL = 1e-3


def floquet_verdicts(
    vb: ArrayLike,
    overrides: Mapping[str, float] | None = None,
    *,
    contact: str = "hertz_damp",
    tension: Tension = "allowed",
) -> list[dict]:
    """The Floquet verdict on the periodic response at each grid point.

    Each point is computed as the run started on the periodic response finds it
    (`beltmdsm.floquet.periodic_response` without a guess), so the verdict belongs to
    the orbit that run starts on.

    Returns
    -------
    list of dict
        per point ``Vb``, ``verdict`` ("stable", "unstable", "grazing" or "absent":
        no periodic response found), ``max_abs_multiplier`` and ``growth_rate``
        (NaN where there is no multiplier).
    """
    out = []
    for v in np.asarray(vb, float):
        try:
            f = floquet({**(overrides or {}), "Vb": float(v)}, contact=contact, tension=tension)
        except NoPeriodicResponse:
            out.append(
                {
                    "Vb": float(v),
                    "verdict": "absent",
                    "max_abs_multiplier": math.nan,
                    "growth_rate": math.nan,
                }
            )
            continue
        verdict = "grazing" if f.stable is None else "stable" if f.stable else "unstable"
        out.append(
            {
                "Vb": float(v),
                "verdict": verdict,
                "max_abs_multiplier": float(f.max_abs_multiplier),
                "growth_rate": float(f.growth_rate),
            }
        )
    return out


def peak_ranges(
    vb: ArrayLike, present: ArrayLike, resolved: ArrayLike, step: float
) -> list[tuple[float, float]]:
    """Ranges where a run shows the omega1 peak, whatever its regime, each point ± h/2.

    ``present`` and ``resolved`` are the sweep's columns; an unresolved point is not
    a point with the peak (and is listed by the caller, never read as "no peak").
    """
    shows = np.asarray(present, bool) & np.asarray(resolved, bool)
    vb = np.asarray(vb, float)
    return [
        (float(vb[i] - step / 2), float(vb[j] + step / 2)) for i, j in intervals.true_runs(shows)
    ]


def periodic_mismatches(
    vb: ArrayLike, verdicts: Sequence[dict], periodic: Mapping, edges: Sequence[float], step: float
) -> dict:
    """Where the run started on the periodic response disagrees with Floquet.

    Floquet's verdict at a grid point is a prediction of that run: the perturbation
    grows into the self-excited oscillation (the omega1 peak) exactly where the
    periodic response is unstable. Points within one grid step of a band edge
    (``edges``: values) are excluded, and so are points without a verdict to test
    (no periodic response, grazing) and runs that cannot tell the peak.

    Parameters
    ----------
    vb : array_like
    verdicts : list of dict (`floquet_verdicts`)
    periodic : dict with ``present`` and ``resolved`` (the periodic-start sweep)
    edges : sequence of float
    step : float

    Returns
    -------
    dict
        ``checked``: how many points were compared; ``mismatches``: list of dicts
        ``Vb``, ``floquet`` (verdict), ``peak`` (bool); ``near_edge``, ``no_verdict``
        (absent or grazing), ``unresolved``: the excluded belt speeds.
    """
    edges = np.asarray(sorted(edges), float)
    out = {"checked": 0, "mismatches": [], "near_edge": [], "no_verdict": [], "unresolved": []}
    for v, verdict, peak, ok in zip(
        np.asarray(vb, float), verdicts, periodic["present"], periodic["resolved"]
    ):
        v = float(v)
        if edges.size and np.min(np.abs(edges - v)) <= step * (1 + 1e-9):
            out["near_edge"].append(v)
        elif verdict["verdict"] not in ("stable", "unstable"):
            out["no_verdict"].append(v)
        elif not ok:
            out["unresolved"].append(v)
        else:
            out["checked"] += 1
            if bool(peak) != (verdict["verdict"] == "unstable"):
                out["mismatches"].append(
                    {"Vb": v, "floquet": verdict["verdict"], "peak": bool(peak)}
                )
    return out


def coexistence(
    vb: ArrayLike,
    verdicts: Sequence[dict],
    runs: Mapping[str, Mapping],
    step: float,
    window_start: float,
) -> dict:
    """Grid points where two attractors are seen: a stable periodic response beside
    a self-excited oscillation.

    A point counts when Floquet says the periodic response is stable, the run started
    on it stays there (resolved, no omega1 peak), and a run from rest or a continued
    sweep (up or down) under the same law shows the omega1 peak (resolved), while
    the periodic response attracts fast enough that a run converging to it would have
    settled by the steady window: ``exp(growth_rate * window_start)`` at most
    `beltmdsm.simulation.TRANSIENT_DECAYED`, the rule the runs apply to the free
    transient. Near a Floquet edge the response attracts too slowly for a run to
    tell a second attractor from a slow approach; those points are listed as
    ``unsettled``.

    Returns
    -------
    dict
        ``points``: the belt speeds; ``ranges``: their runs, each point ± h/2;
        ``found_by``: for each point, the runs that show the peak there;
        ``unsettled``: the points that would count but for the slow attraction.
    """
    vb = np.asarray(vb, float)
    flags, found_by, unsettled = np.zeros(vb.size, bool), {}, []
    for i, v in enumerate(vb):
        stays = runs["periodic"]["resolved"][i] and not runs["periodic"]["present"][i]
        if verdicts[i]["verdict"] != "stable" or not stays:
            continue
        by = [
            key
            for key in ("rest", "up", "down")
            if runs[key]["resolved"][i] and runs[key]["present"][i]
        ]
        if not by:
            continue
        if math.exp(verdicts[i]["growth_rate"] * window_start) > TRANSIENT_DECAYED:
            unsettled.append(float(v))
            continue
        flags[i] = True
        found_by[float(v)] = by
    return {
        "points": [float(v) for v in vb[flags]],
        "ranges": [
            (float(vb[i] - step / 2), float(vb[j] + step / 2))
            for i, j in intervals.true_runs(flags)
        ],
        "found_by": found_by,
        "unsettled": unsettled,
    }


def band_grid_disagreements(
    vb: ArrayLike, verdicts: Sequence[dict], band: Mapping, step: float
) -> list[float]:
    """Grid points whose own Floquet verdict contradicts the band, away from its edges.

    The band (`beltmdsm.floquet.floquet_band`) is found on its own, coarser grid and
    refined at each change; a point more than one grid step from every edge whose
    verdict differs (unstable or absent inside the band, stable outside) means the
    band missed a change. Grazing points have no verdict and are skipped.
    """
    edges = np.asarray([e["value"] for e in band["edges"]], float)
    out = []
    for v, verdict in zip(np.asarray(vb, float), verdicts):
        if verdict["verdict"] == "grazing" or (
            edges.size and np.min(np.abs(edges - v)) <= step * (1 + 1e-9)
        ):
            continue
        inside = any(lo <= v <= hi for lo, hi in band["unstable"])
        if inside != (verdict["verdict"] in ("unstable", "absent")):
            out.append(float(v))
    return out


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


FLOQUET_DEFINITIONS = """\
* **Floquet band.** `beltmdsm.floquet.floquet_band` in `Vb` over [h/2, {cap:g}] m/s: the
  belt speeds where the periodic response of period 2 pi / Omega is unstable (largest
  Floquet multiplier |mu| > 1) or absent (no periodic response found), with every edge
  located to {tol:g} m/s and named by its kind: *multiplier* (|mu| = 1), *grazing* (a
  reversal appears or disappears with a vanishing acceleration), *existence* (the
  periodic response stops existing). This is the quantity the linear analyses
  approximate (docs/modelling.md#what-unstable-means).
* **Verdict at a grid point.** `beltmdsm.floquet.floquet` at that point, on the periodic
  response found without a guess: the orbit the periodic-start run starts on.
* **Runs.** On the validation grid, each case is run five ways: from rest (the file's
  tension law); on the periodic response plus {perturbation:g} m in X1 (*periodic
  start*); continued upwards and downwards in `Vb` (`beltmdsm.sweep.sweep`,
  ``continuation``: each point starts from the previous point's state at excitation
  phase 0); and from rest under the other tension law. A run's range is every point
  that shows the omega1 peak (resolved, any regime), each ± h/2.
* **Mismatch.** A grid point where the periodic-start run shows the omega1 peak and
  Floquet says stable, or the reverse. Not compared: points within one grid step of a
  band edge (of any kind), points without a verdict (no periodic response, or a
  grazing orbit), unresolved runs, and the cases with an excitation harmonic in the
  omega1 band (the forced harmonic reads as the peak whatever the stability).
* **Coexistence.** A grid point where Floquet says stable, the periodic-start run
  stays on the periodic response (resolved, no peak), and the run from rest or a
  continued sweep shows the omega1 peak: two attractors. A point counts only where
  the periodic response attracts fast enough that a run converging to it would have
  settled before the steady window, exp(growth rate × {window:g} s) ≤ {decayed:g} (the
  rule the runs apply to the free transient, `beltmdsm.simulation.TRANSIENT_DECAYED`);
  the other candidates are listed as *unsettled*.
* **Edges against Floquet.** The hull of each analysis' unstable ranges against the
  hull of the Floquet band, lower with lower and upper with upper; Δ = predicted −
  Floquet, exact on both sides (no grid). A Floquet edge at an end of [h/2, {cap:g}] is
  censored (`*`) and not in the MAE. Every case counts: Floquet needs no peak
  criterion. |P Δ F|: the length of the belt speeds in [h/2, {cap:g}] where exactly one
  of the prediction and the band is unstable.
"""


def summarize_mismatches(cases: Sequence[dict]) -> dict:
    """Totals of `periodic_mismatches` over the cases without a harmonic in the band."""
    counted = [c for c in cases if not c["harmonics"]]
    return {
        "checked": sum(c["mismatches"]["checked"] for c in counted),
        "mismatches": [
            {"case": c["name"], **m} for c in counted for m in c["mismatches"]["mismatches"]
        ],
        "cases": len(counted),
        "not_counted": [c["name"] for c in cases if c["harmonics"]],
    }


def _case_sweep(
    case, resolution, edges, executor, cache_dir, progress, extend=True, tension="allowed"
):
    """Sweep ``Vb`` from rest for one case on the grid rule of `Resolution`.

    ``edges``: the predicted and Floquet edges the grid must contain.
    ``extend=False`` keeps the first grid: where a forced harmonic sits in the omega1
    band the peak never closes, and extending to the cap would measure nothing.
    """
    step = resolution.step
    top = max(resolution.min_top, resolution.top_factor * max(edges, default=0.0), step)
    top = min(top, resolution.vb_cap)
    grid = vb_grid(step, top)
    kwargs = dict(
        settings=resolution.settings,
        executor=executor,
        cache_dir=cache_dir,
        progress=progress,
        tension=tension,
    )
    table = sweep("Vb", grid, case.overrides, **kwargs).table
    while True:
        last = table[-1]
        # an unresolved top point does not close the range: it cannot tell
        closed = (
            str(last["regime"]) in SLIDING
            and bool(last["resolved"])
            and not last["omega1_peak_present"]
        )
        if not extend or closed or last["Vb"] >= resolution.vb_cap - 1e-9:
            return table
        top = min(resolution.vb_cap, resolution.extend_factor * last["Vb"])
        new = vb_grid(step, top, start=last["Vb"] + step)
        table = np.concatenate([table, sweep("Vb", new, case.overrides, **kwargs).table])


def validate(
    quick: bool = False,
    *,
    tension: Tension = "allowed",
    executor: cf.Executor | Literal["serial"] | None = None,
    cache_dir: os.PathLike | str | None = "default",
    progress: bool = True,
    cases: Sequence[Case | str] | None = None,
) -> dict:
    """Simulated omega1-peak ranges against every analysis' prediction (Figs. 2, 17-21).

    Parameters
    ----------
    quick : bool
        `QUICK` resolution (1 m/s grid, 300 s runs) instead of `FULL`
        (0.25 m/s, 1000 s)
    tension : {"allowed", "clipped"}
        the tension law of the simulations (docs/modelling.md#tension); see
        `predicted_intervals` for the predictions
    executor : concurrent.futures.Executor, "serial" or None
        where the runs go (`beltmdsm.sweep.sweep`); None: one process pool over the
        local cores for all cases
    cache_dir : path, "default" or None
        the sweep cache (`beltmdsm.sweep.sweep`); None disables it
    progress : bool
        progress bars on stderr
    cases : sequence of Case or of case names, optional
        default: all of `CASES`

    Returns
    -------
    dict
        ``quick``, ``tension``, ``resolution`` (`Resolution`), ``cases`` (one dict
        per case: ``name``, ``figure``, ``overrides``, ``paper``, ``grid`` (``step``,
        ``start``, ``stop``, ``n``), ``Vb``, ``present``, ``resolved``, ``regime``,
        ``peak_ratio``,
        ``simulated`` (`simulated_ranges`), ``harmonics`` (`harmonic_in_band`),
        ``comparable``, ``predicted`` (`predicted_intervals`), ``comparison``
        (per analysis, `compare`)), ``summary`` (`summarize`).
    """
    if tension not in TENSIONS:
        raise ValueError(
            f"tension must be one of {', '.join(map(repr, TENSIONS))}; got {tension!r}"
        )
    resolution = QUICK if quick else FULL
    by_name = {c.name: c for c in CASES}
    unknown = [c for c in cases or () if isinstance(c, str) and c not in by_name]
    if unknown:
        raise ValueError(
            f"unknown case(s) {', '.join(map(repr, unknown))}; known: {', '.join(by_name)}"
        )
    selected = (
        CASES if cases is None else tuple(by_name[c] if isinstance(c, str) else c for c in cases)
    )
    own = executor is None
    if own:
        executor = cf.ProcessPoolExecutor(max_workers=os.cpu_count())
    results = []
    try:
        for case in selected:
            model = Model(**case.overrides, tension=tension)
            predicted = predicted_intervals(model)
            harmonics = harmonic_in_band(model.params)
            band = _floquet_band(case, resolution, tension)
            edges = [x for ranges in predicted.values() for pair in ranges or () for x in pair]
            edges += [e["value"] for e in band["edges"]]
            table = _case_sweep(
                case,
                resolution,
                edges,
                executor,
                cache_dir,
                progress,
                extend=not harmonics,
                tension=tension,
            )
            vb = np.asarray(table["Vb"], float)
            simulated = simulated_ranges(
                vb,
                table["omega1_peak_present"],
                table["regime"],
                resolution.step,
                table["resolved"],
            )
            runs = _other_runs(case, vb, resolution, executor, cache_dir, progress, tension)
            runs["rest"] = table
            runs = {key: _run_columns(runs[key], resolution.step) for key, _, _ in RUNS}
            verdicts = floquet_verdicts(vb, case.overrides, tension=tension)
            edge_values = [e["value"] for e in band["edges"]]
            results.append(
                {
                    "name": case.name,
                    "figure": case.figure,
                    "overrides": dict(case.overrides),
                    "paper": case.paper,
                    "grid": {
                        "step": resolution.step,
                        "start": float(vb[0]),
                        "stop": float(vb[-1]),
                        "n": int(vb.size),
                    },
                    "Vb": vb.tolist(),
                    "present": table["omega1_peak_present"].tolist(),
                    "resolved": table["resolved"].tolist(),
                    "regime": [str(r) for r in table["regime"]],
                    "peak_ratio": (table["peak_omega1"] / table["peak_Omega"]).tolist(),
                    "simulated": simulated,
                    "harmonics": harmonics,
                    "comparable": not harmonics and simulated["sliding_points"] > 0,
                    "predicted": predicted,
                    "comparison": {
                        key: compare(predicted[key], simulated, resolution.step)
                        for key, _, _ in ANALYSES
                    },
                    "floquet": {
                        **{
                            k: band[k]
                            for k in (
                                "unstable",
                                "edges",
                                "grazing_points",
                                "no_periodic_response",
                                "failed",
                            )
                        },
                        "lo": resolution.step / 2,
                        "hi": resolution.vb_cap,
                        "verdicts": verdicts,
                    },
                    "runs": runs,
                    "mismatches": periodic_mismatches(
                        vb, verdicts, runs["periodic"], edge_values, resolution.step
                    ),
                    "coexistence": coexistence(
                        vb, verdicts, runs, resolution.step, resolution.settings.window_start
                    ),
                    "band_disagreements": band_grid_disagreements(
                        vb, verdicts, band, resolution.step
                    ),
                    "floquet_comparison": {
                        key: compare_floquet(
                            predicted[key], band, resolution.step / 2, resolution.vb_cap
                        )
                        for key, _, _ in ANALYSES
                    },
                }
            )
    finally:
        if own:
            executor.shutdown()
    return {
        "quick": bool(quick),
        "tension": tension,
        "resolution": resolution,
        "cases": results,
        "summary": summarize(results),
        "floquet_summary": summarize_floquet(results),
        "mismatch_summary": summarize_mismatches(results),
    }


def _floquet_band(case, resolution, tension):
    """`beltmdsm.floquet.floquet_band` in ``Vb`` over ``[h/2, vb_cap]`` for one case.

    From ``h/2``, the lower end of the lowest grid point's cell, so that an edge
    just below the lowest grid point is found, not taken for the end of the range.
    """
    lo, hi = resolution.step / 2, resolution.vb_cap
    points = math.ceil((hi - lo) / FLOQUET_SPACING) + 1
    return floquet_band(
        "Vb", lo, hi, case.overrides, tension=tension, points=points, tol=FLOQUET_TOL
    )


def _other_runs(case, vb, resolution, executor, cache_dir, progress, tension):
    """The periodic-start, up, down and other-law sweeps of one case on the grid ``vb``.

    The continued sweeps are sequential within themselves; each is one task for the
    executor, so the two directions run side by side.
    """
    other = {"allowed": "clipped", "clipped": "allowed"}[tension]
    common = dict(settings=resolution.settings, cache_dir=cache_dir)
    plans = {
        "periodic": dict(start="periodic", tension=tension),
        "up": dict(continuation="up", tension=tension),
        "down": dict(continuation="down", tension=tension),
        "rest_other": dict(tension=other),
    }
    if executor == "serial":
        return {
            key: sweep(
                "Vb", vb, case.overrides, executor="serial", progress=progress, **common, **kw
            ).table
            for key, kw in plans.items()
        }
    futures = {
        key: executor.submit(
            sweep, "Vb", vb, case.overrides, executor="serial", progress=False, **common, **kw
        )
        for key, kw in plans.items()
    }
    return {key: fut.result().table for key, fut in futures.items()}


def _run_columns(table, step):
    """What the Floquet tables need of one sweep: its flags, regimes and peak ranges."""
    present = np.asarray(table["omega1_peak_present"], bool)
    resolved = np.asarray(table["resolved"], bool)
    vb = np.asarray(table["Vb"], float)
    return {
        "present": present.tolist(),
        "resolved": resolved.tolist(),
        "regime": [str(r) for r in table["regime"]],
        "ranges": peak_ranges(vb, present, resolved, step),
        "unresolved": [float(v) for v in vb[~resolved]],
    }


# ---------------------------------------------------------------- rendering


def _num(x):
    return f"{x:.2f}"


def _ranges_text(ranges):
    return "n/a" if ranges is None else intervals.format_intervals(ranges, ".2f")


def _simulated_text(sim):
    if not sim["ranges"]:
        return "none"
    parts = []
    for r in sim["ranges"]:
        lo = _num(r["lower"]) + ("*" if r["lower_censored"] else "")
        hi = _num(r["upper"]) + ("*" if r["upper_censored"] else "")
        parts.append(f"[{lo}, {hi}]")
    return ", ".join(parts)


def _delta_text(comp):
    if comp["status"] != "paired":
        return {
            "miss": "miss",
            "false_alarm": "false alarm",
            "both_empty": "both none",
            "no_prediction": "n/a",
        }[comp["status"]]
    texts = []
    for side in ("lower", "upper"):
        e = comp[side]
        t = f"{e['delta']:+.2f}"
        if e["censored"]:
            t = f"({t})*"
        if e["from_zero"]:
            t += "⁰"
        texts.append(t)
    return " / ".join(texts)


def _points_text(runs):
    return ", ".join(f"{_num(a)}–{_num(b)}" if a != b else _num(a) for a, b in runs) or "none"


def _runs_text(runs):
    names = {
        "continuous_sliding": "sliding",
        "sliding_with_reversals": "reversals",
        "stick_slip": "**stick-slip**",
        "contact_loss": "**contact loss**",
        UNRESOLVED: "**unresolved**",
    }
    return "; ".join(
        f"{names[r]} {_num(a)}–{_num(b)}" if a != b else f"{names[r]} {_num(a)}" for r, a, b in runs
    )


def _band_text(band):
    if not band["unstable"]:
        return "none"
    text = intervals.format_intervals(band["unstable"], ".3f")
    if band["no_periodic_response"]:
        text += (
            " (none found in "
            + intervals.format_intervals(band["no_periodic_response"], ".3f")
            + ")"
        )
    return text


def _edges_text(band):
    short = {"multiplier": "mu", "grazing": "graz", "existence": "exist"}
    return ", ".join(f"{e['value']:.3f} {short[e['kind']]}" for e in band["edges"]) or "—"


def _run_text(run):
    text = intervals.format_intervals(run["ranges"], ".2f")
    if run["unresolved"]:
        text += f" ({len(run['unresolved'])} unresolved)"
    return text


def _floquet_delta_text(comp):
    if comp["status"] != "paired":
        return {
            "miss": "miss",
            "false_alarm": "false alarm",
            "both_empty": "both none",
            "no_prediction": "n/a",
        }[comp["status"]]
    return " / ".join(
        f"({comp[s]['delta']:+.3f})*" if comp[s]["censored"] else f"{comp[s]['delta']:+.3f}"
        for s in ("lower", "upper")
    )


def _floquet_sections(results):
    """The Floquet tables of `render_markdown`: the runs, mismatches, coexistence, edges."""
    cases, step = results["cases"], results["resolution"].step
    other = {"allowed": "clipped", "clipped": "allowed"}[results.get("tension", "allowed")]
    lines = [
        "## Floquet: where the periodic response is unstable, and what the runs find",
        "",
        "The Floquet band is exact (edges to "
        f"{FLOQUET_TOL:g} m/s, kinds: mu = multiplier, graz = grazing, exist = "
        "existence). The runs' ranges hold the grid points that show the omega1 peak "
        f"(resolved, any regime), each ± {step / 2:g} m/s. Coexistence: a stable "
        "periodic response beside a self-excited oscillation (definitions below).",
        "",
        "| case | Floquet unstable [m/s] | edges | periodic start | from rest | up sweep "
        f"| down sweep | coexistence | from rest, {other} |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for c in cases:
        band, runs = c["floquet"], c["runs"]
        lines.append(
            f"| {c['name']} | {_band_text(band)} | {_edges_text(band)} | "
            + " | ".join(_run_text(runs[k]) for k in ("periodic", "rest", "up", "down"))
            + f" | {intervals.format_intervals(c['coexistence']['ranges'], '.2f')} | "
            f"{_run_text(runs['rest_other'])} |"
        )
    ms = results["mismatch_summary"]
    lines += [
        "",
        "## The periodic start against Floquet",
        "",
        f"**{len(ms['mismatches'])} mismatches** in {ms['checked']} compared grid points "
        f"of {ms['cases']} cases: the run started on the perturbed periodic response "
        "shows the omega1 peak exactly where Floquet says unstable"
        + (" everywhere it is compared." if not ms["mismatches"] else ", except at:"),
    ]
    lines += [
        f"* {m['case']}, Vb = {m['Vb']:g} m/s: Floquet {m['floquet']}, peak "
        f"{'present' if m['peak'] else 'absent'}."
        for m in ms["mismatches"]
    ]
    if ms["not_counted"]:
        lines.append("")
        lines.append(
            "Not counted (an excitation harmonic in the omega1 band): "
            + "; ".join(
                f"{c['name']} ({len(c['mismatches']['mismatches'])} of "
                f"{c['mismatches']['checked']} points differ)"
                for c in cases
                if c["name"] in ms["not_counted"]
            )
            + "."
        )
    lines += [
        "",
        "| case | compared | near an edge | no verdict | unresolved | band and grid disagree |",
        "|---|---|---|---|---|---|",
    ]
    for c in cases:
        m = c["mismatches"]
        lines.append(
            f"| {c['name']} | {m['checked']} | {len(m['near_edge'])} | "
            f"{len(m['no_verdict'])} | {len(m['unresolved'])} | "
            f"{_points_text([(v, v) for v in c['band_disagreements']])} |"
        )
    lines += [
        "",
        "## Coexistence",
        "",
        "| case | coexistence [m/s] | shown by | unsettled (slow attraction) |",
        "|---|---|---|---|",
    ]
    for c in cases:
        co = c["coexistence"]
        by = sorted({k for ks in co["found_by"].values() for k in ks})
        lines.append(
            f"| {c['name']} | {intervals.format_intervals(co['ranges'], '.2f')} | "
            f"{', '.join(by) or '—'} | "
            f"{_points_text([(v, v) for v in co['unsettled']])} |"
        )
    lines += [
        "",
        "## The analyses against Floquet",
        "",
        "Δ = predicted − Floquet [m/s], lower / upper, exact on both sides; `( )*`: censored.",
        "",
        "| case | Floquet | " + " | ".join(lab for _, lab, _ in ANALYSES) + " |",
        "|" + "---|" * (2 + len(ANALYSES)),
    ]
    for c in cases:
        lines.append(
            f"| {c['name']} | {_band_text(c['floquet'])} | "
            + " | ".join(_floquet_delta_text(c["floquet_comparison"][k]) for k, _, _ in ANALYSES)
            + " |"
        )
    fs = results["floquet_summary"]
    lines += [
        "",
        "| analysis | MAE of edges [m/s] | largest \\|Δ\\| | edges *n* | paired | miss "
        "| false alarm | both none | mean \\|P Δ F\\| [m/s] |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for key, lab, _ in ANALYSES:
        s = fs[key]
        cell = ["—" if s[k] is None else f"{s[k]:.3f}" for k in ("mae", "max", "mean_disagreement")]
        lines.append(
            f"| {lab} | {cell[0]} | {cell[1]} | {s['n_edges']} | {s['paired']} | "
            f"{s['miss']} | {s['false_alarm']} | {s['both_empty']} | {cell[2]} |"
        )
    lines += ["", f"Over all {len(cases)} cases.", ""]
    return lines


def _verdict(cases, key, reference, step):
    """One generated sentence: where ``key`` is closer to the simulation than ``reference``."""
    better, worse, tie, none = [], [], [], []
    for c in cases:
        if not c["comparable"]:
            continue
        ours, theirs = (
            c["comparison"][key]["disagreement"],
            c["comparison"][reference]["disagreement"],
        )
        if ours is None or theirs is None:
            none.append(c["name"])
            continue
        d = ours - theirs
        # Differences within one grid step are below the resolution of the sweep.
        (better if d < -step else worse if d > step else tie).append(c["name"])
    label = {k: lab for k, lab, _ in ANALYSES}

    def names(xs):
        return ", ".join(xs) if xs else "none"

    if none and not (better or worse or tie):
        return (
            f"{label[key]} and {label[reference]} are not compared: one of them gives no "
            f"prediction in every comparable case ({names(none)})."
        )
    skipped = f" Not compared where one gives no prediction: {names(none)}." if none else ""
    return (
        f"By the disagreement length, {label[key]} is closer to the simulation than "
        f"{label[reference]} by more than one grid step ({step:g} m/s) in {len(better)} "
        f"of {len(better) + len(worse) + len(tie)} comparable cases ({names(better)}), "
        f"farther in {len(worse)} ({names(worse)}) and within one step in "
        f"{len(tie)} ({names(tie)})." + skipped
    )


def render_markdown(results: dict, quick: bool) -> str:
    """``VALIDATION.md``: tables of ranges, edge differences, the summary and definitions."""
    res = results["resolution"]
    cases = results["cases"]
    step = res.step
    tension = results.get("tension", "allowed")
    command = (
        "python -m derive validate"
        + (" --quick" if quick else "")
        + (f" --tension {tension}" if tension != "allowed" else "")
    )
    law = {
        "allowed": "`allowed` (Eq. 1 as printed: the contact force can pull)",
        "clipped": "`clipped` (a contact that cannot pull: max(F, 0), the surfaces "
        "separate where Eq. 1 would pull)",
    }[tension]
    lines = [
        "# Validation: Floquet stability, the simulated omega1 peak and the analyses",
        "",
        f"Generated by `{command}` (`runtime/validation.py`); do not edit by hand, rerun "
        "the command.",
        "",
        "For the base set (Fig. 2b) and every case of Appendix A.5 (Figs. 17-21): where the "
        "periodic response of Eq. (4) is unstable (Floquet multipliers, exact; "
        "`beltmdsm.floquet`), where runs started on it, from rest and along continued "
        "sweeps show the omega1 peak in the spectrum of X1', where two attractors coexist, "
        "and how far each analysis' unstable range lies from the Floquet band (the "
        "quantity it approximates) and from the runs from rest.",
        "",
        "## Resolution",
        "",
        f"* Mode: {'quick' if quick else 'full'}. Grid: `Vb` = {step:g}, {2 * step:g}, ... "
        f"m/s (step h = {step:g} m/s, so every simulated edge is known to ± {step / 2:g} "
        f"m/s), up to max({res.min_top:g}, {res.top_factor:g} × the largest predicted "
        f"edge), extended by × {res.extend_factor:g} while the top point is not a sliding "
        f"point without the peak (cap {res.vb_cap:g} m/s; not for the cases marked †).",
        f"* Tension law (docs/modelling.md#tension): {law}. The paper's analyses (A1-A4) "
        "linearise at the equilibrium, where the contact force is positive: the same under "
        "both laws."
        + (
            " The consistent MDSM assumes a harmonic fast normal force, which the "
            "clip makes non-harmonic where it cuts it: n/a there "
            "(`beltmdsm.predict.CLIPPED_MDSM`)."
            if tension == "clipped"
            else ""
        ),
        f"* Runs: {res.t_end:g} s from the unforced equilibrium, steady window after "
        f"{0.3 * res.t_end:g} s, solver `{res.settings.solver}` ({res.settings.method}, "
        f"rtol = atol = {res.rtol:g}), sampling {res.settings.dt:g} s.",
        f"* Peak criterion: omega1 peak ≥ {PEAK_PRESENT_RATIO:g} × the peak at Omega "
        "(`beltmdsm.simulation.PEAK_PRESENT_RATIO`).",
        "* Grid per case: "
        + "; ".join(
            f"{c['name']} {_num(c['grid']['start'])}–{_num(c['grid']['stop'])} "
            f"({c['grid']['n']} points)"
            for c in cases
        )
        + ".",
        "",
        "Analyses:",
        "",
    ]
    lines += [f"* **{lab}**: {desc}." for _, lab, desc in ANALYSES]
    lines += [""] + _floquet_sections(results)
    lines += [
        "# Against the runs from rest",
        "",
        "The tables the package has kept since before Floquet: each analysis against "
        "the run from rest, which finds whichever attractor its start leads to.",
    ]
    header = "| case | figure | simulated | " + " | ".join(lab for _, lab, _ in ANALYSES) + " |"
    rule = "|" + "---|" * (3 + len(ANALYSES))
    lines += [
        "",
        "## Unstable ranges [m/s]",
        "",
        "Simulated: the omega1-peak ranges (edges ± h/2; `*` censored). Predicted: "
        "the unstable ranges; `none`: no unstable belt speed.",
        "",
        header,
        rule,
    ]
    for c in cases:
        name = c["name"] + ("" if c["comparable"] else " †")
        lines.append(
            f"| {name} | {c['figure']} | {_simulated_text(c['simulated'])} | "
            + " | ".join(_ranges_text(c["predicted"][k]) for k, _, _ in ANALYSES)
            + " |"
        )
    lines += [
        "",
        "## Edge differences Δ = predicted − simulated [m/s], lower / upper",
        "",
        f"Each Δ is known to ± {step / 2:g} m/s. `⁰`: the predicted lower edge is "
        f"Vb = 0 (unstable from rest), compared with the simulated lower edge "
        f"(the lowest simulated Vb is {step:g} m/s). `( )*`: censored, not in the "
        "MAE. miss: no predicted range, a simulated one; false alarm: the reverse.",
        "",
        "| case | " + " | ".join(lab for _, lab, _ in ANALYSES) + " |",
        "|" + "---|" * (1 + len(ANALYSES)),
    ]
    for c in cases:
        if not c["comparable"]:
            lines.append(f"| {c['name']} † | " + " | ".join("—" for _ in ANALYSES) + " |")
            continue
        lines.append(
            f"| {c['name']} | "
            + " | ".join(_delta_text(c["comparison"][k]) for k, _, _ in ANALYSES)
            + " |"
        )
    summary = results["summary"]
    lines += [
        "",
        "## Summary per analysis",
        "",
        "| analysis | MAE of edges [m/s] | edges *n* | paired | miss | false alarm | "
        "both none | mean \\|P Δ S\\| [m/s] |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for key, lab, _ in ANALYSES:
        s = summary[key]
        mae = "—" if s["mae"] is None else _num(s["mae"])
        dis = "—" if s["mean_disagreement"] is None else _num(s["mean_disagreement"])
        lines.append(
            f"| {lab} | {mae} | {s['n_edges']} | {s['paired']} | {s['miss']} | "
            f"{s['false_alarm']} | {s['both_empty']} | {dis} |"
        )
    n_comp = sum(c["comparable"] for c in cases)
    for key, lab, _ in ANALYSES:
        if summary[key].get("no_prediction"):
            lines.append(
                f"\n{lab} gives no prediction in {summary[key]['no_prediction']} "
                f"comparable case(s) (n/a); its columns count the other "
                f"{summary[key]['n_cases']}."
            )
    lines += [
        "",
        f"Over {n_comp} comparable cases of {len(cases)}.",
        _verdict(cases, "consistent_mdsm", "paper_tangential_paper", step),
        _verdict(cases, "consistent_mdsm", "paper_coupled_paper", step),
        "",
    ]
    lines += [
        "## Regimes and the paper's statements",
        "",
        "The third column counts every point that shows the peak, whatever its regime "
        "(not used in the comparison).",
        "",
        "| case | regimes over the grid (Vb in m/s) | peak, any regime | paper (Appendix A.5) |",
        "|---|---|---|---|",
    ]
    for c in cases:
        runs = regime_runs(c["Vb"], c["regime"])
        note = _runs_text(runs)
        anywhere = [(a, b) for r, a, b in regime_runs(c["Vb"], c["present"]) if r == "True"]
        if c["harmonics"]:
            note += (
                "; † not comparable: "
                + ", ".join(f"{k} Omega = {_num(w)} rad/s" for k, w in c["harmonics"])
                + " lies in the omega1 band"
            )
        elif not c["comparable"]:
            note += "; † not comparable: no sliding point"
        lines.append(
            f"| {c['name']} | {note} | {_points_text(anywhere)} | {c['figure']}: {c['paper']} |"
        )
    lines += [
        "",
        "## Definitions (fixed before the numbers were looked at)",
        "",
        FLOQUET_DEFINITIONS.format(
            cap=res.vb_cap,
            tol=FLOQUET_TOL,
            perturbation=PERTURBATION,
            window=res.settings.window_start,
            decayed=TRANSIENT_DECAYED,
        ),
        DEFINITIONS.format(ratio=PEAK_PRESENT_RATIO, cap=res.vb_cap),
    ]
    return "\n".join(lines)
