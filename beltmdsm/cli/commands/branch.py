"""``branch``: a periodic response continued in one parameter (`beltmdsm.continuation.branch`)."""

from __future__ import annotations

import argparse
import json

from ...excitation import is_autonomous
from ...model import MODEL_PARAMETERS
from ...state_names import rate_column
from .. import generic
from ..flags import (
    json_parent,
    model_from,
    model_parent,
    output_file,
    params_from,
    periods_parent,
    range_flags,
    range_from,
)
from ..models import named, other_params
from ..running import register


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), periods_parent(), json_parent()],
        models=generic.branch,
        help="continue a periodic response in one parameter",
        description="The branch of the response of --periods excitation periods at the "
        "point the model flags give, continued in --param over [--from, --to] by "
        "pseudo-arclength continuation on the period map, through folds, with its "
        "stable and unstable parts and every bifurcation located "
        "(beltmdsm/continuation/branch.py). Without excitation (--alpha 0) the branch of "
        "self-excited cycles born at the Hopf point of steady sliding in the range, its "
        "criticality, the onset of stick, folds and period doubling "
        "(beltmdsm/cycles/branch.py); no start value is needed.",
    )
    sub.add_argument(
        "--param",
        required=True,
        choices=(*MODEL_PARAMETERS, *other_params()),
        help="the parameter continued in (of --model's parameters)",
    )
    range_flags(sub)
    sub.add_argument(
        "--png",
        metavar="FILE",
        type=output_file,
        help=f"draw the bifurcation diagram (amplitude of {rate_column()}, the first "
        "coordinate's rate, against --param) to FILE (needs matplotlib)",
    )


def run(args: argparse.Namespace) -> int:
    from ...branches import branch
    from .. import text

    lo, hi = range_from(args)
    model = model_from(args)
    value = params_from(args).get(args.param)
    if is_autonomous(model):
        # the cycles are born at the Hopf point in the range: no start to give
        found = branch(model, periods=args.periods, param=args.param, lo=lo, hi=hi)
        print(
            json.dumps(text.jsonable(named(found.as_dict()))) if args.json else text.branch(found)
        )
        return 0
    if value is None:
        args.parser.error(f"argument --{args.param}: give the start's {args.param} as well")
    if not lo <= value <= hi:
        args.parser.error(
            f"argument --{args.param}: the start ({value:g}) must lie in [{lo:g}, {hi:g}]"
        )
    found = branch(model, periods=args.periods, param=args.param, lo=lo, hi=hi)
    if args.png:
        from ..figure import save

        save(lambda ax: found.plot(ax), args.png, f"branch in {found.param} ({found.model!r})")
    if args.json:
        print(json.dumps(text.jsonable(named(found.as_dict()))))
    else:
        print(text.branch(found))
        if args.png:
            print(f"drawn to {args.png}")
    return 0
