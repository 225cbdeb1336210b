"""``predict``: the predicted unstable belt speeds (`beltmdsm.prediction`)."""

from __future__ import annotations

import argparse
import json

from ...settings import MAX_VB_POINTS
from ..flags import POSITIVE, integer, json_parent, model_from, model_parent
from ..models import named
from ..running import register


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(exclude=("Vb",)), json_parent()],
        help="predicted unstable belt speeds",
        description="Predicted unstable belt speeds: the paper's analysis and the consistent MDSM.",
    )
    sub.add_argument(
        "--vb-max",
        type=POSITIVE,
        default=None,
        help="top of the Vb grid, > 0 (default: 1.05 x the onset of friction reversal, "
        "for Coulomb's law the linear amplitude; for a law whose coefficient varies in "
        "slip plus the unforced critical belt speed, doubled while a band reaches it); "
        "above the default's top the default grid is kept below it, and the result says "
        "what the coarser step above cannot resolve",
    )
    sub.add_argument(
        "--vb-points",
        type=integer(2, MAX_VB_POINTS),
        default=400,
        help=f"points of the Vb grid, 2 to {MAX_VB_POINTS} (MAX_VB_POINTS in "
        "beltmdsm/settings.py; up to 2 ms a point, 6 ms under Stribeck's law); the "
        "grid also holds the onset of friction reversal (for Coulomb's law the linear "
        "amplitude) and a point just below it, so that edge is found on any grid "
        "(default: 400)",
    )
    sub.add_argument(
        "--no-progress",
        action="store_true",
        help="no progress bar on stderr (shown once the grid takes more than 2 s)",
    )


def run(args: argparse.Namespace) -> int:
    from ...prediction.prediction import predict
    from .. import text

    result = predict(
        model_from(args),
        points=args.vb_points,
        progress=not args.no_progress,
        hi=args.vb_max,
    )
    if args.json:
        print(json.dumps(text.jsonable(named(result.as_dict()))))
    else:
        print(text.prediction(result))
    return 0
