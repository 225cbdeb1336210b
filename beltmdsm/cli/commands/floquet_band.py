"""``floquet-band``: the ranges of one parameter where the periodic response is unstable."""

from __future__ import annotations

import argparse
import json

from ...model import MODEL_PARAMETERS
from ..flags import (
    POSITIVE,
    integer,
    json_parent,
    model_from,
    model_parent,
    number,
    periods_parent,
    register,
    swept,
)


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), periods_parent(), json_parent()],
        help="ranges of a parameter where the periodic response is unstable",
        description="Ranges of one parameter where the periodic response is "
        "unstable, every edge located and labelled with its bifurcation "
        "(beltmdsm/analysis/band.py, docs/modelling.md#bifurcations).",
    )
    sub.add_argument(
        "--param", required=True, choices=MODEL_PARAMETERS, help="the parameter walked"
    )
    sub.add_argument(
        "--from", dest="start", type=number(), required=True, metavar="X", help="lower end"
    )
    sub.add_argument(
        "--to", dest="stop", type=number(), required=True, metavar="X", help="upper end, > --from"
    )
    sub.add_argument(
        "--points",
        type=integer(2),
        default=17,
        help="grid points walked before the refinement (default 17)",
    )
    sub.add_argument(
        "--tol", type=POSITIVE, default=1e-3, help="the edges' tolerance, > 0 (default 1e-3)"
    )


def run(args: argparse.Namespace) -> int:
    from ...analysis.band import floquet_band
    from .. import text

    if not args.stop > args.start:
        args.parser.error(f"argument --to: must be > --from ({args.start:g}); got {args.stop:g}")
    band = floquet_band(
        args.param,
        args.start,
        args.stop,
        model_from(args, skip=(swept(args),)),
        points=args.points,
        tol=args.tol,
        periods=args.periods,
    )
    if args.json:
        print(json.dumps(text.jsonable(band.as_dict())))
    else:
        print(text.band(band, args.start, args.stop))
    return 0
