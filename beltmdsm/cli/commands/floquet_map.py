"""``floquet-map``: where the periodic response is unstable over two parameters."""

from __future__ import annotations

import argparse
import json

from ...model import MODEL_PARAMETERS
from .. import generic_forced
from ..flags import (
    integer,
    json_parent,
    model_from,
    model_parent,
    output_file,
    range_flags,
    range_from,
    swept,
)
from ..models import named, other_params
from ..running import register


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), json_parent()],
        models=generic_forced.floquet_map,
        help="two-parameter map of where the periodic response is unstable",
        description="The region of two parameters where the periodic response of "
        "period T is unstable or absent, its boundary curves (by bifurcation) traced "
        "by continuation row by row, beside the paper's linear analysis "
        "(beltmdsm/continuation/floquet_map.py).",
    )
    for axis in ("x", "y"):
        sub.add_argument(
            f"--{axis}",
            required=True,
            choices=(*MODEL_PARAMETERS, *other_params()),
            help=f"the parameter of {axis}",
        )
        range_flags(sub, axis)
    sub.add_argument(
        "--points",
        "--rows",
        dest="rows",
        type=integer(2),
        default=100,
        help="values of --y (the map's rows; --rows is the same flag), >= 2 and at most "
        "MAX_MAP_ROWS = 10^4 (default 100)",
    )
    sub.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    sub.add_argument(
        "--png", metavar="FILE", type=output_file, help="draw the map to FILE (needs matplotlib)"
    )


def run(args: argparse.Namespace) -> int:
    from ...continuation.floquet_map import floquet_map
    from .. import text

    (x_lo, x_hi), (y_lo, y_hi) = range_from(args, "x"), range_from(args, "y")
    if args.x == args.y:
        args.parser.error(f"argument --y: must differ from --x ({args.x})")
    result = floquet_map(
        model_from(args, skip=(swept(args, "x"), swept(args, "y"))),
        args.x,
        x_lo,
        x_hi,
        args.y,
        y_lo,
        y_hi,
        points=args.rows,
        progress=not args.no_progress,
    )
    if args.png:
        from ..figure import floquet_map as draw

        draw(result, args.png)
    if args.json:
        print(json.dumps(text.jsonable(named(result.as_dict()))))
    else:
        print(text.floquet_map(result, args.png))
    return 0
