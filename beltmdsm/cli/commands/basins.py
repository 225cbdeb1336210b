"""``basins``: which attractor each start of a plane of initial states reaches."""

from __future__ import annotations

import argparse
import json

from ...state_names import column, plane
from .. import generic_studies
from ..flags import (
    cache_dir_from,
    cache_parent,
    executor_from,
    executor_parent,
    integer,
    json_parent,
    model_from,
    model_parent,
    number,
    output_file,
)
from ..models import named
from ..running import register

#: The paper's default plane: its first coordinate and that coordinate's rate.
_X, _Y = plane()


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), executor_parent(), cache_parent(), json_parent()],
        models=generic_studies.basins,
        help="basins of attraction on a plane of initial states, or basin stability by "
        "sampling (--samples)",
        description="Starts on a grid of a plane of states at the excitation's phase 0 "
        f"(default {_X} and {column(None, _Y)} = {_Y}, the normal state on its periodic orbit), "
        "each iterated "
        "on the period map until a known attractor claims it; attractors named by their "
        "kind, period, rotation number and largest Lyapunov exponent "
        "(beltmdsm/basin/basins.py, beltmdsm/attractors/classification.py). Without "
        "excitation the starts are states (the others at steady sliding's) and the "
        "attractors steady sliding and the stable self-excited cycles, each start decided "
        "by the region the computed cycles assign it to or by sticking "
        "(beltmdsm/attractors/self_excited.py); --samples N draws N uniform starts in the "
        "box instead (beltmdsm/basin/basin_stability.py).",
    )
    for axis, default in (("x", _X), ("y", _Y)):
        sub.add_argument(
            f"--{axis}",
            choices=generic_studies.STATES,
            default=default,
            help=f"the {axis} axis (default {default}; {_Y} is {column(None, _Y)}; with "
            f"--model, one of its states, {_X} and {_Y} its first coordinate and its rate)",
        )
        sub.add_argument(
            f"--{axis}-from",
            type=number(),
            default=None,
            metavar="A",
            help="its low end (default: around the attractors found)",
        )
        sub.add_argument(
            f"--{axis}-to", type=number(), default=None, metavar="B", help="its high end"
        )
    sub.add_argument(
        "--points", type=integer(2, 300), default=21, help="starts per axis (default 21)"
    )
    sub.add_argument(
        "--t-end",
        type=number(lambda x: x > 0, "positive"),
        default=2000.0,
        metavar="T",
        help="the length of each classification run [s] (default 2000)",
    )
    sub.add_argument("--png", metavar="FILE", type=output_file, help="draw the map to FILE")
    sampling_flags(sub)


def sampling_flags(sub, samples: int | None = None) -> None:
    """``--samples N --seed S --no-progress``: basin stability by sampling (shared with
    ``basin-stability``, where ``samples`` is the default)."""
    g = sub.add_argument_group("basin stability by sampling (without excitation)")
    g.add_argument(
        "--samples",
        type=integer(1, 10_000_000),
        default=samples,
        metavar="N",
        help="uniform random starts in the box of --x-from..--y-to"
        + (f" (default {samples})" if samples else " instead of a grid")
        + "; each attractor's fraction with its standard error sqrt(p (1 - p) / N)",
    )
    g.add_argument(
        "--seed", type=integer(0), default=0, metavar="S", help="of the random starts (default 0)"
    )
    g.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")


def region_from(args, model) -> dict:
    """The box of starts: ``--x-from .. --y-to``, all four required, each end within
    floating point for ``model`` (`beltmdsm.basin.basins.axis_range`)."""
    xr, yr = _range(args, "x", model), _range(args, "y", model)
    if xr is None or yr is None:
        args.parser.error("argument --samples: needs the box, --x-from/--x-to and --y-from/--y-to")
    if args.x == args.y:
        args.parser.error(f"argument --y: must differ from --x; got {args.y} twice")
    return {args.x: xr, args.y: yr}


def print_estimate(result, as_json: bool) -> None:
    """A `beltmdsm.basin.basin_stability.BasinStability` as text or JSON."""
    from .. import text

    if as_json:
        print(json.dumps(text.jsonable(named({**result.as_dict(), **result.model.as_dict()}))))
        return
    print(repr(result))
    for i, a in enumerate(result.attractors):
        p, e = result.fraction(i)
        period = f", period {a.period:.6g} s" if a.period else ""
        print(f"  {i}: {a.name}{period}: {p:.4f} +- {e:.4f} ({int(result.counts[i])} starts)")
    d = result.decided
    print(
        f"  decided by region at once: {d['region']}; by a run until it stuck: "
        f"{d['stick']}; undecided after the longest run: {d['none']}"
    )
    if result.interrupted:
        print(f"  interrupted: the estimate is of the {result.samples} starts finished")


def _range(args, axis, model):
    from ...basin.basins import axis_range

    lo, hi = getattr(args, f"{axis}_from"), getattr(args, f"{axis}_to")
    if (lo is None) != (hi is None):
        args.parser.error(f"argument --{axis}-from/--{axis}-to: give both or neither")
    if lo is not None and not lo < hi:
        args.parser.error(f"argument --{axis}-to: must be above --{axis}-from; got {hi} <= {lo}")
    try:
        return axis_range(model, axis, getattr(args, axis), lo, hi)
    except ValueError as err:  # beyond floating point, named by the flags
        said = str(err).removeprefix(f"{axis}_lo/{axis}_hi: ")
        args.parser.error(f"argument --{axis}-from/--{axis}-to: {said}")


def _sample(args) -> int:
    from ...basin.basin_stability import basin_stability

    model = model_from(args)
    region = region_from(args, model)
    cache_dir = cache_dir_from(args)
    if cache_dir == "default":
        from ...batch.cache import default_cache_dir

        cache_dir = default_cache_dir()
    with executor_from(args) as executor:
        result = basin_stability(
            model,
            region,
            samples=args.samples,
            seed=args.seed,
            executor=executor,
            cache_dir=cache_dir,
            progress=not args.no_progress,
        )
    print_estimate(result, args.json)
    return 130 if result.interrupted else 0


def run(args: argparse.Namespace) -> int:
    from ...basin.basins import basins
    from ...batch.cache import default_cache_dir
    from .. import text

    if args.samples is not None:
        return _sample(args)
    if args.x == args.y:
        args.parser.error(f"argument --y: must differ from --x; got {args.y} twice")
    model = model_from(args)
    xr, yr = _range(args, "x", model), _range(args, "y", model)
    cache_dir = cache_dir_from(args)
    if cache_dir == "default":
        cache_dir = default_cache_dir()
    with executor_from(args) as executor:
        result = basins(
            model,
            x=args.x,
            x_lo=xr and xr[0],
            x_hi=xr and xr[1],
            y=args.y,
            y_lo=yr and yr[0],
            y_hi=yr and yr[1],
            points=args.points,
            executor=executor,
            cache_dir=cache_dir,
            t_end=args.t_end,
        )
    if args.png:
        import matplotlib

        matplotlib.use("Agg")
        ax = result.plot()
        ax.figure.savefig(args.png, dpi=120, bbox_inches="tight")
    if args.json:
        print(json.dumps(text.jsonable(named({**result.as_dict(), **result.model.as_dict()}))))
    else:
        print(repr(result))
        for a in result.attractors:
            print(f"  {a.label}: {a.attractor!r}: {a.attractor.evidence}")
        if args.png:
            print(f"map drawn to {args.png}")
    return 0
