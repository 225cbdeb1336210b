"""`validate`: the Floquet bands and the sweeps of every case of Figs. 2b and 17-21.

For each case of `CASES` it computes the predictions (Eqs. 22-28 and the consistent
MDSM), the Floquet band in ``Vb`` (`beltmdsm.continuation.band.floquet_band`), the
sweep from rest on a grid that contains every edge and closes the simulated range,
the four other runs of `RUNS` on that grid (on an executor: a process pool, a dask
cluster or ``"serial"``), the exact coexistence over the grid's cells
(`beltmdsm.multistability.coexistence.coexistence`, computed while the executor runs the
sweeps), the Floquet verdict at each grid point, and sets them side by side
(`beltmdsm.paper_reports.validation.comparison`, `beltmdsm.paper_reports.validation.verdicts`,
`beltmdsm.paper_reports.validation.exact`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import concurrent.futures as cf
import math
import os
from collections.abc import Sequence
from typing import Literal

import numpy as np

from ...arguments import cache_dir_of, executor_of, flag
from ...batch.sweep import sweep
from ...continuation.band import floquet_band
from ...model import TENSIONS, Model, Tension
from ...multistability.coexistence import DEFAULT_STEP, coexistence
from .cases import (
    ANALYSES,
    CASES,
    FLOQUET_SPACING,
    FLOQUET_TOL,
    FULL,
    QUICK,
    RUNS,
    SLIDING,
    Case,
    harmonic_in_band,
    vb_grid,
)
from .comparison import compare, compare_floquet, predicted_intervals, simulated_ranges
from .exact import explain_coexistence
from .results import CaseFloquet, CaseResult, Validation
from .verdicts import (
    Run,
    band_grid_disagreements,
    floquet_verdicts,
    periodic_mismatches,
)
from .verdicts import coexistence as coexistence_points


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
    )
    model = {**case.overrides, "tension": tension}
    table = sweep(model, "Vb", grid, **kwargs).table
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
        table = np.concatenate([table, sweep(model, "Vb", new, **kwargs).table])


def validate(
    quick: bool = False,
    *,
    tension: Tension = "allowed",
    executor: cf.Executor | Literal["serial"] | None = None,
    cache_dir: os.PathLike | str | None = "default",
    progress: bool = True,
    cases: Sequence[Case | str] | None = None,
) -> Validation:
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
        where the runs go (`beltmdsm.batch.sweep.sweep`); None: one process pool
        over the local cores for all cases
    cache_dir : path, "default" or None
        the sweep cache (`beltmdsm.batch.sweep.sweep`); None disables it
    progress : bool
        progress bars on stderr
    cases : sequence of Case or of case names, optional
        default: all of `CASES`

    Returns
    -------
    Validation
        one `CaseResult` per case, in the order of ``cases``, and the summaries

    Raises
    ------
    ValueError
        For an unknown tension law or case name.

    See Also
    --------
    beltmdsm.paper_reports.validation.report.render_markdown : ``VALIDATION.md`` from the result.
    beltmdsm.continuation.band.floquet_band : the Floquet band of one case.
    beltmdsm.prediction.prediction.predict : the analyses' predicted ranges.

    Examples
    --------
    The quick validation of the base set (Fig. 2b) takes about 30 s on two cores:

    >>> from beltmdsm import validate
    >>> results = validate(True, cases=["base"], progress=False)  # doctest: +SKIP
    >>> results.mismatch_summary.mismatches  # doctest: +SKIP
    []

    Without cases it returns at once, with empty summaries:

    >>> empty = validate(True, executor="serial", cache_dir=None, progress=False, cases=[])
    >>> empty.cases, empty.mismatch_summary.checked, empty.resolution.step
    ([], 0, 1.0)
    >>> validate(True, cases=["Fig. 99"])
    Traceback (most recent call last):
    ValueError: unknown case(s) 'Fig. 99'; known: ...
    """
    if tension not in TENSIONS:
        raise ValueError(
            f"tension must be one of {', '.join(map(repr, TENSIONS))}; got {tension!r}"
        )
    quick, progress = flag("quick", quick), flag("progress", progress)
    executor, cache_dir = executor_of(executor), cache_dir_of(cache_dir)
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
    try:
        results = [
            _validate_case(case, resolution, tension, executor, cache_dir, progress)
            for case in selected
        ]
    finally:
        if own:
            executor.shutdown()
    return Validation(bool(quick), tension, resolution, results)


def _validate_case(case, resolution, tension, executor, cache_dir, progress):
    """The `CaseResult` of one case (`validate`)."""
    step = resolution.step
    model = Model(**case.overrides, tension=tension)
    predicted = predicted_intervals(model)
    harmonics = harmonic_in_band(model.params)
    band = _floquet_band(model, resolution)
    edges = [x for ranges in predicted.values() for pair in ranges or () for x in pair]
    edges += [e.value for e in band.edges]
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
        vb, table["omega1_peak_present"], table["regime"], step, table["resolved"]
    )
    pending = _other_runs(case, vb, resolution, executor, cache_dir, progress, tension)
    # the exact study runs here while the executor runs the sweeps
    lo, hi = step / 2, float(vb[-1]) + step / 2
    points = max(int(round((hi - lo) / DEFAULT_STEP)), 1) + 1
    exact = coexistence(model, "Vb", lo, hi, points=points)
    tables = {key: table_of() for key, table_of in pending.items()}
    tables["rest"] = table
    runs = {key: Run.from_table(tables[key], step) for key, _, _ in RUNS}
    verdicts = floquet_verdicts(vb, model)
    simulated_coexistence = coexistence_points(
        vb, verdicts, runs, step, resolution.settings.window_start
    )
    lo, hi = step / 2, resolution.vb_cap
    return CaseResult(
        case=case,
        Vb=vb.tolist(),
        runs=runs,
        simulated=simulated,
        harmonics=harmonics,
        comparable=not harmonics and simulated.sliding_points > 0,
        predicted=predicted,
        comparison={key: compare(predicted[key], simulated, step) for key, _, _ in ANALYSES},
        floquet=CaseFloquet(band, lo, hi, verdicts),
        mismatches=periodic_mismatches(
            vb, verdicts, runs["periodic"], [e.value for e in band.edges], step
        ),
        coexistence=simulated_coexistence,
        band_disagreements=band_grid_disagreements(vb, verdicts, band, step),
        floquet_comparison={
            key: compare_floquet(predicted[key], band, lo, hi) for key, _, _ in ANALYSES
        },
        exact=exact,
        explanations=explain_coexistence(
            simulated_coexistence.points,
            simulated_coexistence.found_by,
            runs,
            vb,
            exact,
            resolution.settings,
            DEFAULT_STEP,
        ),
    )


def _floquet_band(model, resolution):
    """`beltmdsm.continuation.band.floquet_band` in ``Vb`` over ``[h/2, vb_cap]`` for one case.

    From ``h/2``, the lower end of the lowest grid point's cell, so that an edge
    just below the lowest grid point is found, not taken for the end of the range.
    """
    lo, hi = resolution.step / 2, resolution.vb_cap
    points = math.ceil((hi - lo) / FLOQUET_SPACING) + 1
    return floquet_band(model, "Vb", lo, hi, points=points, tol=FLOQUET_TOL)


def _other_runs(case, vb, resolution, executor, cache_dir, progress, tension):
    """The periodic-start, up, down and other-law sweeps of one case on the grid ``vb``.

    Returns, by key, a function without arguments that gives the sweep's table. On an
    executor the sweeps are submitted at once, so that they run while the caller
    works; the continued sweeps are sequential within themselves, each one task, so the
    two directions run side by side. With ``"serial"`` each runs when its table is asked
    for.
    """
    other = {"allowed": "clipped", "clipped": "allowed"}[tension]
    common = dict(settings=resolution.settings, cache_dir=cache_dir)
    plans = {
        "periodic": (tension, dict(start="periodic")),
        "up": (tension, dict(continuation="up")),
        "down": (tension, dict(continuation="down")),
        "rest_other": (other, {}),
    }
    if executor == "serial":

        def later(law, kw):
            model = {**case.overrides, "tension": law}
            return lambda: (
                sweep(model, "Vb", vb, executor="serial", progress=progress, **common, **kw).table
            )

        return {key: later(law, kw) for key, (law, kw) in plans.items()}
    futures = {
        key: executor.submit(
            sweep,
            {**case.overrides, "tension": law},
            "Vb",
            vb,
            executor="serial",
            progress=False,
            **common,
            **kw,
        )
        for key, (law, kw) in plans.items()
    }
    return {key: (lambda fut=fut: fut.result().table) for key, fut in futures.items()}
