"""``basins``: which attractor each start of a plane of initial states reaches."""

from __future__ import annotations

import argparse
import json

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
from ..running import register

_AXES = ("X1", "Y1", "X2", "Y2")


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), executor_parent(), cache_parent(), json_parent()],
        help="basins of attraction on a plane of initial states",
        description="Starts on a grid of a plane of states at the excitation's phase 0 "
        "(default X1 and X1' = Y1, the normal state on its periodic orbit), each iterated "
        "on the period map until a known attractor claims it; attractors named by their "
        "kind, period, rotation number and largest Lyapunov exponent "
        "(beltmdsm/studies/basins.py, beltmdsm/attractors/classification.py).",
    )
    for axis, default in (("x", "X1"), ("y", "Y1")):
        sub.add_argument(
            f"--{axis}",
            choices=_AXES,
            default=default,
            help=f"the {axis} axis of the plane (default {default}; Y1 is X1')",
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


def _range(args, axis, model):
    from ...studies.basins import axis_range

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


def run(args: argparse.Namespace) -> int:
    from ...studies.basins import basins
    from ...studies.cache import default_cache_dir
    from .. import text

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
        print(json.dumps(text.jsonable({**result.as_dict(), **result.model.as_dict()})))
    else:
        print(repr(result))
        for a in result.attractors:
            print(f"  {a.label}: {a.attractor!r}: {a.attractor.evidence}")
        if args.png:
            print(f"map drawn to {args.png}")
    return 0
