"""The Floquet verdict at each grid point against the runs: mismatches and coexistence.

The paper's analyses (Sects. 4.2-4.3, Eqs. 22-28) linearise about a slow equilibrium
that stands for the periodic response of Eq. (4); its Floquet multipliers
(`beltmdsm.analysis.floquet`) say exactly where that response is unstable. On the grid
of each case of Figs. 2b and 17-21:

* `floquet_verdicts`: the verdict at each grid point ("stable", "unstable",
  "grazing", "absent");
* `periodic_mismatches`: where the run started on the perturbed periodic response
  disagrees with the verdict (`summarize_mismatches` over the cases);
* `coexistence`: where a stable periodic response coexists with a self-excited
  oscillation found by a run from rest or a continued sweep;
* `band_grid_disagreements`: where the band (found on its own grid) and the verdicts
  at the grid points disagree;
* `peak_ranges`: where a run shows the omega1 peak, whatever its regime.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ... import intervals
from ...analysis.floquet import NoPeriodicResponse, floquet
from ...analysis.summary import TRANSIENT_DECAYED
from ...model import Tension


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
    `beltmdsm.simulate.TRANSIENT_DECAYED`, the rule the runs apply to the free
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
