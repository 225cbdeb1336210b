"""The cases and rules of the validation, fixed before any number was looked at.

The paper validates its stability maps (Figs. 6-8) with amplitude spectra of X1' over
a range of belt speeds (Appendix A.5, Figs. 17-21; Fig. 2b for the base set). This
module holds what the validation compares and by which rules:

* `CASES`: the base set (Fig. 2b) and the 15 parameter sets of Figs. 17-21, each with
  what the paper reports for it;
* `ANALYSES`: the predictions compared: the paper's analysis (Eqs. 22-28) for each
  ``V_hat`` reading (Eq. 23) and each sign convention of Eq. (A4), and the consistent
  MDSM (`beltmdsm.prediction`);
* `RUNS`: the five runs of each grid point;
* `Resolution` (`FULL`, `QUICK`) and `vb_grid`: the belt-speed grid and run length;
* `harmonic_in_band`: where a forced harmonic of Eq. (4) reads as the omega1 peak
  (a case that is not comparable);
* `DEFINITIONS` and `FLOQUET_DEFINITIONS`: the rules, as ``VALIDATION.md`` states them.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ...run.summary import omega1_band
from ...settings import MAX_POINTS, SolverSettings


@dataclass(frozen=True)
class Case:
    """One parameter set of the paper's numerical validation.

    ``overrides`` changes the base set (Fig. 2, ``beltmdsm.generated.parameters.BASE``);
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
        "consistent MDSM with the friction-normal-force correlation (`beltmdsm.prediction`)",
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
  least {ratio:g} of the peak at Omega (`beltmdsm.run.summary.PEAK_PRESENT_RATIO`, fixed
  before any sweep). Points in stick-slip or contact loss are *excluded* (the stability
  analyses describe steady sliding; the paper leaves stick-slip out of Figs. 19b, c),
  and so are *unresolved* points, whose run cannot tell the peak (a steady window too
  short for the omega1 band, or a transient not yet decayed: `resolved` False in
  `beltmdsm.run.summary.summarize`); an unresolved point is never a point without the peak.
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
  (`beltmdsm.run.summary.omega1_band`): the forced harmonics of the nonlinear contact
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
  `beltmdsm.prediction.prediction.CLIPPED_MDSM`), its cells read *n/a* and the case counts
  in none of its columns.
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
        or more than `beltmdsm.settings.MAX_POINTS` points.
    """
    for name, value in (("step", step), ("top", top), ("start", start)):
        if value is not None and not math.isfinite(value):
            raise ValueError(f"{name} must be finite; got {value!r}")
    if not step > 0 or not top >= 0:
        raise ValueError(f"step must be > 0 and top >= 0; got step = {step!r}, top = {top!r}")
    if top / step > MAX_POINTS:
        raise ValueError(
            f"step = {step!r} up to top = {top!r} is more than MAX_POINTS = "
            f"{MAX_POINTS:.0e} points (beltmdsm/settings.py)"
        )
    last = math.ceil(top / step - 1e-9)
    first = 1 if start is None else int(round(start / step))
    return step * np.arange(first, last + 1, dtype=float)


def harmonic_in_band(p: Mapping[str, float]) -> list[tuple[int, float]]:
    """Harmonics ``k Omega`` (``k >= 2``) of the excitation inside the omega1 band.

    The normal force of Eq. (1) is nonlinear, so the sliding response contains every
    harmonic of the excitation; one inside the band of the omega1 peak
    (`beltmdsm.run.summary.omega1_band`) reads as an omega1 peak whatever the
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


#: The runs of each case (all on the validation grid), in table order: (key, label, how
#: it starts). "rest" uses the file's tension law, "rest_other" the other law.
RUNS = (
    ("rest", "from rest", "from the unforced equilibrium at rest (the file's tension law)"),
    (
        "periodic",
        "periodic start",
        "on the periodic response plus `beltmdsm.starts.forced.PERTURBATION` in X1",
    ),
    ("up", "up sweep", "continued upwards in Vb, from rest at the lowest point"),
    ("down", "down sweep", "continued downwards in Vb, from rest at the highest point"),
    ("rest_other", "from rest, other law", "from rest under the other tension law"),
)
#: Largest spacing [m/s] of the first grid of `beltmdsm.continuation.band.floquet_band`: an unstable
#: range narrower than this inside one switch structure could fall between its points.
FLOQUET_SPACING = 0.5
#: Tolerance [m/s] of the Floquet band's edges (issue 13: 1e-3).
FLOQUET_TOL = 1e-3


FLOQUET_DEFINITIONS = """\
* **Floquet band.** `beltmdsm.continuation.band.floquet_band` in `Vb` over [h/2, {cap:g}] m/s: the
  belt speeds where the periodic response of period 2 pi / Omega is unstable (largest
  Floquet multiplier |mu| > 1) or absent (no periodic response found), with every edge
  located to {tol:g} m/s (an edge where the response ends to about 1e-6) and named by
  its bifurcation (docs/modelling.md#bifurcations): *Neimark-Sacker* (a complex pair
  of multipliers leaves the unit circle), *period doubling*, *fold*, *grazing* (the
  switch structure changes: a reversal appears or disappears) and *tangency* (a
  reversal's crossing becomes tangential and the response ends). This is the quantity
  the linear analyses approximate (docs/modelling.md#what-unstable-means).
* **Verdict at a grid point.** `beltmdsm.periodic.floquet.floquet` at that point, on the periodic
  response found without a guess: the orbit the periodic-start run starts on.
* **Runs.** On the validation grid, each case is run five ways: from rest (the file's
  tension law); on the periodic response plus {perturbation:g} m in X1 (*periodic
  start*); continued upwards and downwards in `Vb` (`beltmdsm.batch.sweep.sweep`,
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
  rule the runs apply to the free transient, `beltmdsm.run.summary.TRANSIENT_DECAYED`);
  the other candidates are listed as *unsettled*.
* **Exact coexistence.** `beltmdsm.multistability.coexistence.coexistence` in `Vb` over the
  cells of the case's grid, [h/2, top + h/2]: the periodic response of period
  2 pi / Omega and every phase-locked response (a fixed point of the k-fold period
  map, k up to {limit}) that its seeds reach (shooting; runs from rest and ladders
  continued up and down on the period map, every {seeds:g} m/s), each continued in
  `Vb` through its folds, with its stable parts and the bifurcations that bound them.
* **Explained.** A run that shows the omega1 peak at a point of simulated
  coexistence is explained by a computed response when that response is stable at the
  point and the run's smallest and largest X1' over its steady window are the
  response's to (Omega dt)^2 / 4 of its amplitude (dt the sampling step: a sample
  falls at most dt/2 from an extreme; `beltmdsm.paper_reports.validation.exact.range_tolerance`).
  Otherwise it is *not locked* where a seed of the same kind of run within
  {seeds:g} m/s does not lock within {limit} periods (quasi-periodic motion on an
  invariant torus, or a longer period); *not settled* where the closest stable
  response attracts too slowly for the run to have reached it by the steady window
  (|mu|^(window / kT) > {decayed:g}, the rule of the coexistence points); else
  *unexplained*, with the closest response's deviation.
* **Edges against Floquet.** The hull of each analysis' unstable ranges against the
  hull of the Floquet band, lower with lower and upper with upper; Δ = predicted −
  Floquet, exact on both sides (no grid). A Floquet edge at an end of [h/2, {cap:g}] is
  censored (`*`) and not in the MAE. Every case counts: Floquet needs no peak
  criterion. |P Δ F|: the length of the belt speeds in [h/2, {cap:g}] where exactly one
  of the prediction and the band is unstable.
"""
