"""The studies of a model other than the paper's (``--model NAME``) on the generic
runtime: ``sweep`` (`beltmdsm.oscillator.sweep`), ``lyapunov``
(`beltmdsm.oscillator.lyapunov`) and ``basins`` (`beltmdsm.oscillator.basins`).

As `beltmdsm.cli.generic`: each reads `system_from`'s `System`, refuses in one line the
flags that apply to the paper's model only, names states as the model does, and its
JSON and CSV name the model (``"model": NAME``).
"""

from __future__ import annotations

import argparse

import numpy as np

from ..state_names import plane
from .generic import _head, _print
from .models import model_of, refuse_flags, system_from

__all__ = [
    "sweep", "lyapunov", "basins", "responses", "coexistence", "basin_stability", "STATES",
    "sweep_values",
]  # fmt: skip


def _plane(args: argparse.Namespace, system) -> tuple[str, str]:
    """The two states of ``--x`` and ``--y``, named as the model names them (the paper's
    defaults X1 and Y1, `beltmdsm.state_names.plane`: the first coordinate and its
    velocity), checked once."""
    default, own = plane(), plane(system.name)
    x = own[0] if args.x == default[0] else args.x
    y = own[1] if args.y == default[1] else args.y
    for axis, state in (("x", x), ("y", y)):
        if state not in system.states:
            args.parser.error(
                f"argument --{axis}: not a state of model {system.name!r} "
                f"({', '.join(system.states)}); got {state}"
            )
    return x, y


def _states() -> tuple[str, ...]:
    from beltmdsm.generated.models import MODELS, load

    names: list[str] = []
    for model in MODELS:
        names += [s for s in load(model).STATES if s not in names]
    return tuple(names)


#: Every registered model's states (the choices of ``basins --x/--y``).
STATES = _states()


def sweep_values(args: argparse.Namespace) -> np.ndarray:
    """The values of ``--from/--to/--step`` or ``--values`` (a bad grid: exit 2)."""

    from ..batch.sweep import linear_values

    if args.values:
        grid = (("--from", args.start), ("--to", args.stop), ("--step", args.step))
        given = [flag for flag, value in grid if value is not None]
        if given:
            args.parser.error(f"argument --values: give --values or {', '.join(given)}, not both")
        return np.asarray(args.values)
    if None in (args.start, args.stop, args.step):
        args.parser.error("give --from, --to and --step, or --values")
    if args.stop < args.start:
        args.parser.error(f"argument --to: must be >= --from ({args.start:g}); got {args.stop:g}")
    try:
        return linear_values(args.start, args.stop, args.step)
    except ValueError as err:
        args.parser.error(f"argument --step: {err}")


class DiskCache:
    """A generic sweep's rows on the sweeps' disk cache (beltmdsm/batch/cache.py: one
    checked JSON file per point, named by the SHA-256 of its identity, the package's
    version and its code), for `beltmdsm.oscillator.sweep.sweep`'s ``cache``."""

    def __init__(self, folder) -> None:
        from pathlib import Path

        self.folder = Path(folder)

    def _path(self, ident: dict):
        from ..batch.cache import cache_key

        return self.folder / f"{cache_key({'generic': ident})}.json"

    def get(self, ident: dict) -> dict | None:
        from ..batch.cache import read_cached

        row, _ = read_cached(self._path(ident), {"generic": ident}, ("regime",))
        return row

    def put(self, ident: dict, row: dict) -> None:
        from ..batch.cache import write_cached

        self.folder.mkdir(parents=True, exist_ok=True)
        write_cached(self._path(ident), {"generic": ident}, row)


def sweep(args: argparse.Namespace) -> int:
    """``sweep --model NAME``: a run per value of ``--param`` and what it settles on."""
    from ..batch.cache import default_cache_dir
    from ..oscillator.sweep import sweep as run
    from .flags import cache_dir_from, executor_from, swept

    refuse_flags(args, ("continuation", "modulation", "solver", "on_contact_loss"))
    name = swept(args)
    system = system_from(args)
    if name not in system.params:
        args.parser.error(
            f"argument --param: not a parameter of model {system.name!r} "
            f"({', '.join(system.params)}); got {name}"
        )
    values = sweep_values(args)
    folder = cache_dir_from(args)
    if folder == "default":
        folder = default_cache_dir()
    with executor_from(args) as executor:
        result = run(
            system, name, values, t_end=args.t_end, t_discard=args.t_discard, dt=args.dt,
            rtol=args.rtol, atol=args.atol,
            executor=None if executor in (None, "serial") else executor,
            cache=None if folder is None else DiskCache(folder),
        )  # fmt: skip
    if args.out:
        result.to_csv(args.out)
    out = {**result.as_dict(), **({"saved": args.out} if args.out else {})}
    lines = [
        _head(system),
        f"sweep of {name} over {len(result.rows)} values ({result.n_cached} from the cache):",
    ]
    for row in result.rows:
        ranges = ", ".join(
            f"{s} in [{row[f'{s}_min']:.6g}, {row[f'{s}_max']:.6g}] {u}"
            for s, u in zip(system.states, system.units)
        )
        lines.append(
            f"  {name} = {row[name]:.6g}: {row['regime']}, {row['sticks']} sticks; {ranges}"
        )
    if args.out:
        lines.append(f"table written to {args.out}")
    _print(args, out, lines)
    return 0


def lyapunov(args: argparse.Namespace) -> int:
    """``lyapunov --model NAME``: the spectrum of a run through the switches, from rest
    or from the periodic orbit (forced response or self-excited cycle) moved by
    ``--perturbation`` along the first state."""
    from ..oscillator import forced_response, self_excited_cycle
    from ..oscillator.lyapunov import lyapunov as spectrum

    system = system_from(args)
    y0 = None
    if args.start == "periodic":
        orbit = (
            self_excited_cycle(system)
            if system.excitation_period() is None
            else forced_response(system)
        )
        y0 = orbit.state.copy()
        y0[0] += 1e-2 if args.perturbation is None else args.perturbation
    elif args.perturbation is not None:
        args.parser.error(
            "argument --perturbation: moves the start on the periodic response; "
            "give --start periodic, or drop it"
        )
    spec = spectrum(system, y0, t_end=args.t_end, t_transient=args.t_transient)
    out = {**system.as_dict(), **spec.as_dict(), "start": args.start}
    lines = [
        _head(system),
        repr(spec),
        "exponents: " + ", ".join(f"{v:.6g}" for v in spec.exponents),
        f"{spec.collapsed} direction(s) removed by stick (exponent -inf)",
    ]
    _print(args, out, lines)
    return 0


def basins(args: argparse.Namespace) -> int:
    """``basins --model NAME``: which attractor each start of a plane of two of the
    model's states lands on (steady sliding, stick-slip or slip cycles, forced
    responses)."""
    from ..oscillator.basins import basins as run
    from .flags import executor_from

    refuse_flags(args, ("png",))
    system = system_from(args)
    x, y = _plane(args, system)
    ends = (args.x_from, args.x_to, args.y_from, args.y_to)
    if None in ends:
        args.parser.error(
            f"argument --{'samples' if args.samples is not None else 'x-from'}: model "
            f"{system.name!r} needs the plane's box: --x-from, --x-to, --y-from and --y-to"
        )
    if args.samples is not None:
        return _sampled(args, system, x, y, ends)
    with executor_from(args) as executor:
        result = run(
            system, x, ends[:2], y, ends[2:], points=args.points, t_end=args.t_end,
            executor=None if executor in (None, "serial") else executor,
        )  # fmt: skip
    lines = [_head(system), repr(result)]
    for i, (a, share) in enumerate(zip(result.attractors, result.shares())):
        state = ", ".join(f"{v:.6g}" for v in a.state)
        lines.append(f"  {i}: {a.kind} ({a.periods}), {share:.1%} of the starts; at ({state})")
    unresolved = float(np.mean(result.labels < 0))
    if unresolved:
        lines.append(f"  unresolved: {unresolved:.1%} of the starts")
    _print(args, result.as_dict(), lines)
    return 0


def _sampled(args: argparse.Namespace, system, x: str, y: str, ends) -> int:
    """``basins --model NAME --samples N``: `beltmdsm.basin_stability` of the model, each
    attractor's share of ``N`` uniform starts in the box with its standard error (the
    function ``basin-stability --model`` runs at each value of its parameter)."""
    from ..basin.basin_stability import basin_stability
    from .flags import executor_from

    region = {x: tuple(ends[:2]), y: tuple(ends[2:])}
    with executor_from(args) as executor:
        result = basin_stability(
            model_of(system), region, samples=args.samples, seed=args.seed,
            executor=executor, cache_dir=None,
        )  # fmt: skip
    lines = [_head(system), repr(result)]
    for a, p, e in zip(result.attractors, result.fractions, result.errors):
        lines.append(f"  {a.kind} ({a.periods}): {p:.4f} +- {e:.4f}")
    if result.unresolved:
        lines.append(f"  unresolved: {result.unresolved:.1%} of the starts")
    _print(args, result.as_dict(), lines)
    return 0


def _found_lines(found) -> list[str]:
    lines = []
    for f in found.found:
        a, o = f.attractor, f.orbit
        head = f"  {a.kind} ({a.periods}), {f.share:.0%} of the starts"
        if o is None:
            lines.append(f"{head}: shooting failed: {f.failure}")
        elif hasattr(o, "multipliers"):
            mults = ", ".join(f"{abs(z):.6g}" for z in o.multipliers)
            word = "stable" if o.stable else "unstable"
            lines.append(f"{head}: period {o.period:.10g} s, |multipliers| {mults}; {word}")
        else:
            lines.append(f"{head}: growth rate {o.growth_rate:.6g}")
    return lines


def responses(args: argparse.Namespace) -> int:
    """``responses --model NAME``: `beltmdsm.responses` of the model, the stable
    attractors that runs from a grid of starts land on, each shot exactly with its
    Floquet multipliers (or eigenvalues)."""
    from ..multistability.responses import responses as find

    refuse_flags(args, ("ladder",))
    system = system_from(args)
    model = model_of(system)
    found = find(model, t_end=args.t_end, limit=args.limit)
    lines = [_head(system), repr(found), *_found_lines(found)]
    if found.unresolved:
        lines.append(f"  unresolved: {found.unresolved:.0%} of the starts")
    _print(args, found.as_dict(), lines)
    return 0


def coexistence(args: argparse.Namespace) -> int:
    """``coexistence --model NAME``: `beltmdsm.coexistence` of the model, the stable
    attractors at points of ``--param`` spaced by about ``--step``, and the ranges where
    two or more coexist."""
    from ..multistability.coexistence import coexistence as walk
    from ..multistability.coexistence import seed_points
    from .flags import range_from, swept

    refuse_flags(args, ("png",))
    name = swept(args)
    system = system_from(args)
    model = model_of(system)
    if name not in system.params:
        args.parser.error(
            f"argument --param: not a parameter of model {system.name!r} "
            f"({', '.join(system.params)}); got {name}"
        )
    lo, hi = range_from(args)
    try:
        points = seed_points(lo, hi, args.step)
    except ValueError as err:
        args.parser.error(f"argument --step: {err}")
    result = walk(model, name, lo, hi, points=points, limit=args.limit)
    lines = [_head(system), repr(result)]
    for p in result.points:
        kinds = ", ".join(
            f"{f.attractor.kind}({f.attractor.periods})"
            for f in p.found
            if f.orbit is not None and f.orbit.stable
        )
        lines.append(f"  {name} = {p.system.params[name]:.6g}: {kinds or 'none'}")
    _print(args, result.as_dict(), lines)
    return 0


def basin_stability(args: argparse.Namespace) -> int:
    """``basin-stability --model NAME``: at ``--points`` values of ``--param``, each
    attractor's share of ``--samples`` random starts in the box, with its standard
    error (the same starts at every value)."""
    from ..oscillator.basins import basin_stability as shares
    from .flags import executor_from, range_from

    refuse_flags(args, ("png",))
    system = system_from(args)
    if args.param not in system.params:
        args.parser.error(
            f"argument --param: not a parameter of model {system.name!r} "
            f"({', '.join(system.params)}); got {args.param}"
        )
    lo, hi = range_from(args)
    x, y = _plane(args, system)
    rows = []
    with executor_from(args) as executor:
        for value in np.linspace(lo, hi, args.points):
            rows.append(
                shares(
                    system.replace(**{args.param: float(value)}), x, (args.x_from, args.x_to),
                    y, (args.y_from, args.y_to), samples=args.samples, seed=args.seed,
                    executor=None if executor in (None, "serial") else executor,
                )
            )  # fmt: skip
    out = {
        **system.as_dict(),
        "param": args.param,
        "values": [r.system.params[args.param] for r in rows],
        "points": [r.as_dict() for r in rows],
    }
    lines = [_head(system)]
    for r in rows:
        cells = ", ".join(
            f"{a.kind}({a.periods}) {p:.4f} +- {e:.4f}"
            for a, p, e in zip(r.attractors, r.fractions, r.errors)
        )
        lines.append(f"  {args.param} = {r.system.params[args.param]:.6g}: {cells}")
    _print(args, out, lines)
    return 0
