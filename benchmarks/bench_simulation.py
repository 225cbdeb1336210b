"""Speed against error of the simulation of Eq. (4) and of the Floquet band.

All in one run on this machine, serially (one core):

1. A reference: the event-driven integrator (`beltmdsm.integrate.events`, compiled DOP853) at
   rtol = atol = 1e-12, for every belt speed of the sweep.
2. Methods and tolerances on three belt speeds: wall time against the error of
   peak_omega1, of the mean friction and of the final state.
3. The targets, on the sweep (64 points of 1000 s at the base set by default):
   * the fast configuration, the event-driven integrator alone (the default
     solver), against the named baseline, plain
     ``solve_ivp(rhs, method="RK45", rtol=1e-9)`` (default atol) with a Python
     right-hand side using np.sign, sampled on the same grid and analysed with the
     same spectrum code (targets: at least 25x for the sweep, at least 10x for the
     events solver alone, peak_omega1 within 1e-6 of the reference);
   * the superposition integrator at the same tolerance;
   * each with ``backend="python"`` (no numba) too, where ``--python`` is given;
   * the Floquet band of the same case (`beltmdsm.continuation.band.floquet_band`, edges to
     1e-3) against the from-rest sweep (target: at most 1/50 of its time).
   Printed: the wall times, their ratios and each configuration's largest relative
   error of peak_omega1 where the peak is present (>= 1 % of the Omega peak of the
   reference); where it is absent the value is leakage at the 1e-8 level and its
   error is printed relative to the Omega peak instead.

numba's compilation is done before any timed region (one short run per
configuration), and the shared normal motion of the superposition is cleared before
its timed sweep, so the sweep pays for it once, as a user's sweep does.

Usage: python -m benchmarks.bench_simulation [--quick] [--points N] [--t-end T] [--python]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from beltmdsm.continuation.band import floquet_band  # noqa: E402
from beltmdsm.excitation import initial_state
from beltmdsm.integrate import superposition  # noqa: E402
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet
from beltmdsm.run.spectra import peak_amplitudes  # noqa: E402
from beltmdsm.run.summary import PEAK_PRESENT_RATIO, omega1_band  # noqa: E402
from beltmdsm.settings import SolverSettings  # noqa: E402
from beltmdsm.simulation import simulate  # noqa: E402

#: The fast configuration: the event-driven integrator (the default solver), at the
#: tolerance that keeps peak_omega1 within 1e-6 of the reference with a margin.
FAST = dict(solver="events", rtol=1e-7, atol=1e-7)
#: The superposition integrator at the same tolerance (its normal motion integrated
#: once per sweep).
SUPERPOSITION = dict(solver="superposition", rtol=1e-7, atol=1e-7)
REFERENCE = dict(solver="events", rtol=1e-12, atol=1e-12)


def baseline(Vb, t_end, dt, t_discard):
    """Plain solve_ivp(RK45, rtol=1e-9) on Eq. (4) with np.sign; same analysis.

    The right-hand side is typed here on purpose: it is the naive program the
    package is measured against, not part of the package.
    """
    start = time.perf_counter()
    model = Model(Vb=Vb)
    p = model.params
    b1, w1, b2, w2 = p["beta1"], p["omega1"], p["beta2"], p["omega2"]
    al, Om, mu, g = p["alpha"], p["Omega"], p["mu_s"], p["g"]

    def rhs(t, y):
        X1, Y1, X2, Y2 = y
        Fn = (2 * b2 * w2 * Y2 + w2**2) * X2**1.5 if X2 > 0 else 0.0
        f = al * Om**2 * np.sin(Om * t)
        return np.array(
            [Y1, f - 2 * b1 * w1 * Y1 - w1**2 * X1 - mu * np.sign(Y1 - Vb) * Fn, Y2, -f + g - Fn]
        )

    n = int(math.floor(t_end / dt + 1e-9)) + 1
    grid = dt * np.arange(n)
    sol = solve_ivp(rhs, (0, t_end), initial_state(model), method="RK45", rtol=1e-9, t_eval=grid)
    y = sol.y
    win = grid >= t_discard
    res = 2 * np.pi / (win.sum() * dt)
    (_, peak1), (_, peakO) = peak_amplitudes(y[1, win], dt, [omega1_band(p), (Om - res, Om + res)])
    Fn = np.where(y[2] > 0, (2 * b2 * w2 * y[3] + w2**2) * np.maximum(y[2], 0) ** 1.5, 0.0)
    friction = -mu * np.sign(y[1] - Vb) * Fn
    return {
        "peak_omega1": peak1,
        "peak_Omega": peakO,
        "mean_friction": friction[win].mean(),
        "final_state": y[:, -1],
        "wall_s": time.perf_counter() - start,
    }


def run(Vb, t_end, dt, config):
    s = simulate(Model(Vb=Vb), settings=SolverSettings(t_end=t_end, dt=dt, **config)).summary
    return {
        "peak_omega1": s.peak_omega1,
        "peak_Omega": s.peak_Omega,
        "mean_friction": s.mean_friction,
        "final_state": np.array(s.final_state),
        "wall_s": s.wall_s,
        "energy_residual": s.energy_residual,
    }


def errors(r, ref):
    present = ref["peak_omega1"] >= PEAK_PRESENT_RATIO * ref["peak_Omega"]
    scale = ref["peak_omega1"] if present else ref["peak_Omega"]
    return {
        "peak": abs(r["peak_omega1"] - ref["peak_omega1"]) / scale,
        "present": present,
        "friction": abs(r["mean_friction"] / ref["mean_friction"] - 1),
        "state": float(np.max(np.abs(r["final_state"] - ref["final_state"]))),
    }


def sweep_time(values, t_end, dt, config):
    """Wall time and results of the serial sweep in one configuration."""
    superposition.clear_cache()
    t0 = time.perf_counter()
    out = {Vb: run(Vb, t_end, dt, config) for Vb in values}
    return time.perf_counter() - t0, out


def summary_row(name, wall, results, ref, values, base_wall):
    e = [errors(results[Vb], ref[Vb]) for Vb in values]
    present = [x["peak"] for x in e if x["present"]]
    absent = [x["peak"] for x in e if not x["present"]]
    return {
        "name": name,
        "wall_s": wall,
        "ratio": base_wall / wall,
        "peak_present": max(present, default=float("nan")),
        "peak_absent": max(absent, default=float("nan")),
        "friction": max(x["friction"] for x in e),
        "state": max(x["state"] for x in e),
    }


def measure(points=64, t_end=1000.0, dt=0.02, python=False, progress=print):
    """Every number the benchmark prints, as rows (for the notebook speed_vs_error)."""
    warnings.simplefilter("ignore", RuntimeWarning)  # unresolved short warm-up runs
    t_discard = 0.3 * t_end
    values = np.linspace(0.5, 32.0, points)
    configs = [("fast: events", FAST), ("superposition", SUPERPOSITION)]
    if python:
        configs += [
            ("events, backend python", dict(FAST, backend="python")),
            ("superposition, python", dict(SUPERPOSITION, backend="python")),
        ]
    for _, cfg in configs + [("reference", REFERENCE)]:
        run(4.0, 20.0, dt, cfg)  # compile before timing
    floquet(Model(Vb=4.0))
    progress(f"[1] reference: events at rtol = atol = 1e-12 on {points} points of {t_end:g} s ...")
    ref = {Vb: run(Vb, t_end, dt, REFERENCE) for Vb in values}
    progress(f"    max energy residual {max(r['energy_residual'] for r in ref.values()):.2e}")

    progress("[2] methods and tolerances (3 belt speeds)")
    probe = [values[np.argmin(np.abs(values - v))] for v in (2.0, 4.0, 12.0)]
    probes = [("baseline RK45 rtol=1e-9 np.sign", None)]
    for tol in (1e-7, 1e-8, 1e-9, 1e-10):
        probes.append((f"events tol={tol:g}", dict(solver="events", rtol=tol, atol=tol)))
    for tol in (1e-7, 1e-8, 1e-10):
        probes.append(
            (f"superposition tol={tol:g}", dict(solver="superposition", rtol=tol, atol=tol))
        )
    method_rows = []
    for name, cfg in probes:
        walls, errs = [], []
        for Vb in probe:
            if cfg is not None and cfg["solver"] == "superposition":
                superposition.clear_cache()
            r = baseline(Vb, t_end, dt, t_discard) if cfg is None else run(Vb, t_end, dt, cfg)
            walls.append(r["wall_s"])
            errs.append(errors(r, ref[Vb]))
        method_rows.append(
            {
                "name": name,
                "wall_s": float(np.mean(walls)),
                "peak": max(e["peak"] for e in errs),
                "friction": max(e["friction"] for e in errs),
                "state": max(e["state"] for e in errs),
            }
        )

    progress(f"[3] targets: the {points}-point sweep, serial")
    t0 = time.perf_counter()
    base = {Vb: baseline(Vb, t_end, dt, t_discard) for Vb in values}
    base_wall = time.perf_counter() - t0
    rows = [summary_row("baseline (RK45, np.sign)", base_wall, base, ref, values, base_wall)]
    for name, cfg in configs:
        wall, res = sweep_time(values, t_end, dt, cfg)
        rows.append(summary_row(name, wall, res, ref, values, base_wall))
    t0 = time.perf_counter()
    band = floquet_band(None, "Vb", float(values[0]), float(values[-1]))
    band_wall = time.perf_counter() - t0
    return {
        "points": points,
        "t_end": t_end,
        "methods": method_rows,
        "sweeps": rows,
        "floquet_band": {
            "wall_s": band_wall,
            "unstable": band.unstable,
            "sweep_over_band": rows[1]["wall_s"] / band_wall,
        },
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="8 points of 300 s")
    ap.add_argument("--points", type=int, default=None)
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--dt", type=float, default=0.02)
    ap.add_argument(
        "--python",
        action="store_true",
        help="also time the sweeps with backend='python' (no numba; slow)",
    )
    args = ap.parse_args(argv)
    points = args.points or (8 if args.quick else 64)
    t_end = args.t_end or (300.0 if args.quick else 1000.0)
    out = measure(points, t_end, args.dt, args.python, progress=lambda s: print(s, flush=True))
    print(
        f"\n    {'configuration':34s} {'wall/point s':>12s} {'peak_omega1':>12s} "
        f"{'mean friction':>13s} {'final state':>12s}"
    )
    for r in out["methods"]:
        print(
            f"    {r['name']:34s} {r['wall_s']:12.3f} {r['peak']:12.2e} {r['friction']:13.2e} "
            f"{r['state']:12.2e}"
        )
    print(
        f"\n    {'sweep':26s} {'wall s':>8s} {'ratio':>7s} {'peak_omega1 rel':>16s} "
        f"{'(absent, /Omega)':>17s} {'mean friction':>13s} {'final state':>12s}"
    )
    for r in out["sweeps"]:
        print(
            f"    {r['name']:26s} {r['wall_s']:8.2f} {r['ratio']:7.1f} {r['peak_present']:16.2e} "
            f"{r['peak_absent']:17.2e} {r['friction']:13.2e} {r['state']:12.2e}"
        )
    fb = out["floquet_band"]
    print(
        f"\n    Floquet band over the same Vb range: {fb['wall_s']:.3f} s, unstable "
        f"{[[round(a, 3), round(b, 3)] for a, b in fb['unstable']]}; the fast sweep takes "
        f"{fb['sweep_over_band']:.0f}x as long (target >= 50)"
    )
    print(f"    fast configuration (events alone) {FAST}; superposition {SUPERPOSITION}")
    fast, sup = out["sweeps"][1], out["sweeps"][2]
    print(
        f"    targets: sweep >= 25x and events alone >= 10x: {fast['ratio']:.1f}x "
        f"(superposition {sup['ratio']:.1f}x); peak_omega1 within 1e-6 where present: "
        f"{fast['peak_present']:.1e} (superposition {sup['peak_present']:.1e})"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
