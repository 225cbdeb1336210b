"""``sweep``: one parameter of Eq. (4) over a range (`beltmdsm.batch.sweep`)."""

from __future__ import annotations

import argparse
import contextlib
import json

from ...model import MODEL_PARAMETERS
from ...settings import MAX_POINTS
from .. import generic_studies
from ..flags import (
    POSITIVE,
    cache_dir_from,
    cache_parent,
    executor_from,
    executor_parent,
    json_parent,
    model_from,
    model_parent,
    number,
    output_file,
    settings_from,
    solver_parent,
    swept,
)
from ..generic_studies import sweep_values
from ..models import named, other_params
from ..running import register


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), solver_parent(), executor_parent(), cache_parent(), json_parent()],
        models=generic_studies.sweep,
        help="sweep one parameter of Eq. (4)",
        description="Sweep one parameter of Eq. (4) (beltmdsm/batch/sweep.py; at most "
        f"{MAX_POINTS:.0e} points).",
    )
    grid = sub.add_argument_group("the swept parameter")
    grid.add_argument(
        "--param",
        required=True,
        choices=(*MODEL_PARAMETERS, *other_params()),
        help="the parameter swept (of --model's parameters)",
    )
    grid.add_argument(
        "--from", dest="start", type=number(), metavar="X", help="first value (with --to, --step)"
    )
    grid.add_argument("--to", dest="stop", type=number(), metavar="X", help="last value, >= --from")
    grid.add_argument("--step", type=POSITIVE, metavar="H", help="step between the values, > 0")
    grid.add_argument(
        "--values",
        type=number(),
        nargs="+",
        metavar="X",
        help="explicit values instead of --from/--to/--step (sorted, duplicates run once)",
    )
    sub.add_argument(
        "--continue",
        dest="continuation",
        choices=("up", "down"),
        default=None,
        help="follow an attractor: run the points in ascending (up) or "
        "descending (down) order, each from the previous point's state "
        "at its last whole excitation period (excitation phase 0), the "
        "first from rest; sequential, in this process (no --jobs N > 1 "
        "or --scheduler)",
    )
    sub.add_argument(
        "--modulation", action="store_true", help="add friction modulation columns (Figs. 10-12)"
    )
    sub.add_argument("--out", metavar="CSV", type=output_file, help="write the table as CSV")
    sub.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")


def run(args: argparse.Namespace) -> int:
    from ...batch.sweep import sweep
    from ...batch.table import table_to_csv
    from .. import text

    values = sweep_values(args)
    if args.continuation and (args.scheduler or (args.jobs or 1) > 1):
        args.parser.error(
            "argument --continue: a continued sweep runs its points one after "
            "another in this process (each starts from the previous point's "
            "state); drop --jobs/--scheduler"
        )
    model = model_from(args, skip=(swept(args),))
    with contextlib.nullcontext("serial") if args.continuation else executor_from(args) as executor:
        result = sweep(
            model,
            args.param,
            values,
            settings=settings_from(args),
            executor=executor,
            cache_dir=cache_dir_from(args),
            progress=not args.no_progress,
            modulation=args.modulation,
            continuation=args.continuation,
        )
    if args.out:
        table_to_csv(result.table, args.out)
    if args.json:
        print(json.dumps(text.jsonable(named(result.as_dict()))))
    else:
        print(text.sweep(result, args.out))
    return 0
