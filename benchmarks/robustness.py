"""Robustness of the integrators over the paper's cases (issue 11, item 3).

The requirement: "Every case of the paper's figures, over Vb = 0..40, in both tension
laws, completes 1000 s with status `done` in under 10 s on one core."

The cases (`CASES` below):

* `beltmdsm.paper_reports.validation.CASES`: the base set (Fig. 2) and the 15 cases of Figs. 17-21;
* the excitations of Figs. 14-15: ``Omega = 4.5``; ``alpha_t = 2, Omega_t = 6,
  alpha_n = 2, Omega_n = 4``; ``phase_t = pi/2``;
* the linear contact of Fig. 16: ``contact="kelvin_voigt", omega2 = 0.5, beta2 = 3``.

Every case runs at ``Vb = 0, step, 2 step, ..., 40`` (default step 0.5 m/s) in both
tension laws with the default settings (`beltmdsm.settings.SolverSettings`: solver
superposition, DOP853, rtol = atol = 1e-10, t_end = 1000 s), and with
``solver="events"`` on a coarser grid (default 2 m/s). Each run records its status,
wall time (around `simulate`, after the numba kernels are compiled), switches, Zeno
limits and energy residual.

The runs go to ``--jobs`` worker processes (default 1, so that the wall times are
one core's), one run at a time per worker; a run that takes longer than
``--hard-limit`` seconds (default 120) is killed with its worker and reported as
``stalled`` (a compiled loop that never returns cannot be interrupted otherwise).

Printed: the counts per status, every run that is not ``done`` (with a command that
reproduces it), the runs over the time limit, the slowest runs and the largest
energy residuals. ``--out FILE.json`` keeps every record.

Usage: python benchmarks/robustness.py [--step 0.5] [--events-step 2] [--jobs 1]
       [--t-end 1000] [--hard-limit 120] [--out results.json] [--cases NAME ...]
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing as mp
import sys
import time
import warnings
from multiprocessing.connection import wait
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

#: Wall time a run may take on one core, and the largest energy residual (the issue's
#: numbers; the residual is the tolerance of tests/beltmdsm/integrate/test_simulate.py).
TIME_LIMIT = 10.0
RESIDUAL_LIMIT = 1e-8


def cases():
    """``[(name, overrides, contact), ...]``: the paper's figures (module docstring)."""
    from beltmdsm.paper_reports.validation import CASES

    out = [(c.name, dict(c.overrides), "hertz_damp") for c in CASES]
    out += [
        ("fig14a Omega=4.5", {"Omega": 4.5}, "hertz_damp"),
        (
            "fig14b Omega_t=6,Omega_n=4",
            {"alpha_t": 2.0, "Omega_t": 6.0, "alpha_n": 2.0, "Omega_n": 4.0},
            "hertz_damp",
        ),
        ("fig15 phase_t=pi/2", {"phase_t": math.pi / 2}, "hertz_damp"),
        ("fig16 kelvin_voigt", {"omega2": 0.5, "beta2": 3.0}, "kelvin_voigt"),
    ]
    return out


def command(task):
    """A command line that reproduces one run."""
    flags = " ".join(f"--{k} {v!r}" for k, v in task["overrides"].items())
    return (
        f"python -m beltmdsm simulate --json --Vb {task['Vb']:g} {flags} --contact "
        f"{task['contact']} --tension {task['tension']} --solver {task['solver']} "
        f"--t-end {task['t_end']:g}"
    ).replace("  ", " ")


def run(task):
    """One run: the record of `module docstring` (never raises)."""
    from beltmdsm.simulation import simulate

    record = dict(task)
    start = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # unresolved peaks: not this study's question
            sim = simulate(
                {
                    **task["overrides"],
                    "Vb": task["Vb"],
                    "contact": task["contact"],
                    "tension": task["tension"],
                },
                solver=task["solver"],
                t_end=task["t_end"],
            )
    except Exception as err:  # a failure is a result here
        record.update(
            status="error",
            message=f"{type(err).__name__}: {err}",
            wall_s=time.perf_counter() - start,
        )
        return record
    s = sim.summary
    record.update(
        status=s.status,
        message=s.message,
        wall_s=time.perf_counter() - start,
        solver_used=s.solver,
        n_switches=s.n_switches,
        n_zeno=s.n_zeno,
        n_separations=s.n_separations,
        energy_residual=s.energy_residual,
        regime=s.regime,
        resolved=s.resolved,
        t_reached=s.t_end,
    )
    return record


def _warm_up():
    """Compile the numba kernels of every combination before anything is timed."""
    from beltmdsm.simulation import simulate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for solver in ("superposition", "events"):
            for tension in ("allowed", "clipped"):
                for contact in ("hertz_damp", "kelvin_voigt"):
                    simulate(
                        {"Vb": 4.0, "contact": contact, "tension": tension},
                        solver=solver,
                        t_end=20.0,
                    )


def _worker(conn):
    _warm_up()
    conn.send("ready")
    while True:
        task = conn.recv()
        if task is None:
            return
        conn.send(run(task))


def run_all(tasks, jobs, hard_limit, progress=True):
    """Run ``tasks`` on ``jobs`` workers; a run over ``hard_limit`` s is killed."""
    ctx = mp.get_context("spawn")
    todo = list(reversed(tasks))
    results, workers = [], {}

    def start_worker():
        parent, child = ctx.Pipe()
        proc = ctx.Process(target=_worker, args=(child,), daemon=True)
        proc.start()
        parent.recv()  # after its warm-up
        workers[parent] = {"proc": proc, "task": None, "since": None}

    def feed(conn):
        w = workers[conn]
        if todo:
            w["task"], w["since"] = todo.pop(), time.perf_counter()
            conn.send(w["task"])
        else:
            w["task"] = None

    for _ in range(min(jobs, len(tasks))):
        start_worker()
    for conn in list(workers):
        feed(conn)
    t0 = last_report = time.perf_counter()
    while any(w["task"] is not None for w in workers.values()):
        ready = wait([c for c, w in workers.items() if w["task"] is not None], timeout=1.0)
        for conn in ready:
            results.append(conn.recv())
            feed(conn)
        now = time.perf_counter()
        for conn, w in list(workers.items()):
            if w["task"] is not None and now - w["since"] > hard_limit:
                w["proc"].kill()
                w["proc"].join()
                results.append(
                    {
                        **w["task"],
                        "status": "stalled",
                        "wall_s": now - w["since"],
                        "message": f"killed after {hard_limit:g} s (--hard-limit)",
                    }
                )
                del workers[conn]
                start_worker()
                feed(list(workers)[-1])
        if progress and ready and now - last_report > 30:
            last_report = now
            done = len(results)
            rate = (now - t0) / done
            print(
                f"{done}/{len(tasks)} runs, {rate:.2f} s/run, about "
                f"{rate * (len(tasks) - done) / 60:.0f} min left",
                file=sys.stderr,
                flush=True,
            )
    for conn, w in workers.items():
        conn.send(None)
        w["proc"].join(timeout=10)
    return results


def report(results, time_limit=TIME_LIMIT, residual_limit=RESIDUAL_LIMIT, top=10):
    """The summary text (module docstring)."""
    lines = []
    results = sorted(results, key=lambda r: (r["case"], r["tension"], r["solver"], r["Vb"]))
    for solver in sorted({r["solver"] for r in results}):
        rs = [r for r in results if r["solver"] == solver]
        counts = {}
        for r in rs:
            counts[r["status"]] = counts.get(r["status"], 0) + 1
        walls = np.array([r["wall_s"] for r in rs])
        res = np.array([r.get("energy_residual", np.nan) for r in rs])
        lines.append(
            f"solver {solver}: {len(rs)} runs; status "
            + ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
            + f"; wall median "
            f"{np.median(walls):.2f} s, max {walls.max():.2f} s; energy residual max "
            f"{np.nanmax(res):.2e}; Zeno limits in {sum(r.get('n_zeno', 0) > 0 for r in rs)} "
            f"runs; fell back to events in "
            f"{sum(r.get('solver_used') == 'events' for r in rs if solver != 'events')}"
        )
    bad = [r for r in results if r["status"] != "done"]
    lines.append(f"\nnot done: {len(bad)}")
    for r in bad:
        lines.append(
            f"  {r['case']}, Vb = {r['Vb']:g}, {r['tension']}, {r['solver']}: "
            f"{r['status']} ({r['message']})\n    {command(r)}"
        )
    slow = [r for r in results if r["wall_s"] > time_limit]
    lines.append(f"\nslower than {time_limit:g} s: {len(slow)}")
    for r in slow:
        lines.append(
            f"  {r['case']}, Vb = {r['Vb']:g}, {r['tension']}, {r['solver']}: "
            f"{r['wall_s']:.1f} s\n    {command(r)}"
        )
    high = [r for r in results if r.get("energy_residual", 0) > residual_limit]
    lines.append(f"\nenergy residual above {residual_limit:g}: {len(high)}")
    for r in high:
        lines.append(
            f"  {r['case']}, Vb = {r['Vb']:g}, {r['tension']}, {r['solver']}: "
            f"{r['energy_residual']:.2e}\n    {command(r)}"
        )
    lines.append(f"\nslowest {top}:")
    for r in sorted(results, key=lambda r: -r["wall_s"])[:top]:
        lines.append(
            f"  {r['wall_s']:6.2f} s  {r['case']}, Vb = {r['Vb']:g}, {r['tension']}, "
            f"{r['solver']} ({r['status']}, {r.get('n_switches', '-')} switches)"
        )
    lines.append(f"\nlargest energy residuals ({top}):")
    done = [r for r in results if "energy_residual" in r]
    for r in sorted(done, key=lambda r: -r["energy_residual"])[:top]:
        lines.append(
            f"  {r['energy_residual']:.2e}  {r['case']}, Vb = {r['Vb']:g}, "
            f"{r['tension']}, {r['solver']} ({r.get('n_switches')} switches, "
            f"{r.get('n_zeno')} Zeno limits)"
        )
    return "\n".join(lines)


def tasks_for(names=None, step=0.5, events_step=2.0, vb_max=40.0, t_end=1000.0):
    """Every (case, Vb, tension, solver) of the study."""
    chosen = [c for c in cases() if names is None or c[0] in names]
    if names is not None and len(chosen) != len(names):
        known = [c[0] for c in cases()]
        raise SystemExit(f"--cases: unknown {sorted(set(names) - set(known))}; known: {known}")
    out = []
    for solver, h in (("superposition", step), ("events", events_step)):
        if h <= 0:
            continue
        vbs = h * np.arange(int(math.floor(vb_max / h + 1e-9)) + 1)
        for name, overrides, contact in chosen:
            for tension in ("allowed", "clipped"):
                for vb in vbs:
                    out.append(
                        {
                            "case": name,
                            "overrides": overrides,
                            "contact": contact,
                            "tension": tension,
                            "solver": solver,
                            "Vb": float(vb),
                            "t_end": t_end,
                        }
                    )
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--step", type=float, default=0.5, help="Vb grid of the superposition runs")
    ap.add_argument(
        "--events-step", type=float, default=2.0, help="Vb grid of the events runs (0: none)"
    )
    ap.add_argument("--vb-max", type=float, default=40.0)
    ap.add_argument("--t-end", type=float, default=1000.0)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--hard-limit", type=float, default=120.0)
    ap.add_argument("--cases", nargs="+", default=None)
    ap.add_argument("--out", default=None, help="write every record as JSON")
    args = ap.parse_args(argv)
    tasks = tasks_for(args.cases, args.step, args.events_step, args.vb_max, args.t_end)
    print(
        f"{len(tasks)} runs ({len(cases() if args.cases is None else args.cases)} cases, "
        f"Vb = 0..{args.vb_max:g} by {args.step:g} (superposition) and "
        f"{args.events_step:g} (events), both tension laws, t_end = {args.t_end:g} s) on "
        f"{args.jobs} worker(s)",
        flush=True,
    )
    start = time.perf_counter()
    results = run_all(tasks, args.jobs, args.hard_limit)
    print(f"total {time.perf_counter() - start:.0f} s")
    if args.out:
        Path(args.out).write_text(json.dumps(results, indent=0, default=float))
    print(report(results))
    bad = [
        r
        for r in results
        if r["status"] != "done"
        or r["wall_s"] > TIME_LIMIT
        or r.get("energy_residual", 0) > RESIDUAL_LIMIT
    ]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
