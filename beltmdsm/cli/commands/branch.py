"""``branch``: a periodic response continued in one parameter (`beltmdsm.analysis.branch`)."""

from __future__ import annotations

import argparse
import json

from ...model import MODEL_PARAMETERS
from ..flags import (
    json_parent,
    model_from,
    model_parent,
    number,
    params_from,
    periods_parent,
    register,
)


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), periods_parent(), json_parent()],
        help="continue a periodic response in one parameter",
        description="The branch of the response of --periods excitation periods at the "
        "point the model flags give, continued in --param over [--from, --to] by "
        "pseudo-arclength continuation on the period map, through folds, with its "
        "stable and unstable parts and every bifurcation located "
        "(beltmdsm/analysis/branch.py).",
    )
    sub.add_argument(
        "--param", required=True, choices=MODEL_PARAMETERS, help="the parameter continued in"
    )
    sub.add_argument(
        "--from", dest="start", type=number(), required=True, metavar="X", help="lower end"
    )
    sub.add_argument(
        "--to", dest="stop", type=number(), required=True, metavar="X", help="upper end, > --from"
    )


def run(args: argparse.Namespace) -> int:
    from ...analysis.branch import branch
    from .. import text

    if not args.stop > args.start:
        args.parser.error(f"argument --to: must be > --from ({args.start:g}); got {args.stop:g}")
    value = params_from(args).get(args.param)
    if value is None:
        args.parser.error(f"argument --{args.param}: give the start's {args.param} as well")
    if not args.start <= value <= args.stop:
        args.parser.error(
            f"argument --{args.param}: the start ({value:g}) must lie in "
            f"[{args.start:g}, {args.stop:g}]"
        )
    found = branch(
        model_from(args), periods=args.periods, param=args.param, lo=args.start, hi=args.stop
    )
    if args.json:
        print(json.dumps(text.jsonable(found.as_dict())))
    else:
        print(text.branch(found))
    return 0
