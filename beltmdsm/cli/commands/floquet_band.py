"""``floquet-band``: the ranges of one parameter where the periodic response is unstable."""

from __future__ import annotations

import argparse
import json

from ...model import MODEL_PARAMETERS
from ...settings import MAX_BAND_POINTS, MIN_TOL_ULPS
from .. import generic_forced
from ..flags import (
    POSITIVE,
    integer,
    json_parent,
    model_from,
    model_parent,
    output_file,
    periods_parent,
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
        [model_parent(), periods_parent(), json_parent()],
        models=generic_forced.floquet_band,
        help="ranges of a parameter where the periodic response is unstable",
        description="Ranges of one parameter where the periodic response is "
        "unstable, every edge located and labelled with its bifurcation "
        "(beltmdsm/continuation/band.py, docs/modelling.md#bifurcations).",
    )
    sub.add_argument(
        "--param",
        required=True,
        choices=(*MODEL_PARAMETERS, *other_params()),
        help="the parameter walked",
    )
    range_flags(sub)
    sub.add_argument(
        "--points",
        type=integer(2, MAX_BAND_POINTS),
        default=17,
        help=f"grid points walked before the refinement, 2 to {MAX_BAND_POINTS} "
        "(MAX_BAND_POINTS in beltmdsm/settings.py; about 2 ms a point) (default: 17)",
    )
    sub.add_argument(
        "--tol",
        type=POSITIVE,
        default=1e-3,
        help=f"the edges' tolerance, at least {MIN_TOL_ULPS} ulps of the larger end of "
        "the range and at most the grid's step (to - from) / (points - 1); edges closer "
        "than it are one edge, and the text says where that merges a range away "
        "(default: 1e-3)",
    )
    sub.add_argument(
        "--png",
        metavar="FILE",
        type=output_file,
        help="draw the largest multiplier, the unstable ranges and the edges to FILE "
        "(needs matplotlib)",
    )
    sub.add_argument(
        "--no-progress",
        action="store_true",
        help="no progress bar on stderr (shown once the band takes more than 2 s)",
    )


def run(args: argparse.Namespace) -> int:
    from ...continuation.band import floquet_band
    from .. import text

    lo, hi = range_from(args)
    band = floquet_band(
        model_from(args, skip=(swept(args),)),
        args.param,
        lo,
        hi,
        points=args.points,
        tol=args.tol,
        periods=args.periods,
        progress=not args.no_progress,
    )
    if args.png:
        from ..figure import save

        save(lambda ax: band.plot(ax), args.png, f"Floquet band in {band.param} ({band.model!r})")
    if args.json:
        print(json.dumps(text.jsonable(named(band.as_dict()))))
    else:
        print(text.band(band, lo, hi))
        if args.png:
            print(f"drawn to {args.png}")
    return 0
