"""``basin-stability``: each attractor's share of random starts, along a parameter."""

from __future__ import annotations

import argparse
import json

from ...model import MODEL_PARAMETERS
from ...state_names import column, plane
from .. import generic_studies
from ..flags import (
    cache_dir_from,
    cache_parent,
    executor_from,
    executor_parent,
    integer,
    json_parent,
    model_from,
    model_parent,
    number,
    output_file,
    range_flags,
    range_from,
)
from ..models import named, other_params
from ..running import register
from .basins import region_from, sampling_flags

#: The paper's default plane: its first coordinate and that coordinate's rate.
_X, _Y = plane()


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), executor_parent(), cache_parent(), json_parent()],
        models=generic_studies.basin_stability,
        help="basin stability by sampling, along a parameter (without excitation)",
        description="At --points values of --param in [--from, --to], the share of --samples "
        "uniform random starts in the box --x-from..--y-to (the same starts at every value) "
        "that each attractor claims, with its standard error; steady sliding and the stable "
        "self-excited cycles matched across values by continuation, each birth or death "
        "named by its bifurcation (beltmdsm/basin/basin_stability_along.py).",
    )
    sub.add_argument(
        "--param",
        choices=(*MODEL_PARAMETERS, *other_params()),
        default="Vb",
        help="the parameter (default Vb; of --model's parameters)",
    )
    range_flags(sub)
    sub.add_argument(
        "--points", type=integer(2, 200), default=5, help="values of the parameter (default 5)"
    )
    for axis, default in (("x", _X), ("y", _Y)):
        sub.add_argument(
            f"--{axis}",
            choices=generic_studies.STATES,
            default=default,
            help=f"the {axis} axis (default {default}; {_Y} is {column(None, _Y)}; with "
            f"--model, one of its states, {_X} and {_Y} its first coordinate and its rate)",
        )
        for end, meta, word in (("from", "A", "low"), ("to", "B", "high")):
            sub.add_argument(
                f"--{axis}-{end}",
                type=number(),
                required=True,
                metavar=meta,
                help=f"the box's {word} end on the {axis} axis",
            )
    sampling_flags(sub, 1000)
    sub.add_argument(
        "--png", metavar="FILE", type=output_file, help="draw the stacked fractions to FILE"
    )


def run(args: argparse.Namespace) -> int:
    from ...basin.basin_stability_along import basin_stability_along
    from .. import text

    lo, hi = range_from(args)
    model = model_from(args, skip=(args.param,))
    region = region_from(args, model)
    cache_dir = cache_dir_from(args)
    if cache_dir == "default":
        from ...batch.cache import default_cache_dir

        cache_dir = default_cache_dir()
    with executor_from(args) as executor:
        result = basin_stability_along(
            model,
            region,
            param=args.param,
            lo=lo,
            hi=hi,
            points=args.points,
            samples=args.samples,
            seed=args.seed,
            executor=executor,
            cache_dir=cache_dir,
            progress=not args.no_progress,
        )
    if args.png:
        from ..figure import save

        save(lambda ax: result.plot(ax), args.png, f"basin stability in {result.param}")
    if args.json:
        print(json.dumps(text.jsonable(named(result.as_dict()))))
        return 0
    print(repr(result))
    head = f"{result.param:>10}  " + "  ".join(f"{n[:28]:>28}" for n in result.names)
    print(head)
    for k, v in enumerate(result.values):
        cells = "  ".join(
            f"{result.fractions[k, j]:>19.4f} +- {result.errors[k, j]:.4f}"
            for j in range(len(result.names))
        )
        print(f"{v:>10.6g}  {cells}")
    for e in result.edges:
        print(f"  {e.attractor} {e.event} at {e.kind}, {result.param} = {e.value:.6f}")
    if args.png:
        print(f"drawn to {args.png}")
    return 0
