"""``coexistence``: where stable periodic responses coexist
(`beltmdsm.multistability.coexistence`)."""

from __future__ import annotations

import argparse
import json

from ...model import MODEL_PARAMETERS
from ...state_names import rate_column
from .. import generic_studies
from ..flags import (
    POSITIVE,
    json_parent,
    lock_parent,
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
        [model_parent(), lock_parent(), json_parent()],
        models=generic_studies.coexistence,
        help="where two or more stable periodic responses coexist",
        description="The ranges of one parameter where two or more stable periodic "
        "responses (the T-periodic one and phase-locked ones) coexist, each edge with "
        "its bifurcation: seeds from shooting, runs from rest and continued ladders, "
        "each continued as a branch (beltmdsm/multistability/coexistence.py).",
    )
    sub.add_argument(
        "--param",
        required=True,
        choices=(*MODEL_PARAMETERS, *other_params()),
        help="the parameter walked (of --model's parameters)",
    )
    range_flags(sub)
    sub.add_argument(
        "--step",
        type=POSITIVE,
        default=0.5,
        help="spacing of the seeds, > 0, at most (to - from) / 2 (a seed inside) and "
        "giving at most MAX_SEED_POINTS = 1000 of them; a response stable only between two "
        "seeds may be missed (default 0.5)",
    )
    sub.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    sub.add_argument(
        "--png",
        metavar="FILE",
        type=output_file,
        help=f"draw each response's branch (amplitude of {rate_column()}, the first "
        "coordinate's rate) and the coexistence ranges to FILE (needs matplotlib)",
    )


def run(args: argparse.Namespace) -> int:
    from ...multistability.coexistence import coexistence, seed_points
    from .. import text

    lo, hi = range_from(args)
    found = coexistence(
        model_from(args, skip=(swept(args),)),
        args.param,
        lo,
        hi,
        points=seed_points(lo, hi, args.step),
        limit=args.limit,
        progress=not args.no_progress,
    )
    if args.png:
        from ..figure import save

        save(
            lambda ax: found.plot(ax),
            args.png,
            f"stable responses in {found.param} ({found.model!r})",
        )
    if args.json:
        print(json.dumps(text.jsonable(named(found.as_dict()))))
    else:
        print(text.coexistence(found))
        if args.png:
            print(f"drawn to {args.png}")
    return 0
