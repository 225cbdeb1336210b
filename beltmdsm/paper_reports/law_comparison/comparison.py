"""Whether friction that falls with speed self-excites without tension: `answer`, `compare`.

`answer`, per friction law and tension law: whether a self-excited vibration exists
without tension once friction falls with speed, and where the excitation stabilises or
destabilises steady sliding (the question of Thomsen and of Michaux et al. that the
paper's introduction cites), from the three computed parts: (a) where steady sliding is
unstable (`beltmdsm.paper_reports.law_comparison.steady`), (b) where the forced
response is (`beltmdsm.paper_reports.law_comparison.forced`) and (c) where runs from
rest show the ``omega1`` vibration (`beltmdsm.paper_reports.law_comparison.runs`).
`compare`: all of it for the laws of `LAWS` and both tension laws, timing each
expensive call.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ...intervals import clip, difference, format_intervals, runs, union
from ...model import Model
from ...settings import SolverSettings
from .forced import ForcedStability, forced_stability
from .laws import FORCED_STARTS, LAWS, STARTS, TENSIONS, VB_RANGE, Law
from .runs import RunScan, runs_from_rest
from .steady import SteadySliding, steady_sliding

__all__ = ["Answer", "answer", "LawComparison", "compare"]


@dataclass(frozen=True)
class Answer:
    """Steady sliding unforced against the forced response, for one law and tension law.

    Attributes
    ----------
    law : Law
    tension : str
    unforced_unstable : list of (lo, hi)
        Where steady sliding is unstable without excitation (`SteadySliding.unstable`),
        up to the top of the range studied.
    forced_unstable : list of (lo, hi)
        Where the forced periodic response is unstable (`ForcedStability.unstable`).
    stabilised : list of (lo, hi)
        Unstable unforced, stable forced: where the excitation stabilises sliding.
    destabilised : list of (lo, hi)
        Stable unforced, unstable forced: where it destabilises it.
    unforced_vibration : list of (lo, hi)
        Where an unforced run (any start) shows the ``omega1`` vibration.
    forced_vibration : list of (lo, hi)
        Where a forced run (from rest, or from the unforced vibration) shows it.
    quenched : list of (lo, hi)
        Where the unforced run from ``"released"`` shows the vibration and the forced run
        started on it does not: the excitation quenches it (grid runs).
    vibration_without_tension : bool
        Whether an unforced run shows the vibration while its normal force never turned
        negative: a self-excited vibration that needs no pulling contact.

    See Also
    --------
    beltmdsm.paper_reports.law_comparison.comparison.answer : what builds it.

    Examples
    --------
    Built by hand (the ranges are those of `answer`'s example):

    >>> from beltmdsm.paper_reports.law_comparison import LAWS
    >>> a = Answer(LAWS["stribeck_A"], "allowed", [(0.0, 1.996)], [(5.705, 6.0)],
    ...            [(0.2, 1.996)], [(5.705, 6.0)], [(1.0, 2.0)], [(1.0, 1.0)],
    ...            [(2.0, 2.0)], True)
    >>> d = a.as_dict()
    >>> d["law"], d["stabilised"], d["quenched"], d["vibration_without_tension"]
    ('stribeck A', [[0.2, 1.996]], [[2.0, 2.0]], True)
    """

    law: Law
    tension: str
    unforced_unstable: list[tuple[float, float]]
    forced_unstable: list[tuple[float, float]]
    stabilised: list[tuple[float, float]]
    destabilised: list[tuple[float, float]]
    unforced_vibration: list[tuple[float, float]]
    forced_vibration: list[tuple[float, float]]
    quenched: list[tuple[float, float]]
    vibration_without_tension: bool

    def as_dict(self) -> dict:
        """For JSON: the ranges as lists."""
        out: dict[str, Any] = {"law": self.law.name, "tension": self.tension}
        for key in (
            "unforced_unstable",
            "forced_unstable",
            "stabilised",
            "destabilised",
            "unforced_vibration",
            "forced_vibration",
            "quenched",
        ):
            out[key] = [list(r) for r in getattr(self, key)]
        out["vibration_without_tension"] = self.vibration_without_tension
        return out


def answer(
    steady: SteadySliding,
    forced: ForcedStability,
    unforced_runs: Sequence[RunScan],
    forced_runs: Sequence[RunScan],
    vb_range: tuple[float, float] = VB_RANGE,
) -> Answer:
    """The answer for one law and tension law, from (a), (b) and (c).

    ``unforced_runs`` and ``forced_runs`` are the scans of each start (`STARTS`,
    `FORCED_STARTS`), on one grid.

    The stabilised and destabilised ranges are set differences of the unstable ranges
    within ``vb_range``, where both are computed (`beltmdsm.intervals.difference`:
    pieces of positive length).

    Parameters
    ----------
    steady : SteadySliding
        part (a)
    forced : ForcedStability
        part (b)
    unforced_runs, forced_runs : sequence of RunScan
        part (c), a scan per start, on one grid
    vb_range : (float, float)
        the belt speeds compared [m/s]

    Returns
    -------
    Answer

    Raises
    ------
    ValueError
        if the released and the vibrating scans are on different grids.

    See Also
    --------
    beltmdsm.intervals.difference : the set difference used.
    beltmdsm.paper_reports.law_comparison.comparison.compare : every law and tension law.

    Examples
    --------
    Stribeck's law A: sliding unstable unforced below 1.996 m/s, the forced response
    unstable from 5.705 m/s (a band over 5.5-6 m/s); the scans are built by hand, the
    unforced vibration at 2 m/s quenched by the excitation, the normal force positive:

    >>> import numpy as np
    >>> from beltmdsm.paper_reports.law_comparison import (
    ...     LAWS, RunScan, answer, forced_stability, steady_sliding)
    >>> law = LAWS["stribeck_A"]
    >>> steady = steady_sliding(law, vb=np.linspace(0.2, 12.0, 60))
    >>> forced = forced_stability(law, "allowed", lo=5.5, hi=6.0, points=3)
    >>> def scan(forced, start, present):  # runs at 1, 2, 3 m/s, by hand
    ...     return RunScan(law, "allowed", forced, start, np.array([1.0, 2.0, 3.0]),
    ...                    np.array(present, dtype=object), np.zeros(3), np.full(3, 0.5),
    ...                    np.array(["stick_slip"] * 3), np.ones(3, dtype=bool), 0.0)
    >>> released = scan(False, "released", [True, True, False])
    >>> vibrating = scan(True, "vibrating", [True, False, False])
    >>> a = answer(steady, forced, [released], [vibrating], vb_range=(0.2, 6.0))
    >>> [(lo, round(hi, 3)) for lo, hi in a.stabilised]
    [(0.2, 1.996)]
    >>> [(round(lo, 3), hi) for lo, hi in a.destabilised]
    [(5.705, 6.0)]
    >>> a.unforced_vibration, a.quenched, a.vibration_without_tension
    ([(1.0, 2.0)], [(2.0, 2.0)], True)
    """
    lo, hi = vb_range
    free = clip(steady.unstable, lo, hi)
    band = clip(forced.unstable, lo, hi)
    shows = [s for s in unforced_runs if any(p is True for p in s.present)]
    released = next((s for s in unforced_runs if s.start == "released"), None)
    vibrating = next((s for s in forced_runs if s.start == "vibrating"), None)
    quenched = []
    if released is not None and vibrating is not None:
        if not np.array_equal(released.values, vibrating.values):
            raise ValueError("the released and the vibrating runs must share one grid")
        quenched = runs(
            released.values,
            (released.present == True) & (vibrating.present == False),  # noqa: E712
        )
    without_tension = any(
        bool(np.all(s.min_normal_force[s.present == True] >= 0))  # noqa: E712
        for s in shows
    )
    return Answer(
        law=steady.law,
        tension=forced.tension,
        unforced_unstable=clip(steady.unstable, 0.0, hi),
        forced_unstable=band,
        stabilised=difference(free, band),
        destabilised=difference(band, free),
        unforced_vibration=union(r for s in unforced_runs for r in s.present_ranges),
        forced_vibration=union(r for s in forced_runs for r in s.present_ranges),
        quenched=quenched,
        vibration_without_tension=without_tension,
    )


# --------------------------------------------------------------------------- all


@dataclass(frozen=True)
class LawComparison:
    """Items 8a-8e for every law and tension law (`compare`).

    Attributes
    ----------
    steady : dict of str to SteadySliding
        By the key of the law (`LAWS`).
    forced : dict of (str, str) to ForcedStability
        By law and tension law.
    forced_runs : dict of (str, str, str) to RunScan
        By law, tension law and start (`FORCED_STARTS`).
    unforced_runs : dict of (str, str, str) to RunScan
        By law, tension law and start (`STARTS`).
    answers : dict of (str, str) to Answer
    wall_s : dict of str to float
        The wall time of each part: ``steady``, ``floquet``, ``forced_runs``,
        ``unforced_runs``.

    See Also
    --------
    beltmdsm.paper_reports.law_comparison.comparison.compare : what builds it.

    Examples
    --------
    Built by hand from the parts of `answer`'s example; ``table`` is a row per
    tension law:

    >>> import numpy as np
    >>> from beltmdsm.paper_reports.law_comparison import (
    ...     LAWS, RunScan, answer, forced_stability, steady_sliding)
    >>> law = LAWS["stribeck_A"]
    >>> steady = steady_sliding(law, vb=np.linspace(0.2, 12.0, 60))
    >>> forced = forced_stability(law, "allowed", lo=5.5, hi=6.0, points=3)
    >>> def scan(forced, start, present):  # runs at 1, 2, 3 m/s, by hand
    ...     return RunScan(law, "allowed", forced, start, np.array([1.0, 2.0, 3.0]),
    ...                    np.array(present, dtype=object), np.zeros(3), np.full(3, 0.5),
    ...                    np.array(["stick_slip"] * 3), np.ones(3, dtype=bool), 0.0)
    >>> released = scan(False, "released", [True, True, False])
    >>> vibrating = scan(True, "vibrating", [True, False, False])
    >>> key = ("stribeck_A", "allowed")
    >>> a = answer(steady, forced, [released], [vibrating], vb_range=(0.2, 6.0))
    >>> result = LawComparison({"stribeck_A": steady}, {key: forced},
    ...                        {(*key, "vibrating"): vibrating},
    ...                        {(*key, "released"): released}, {key: a}, {"steady": 0.0})
    >>> row = result.table("stribeck_A").splitlines()[-1].strip("| ").split(" | ")
    >>> row[:4]
    ['allowed', '[0.000, 1.996]', '[5.705, 6.000]', '5.705 neimark_sacker']
    >>> row[6:]
    ['[0.200, 1.996]', '[5.705, 6.000]', '[2.00, 2.00]']
    >>> sorted(result.as_dict()["answers"])
    ['stribeck_A/allowed']
    """

    steady: dict[str, SteadySliding]
    forced: dict[tuple[str, str], ForcedStability]
    forced_runs: dict[tuple[str, str, str], RunScan]
    unforced_runs: dict[tuple[str, str, str], RunScan]
    answers: dict[tuple[str, str], Answer]
    wall_s: dict[str, float]

    def table(self, law: str, digits: int = 3) -> str:
        """A Markdown table of one law: a row per tension law (docs/stribeck.md)."""
        fmt = f".{digits}f"
        head = (
            "| tension | steady sliding unstable (unforced) | Floquet unstable (forced) | "
            "edges | omega1 peak, unforced runs | omega1 peak, forced runs | "
            "stabilised by the excitation | destabilised | vibration quenched |\n"
            "|---|---|---|---|---|---|---|---|---|"
        )
        lines = [head]
        for tension in [t for t in TENSIONS if (law, t) in self.answers]:
            a, f = self.answers[(law, tension)], self.forced[(law, tension)]
            edges = ", ".join(f"{v:{fmt}} {k}" for v, k in f.edges) or "none"
            lines.append(
                f"| {tension} | {format_intervals(a.unforced_unstable, fmt)} | "
                f"{format_intervals(a.forced_unstable, fmt)} | {edges} | "
                f"{format_intervals(a.unforced_vibration, '.2f')} | "
                f"{format_intervals(a.forced_vibration, '.2f')} | "
                f"{format_intervals(a.stabilised, fmt)} | "
                f"{format_intervals(a.destabilised, fmt)} | "
                f"{format_intervals(a.quenched, '.2f')} |"
            )
        return "\n".join(lines)

    def as_dict(self) -> dict:
        """For JSON: every part's ``as_dict``, keys joined by ``/``."""
        return {
            "steady": {k: v.as_dict() for k, v in self.steady.items()},
            "forced": {"/".join(k): v.as_dict() for k, v in self.forced.items()},
            "forced_runs": {"/".join(k): v.as_dict() for k, v in self.forced_runs.items()},
            "unforced_runs": {"/".join(k): v.as_dict() for k, v in self.unforced_runs.items()},
            "answers": {"/".join(k): v.as_dict() for k, v in self.answers.items()},
            "wall_s": dict(self.wall_s),
        }


def compare(
    laws: Mapping[str, Law] | None = None,
    model: Model | Mapping[str, Any] | None = None,
    *,
    tensions: Iterable[str] = TENSIONS,
    band_points: int = 49,
    run_values: ArrayLike | None = None,
    settings: SolverSettings | None = None,
    starts: Iterable[str] = STARTS,
    forced_starts: Iterable[str] = FORCED_STARTS,
) -> LawComparison:
    """Items 8a-8d for each law and tension law, each part timed.

    Parameters
    ----------
    laws : dict of str to Law, optional
        Default `LAWS`.
    model : Model or dict, optional
        The other parameters (default: the base set).
    tensions : iterable of str
    band_points : int
        Grid values of each Floquet band (`forced_stability`).
    run_values : array_like, optional
        The belt speeds of the runs (default 0.5 to 12 m/s in steps of 0.5).
    settings : SolverSettings, optional
        Of the runs (default `RUN_SETTINGS`).
    starts : iterable of str
        The starts of the unforced runs (`STARTS`).
    forced_starts : iterable of str
        The starts of the forced runs (`FORCED_STARTS`).

    Returns
    -------
    LawComparison
        Every part by law (and tension law, and start), the answers, and the wall time
        of each part; ``table(law)`` is the Markdown of docs/stribeck.md.

    Raises
    ------
    ValueError
        For a start not in `STARTS` (unforced) or `FORCED_STARTS` (forced), an
        unknown tension law, or a bad parameter of a law or of ``model``.

    See Also
    --------
    beltmdsm.paper_reports.law_comparison.steady.steady_sliding : part (a).
    beltmdsm.paper_reports.law_comparison.forced.forced_stability : part (b).
    beltmdsm.paper_reports.law_comparison.runs.runs_from_rest : part (c).
    beltmdsm.paper_reports.law_comparison.comparison.answer : part (d).

    Examples
    --------
    One Stribeck law, one tension law, a coarse band and one short run (the study of
    docs/stribeck.md takes the defaults): steady sliding is unstable below about
    2 m/s without excitation, the forced response between about 5.7 and 7.06 m/s.

    >>> from beltmdsm import SolverSettings
    >>> from beltmdsm.paper_reports.law_comparison import LAWS, compare
    >>> result = compare(
    ...     {"stribeck_A": LAWS["stribeck_A"]},
    ...     tensions=("allowed",),
    ...     band_points=5,
    ...     run_values=[2.0],
    ...     settings=SolverSettings(t_end=100.0),
    ...     starts=("perturbed",),
    ...     forced_starts=("rest",),
    ... )
    >>> a = result.answers[("stribeck_A", "allowed")]
    >>> [(round(lo, 3), round(hi, 3)) for lo, hi in a.unforced_unstable]
    [(0.0, 1.996)]
    >>> [(round(lo, 2), round(hi, 2)) for lo, hi in a.forced_unstable]
    [(5.7, 7.06)]
    >>> sorted(result.wall_s)
    ['floquet', 'forced_runs', 'steady', 'unforced_runs']
    """
    laws = dict(LAWS if laws is None else laws)
    tensions, starts, forced_starts = tuple(tensions), tuple(starts), tuple(forced_starts)
    values = np.arange(1, 25) * 0.5 if run_values is None else np.asarray(run_values, float)
    wall = dict.fromkeys(("steady", "floquet", "forced_runs", "unforced_runs"), 0.0)
    steady, forced, forced_runs, unforced_runs, answers = {}, {}, {}, {}, {}
    for key, law in laws.items():
        steady[key] = steady_sliding(law, model)
        wall["steady"] += steady[key].wall_s
        for tension in tensions:
            forced[(key, tension)] = f = forced_stability(law, tension, model, points=band_points)
            wall["floquet"] += f.wall_s
            for start in forced_starts:
                forced_runs[(key, tension, start)] = r = runs_from_rest(
                    law, tension, values, model, start=start, settings=settings
                )
                wall["forced_runs"] += r.wall_s
            for start in starts:
                unforced_runs[(key, tension, start)] = u = runs_from_rest(
                    law, tension, values, model, forced=False, start=start, settings=settings
                )
                wall["unforced_runs"] += u.wall_s
            answers[(key, tension)] = answer(
                steady[key],
                f,
                [unforced_runs[(key, tension, s)] for s in starts],
                [forced_runs[(key, tension, s)] for s in forced_starts],
            )
    return LawComparison(steady, forced, forced_runs, unforced_runs, answers, wall)
