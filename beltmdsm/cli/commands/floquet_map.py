"""``floquet-map``: where the periodic response is unstable over two parameters."""

from __future__ import annotations

import argparse
import json

from ...model import MODEL_PARAMETERS
from ..flags import (
    integer,
    json_parent,
    model_from,
    model_parent,
    number,
    output_file,
    register,
    swept,
)


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), json_parent()],
        help="two-parameter map of where the periodic response is unstable",
        description="The region of two parameters where the periodic response of "
        "period T is unstable or absent, its boundary curves (by bifurcation) traced "
        "by continuation row by row, beside the paper's linear analysis "
        "(beltmdsm/analysis/floquet_map.py).",
    )
    for axis in ("x", "y"):
        sub.add_argument(
            f"--{axis}", required=True, choices=MODEL_PARAMETERS, help=f"the parameter of {axis}"
        )
        sub.add_argument(
            f"--{axis}-from",
            dest=f"{axis}_from",
            type=number(),
            required=True,
            metavar="X",
            help="lower end",
        )
        sub.add_argument(
            f"--{axis}-to",
            dest=f"{axis}_to",
            type=number(),
            required=True,
            metavar="X",
            help=f"upper end, > --{axis}-from",
        )
    sub.add_argument(
        "--rows", type=integer(2), default=100, help="values of --y, >= 2 (default 100)"
    )
    sub.add_argument(
        "--png", metavar="FILE", type=output_file, help="draw the map to FILE (needs matplotlib)"
    )


def run(args: argparse.Namespace) -> int:
    from ...analysis.floquet_map import floquet_map
    from .. import text

    for axis in ("x", "y"):
        lo, hi = getattr(args, f"{axis}_from"), getattr(args, f"{axis}_to")
        if not hi > lo:
            args.parser.error(f"argument --{axis}-to: must be > --{axis}-from ({lo:g}); got {hi:g}")
    if args.x == args.y:
        args.parser.error(f"argument --y: must differ from --x ({args.x})")
    result = floquet_map(
        args.x,
        args.x_from,
        args.x_to,
        args.y,
        args.y_from,
        args.y_to,
        model_from(args, skip=(swept(args, "x"), swept(args, "y"))),
        rows=args.rows,
    )
    if args.png:
        from ..figure import floquet_map as draw

        draw(result, args.png)
    if args.json:
        print(json.dumps(text.jsonable(result.as_dict())))
    else:
        print(text.floquet_map(result, args.png))
    return 0
