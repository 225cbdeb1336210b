"""``lyapunov``: the Lyapunov spectrum of a run, through the switches."""

from __future__ import annotations

import argparse
import json

from ...state_names import columns
from .. import generic_studies
from ..flags import json_parent, model_from, model_parent, number
from ..models import named
from ..running import register

#: The paper's first coordinate, which --perturbation moves.
_X = columns()[0]


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), json_parent()],
        models=generic_studies.lyapunov,
        help="Lyapunov exponents of a run (saltation matrices at every switch)",
        description="The Lyapunov spectrum of a run of Eq. (4), largest first, by the "
        "variational equations with the saltation matrix at every switch and QR "
        "re-orthonormalisation (beltmdsm/attractors/lyapunov.py); -inf (null in JSON) for "
        "a direction a stick phase removes.",
    )
    sub.add_argument(
        "--start",
        choices=("rest", "periodic"),
        default="rest",
        help="start from the equilibrium at rest (default; without excitation where steady "
        "sliding is unstable, moved 1e-6 off it along its unstable direction, as simulate), "
        f"or on the periodic response with {_X} moved by --perturbation",
    )
    sub.add_argument(
        "--perturbation",
        type=number(),
        default=None,
        metavar=f"D{_X}",
        help=f"the move of {_X} from the periodic response [m], with --start periodic only "
        "(default 1e-2)",
    )
    sub.add_argument(
        "--t-end",
        type=number(lambda x: x > 0, "positive"),
        default=1000.0,
        metavar="T",
        help="the run's length [s] (default 1000): 30 %% transient, then the average",
    )
    sub.add_argument(
        "--t-transient",
        type=number(lambda x: x >= 0, "nonnegative"),
        default=None,
        metavar="T",
        help="time run before averaging [s] (default 30 %% of --t-end, or from a start "
        "moved off unstable steady sliding the time to leave it, where --t-end allows)",
    )


def run(args: argparse.Namespace) -> int:
    from ...attractors.lyapunov import lyapunov
    from .. import text

    if args.perturbation is not None and args.start != "periodic":
        args.parser.error(
            "argument --perturbation: moves the start on the periodic response; "
            "give --start periodic, or drop it"
        )
    model = model_from(args)
    y0 = None
    if args.start == "periodic":
        from ...starts.forced import PERTURBATION, periodic_start

        if args.perturbation is None:
            args.perturbation = PERTURBATION
        y0 = periodic_start(model, args.perturbation)
    spec = lyapunov(model, y0=y0, t_end=args.t_end, t_transient=args.t_transient)
    from ...attractors.classification import unstable_set

    # a positive exponent of a run that stays on an unstable invariant set is its
    # instability: say which set (beltmdsm/attractors/classification.py)
    unstable = unstable_set(model, spec) if spec.largest > 0 else None
    out = spec.as_dict()
    out["unstable_set"] = None if unstable is None else unstable[0]
    out["start"] = args.start
    if args.start == "periodic":
        out["perturbation"] = args.perturbation
    out.update(model.as_dict())
    if args.json:
        print(json.dumps(text.jsonable(named(out))))
    else:
        print(repr(spec))
        if spec.start_perturbation:
            print(
                f"start: steady sliding is unstable here; the run starts on it moved by "
                f"{spec.start_perturbation:g} along its unstable direction (as simulate's)"
            )
        if unstable is not None:
            print(f"not chaos: {unstable[0]}")
        print(
            f"error from the spread over {8} blocks and the drift of the running mean; "
            f"{spec.collapsed} direction(s) removed by stick (exponent -inf)"
        )
    return 0
