"""The Floquet verdict at each grid point against the runs: mismatches and coexistence.

The paper's analyses (Sects. 4.2-4.3, Eqs. 22-28) linearise about a slow equilibrium
that stands for the periodic response of Eq. (4); its Floquet multipliers
(`beltmdsm.periodic.floquet`) say exactly where that response is unstable. On the grid
of each case of Figs. 2b and 17-21:

* `floquet_verdicts`: the verdict at each grid point (`PointVerdict`);
* `Run`: what one of the five runs of `RUNS` shows at the grid points;
* `periodic_mismatches`: where the run started on the perturbed periodic response
  disagrees with the verdict (`Mismatches`);
* `coexistence`: where a stable periodic response coexists with a self-excited
  oscillation found by a run from rest or a continued sweep (`Coexistence`);
* `band_grid_disagreements`: where the band (found on its own grid) and the verdicts
  at the grid points disagree;
* `peak_ranges`: where a run shows the omega1 peak, whatever its regime.

The rules are `FLOQUET_DEFINITIONS` (`beltmdsm.paper_reports.validation.cases`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from ... import intervals
from ...continuation.band_result import Band
from ...errors import NoPeriodicResponse
from ...model import Model, as_model
from ...periodic.floquet import floquet
from ...run.summary import TRANSIENT_DECAYED

#: The Floquet verdict on the periodic response at a grid point: `Floquet.verdict`
#: (`beltmdsm.periodic.floquet`), or "absent" where no periodic response is found.
Verdict = Literal["stable", "unstable", "grazing", "absent"]


@dataclass(frozen=True)
class PointVerdict:
    """The Floquet verdict at one grid point (`floquet_verdicts`).

    Attributes
    ----------
    Vb : float
        the belt speed
    verdict : {"stable", "unstable", "grazing", "absent"}
        see `Verdict`
    max_abs_multiplier, growth_rate : float
        of the periodic response; NaN where there is no multiplier (absent, grazing)
    """

    Vb: float
    verdict: Verdict
    max_abs_multiplier: float
    growth_rate: float


def floquet_verdicts(
    vb: ArrayLike, model: Model | Mapping[str, Any] | None = None, **kw: Any
) -> list[PointVerdict]:
    """The Floquet verdict on the periodic response at each grid point.

    Each point is computed as the run started on the periodic response finds it
    (`beltmdsm.periodic.shooting.periodic_response` without a guess), so the verdict
    belongs to the orbit that run starts on.

    Parameters
    ----------
    vb : array_like
        the belt speeds
    model : Model or mapping, optional
        the other parameters and the options (default: the base set); ``**kw`` too

    Returns
    -------
    list of PointVerdict
        one per belt speed, in its order
    """
    model = as_model(model, **kw)
    out = []
    for v in np.asarray(vb, float):
        try:
            f = floquet(model.replace(Vb=float(v)))
        except NoPeriodicResponse:
            out.append(PointVerdict(float(v), "absent", math.nan, math.nan))
            continue
        out.append(
            PointVerdict(float(v), f.verdict, float(f.max_abs_multiplier), float(f.growth_rate))
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


@dataclass(frozen=True)
class Run:
    """What one run of a case (a key of `RUNS`) shows at each grid point.

    Attributes
    ----------
    present : list of bool
        the omega1 peak is present (``omega1_peak_present`` of the sweep)
    resolved : list of bool
        the run can tell the peak (``resolved``)
    regime : list of str
        the regime of each point (`beltmdsm.run.summary.REGIMES`)
    peak_ratio : list of float
        the omega1 peak over the peak at Omega
    ranges : list of (float, float)
        the points that show the peak (resolved, any regime), each ± h/2 (`peak_ranges`)
    unresolved : list of float
        the belt speeds of the unresolved points
    velocity_range : list of (float, float)
        the smallest and largest X1' of each point's steady window [m/s] (the sweep's
        ``vr_min`` and ``vr_max`` plus ``Vb``): what `explain_coexistence` compares with
        a computed response
    """

    present: list[bool]
    resolved: list[bool]
    regime: list[str]
    peak_ratio: list[float]
    ranges: list[tuple[float, float]]
    unresolved: list[float]
    velocity_range: list[tuple[float, float]]

    @classmethod
    def from_table(cls, table: np.ndarray, step: float) -> Run:
        """The run of a sweep's table (`beltmdsm.batch.sweep.Sweep.table`), grid step ``step``."""
        present = np.asarray(table["omega1_peak_present"], bool)
        resolved = np.asarray(table["resolved"], bool)
        vb = np.asarray(table["Vb"], float)
        return cls(
            present=present.tolist(),
            resolved=resolved.tolist(),
            regime=[str(r) for r in table["regime"]],
            peak_ratio=(table["peak_omega1"] / table["peak_Omega"]).tolist(),
            ranges=peak_ranges(vb, present, resolved, step),
            unresolved=[float(v) for v in vb[~resolved]],
            velocity_range=[
                (float(v + lo), float(v + hi))
                for v, lo, hi in zip(vb, table["vr_min"], table["vr_max"])
            ],
        )


@dataclass(frozen=True)
class Mismatch:
    """A grid point where the periodic-start run and Floquet disagree.

    Attributes
    ----------
    Vb : float
    floquet : {"stable", "unstable"}
        the verdict
    peak : bool
        the run shows the omega1 peak
    """

    Vb: float
    floquet: Verdict
    peak: bool


@dataclass(frozen=True)
class Mismatches:
    """The periodic-start run against Floquet for one case (`periodic_mismatches`).

    Attributes
    ----------
    checked : int
        how many points were compared
    mismatches : list of Mismatch
    near_edge, no_verdict, unresolved : list of float
        the belt speeds not compared: within one grid step of a band edge, without
        a verdict (absent or grazing), or with a run that cannot tell the peak
    """

    checked: int
    mismatches: list[Mismatch]
    near_edge: list[float]
    no_verdict: list[float]
    unresolved: list[float]


def periodic_mismatches(
    vb: ArrayLike,
    verdicts: Sequence[PointVerdict],
    periodic: Run,
    edges: Sequence[float],
    step: float,
) -> Mismatches:
    """Where the run started on the periodic response disagrees with Floquet.

    Floquet's verdict at a grid point is a prediction of that run: the perturbation
    grows into the self-excited oscillation (the omega1 peak) exactly where the
    periodic response is unstable. Points within one grid step of a band edge
    (``edges``: values) are excluded, and so are points without a verdict to test
    (no periodic response, grazing) and runs that cannot tell the peak.

    Parameters
    ----------
    vb : array_like
    verdicts : sequence of PointVerdict
        `floquet_verdicts` on ``vb``
    periodic : Run
        the periodic-start run on ``vb``
    edges : sequence of float
    step : float

    Returns
    -------
    Mismatches
    """
    edges = np.asarray(sorted(edges), float)
    checked, mismatches, near_edge, no_verdict, unresolved = 0, [], [], [], []
    for v, verdict, peak, ok in zip(
        np.asarray(vb, float), verdicts, periodic.present, periodic.resolved
    ):
        v = float(v)
        if edges.size and np.min(np.abs(edges - v)) <= step * (1 + 1e-9):
            near_edge.append(v)
        elif verdict.verdict not in ("stable", "unstable"):
            no_verdict.append(v)
        elif not ok:
            unresolved.append(v)
        else:
            checked += 1
            if bool(peak) != (verdict.verdict == "unstable"):
                mismatches.append(Mismatch(v, verdict.verdict, bool(peak)))
    return Mismatches(checked, mismatches, near_edge, no_verdict, unresolved)


@dataclass(frozen=True)
class Coexistence:
    """Where two attractors are seen in one case (`coexistence`).

    Attributes
    ----------
    points : list of float
        the belt speeds
    ranges : list of (float, float)
        their runs, each point ± h/2
    found_by : dict of float to list of str
        for each point, the runs (keys of `RUNS`) that show the peak there
    unsettled : list of float
        the points that would count but for the slow attraction
    """

    points: list[float]
    ranges: list[tuple[float, float]]
    found_by: dict[float, list[str]]
    unsettled: list[float]


def coexistence(
    vb: ArrayLike,
    verdicts: Sequence[PointVerdict],
    runs: Mapping[str, Run],
    step: float,
    window_start: float,
) -> Coexistence:
    """Grid points where two attractors are seen: a stable periodic response beside
    a self-excited oscillation.

    A point counts when Floquet says the periodic response is stable, the run started
    on it stays there (resolved, no omega1 peak), and a run from rest or a continued
    sweep (up or down) under the same law shows the omega1 peak (resolved), while
    the periodic response attracts fast enough that a run converging to it would have
    settled by the steady window: ``exp(growth_rate * window_start)`` at most
    `beltmdsm.run.summary.TRANSIENT_DECAYED`, the rule the runs apply to the free
    transient. Near a Floquet edge the response attracts too slowly for a run to
    tell a second attractor from a slow approach; those points are listed as
    ``unsettled``.

    Parameters
    ----------
    vb : array_like
    verdicts : sequence of PointVerdict
        `floquet_verdicts` on ``vb``
    runs : mapping of str to Run
        the runs "periodic", "rest", "up" and "down" on ``vb``
    step : float
    window_start : float
        the start of the runs' steady window [s]

    Returns
    -------
    Coexistence
    """
    vb = np.asarray(vb, float)
    flags, found_by, unsettled = np.zeros(vb.size, bool), {}, []
    for i, v in enumerate(vb):
        stays = runs["periodic"].resolved[i] and not runs["periodic"].present[i]
        if verdicts[i].verdict != "stable" or not stays:
            continue
        by = [
            key for key in ("rest", "up", "down") if runs[key].resolved[i] and runs[key].present[i]
        ]
        if not by:
            continue
        if math.exp(verdicts[i].growth_rate * window_start) > TRANSIENT_DECAYED:
            unsettled.append(float(v))
            continue
        flags[i] = True
        found_by[float(v)] = by
    return Coexistence(
        points=[float(v) for v in vb[flags]],
        ranges=[
            (float(vb[i] - step / 2), float(vb[j] + step / 2))
            for i, j in intervals.true_runs(flags)
        ],
        found_by=found_by,
        unsettled=unsettled,
    )


def band_grid_disagreements(
    vb: ArrayLike, verdicts: Sequence[PointVerdict], band: Band, step: float
) -> list[float]:
    """Grid points whose own Floquet verdict contradicts the band, away from its edges.

    The band (`beltmdsm.continuation.band.floquet_band`) is found on its own, coarser
    grid and refined at each change; a point more than one grid step from every edge
    whose verdict differs (unstable or absent inside the band, stable outside) means
    the band missed a change. Grazing points have no verdict and are skipped.
    """
    edges = np.asarray([e.value for e in band.edges], float)
    out = []
    for v, verdict in zip(np.asarray(vb, float), verdicts):
        if verdict.verdict == "grazing" or (
            edges.size and np.min(np.abs(edges - v)) <= step * (1 + 1e-9)
        ):
            continue
        inside = any(lo <= v <= hi for lo, hi in band.unstable)
        if inside != (verdict.verdict in ("unstable", "absent")):
            out.append(float(v))
    return out
