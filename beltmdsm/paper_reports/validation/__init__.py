"""Validation: Floquet stability, the simulated omega1 peak and the analyses' predictions.

The paper validates its stability maps (Figs. 6-8) with amplitude spectra of X1'
over a range of belt speeds (Appendix A.5, Figs. 17-21; Fig. 2b for the base set):
where the steady sliding state is unstable, friction-induced vibration shows as a
peak at omega1. The analyses approximate the linear stability of the periodic
response; `beltmdsm.periodic.floquet` computes it exactly. For the base set and every
case of Figs. 17-21 this package sets side by side:

* the Floquet band (`beltmdsm.continuation.band.floquet_band`) and the verdict at each
  grid point (`floquet_verdicts`);
* five runs per grid point (`RUNS`): from rest under each tension law, on the
  periodic response plus a small perturbation, and continued up and down in ``Vb``;
  where the periodic start disagrees with Floquet (`periodic_mismatches`), and where
  a stable periodic response coexists with a self-excited oscillation
  (`coexistence`);
* the exact coexistence (`beltmdsm.multistability.coexistence.coexistence`): every periodic
  response found, phase-locked ones too, with its stable parts, and each run of the
  simulated coexistence explained by one of them or listed as unexplained
  (`explain_coexistence`);
* each analysis' edges against the Floquet band (`compare_floquet`), exact on both
  sides;

and, as before Floquet, against the run from rest:

* the simulated range: the belt speeds ``Vb`` of a sweep
  (`beltmdsm.batch.sweep.sweep`) where the omega1 peak is present
  (`beltmdsm.run.summary.PEAK_PRESENT_RATIO`, fixed before any sweep) and the
  mass slides (stick-slip and contact loss are marked and left out, as the paper
  leaves stick-slip out of Figs. 19b, c; so are the runs that cannot tell the peak,
  ``resolved`` False, which are never "no peak");
* the predicted ranges: the paper's analysis (Eqs. 22-28, closed form in
  `beltmdsm.generated.stability.unstable_interval`) for each ``V_hat`` reading and each sign
  convention, and the consistent MDSM (`beltmdsm.prediction.scan.unstable_intervals`);
* the differences of the edges, their mean absolute error per analysis and the
  length of the belt-speed set where prediction and simulation disagree.

The simulations use one tension law (``tension=``, docs/modelling.md#tension), named
in the file. The paper's closed forms linearise at the equilibrium and are the same
under both; under ``"clipped"`` the consistent MDSM has no prediction where the clip
cuts its harmonic fast normal force (`beltmdsm.prediction.prediction.CLIPPED_MDSM`), and its
column says so instead of counting as "predicts nothing".

`render_markdown` writes ``VALIDATION.md``; ``python -m beltmdsm validate`` (or
``python -m beltmdsm validate``) runs it. The edge rules are stated in `DEFINITIONS`
(and in the file): they were fixed before the numbers were looked at.

Modules, one concept each:

* `beltmdsm.paper_reports.validation.cases`: the cases of Figs. 2b and 17-21, the analyses,
  the runs, the grid and the rules (`DEFINITIONS`);
* `beltmdsm.paper_reports.validation.comparison`: the analyses' edges against the runs from
  rest and against the Floquet band (`Comparison`), and the summary of one analysis'
  comparisons;
* `beltmdsm.paper_reports.validation.verdicts`: the Floquet verdicts at the grid points
  against the runs: mismatches, coexistence;
* `beltmdsm.paper_reports.validation.exact`: the exact coexistence of each case
  (`beltmdsm.multistability.coexistence`) beside the simulated one, each simulated coexistence
  point explained by a computed response or listed as unexplained;
* `beltmdsm.paper_reports.validation.results`: what `validate` returns (`Validation`, one
  `CaseResult` per case) and the summaries over the cases;
* `beltmdsm.paper_reports.validation.run`: `validate`, the orchestration of the bands and
  the sweeps on an executor;
* `beltmdsm.paper_reports.validation.report`: `render_markdown`, with the Floquet half of the
  file in `beltmdsm.paper_reports.validation.floquet_report` and the text of each cell in
  `beltmdsm.paper_reports.validation.cells`.

Studies layer: imports ``beltmdsm.generated``, the lower layers of ``beltmdsm``, numpy and
scipy, never SymPy or the command line.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from .cases import (
    ANALYSES,
    CASES,
    DEFINITIONS,
    FLOQUET_DEFINITIONS,
    FLOQUET_SPACING,
    FLOQUET_TOL,
    FULL,
    QUICK,
    RUNS,
    SLIDING,
    UNRESOLVED,
    Case,
    Resolution,
    harmonic_in_band,
    vb_grid,
)
from .comparison import (
    Comparison,
    Edge,
    EdgeSummary,
    SimulatedRange,
    SimulatedRanges,
    compare,
    compare_floquet,
    disagreement_length,
    predicted_intervals,
    regime_runs,
    simulated_ranges,
    summarize_edges,
)
from .exact import SEED_SOURCES, STATUSES, Explanation, explain_coexistence, range_tolerance
from .report import render_markdown
from .results import (
    CaseFloquet,
    CaseResult,
    MismatchSummary,
    Validation,
    summarize,
    summarize_floquet,
    summarize_mismatches,
)
from .run import validate
from .verdicts import (
    Coexistence,
    Mismatch,
    Mismatches,
    PointVerdict,
    Run,
    band_grid_disagreements,
    coexistence,
    floquet_verdicts,
    peak_ranges,
    periodic_mismatches,
)

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
    # the result types
    "Validation",
    "CaseResult",
    "CaseFloquet",
    "MismatchSummary",
    "SimulatedRange",
    "SimulatedRanges",
    "Edge",
    "Comparison",
    "EdgeSummary",
    "summarize_edges",
    "PointVerdict",
    "Run",
    "Mismatch",
    "Mismatches",
    "Coexistence",
    "Explanation",
    "SEED_SOURCES",
    "STATUSES",
    "explain_coexistence",
    "range_tolerance",
]
