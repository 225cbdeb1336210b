"""``responses``: every periodic response at one point (`beltmdsm.multistability.responses`)."""

from __future__ import annotations

import argparse
import json

from .. import generic_studies
from ..flags import (
    NONNEGATIVE,
    POSITIVE,
    json_parent,
    lock_parent,
    model_from,
    model_parent,
)
from ..models import named
from ..running import register


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), lock_parent(), json_parent()],
        models=generic_studies.responses,
        help="every periodic response found at one point, locked ones included",
        description="The periodic responses of Eq. (4) at one point: the one of the "
        "excitation period T and every one locked at k T (k up to --limit), found from "
        "the run from rest, the run from the perturbed periodic response and ladders "
        "continued up and down in Vb, each by shooting on the k-fold period map, with "
        "its Floquet multipliers (beltmdsm/multistability/responses.py).",
    )
    sub.add_argument(
        "--ladder",
        type=NONNEGATIVE,
        default=2.0,
        help="span of the ladders continued up and down in Vb [m/s], 0: none (default 2)",
    )
    sub.add_argument(
        "--t-end", type=POSITIVE, default=1000.0, help="duration of the runs [s] (default 1000)"
    )


def run(args: argparse.Namespace) -> int:
    from ...multistability.responses import responses
    from .. import text

    found = responses(model_from(args), limit=args.limit, ladder=args.ladder, t_end=args.t_end)
    if args.json:
        print(json.dumps(text.jsonable(named(found.as_dict()))))
    else:
        print(text.responses(found))
    return 0
