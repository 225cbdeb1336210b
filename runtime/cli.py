"""``python -m derive simulate ...`` and ``python -m derive sweep ...``.

simulate: one run of Eq. (4); ``--json`` prints one JSON object (the summary of
`runtime.simulate.summarize` plus the parameters), otherwise a readable summary.
sweep: one parameter over a range (`runtime.sweep.sweep`), with a progress bar;
prints the table (or JSON with ``--json``), writes CSV with ``--out``; for a sweep
over Vb it adds the validation line on the omega1 peak (Fig. 2b).
"""
from __future__ import annotations

import argparse
import json
import sys

import numpy as np

from generated.parameters import PARAMETERS

from .model import CONTACTS
from .simulate import DEFAULT_T_END, SolverSettings, simulate

__all__ = ["main"]

_MODEL_PARAMS = [p for p in PARAMETERS if p["name"] != "Vhat"]
PAPER_STATEMENT = "the omega1 peak 'vanishes after Vb ~ 8 m/s' (Sect. 3, Fig. 2b)"


def _common(parser):
    g = parser.add_argument_group("model parameters (default: the base set, Fig. 2)")
    for p in _MODEL_PARAMS:
        flags = [f"--{p['name']}"]
        if "_" in p["name"]:
            flags.append(f"--{p['name'].replace('_', '-')}")
        g.add_argument(*flags, dest=p["name"], type=float, default=None,
                       help=f"{p['description']} [{p['unit']}]")
    g.add_argument("--contact", choices=CONTACTS, default="hertz_damp")
    s = parser.add_argument_group("solver")
    s.add_argument("--solver", choices=("superposition", "events"), default="superposition",
                   help="superposition (fast, falls back to events on loss of contact) or "
                        "events (solve_ivp on Eq. 4)")
    s.add_argument("--method", default="DOP853", help="solve_ivp method")
    s.add_argument("--rtol", type=float, default=1e-10)
    s.add_argument("--atol", type=float, default=1e-10)
    s.add_argument("--t-end", type=float, default=DEFAULT_T_END, help="duration [s]")
    s.add_argument("--t-discard", type=float, default=None,
                   help="start of the steady window [s] (default 30%% of --t-end)")
    s.add_argument("--dt", type=float, default=0.02, help="sampling step [s]")
    s.add_argument("--on-contact-loss", choices=("continue", "stop"), default="continue")
    parser.add_argument("--json", action="store_true", help="print JSON")


def _settings(args):
    return SolverSettings(solver=args.solver, method=args.method, rtol=args.rtol, atol=args.atol,
                          t_end=args.t_end, t_discard=args.t_discard, dt=args.dt,
                          on_contact_loss=args.on_contact_loss)


def _params(args, skip=()):
    return {p["name"]: getattr(args, p["name"]) for p in _MODEL_PARAMS
            if getattr(args, p["name"]) is not None and p["name"] not in skip}


def _jsonable(x):
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, (np.floating, float)):
        return None if not np.isfinite(x) else float(x)
    if isinstance(x, (np.integer, np.bool_)):
        return x.item()
    return x


def _simulate(argv):
    parser = argparse.ArgumentParser(prog="python -m derive simulate",
                                     description="Simulate Eq. (4) and summarise the run.")
    _common(parser)
    parser.add_argument("--modulation", action="store_true",
                        help="add friction modulation averages (Figs. 10-12)")
    parser.add_argument("--save", metavar="NPZ", help="save t, X1, Y1, X2, Y2, Fn, friction")
    args = parser.parse_args(argv)
    sim = simulate(_params(args), contact=args.contact, settings=_settings(args))
    out = dict(sim.summary)
    if args.modulation:
        from .modulation import modulation_scatter
        out.update(modulation_scatter(sim))
    out["params"] = sim.params
    out["contact"] = sim.contact
    if args.save:
        np.savez(args.save, t=sim.t, X1=sim.y[0], Y1=sim.y[1], X2=sim.y[2], Y2=sim.y[3],
                 Fn=sim.normal_force, friction=sim.friction)
    if args.json:
        print(json.dumps(_jsonable(out)))
        return 0 if sim.status == "done" else 2
    p = sim.params
    e = out["energy"]
    lines = [
        f"Eq. (4), {sim.contact}, Vb = {p['Vb']:g} m/s, t = 0..{out['t_end']:g} s "
        f"(steady window from {out['t_discard']:g} s), solver: {out['solver']}",
        f"status: {sim.status} ({sim.message})",
        f"regime: {out['regime']}  (time in slip-/slip+/stick/flight: "
        + "/".join(f"{100 * v:.1f}%" for v in out["time_fraction"].values()) + ")",
        f"switches: {out['n_switches']} (reversals {out['n_reversals']}, sticks {out['n_sticks']}, "
        f"contact losses {out['n_contact_losses']})",
        f"X1' spectrum: {out['peak_omega1']:.6g} m/s at {out['omega1_peak_at']:.6g} rad/s "
        f"(omega1 = {p['omega1']:g}), {out['peak_Omega']:.6g} m/s at Omega = {p['Omega_t']:g}; "
        f"omega1 peak {'PRESENT' if out['omega1_peak_present'] else 'absent'} "
        "(friction-induced vibration)" ,
        f"energy balance: residual {out['energy_residual']:.3g} (dE = {e['energy_change']:.6g}, "
        f"W_in = {e['work_input']:.6g}, W_visc = {e['work_viscous']:.6g}, "
        f"W_fric = {e['work_friction']:.6g})",
        f"normal force: min {out['min_normal_force']:.4g} m/s^2, negative (tensile, Eq. 1 as "
        f"printed) {100 * out['tension_fraction']:.1f}% of the steady window",
        f"Vr range in the window: {out['vr_min']:.4g} .. {out['vr_max']:.4g} m/s; "
        f"mean friction {out['mean_friction']:.6g} m/s^2",
    ]
    if args.modulation:
        lines.append("mu_eff over 2pi/Omega: {mu_eff_Omega_mean:.5g} +- {mu_eff_Omega_std:.3g}; "
                     "over 2pi/omega1: {mu_eff_omega1_mean:.5g} +- {mu_eff_omega1_std:.3g}"
                     .format(**out))
    lines.append(f"wall time {out['wall_s']:.2f} s")
    print("\n".join(lines))
    return 0 if sim.status == "done" else 2


def validation_lines(table, param="Vb"):
    """The validation print-out: where the omega1 peak appears, beside the paper."""
    from .intervals import format_intervals
    from .simulate import PEAK_PRESENT_RATIO
    from .sweep import omega1_peak_ranges
    ranges = omega1_peak_ranges(table, param)
    found = format_intervals(ranges, "g", "nowhere")
    x = np.asarray(table[param], float)
    return [f"omega1 peak (>= {100 * PEAK_PRESENT_RATIO:g}% of the Omega peak) present for "
            f"{param} in {found} m/s of the swept {x.min():g}..{x.max():g} m/s "
            f"({int(np.sum(table['omega1_peak_present']))} of {x.size} points)",
            f"paper: {PAPER_STATEMENT}"]


def _sweep(argv):
    parser = argparse.ArgumentParser(prog="python -m derive sweep",
                                     description="Sweep one parameter of Eq. (4).")
    parser.add_argument("--param", required=True,
                        choices=[p["name"] for p in _MODEL_PARAMS])
    parser.add_argument("--from", dest="start", type=float)
    parser.add_argument("--to", dest="stop", type=float)
    parser.add_argument("--step", type=float)
    parser.add_argument("--values", type=float, nargs="+", help="explicit values instead")
    _common(parser)
    parser.add_argument("--jobs", type=int, default=None,
                        help="process pool size (default: all cores; 1: serial)")
    parser.add_argument("--scheduler", default=None,
                        help="dask.distributed scheduler address (needs the 'dask' extra)")
    parser.add_argument("--cache-dir", default="default", help="default: $BELTMDSM_CACHE or "
                        "~/.cache/beltmdsm/sweeps")
    parser.add_argument("--no-cache", action="store_true")
    parser.add_argument("--modulation", action="store_true",
                        help="add friction modulation columns (Figs. 10-12)")
    parser.add_argument("--out", metavar="CSV", help="write the table as CSV")
    parser.add_argument("--no-progress", action="store_true")
    args = parser.parse_args(argv)
    if args.values:
        values = np.asarray(args.values)
    else:
        if None in (args.start, args.stop, args.step):
            parser.error("give --from, --to and --step, or --values")
        if not args.step > 0 or args.stop < args.start:
            parser.error("--step must be > 0 and --to >= --from")
        values = args.start + args.step * np.arange(int(np.floor((args.stop - args.start) / args.step
                                                                   + 1e-9)) + 1)
    from .sweep import sweep, table_to_csv
    import concurrent.futures as cf
    client = None
    if args.scheduler:
        from distributed import Client
        client = Client(args.scheduler)
        executor = client.get_executor()
    elif args.jobs is not None and args.jobs <= 1:
        executor = "serial"
    elif args.jobs is not None:
        executor = cf.ProcessPoolExecutor(max_workers=args.jobs)
    else:
        executor = None
    try:
        table = sweep(args.param, values, _params(args, skip=(args.param,)), contact=args.contact,
                      settings=_settings(args), executor=executor,
                      cache_dir=None if args.no_cache else args.cache_dir,
                      progress=not args.no_progress, modulation=args.modulation)
    finally:
        if isinstance(executor, cf.Executor):
            executor.shutdown()
        if client is not None:
            client.close()
    if args.out:
        table_to_csv(table, args.out)
    if args.json:
        print(json.dumps([_jsonable(dict(zip(table.dtype.names, r.tolist()))) for r in table]))
        return 0
    names = [args.param, "regime", "peak_omega1", "peak_Omega", "energy_residual", "n_switches",
             "wall_s"]
    print("  ".join(f"{n:>22}" if n == "regime" else f"{n:>15}" for n in names))
    for r in table:
        print("  ".join(f"{r[n]:>22}" if n == "regime" else
                        (f"{r[n]:>15d}" if n == "n_switches" else f"{r[n]:>15.6g}") for n in names))
    if args.param == "Vb":
        print("\n".join(validation_lines(table)))
    if args.out:
        print(f"table written to {args.out}")
    return 0


def main(argv=None):
    """Entry point; ``argv[0]`` is the subcommand ("simulate" or "sweep")."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or argv[0] not in ("simulate", "sweep"):
        print("usage: python -m derive simulate|sweep [options]  (--help for each)",
              file=sys.stderr)
        return 2
    command, rest = argv[0], argv[1:]
    try:
        return _simulate(rest) if command == "simulate" else _sweep(rest)
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
