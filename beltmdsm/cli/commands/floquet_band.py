"""``floquet-band``: the ranges of one parameter where the periodic response is unstable."""

from __future__ import annotations

import argparse
import json

from ..flags import (
    POSITIVE,
    integer,
    json_parent,
    model_from,
    model_parent,
    number,
    register,
    swept,
)


def add(commands, name: str) -> None:
    from ...analysis.floquet import MAX_BAND_POINTS, MIN_TOL_ULPS
    from ...studies.sweep import SWEEPABLE

    sub = register(
        commands,
        name,
        run,
        [model_parent(), json_parent()],
        help="ranges of a parameter where the periodic response is unstable",
        description="Ranges of one parameter where the periodic response is "
        "unstable, edges located by bisection (beltmdsm/analysis/floquet.py).",
    )
    sub.add_argument("--param", required=True, choices=SWEEPABLE, help="the parameter walked")
    sub.add_argument(
        "--from",
        dest="start",
        type=number(),
        required=True,
        metavar="X",
        help="lower end of the range, in the parameter's domain",
    )
    sub.add_argument(
        "--to",
        dest="stop",
        type=number(),
        required=True,
        metavar="X",
        help="upper end of the range, strictly above --from",
    )
    sub.add_argument(
        "--points",
        type=integer(2, MAX_BAND_POINTS),
        default=17,
        help=f"grid points walked before the bisection, 2 to {MAX_BAND_POINTS} "
        "(MAX_BAND_POINTS in beltmdsm/analysis/floquet.py; about 2 ms a point) "
        "(default: 17)",
    )
    sub.add_argument(
        "--tol",
        type=POSITIVE,
        default=1e-3,
        help=f"the edges' tolerance, at least {MIN_TOL_ULPS} ulps of the larger end of "
        "the range; edges closer than it are one edge (default: 1e-3)",
    )
    sub.add_argument(
        "--no-progress",
        action="store_true",
        help="no progress bar on stderr (shown once the band takes more than 2 s)",
    )


def run(args: argparse.Namespace) -> int:
    from ...analysis.floquet import floquet_band
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
        progress=not args.no_progress,
    )
    if args.json:
        print(json.dumps(text.jsonable(band)))
    else:
        print(text.band(band, args.param, args.start, args.stop))
    return 0
