"""The runtime commands of ``python -m derive`` (and ``beltmdsm``).

simulate, sweep, predict, floquet, floquet-band, validate.

`derive.cli` builds the one argparse tree and calls `add_commands` to hang these
commands on it. The flags they share are declared once, as parent parsers:

* `model_parent`: every parameter of ``generated.parameters.PARAMETERS`` as a flag
  (``--mu_s`` and ``--mu-s``), checked against its domain, and the model options of
  `MODEL_OPTIONS` that the command takes (``--contact``);
* `solver_parent`: the fields of `runtime.simulate.SolverSettings`;
* `executor_parent` and `executor_from`: ``--jobs``/``--scheduler`` and the executor
  they ask for (sweep, validate); `cache_parent`: the sweep cache.

To add a model option, add one `ModelOption` line to `MODEL_OPTIONS` naming the
commands that take it; `model_kwargs` passes its value on as the keyword of its
name. A new command that takes every model flag of ``simulate`` uses
``model_parent("simulate")`` and ``model_kwargs(args, "simulate")``.

Every flag is checked when it is parsed (finite numbers, domains, ranges, existing
output folders); a bad one is a one-line error naming it, exit status 2. A bad value
found later (a ValueError from the generated checks) is reported the same way.

simulate: one run of Eq. (4); ``--json`` prints one JSON object (the summary of
`runtime.simulate.summarize` plus the parameters), otherwise a readable summary.
sweep: one parameter over a range (`runtime.sweep.sweep`), with a progress bar;
prints the table (or JSON with ``--json``), writes CSV with ``--out``; for a sweep
over Vb it adds the validation line on the omega1 peak (Fig. 2b).
predict: the predicted unstable belt speeds (`runtime.predict.predict`).
validate: writes VALIDATION.md (`runtime.validation`).
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import contextlib
import json
import math
import os
import sys
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from generated.parameters import DOMAINS, PARAMETERS

from .model import TENSIONS
from .parameters import CONTACTS, METHODS
from .simulate import DEFAULT_T_END

__all__ = [
    "main",
    "run_command",
    "add_commands",
    "COMMANDS",
    "ModelOption",
    "MODEL_OPTIONS",
    "model_parent",
    "model_kwargs",
    "solver_parent",
    "executor_parent",
    "cache_parent",
    "executor_from",
    "validation_lines",
]

COMMANDS = ("simulate", "sweep", "predict", "validate", "floquet", "floquet-band")
_MODEL_PARAMS = [p for p in PARAMETERS if p["name"] != "Vhat"]
PAPER_STATEMENT = "the omega1 peak 'vanishes after Vb ~ 8 m/s' (Sect. 3, Fig. 2b)"
_DOMAIN_TEXT = {
    "positive": (lambda x: x > 0, "> 0"),
    "nonnegative": (lambda x: x >= 0, ">= 0"),
    "real": (lambda x: True, "a number"),
}


@dataclass(frozen=True)
class ModelOption:
    """A model option beyond the parameters: one choice, on the commands that take it.

    The flag is ``--<name>`` (``flag`` overrides it); its value reaches the run
    functions as the keyword ``name`` (`model_kwargs`).
    """

    name: str
    commands: tuple
    choices: tuple
    default: str
    help: str
    flag: str | None = None


#: The model options, one line each.
MODEL_OPTIONS = (
    ModelOption(
        "contact",
        ("simulate", "sweep", "predict", "floquet", "floquet-band"),
        CONTACTS,
        "hertz_damp",
        "contact law: Hertz-Damp, Eq. (1), or the linear contact of Fig. 16",
    ),
    ModelOption(
        "tension",
        ("simulate", "sweep", "predict", "validate", "floquet", "floquet-band"),
        TENSIONS,
        "allowed",
        "tension law (docs/modelling.md#tension): Eq. (1) as printed, which can pull, "
        "or a contact that cannot pull (max(F, 0): the surfaces separate)",
    ),
)


# ---------------------------------------------------------------- checked flag types


def _number(check=None, text=""):
    """An argparse type: a finite float, and ``check(x)`` if given ("must be <text>")."""

    def parse(s):
        try:
            x = float(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a number; got {s!r}") from None
        if not math.isfinite(x):
            raise argparse.ArgumentTypeError(f"must be finite; got {s}")
        if check is not None and not check(x):
            raise argparse.ArgumentTypeError(f"must be {text}; got {s}")
        return x

    return parse


def _integer(minimum):
    def parse(s):
        try:
            n = int(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be an integer; got {s!r}") from None
        if n < minimum:
            raise argparse.ArgumentTypeError(f"must be >= {minimum}; got {n}")
        return n

    return parse


def _output_file(s):
    """A file to write: its folder must exist, and it must not be a folder itself."""
    path = Path(s)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise argparse.ArgumentTypeError(f"folder {folder} does not exist")
    if path.is_dir():
        raise argparse.ArgumentTypeError(f"{path} is a folder, not a file")
    if not os.access(folder, os.W_OK):
        raise argparse.ArgumentTypeError(f"folder {folder} is not writable")
    return s


def _cache_folder(s):
    if s != "default" and Path(s).exists() and not Path(s).is_dir():
        raise argparse.ArgumentTypeError(f"{s} exists and is not a folder")
    return s


_POSITIVE = _number(lambda x: x > 0, "> 0")
_NONNEGATIVE = _number(lambda x: x >= 0, ">= 0")


# ---------------------------------------------------------------- shared parents


def model_parent(
    command: str, *, parameters: bool = True, exclude: Sequence[str] = ()
) -> argparse.ArgumentParser:
    """Parent parser: the model parameters as flags and the model options of ``command``.

    Parameters
    ----------
    command : str
        the command whose `MODEL_OPTIONS` are wanted (a new command that takes every
        model flag of simulate passes "simulate")
    parameters : bool
        add a flag per parameter of ``generated.parameters.PARAMETERS`` (but ``Vhat``)
    exclude : tuple of str
        parameters without a flag (``predict`` scans ``Vb`` itself)
    """
    parent = argparse.ArgumentParser(add_help=False)
    if parameters:
        group = parent.add_argument_group("model parameters (default: the base set, Fig. 2)")
        for p in _MODEL_PARAMS:
            if p["name"] in exclude:
                continue
            flags = [f"--{p['name']}"]
            if "_" in p["name"]:
                flags.append(f"--{p['name'].replace('_', '-')}")
            check, text = _DOMAIN_TEXT[DOMAINS[p["name"]]]
            default = (
                f"default: {p['default_from']}"
                if p["default_from"]
                else f"default: {p['base']:g}"
                if p["base"] is not None
                else ""
            )
            group.add_argument(
                *flags,
                dest=p["name"],
                type=_number(check, text),
                default=None,
                metavar="X",
                help=f"{p['description']} [{p['unit']}]; {default}".rstrip("; "),
            )
    options = [o for o in MODEL_OPTIONS if command in o.commands]
    if options:
        group = parent.add_argument_group("model options")
        for o in options:
            group.add_argument(
                o.flag or f"--{o.name}",
                dest=o.name,
                choices=o.choices,
                default=o.default,
                help=f"{o.help} (default: {o.default})",
            )
    return parent


def model_kwargs(args: argparse.Namespace, command: str) -> dict:
    """The model options of ``command`` as keywords for the run functions."""
    return {o.name: getattr(args, o.name) for o in MODEL_OPTIONS if command in o.commands}


def _params(args, skip=()):
    return {
        p["name"]: getattr(args, p["name"])
        for p in _MODEL_PARAMS
        if getattr(args, p["name"], None) is not None and p["name"] not in skip
    }


def solver_parent() -> argparse.ArgumentParser:
    """Parent parser: the fields of `runtime.simulate.SolverSettings`."""
    parent = argparse.ArgumentParser(add_help=False)
    s = parent.add_argument_group("solver")
    s.add_argument(
        "--solver",
        choices=("events", "superposition"),
        default="events",
        help="superposition (fast, falls back to events on loss of contact) or "
        "events (solve_ivp on Eq. 4)",
    )
    s.add_argument(
        "--method", choices=METHODS, default="DOP853", help="solve_ivp method (default: DOP853)"
    )
    s.add_argument("--rtol", type=_POSITIVE, default=1e-10, help="> 0 (default: 1e-10)")
    s.add_argument("--atol", type=_POSITIVE, default=1e-10, help="> 0 (default: 1e-10)")
    s.add_argument(
        "--t-end",
        type=_POSITIVE,
        default=DEFAULT_T_END,
        help=f"duration [s], > 0 (default: {DEFAULT_T_END:g})",
    )
    s.add_argument(
        "--t-discard",
        type=_NONNEGATIVE,
        default=None,
        help="start of the steady window [s] (default 30%% of --t-end)",
    )
    s.add_argument(
        "--dt", type=_POSITIVE, default=0.02, help="sampling step [s], > 0 (default: 0.02)"
    )
    s.add_argument("--on-contact-loss", choices=("continue", "stop"), default="continue")
    return parent


def _settings(args):
    from .simulate import SolverSettings

    try:
        return SolverSettings(
            solver=args.solver,
            method=args.method,
            rtol=args.rtol,
            atol=args.atol,
            t_end=args.t_end,
            t_discard=args.t_discard,
            dt=args.dt,
            on_contact_loss=args.on_contact_loss,
        )
    except ValueError as err:
        # every field is checked alone when parsed: what is left is how they fit together
        args.parser.error(f"argument --t-end/--t-discard/--dt: {err}")


def executor_parent() -> argparse.ArgumentParser:
    """Parent parser: where the runs go, ``--jobs`` and ``--scheduler`` (`executor_from`)."""
    parent = argparse.ArgumentParser(add_help=False)
    g = parent.add_argument_group("where the runs go")
    g.add_argument(
        "--jobs",
        type=_integer(1),
        default=None,
        help="worker processes (default: all cores; 1: in this process)",
    )
    g.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="a dask.distributed scheduler, e.g. tcp://host:8786 (needs the "
        "'dask' extra); overrides --jobs",
    )
    return parent


@contextlib.contextmanager
def executor_from(args: argparse.Namespace) -> Iterator[cf.Executor | str | None]:
    """The executor that ``--scheduler``/``--jobs`` ask for, closed when the block ends.

    Yields
    ------
    ``Client(ADDRESS).get_executor()`` of a dask.distributed cluster for
    ``--scheduler``; ``"serial"`` for ``--jobs 1``; a process pool of ``--jobs N``
    workers; None without either (the sweep opens a pool over the local cores).
    """
    if args.scheduler:
        try:
            from distributed import Client
        except ImportError:
            args.parser.error(
                "argument --scheduler: needs dask.distributed (pip install 'beltmdsm[dask]')"
            )
        try:
            client = Client(args.scheduler, timeout="10s")
        except (OSError, ValueError, TypeError) as err:
            args.parser.error(f"argument --scheduler: cannot connect to {args.scheduler}: {err}")
        executor = client.get_executor()
        try:
            yield executor
        finally:
            executor.shutdown()
            client.close()
    elif args.jobs == 1:
        yield "serial"
    elif args.jobs:
        import concurrent.futures as cf

        with cf.ProcessPoolExecutor(max_workers=args.jobs) as pool:
            yield pool
    else:
        yield None


def cache_parent() -> argparse.ArgumentParser:
    """Parent parser: the sweep cache (`runtime.sweep`)."""
    parent = argparse.ArgumentParser(add_help=False)
    g = parent.add_argument_group("cache")
    g.add_argument(
        "--cache-dir",
        type=_cache_folder,
        default="default",
        help="default: $BELTMDSM_CACHE or ~/.cache/beltmdsm/sweeps",
    )
    g.add_argument("--no-cache", action="store_true", help="do not use the sweep cache")
    return parent


def _cache_dir(args):
    return None if args.no_cache else args.cache_dir


def _json_parent():
    parent = argparse.ArgumentParser(add_help=False)
    parent.add_argument("--json", action="store_true", help="print JSON")
    return parent


def _jsonable(x):
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, (np.floating, float)):
        return None if not np.isfinite(x) else float(x)
    if isinstance(x, (np.integer, np.bool_)):
        return x.item()
    return x


# ---------------------------------------------------------------- simulate


def _simulate(args):
    from .simulate import simulate

    sim = simulate(
        _params(args),
        **model_kwargs(args, "simulate"),
        settings=_settings(args),
        start=args.start,
        perturbation=args.perturbation,
    )
    out = dict(sim.summary)
    if args.modulation:
        from .modulation import modulation_scatter

        out.update(modulation_scatter(sim))
    out["params"] = sim.params
    out["contact"] = sim.contact
    out["tension"] = sim.tension
    if args.save:
        np.savez(
            args.save,
            t=sim.t,
            X1=sim.y[0],
            Y1=sim.y[1],
            X2=sim.y[2],
            Y2=sim.y[3],
            Fn=sim.normal_force,
            friction=sim.friction,
        )
    if args.json:
        print(json.dumps(_jsonable(out)))
        return 0 if sim.status == "done" else 2
    p = sim.params
    e = out["energy"]
    fractions = out["time_fraction"]
    if sim.tension == "clipped":
        force = (
            f"normal force: min {out['min_normal_force']:.4g} m/s^2 (clipped: the contact "
            f"cannot pull; separated {100 * fractions.get('separated', 0.0):.1f}% of the "
            f"steady window, {out['n_separations']} separations)"
        )
    else:
        force = (
            f"normal force: min {out['min_normal_force']:.4g} m/s^2, negative (tensile, "
            f"Eq. 1 as printed) {100 * out['tension_fraction']:.1f}% of the steady window"
        )
    lines = [
        f"Eq. (4), {sim.contact}, tension {sim.tension}, Vb = {p['Vb']:g} m/s, "
        f"t = 0..{out['t_end']:g} s (steady window from {out['t_discard']:g} s), "
        f"solver: {out['solver']}",
        f"status: {sim.status} ({sim.message})",
        f"regime: {out['regime']}  (time in "
        + "/".join(fractions)
        + ": "
        + "/".join(f"{100 * v:.1f}%" for v in fractions.values())
        + ")",
        f"switches: {out['n_switches']} (reversals {out['n_reversals']}, sticks {out['n_sticks']}, "
        f"contact losses {out['n_contact_losses']}, separations {out['n_separations']}, "
        f"Zeno limits {out['n_zeno']})",
        f"X1' spectrum: {out['peak_omega1']:.6g} m/s at {out['omega1_peak_at']:.6g} rad/s "
        f"(omega1 = {p['omega1']:g}), {out['peak_Omega']:.6g} m/s at Omega = {p['Omega_t']:g}; "
        f"omega1 peak {_peak_text(out)}",
        f"energy balance: residual {out['energy_residual']:.3g} (dE = {e['energy_change']:.6g}, "
        f"W_in = {e['work_input']:.6g}, W_visc = {e['work_viscous']:.6g}, "
        f"W_fric = {e['work_friction']:.6g})",
        force,
        f"Vr range in the window: {out['vr_min']:.4g} .. {out['vr_max']:.4g} m/s; "
        f"mean friction {out['mean_friction']:.6g} m/s^2",
    ]
    if args.modulation:
        lines.append(
            "mu_eff over 2pi/Omega: {mu_eff_Omega_mean:.5g} +- {mu_eff_Omega_std:.3g}; "
            "over 2pi/omega1: {mu_eff_omega1_mean:.5g} +- {mu_eff_omega1_std:.3g}".format(**out)
        )
    lines.append(f"wall time {out['wall_s']:.2f} s")
    print("\n".join(lines))
    return 0 if sim.status == "done" else 2


def _floquet(args):
    from .floquet import floquet

    f = floquet(_params(args), **model_kwargs(args, "floquet"))
    out = f.as_dict()
    out["params"] = f.response.params
    out["contact"], out["tension"] = f.response.contact, f.response.tension
    out["switches"] = [
        {"t": t, "before": b.name.lower(), "after": a.name.lower(), "surface": s}
        for t, b, a, s in f.response.switches
    ]
    if args.json:
        print(json.dumps(_jsonable(out)))
        return 0
    p = f.response.params
    mus = ", ".join(f"{z.real:.6g}{z.imag:+.6g}j" for z in f.multipliers)
    lines = [
        f"periodic response of Eq. (4), {f.response.contact}, tension "
        f"{f.response.tension}, Vb = {p['Vb']:g} m/s: period {f.period:.6g} s, "
        f"{f.n_reversals} reversals and {f.n_sticks} sticks per period, Newton "
        f"{f.response.iterations} iterations (residual {f.response.residual:.1e})"
    ]
    if f.grazing is not None:
        lines.append(
            f"GRAZING: a reversal at t = {f.grazing['t']:.6g} s is reached with a "
            f"vanishing acceleration (ratio {f.grazing['ratio']:.1e}); no multiplier "
            "is reported"
        )
    else:
        lines += [
            f"Floquet multipliers: {mus}",
            f"largest |mu| = {f.max_abs_multiplier:.6g}: "
            f"{'stable' if f.stable else 'UNSTABLE'}; growth rate "
            f"{f.growth_rate:.6g} 1/s, critical pair at {f.frequency:.6g} rad/s "
            f"(omega1 = {p['omega1']:g}; modulo {2 * math.pi / f.period:.6g})",
        ]
    print("\n".join(lines))
    return 0


def _floquet_band(args):
    from .floquet import floquet_band

    if not args.stop > args.start:
        args.parser.error(f"argument --to: must be > --from ({args.start:g}); got {args.stop:g}")
    band = floquet_band(
        args.param,
        args.start,
        args.stop,
        _params(args, skip=(args.param,)),
        **model_kwargs(args, "floquet-band"),
        points=args.points,
        tol=args.tol,
    )
    if args.json:
        print(json.dumps(_jsonable(band)))
        return 0
    from .intervals import format_intervals

    lines = [
        f"periodic response unstable (or absent) for {args.param} in "
        f"{format_intervals(band['unstable'], '.4f')} of {args.start:g}..{args.stop:g}"
    ]
    sides = {
        (False, True): "unstable above",
        (True, False): "unstable below",
        (False, False): "stable on both sides",
        (True, True): "unstable on both sides",
    }
    for e in band["edges"]:
        lines.append(
            f"  edge at {e['value']:.4f} ({e['kind']}; "
            f"{sides[e['unstable_below'], e['unstable_above']]})"
        )
    if band["no_periodic_response"]:
        lines.append(
            f"  no periodic response in {format_intervals(band['no_periodic_response'], '.4f')}"
        )
    for f in band["failed"]:
        lines.append(f"  no periodic response found at {f['value']:g}: {f['reason']}")
    print("\n".join(lines))
    return 0


def _peak_text(out):
    """The verdict on the omega1 peak: unresolved (and why), PRESENT or absent."""
    if not out["resolved"]:
        return f"unresolved ({out['unresolved_reason']})"
    if out["omega1_peak_present"]:
        return "PRESENT (friction-induced vibration)"
    return "absent"


# ---------------------------------------------------------------- sweep


def validation_lines(table: np.ndarray, param: str = "Vb") -> list[str]:
    """The validation print-out: where the omega1 peak appears, beside the paper."""
    from .intervals import format_intervals
    from .simulate import PEAK_PRESENT_RATIO
    from .sweep import omega1_peak_ranges, resolved_mask, unresolved_values

    ranges = omega1_peak_ranges(table, param)
    found = format_intervals(ranges, "g", "nowhere")
    x = np.asarray(table[param], float)
    resolved = resolved_mask(table, param)
    present = np.asarray(table["omega1_peak_present"], bool) & resolved
    lines = [
        f"omega1 peak (>= {100 * PEAK_PRESENT_RATIO:g}% of the Omega peak) present for "
        f"{param} in {found} m/s of the swept {x.min():g}..{x.max():g} m/s "
        f"({int(present.sum())} of {int(resolved.sum())} resolved points)"
    ]
    unresolved = unresolved_values(table, param)
    if unresolved:
        lines.append(
            f"unresolved (the run cannot tell; neither present nor absent) at {param} = "
            + ", ".join(f"{v:g}" for v in unresolved)
            + " m/s; lengthen --t-end"
        )
    return lines + [f"paper: {PAPER_STATEMENT}"]


def _sweep_values(args):
    from .sweep import linear_values

    if args.values:
        return np.asarray(args.values)
    if None in (args.start, args.stop, args.step):
        args.parser.error("give --from, --to and --step, or --values")
    if args.stop < args.start:
        args.parser.error(f"argument --to: must be >= --from ({args.start:g}); got {args.stop:g}")
    try:
        return linear_values(args.start, args.stop, args.step)
    except ValueError as err:
        args.parser.error(f"argument --step: {err}")


def _sweep(args):
    from .sweep import sweep, table_to_csv

    values = _sweep_values(args)
    if args.continuation and (args.scheduler or (args.jobs or 1) > 1):
        args.parser.error(
            "argument --continue: a continued sweep runs its points one after "
            "another in this process (each starts from the previous point's "
            "state); drop --jobs/--scheduler"
        )
    with contextlib.nullcontext("serial") if args.continuation else executor_from(args) as executor:
        table = sweep(
            args.param,
            values,
            _params(args, skip=(args.param,)),
            **model_kwargs(args, "sweep"),
            settings=_settings(args),
            executor=executor,
            cache_dir=_cache_dir(args),
            progress=not args.no_progress,
            modulation=args.modulation,
            continuation=args.continuation,
        )
    if args.out:
        table_to_csv(table, args.out)
    if args.json:
        print(json.dumps([_jsonable(dict(zip(table.dtype.names, r.tolist()))) for r in table]))
        return 0
    names = [
        args.param,
        "regime",
        "peak_omega1",
        "peak_Omega",
        "resolved",
        "energy_residual",
        "n_switches",
        "wall_s",
    ]
    text = {"regime": 22, "resolved": 8}
    print("  ".join(f"{n:>{text.get(n, 15)}}" for n in names))
    for r in table:
        print(
            "  ".join(
                f"{str(r[n]):>{text[n]}}"
                if n in text
                else (f"{r[n]:>15d}" if n == "n_switches" else f"{r[n]:>15.6g}")
                for n in names
            )
        )
    how = (
        f"continued {args.continuation} from rest at {args.param} = "
        f"{(table[args.param].min() if args.continuation == 'up' else table[args.param].max()):g}"
        if args.continuation
        else "each point from rest"
    )
    print(f"tension {args.tension}; {how}")
    if args.param == "Vb":
        print("\n".join(validation_lines(table)))
    if args.out:
        print(f"table written to {args.out}")
    return 0


# ---------------------------------------------------------------- predict


def _predict(args):
    from .intervals import format_intervals
    from .predict import predict

    vb = None
    if args.vb_max is not None:
        vb = np.linspace(args.vb_max / args.vb_points, args.vb_max, args.vb_points)
    result = predict(
        _params(args, skip=("Vb",)), **model_kwargs(args, "predict"), vb=vb, points=args.vb_points
    )
    if args.json:
        print(json.dumps(result))
        return 0
    reasons = result.get("reasons", {})
    for name in ("paper_tangential_vhat", "paper_coupled_vhat", "consistent_mdsm"):
        found = result[name]
        if found is None:
            print(f"no prediction for {name}: {reasons[name]}")
            continue
        note = f"; {reasons[name]}" if name in reasons else ""
        print(f"{name:>22}: unstable Vb in {format_intervals(found, '.3f')}{note}")
    return 0


# ---------------------------------------------------------------- validate


def _validate(args):
    from . import validation

    with executor_from(args) as executor:
        results = validation.validate(
            args.quick,
            **model_kwargs(args, "validate"),
            executor=executor,
            cache_dir=_cache_dir(args),
            progress=not args.no_progress,
        )
    Path(args.out).write_text(validation.render_markdown(results, args.quick))
    for key, lab, _ in validation.ANALYSES:
        s = results["summary"][key]
        mae = "—" if s["mae"] is None else f"{s['mae']:.2f} m/s"
        na = f", no prediction {s['no_prediction']}" if s.get("no_prediction") else ""
        print(
            f"{lab:>4}: MAE of edges {mae} (n = {s['n_edges']}), miss {s['miss']}, "
            f"false alarm {s['false_alarm']}{na}"
        )
    for key, lab, _ in validation.ANALYSES:
        s = results["floquet_summary"][key]
        mae = "—" if s["mae"] is None else f"{s['mae']:.3f} m/s"
        print(f"{lab:>4}: against Floquet, MAE of edges {mae} (n = {s['n_edges']})")
    ms = results["mismatch_summary"]
    print(
        f"periodic start against Floquet: {len(ms['mismatches'])} mismatches in "
        f"{ms['checked']} points"
    )
    print(f"tension law: {results['tension']}")
    print(f"wrote {args.out}")
    return 0


# ---------------------------------------------------------------- the tree


def _run(args):
    """Run a parsed command; a bad value found on the way is a one-line error."""
    try:
        return args.handler(args)
    except ValueError as err:
        args.parser.error(str(err))
    except OSError as err:
        print(f"{args.parser.prog}: error: {err}", file=sys.stderr)
        return 1


def _add(commands, name, handler, parents, **kwargs):
    sub = commands.add_parser(name, parents=parents, **kwargs)
    sub.set_defaults(run=_run, handler=handler, parser=sub)
    return sub


def add_commands(commands: argparse._SubParsersAction) -> None:
    """Add simulate, sweep, predict and validate to ``commands`` (an argparse subparsers)."""
    sim = _add(
        commands,
        "simulate",
        _simulate,
        [model_parent("simulate"), solver_parent(), _json_parent()],
        help="simulate Eq. (4) and summarise the run",
        description="Simulate Eq. (4) and summarise the run.",
    )
    sim.add_argument(
        "--start",
        choices=("rest", "periodic"),
        default="rest",
        help="start from the equilibrium at rest (default), or on the periodic "
        "response (runtime.floquet) with X1 moved by --perturbation",
    )
    sim.add_argument(
        "--perturbation",
        type=_number(),
        default=1e-2,
        metavar="DX1",
        help="the move of X1 from the periodic response [m] (default 1e-2)",
    )
    sim.add_argument(
        "--modulation", action="store_true", help="add friction modulation averages (Figs. 10-12)"
    )
    sim.add_argument(
        "--save", metavar="NPZ", type=_output_file, help="save t, X1, Y1, X2, Y2, Fn, friction"
    )

    from .sweep import MAX_POINTS, SWEEPABLE

    swp = _add(
        commands,
        "sweep",
        _sweep,
        [model_parent("sweep"), solver_parent(), executor_parent(), cache_parent(), _json_parent()],
        help="sweep one parameter of Eq. (4)",
        description="Sweep one parameter of Eq. (4) (runtime.sweep; at most "
        f"{MAX_POINTS:.0e} points).",
    )
    grid = swp.add_argument_group("the swept parameter")
    grid.add_argument("--param", required=True, choices=SWEEPABLE)
    grid.add_argument("--from", dest="start", type=_number(), metavar="X")
    grid.add_argument("--to", dest="stop", type=_number(), metavar="X")
    grid.add_argument("--step", type=_POSITIVE, metavar="H", help="> 0")
    grid.add_argument(
        "--values", type=_number(), nargs="+", metavar="X", help="explicit values instead"
    )
    swp.add_argument(
        "--continue",
        dest="continuation",
        choices=("up", "down"),
        default=None,
        help="follow an attractor: run the points in ascending (up) or "
        "descending (down) order, each from the previous point's state "
        "at its last whole excitation period (excitation phase 0), the "
        "first from rest; sequential, in this process (no --jobs N > 1 "
        "or --scheduler)",
    )
    swp.add_argument(
        "--modulation", action="store_true", help="add friction modulation columns (Figs. 10-12)"
    )
    swp.add_argument("--out", metavar="CSV", type=_output_file, help="write the table as CSV")
    swp.add_argument("--no-progress", action="store_true")

    pre = _add(
        commands,
        "predict",
        _predict,
        [model_parent("predict", exclude=("Vb",)), _json_parent()],
        help="predicted unstable belt speeds",
        description="Predicted unstable belt speeds: the paper's analysis and the consistent MDSM.",
    )
    pre.add_argument(
        "--vb-max",
        type=_POSITIVE,
        default=None,
        help="top of the Vb grid, > 0 (default: 1.05 x the linear amplitude)",
    )
    pre.add_argument(
        "--vb-points",
        type=_integer(2),
        default=400,
        help="points of the Vb grid, >= 2 (default: 400)",
    )

    _add(
        commands,
        "floquet",
        _floquet,
        [model_parent("floquet"), _json_parent()],
        help="Floquet multipliers of the periodic response",
        description="The periodic response of Eq. (4) by shooting and its Floquet "
        "multipliers, with saltation matrices at the switches "
        "(runtime.floquet).",
    )
    band = _add(
        commands,
        "floquet-band",
        _floquet_band,
        [model_parent("floquet-band"), _json_parent()],
        help="ranges of a parameter where the periodic response is unstable",
        description="Ranges of one parameter where the periodic response is "
        "unstable, edges located by bisection (runtime.floquet).",
    )
    band.add_argument("--param", required=True, choices=SWEEPABLE)
    band.add_argument("--from", dest="start", type=_number(), required=True, metavar="X")
    band.add_argument("--to", dest="stop", type=_number(), required=True, metavar="X")
    band.add_argument(
        "--points",
        type=_integer(2),
        default=17,
        help="grid points walked before the bisection (default 17)",
    )
    band.add_argument(
        "--tol", type=_POSITIVE, default=1e-3, help="the edges' tolerance, > 0 (default 1e-3)"
    )

    val = _add(
        commands,
        "validate",
        _validate,
        [model_parent("validate", parameters=False), executor_parent(), cache_parent()],
        help="write VALIDATION.md",
        description="Write VALIDATION.md: the simulated omega1-peak ranges of Vb "
        "against the predicted unstable ranges (Figs. 2, 17-21).",
    )
    val.add_argument(
        "--quick",
        action="store_true",
        help="1 m/s grid and 300 s runs instead of 0.25 m/s and 1000 s",
    )
    val.add_argument(
        "--out",
        type=_output_file,
        default=str(Path(__file__).resolve().parents[1] / "VALIDATION.md"),
        help="output file (default: VALIDATION.md at the repository root)",
    )
    val.add_argument("--no-progress", action="store_true")


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m derive simulate|sweep|predict|validate ...``; returns the exit status.

    The runtime commands of the one command line (`derive.cli.main`); ``argv[0]`` is
    the command.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or argv[0] not in COMMANDS:
        print(
            f"usage: python -m derive {{{','.join(COMMANDS)}}} [options]  (--help for each)",
            file=sys.stderr,
        )
        return 2
    from derive.cli import main as cli_main

    return cli_main(argv)


def run_command(command: str, argv: Sequence[str] | None = None) -> int:
    """`main` for one command, with or without the command's name in front of ``argv``."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == [command]:
        argv = argv[1:]
    return main([command, *argv])
