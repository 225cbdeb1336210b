"""What `validate` returns: one `CaseResult` per case of Figs. 2b and 17-21, and the summaries.

`Validation` holds the resolution, the tension law and the case results; its summaries
over the cases (the tables "Summary per analysis" and "The periodic start against
Floquet" of ``VALIDATION.md``) are derived from them: `summarize` (the analyses, Eqs.
22-28 and the consistent MDSM, against the runs from rest, over the comparable
cases), `summarize_floquet` (against the exact Floquet band, over every case) and
`summarize_mismatches` (the periodic-start run against Floquet).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property

from ...continuation.band_result import Band
from ...model import Tension
from ...multistability import coexistence as exact_coexistence
from .cases import ANALYSES, Case, Resolution
from .comparison import Comparison, EdgeSummary, SimulatedRanges, summarize_edges
from .exact import Explanation
from .verdicts import Coexistence, Mismatch, Mismatches, PointVerdict, Run


@dataclass(frozen=True)
class CaseFloquet:
    """The Floquet side of one case.

    Attributes
    ----------
    band : Band
        `beltmdsm.continuation.band.floquet_band` in ``Vb`` over ``[lo, hi]``
    lo, hi : float
        the range of the band: half a grid step, and the grid's cap
        (`Resolution.vb_cap`)
    verdicts : list of PointVerdict
        the verdict at each grid point of the case (`floquet_verdicts`)
    """

    band: Band
    lo: float
    hi: float
    verdicts: list[PointVerdict]


@dataclass(frozen=True)
class CaseResult:
    """The validation of one case: the runs, Floquet and every analysis, side by side.

    Attributes
    ----------
    case : Case
    Vb : list of float
        the grid ``h, 2 h, ...`` (h: `Resolution.step`) of every run of the case
    runs : dict of str to Run
        one `Run` for each key of `RUNS`, on ``Vb``
    simulated : SimulatedRanges
        the omega1-peak ranges of the run from rest (`simulated_ranges`)
    harmonics : list of (int, float)
        the excitation harmonics ``(k, k Omega)`` in the omega1 band
        (`harmonic_in_band`); empty where the peak is unambiguous
    comparable : bool
        no harmonic in the band and at least one sliding point (`DEFINITIONS`)
    predicted : dict
        each analysis' unstable ranges, None for no prediction (`predicted_intervals`)
    comparison : dict of str to Comparison
        each analysis against the run from rest (`compare`)
    floquet : CaseFloquet
    mismatches : Mismatches
        the periodic-start run against the verdicts (`periodic_mismatches`)
    coexistence : Coexistence
        where the runs find two attractors
        (`beltmdsm.paper_reports.validation.verdicts.coexistence`)
    band_disagreements : list of float
        the grid points whose verdict contradicts the band (`band_grid_disagreements`)
    floquet_comparison : dict of str to Comparison
        each analysis against the Floquet band (`compare_floquet`)
    exact : beltmdsm.multistability.coexistence.Coexistence
        every periodic response found in ``Vb`` over the grid's cells, with its stable
        parts, and where stable ones coexist (`beltmdsm.multistability.coexistence.coexistence`)
    explanations : list of Explanation
        each run at each point of ``coexistence``, explained by a response of ``exact``
        or not (`beltmdsm.paper_reports.validation.exact.explain_coexistence`)
    """

    case: Case
    Vb: list[float]
    runs: dict[str, Run]
    simulated: SimulatedRanges
    harmonics: list[tuple[int, float]]
    comparable: bool
    predicted: dict[str, list[tuple[float, float]] | None]
    comparison: dict[str, Comparison]
    floquet: CaseFloquet
    mismatches: Mismatches
    coexistence: Coexistence
    band_disagreements: list[float]
    floquet_comparison: dict[str, Comparison]
    exact: exact_coexistence.Coexistence
    explanations: list[Explanation]


@dataclass(frozen=True)
class MismatchSummary:
    """The periodic-start run against Floquet over the cases (`summarize_mismatches`).

    Attributes
    ----------
    checked : int
        the compared grid points of the counted cases
    mismatches : list of (str, Mismatch)
        each mismatch with its case's name
    cases : int
        how many cases are counted: those without an excitation harmonic in the
        omega1 band
    not_counted : list of str
        the names of the other cases
    """

    checked: int
    mismatches: list[tuple[str, Mismatch]]
    cases: int
    not_counted: list[str]


def _per_analysis(comparisons: Sequence[Mapping[str, Comparison]]) -> dict[str, EdgeSummary]:
    return {key: summarize_edges([c[key] for c in comparisons]) for key, _, _ in ANALYSES}


def summarize(cases: Sequence[CaseResult]) -> dict[str, EdgeSummary]:
    """Per analysis (key of `ANALYSES`), against the runs from rest: the MAE of the
    edges, the counts of the statuses, the mean |P Δ S|.

    The cases that are not comparable are left out (see `DEFINITIONS`).
    """
    return _per_analysis([c.comparison for c in cases if c.comparable])


def summarize_floquet(cases: Sequence[CaseResult]) -> dict[str, EdgeSummary]:
    """Per analysis, against Floquet: MAE of the uncensored edges, status counts, mean
    disagreement length; over every case (Floquet needs no comparability rule)."""
    return _per_analysis([c.floquet_comparison for c in cases])


def summarize_mismatches(cases: Sequence[CaseResult]) -> MismatchSummary:
    """Totals of `periodic_mismatches` over the cases without a harmonic in the band."""
    counted = [c for c in cases if not c.harmonics]
    return MismatchSummary(
        checked=sum(c.mismatches.checked for c in counted),
        mismatches=[(c.case.name, m) for c in counted for m in c.mismatches.mismatches],
        cases=len(counted),
        not_counted=[c.case.name for c in cases if c.harmonics],
    )


@dataclass(frozen=True)
class Validation:
    """The result of `validate`: every case, and the summaries over them.

    Parameters
    ----------
    quick : bool
        `QUICK` resolution (else `FULL`)
    tension : {"allowed", "clipped"}
        the tension law of the runs from rest, the periodic start and the continued
        sweeps (the other law's run from rest is ``runs["rest_other"]``)
    resolution : Resolution
        the grid and the runs' settings
    cases : list of CaseResult
        in the order they were asked for

    Attributes
    ----------
    summary : dict of str to EdgeSummary
        `summarize` of ``cases``, by analysis
    floquet_summary : dict of str to EdgeSummary
        `summarize_floquet` of ``cases``, by analysis
    mismatch_summary : MismatchSummary
        `summarize_mismatches` of ``cases``

    See Also
    --------
    beltmdsm.paper_reports.validation.run.validate : what builds it.
    beltmdsm.paper_reports.validation.report.render_markdown : ``VALIDATION.md`` from it.

    Examples
    --------
    Built by `validate`; here by hand, without cases (the summaries are empty):

    >>> from beltmdsm.paper_reports.validation import QUICK, Validation, render_markdown
    >>> v = Validation(True, "allowed", QUICK, [])
    >>> v.mismatch_summary.checked, v.summary["consistent_mdsm"].n_edges
    (0, 0)
    >>> render_markdown(v, quick=True).splitlines()[0]
    '# Validation: Floquet stability, the simulated omega1 peak and the analyses'
    """

    quick: bool
    tension: Tension
    resolution: Resolution
    cases: list[CaseResult]

    @cached_property
    def summary(self) -> dict[str, EdgeSummary]:
        return summarize(self.cases)

    @cached_property
    def floquet_summary(self) -> dict[str, EdgeSummary]:
        return summarize_floquet(self.cases)

    @cached_property
    def mismatch_summary(self) -> MismatchSummary:
        return summarize_mismatches(self.cases)
