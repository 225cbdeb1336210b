"""``simulate``: one run of Eq. (4) and its summary (`beltmdsm.simulation`)."""

from __future__ import annotations

import argparse
import json

from ...state_names import columns, names, rate_column
from .. import generic
from ..flags import (
    json_parent,
    model_from,
    model_parent,
    npz_file,
    number,
    output_file,
    settings_from,
    solver_parent,
)
from ..models import named
from ..running import register

#: The paper's first coordinate, which --perturbation moves.
_X = columns()[0]


def add(commands, name: str) -> None:
    sub = register(
        commands,
        name,
        run,
        [model_parent(), solver_parent(), json_parent()],
        models=generic.simulate,
        help="simulate Eq. (4) and summarise the run",
        description="Simulate Eq. (4) and summarise the run.",
    )
    sub.add_argument(
        "--start",
        choices=("rest", "periodic"),
        default="rest",
        help="start from the equilibrium at rest (default), or on the periodic "
        f"response (beltmdsm/starts/forced.py) with {_X} moved by --perturbation",
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
        "--modulation", action="store_true", help="add friction modulation averages (Figs. 10-12)"
    )
    sub.add_argument(
        "--save",
        metavar="NPZ",
        type=npz_file,
        help=f"save the samples t, {', '.join(names())}, Fn, friction to this .npz file (.npz "
        "added to a name without it, as numpy.savez does; the name written is printed)",
    )
    sub.add_argument(
        "--png",
        metavar="FILE",
        type=output_file,
        help=f"draw the run ({rate_column()} against time) and its friction loop to FILE "
        "(needs matplotlib)",
    )
    sub.add_argument(
        "--classify",
        action="store_true",
        help="name the attractor the run settles on (periodic with its period, "
        "quasi-periodic, chaotic, equilibrium) by its Lyapunov spectrum and its returns, "
        "from the same start (beltmdsm/attractors/classification.py; a run of max(2000 s, "
        "--t-end) more); JSON key 'attractor'",
    )
    sub.add_argument(
        "--no-progress",
        action="store_true",
        help="no progress bar on stderr (shown once the run takes more than 2 s; it "
        "advances at every switch)",
    )


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from ...settings import check_request
    from ...simulation import simulate
    from .. import text

    if args.perturbation is not None and args.start != "periodic":
        args.parser.error(
            "argument --perturbation: moves the start on the periodic response; "
            "give --start periodic, or drop it"
        )
    model = model_from(args)
    settings = settings_from(args)
    check_request(model, settings)  # before the periodic start is computed
    y0 = None
    if args.start == "periodic":
        from ...starts.forced import PERTURBATION, periodic_start

        if args.perturbation is None:
            args.perturbation = PERTURBATION
        y0 = periodic_start(model, args.perturbation)
    sim = simulate(model, settings=settings, y0=y0, progress=not args.no_progress)
    out = sim.summary.as_dict()
    out["start"] = args.start
    if args.start == "periodic":
        out["perturbation"] = args.perturbation
    if args.modulation:
        from ...run.modulation import modulation_scatter

        out.update(modulation_scatter(sim))
    out.update(model.as_dict())
    attractor = None
    if args.classify:
        from ...attractors.classification import classify

        attractor = classify(model, y0=sim.y[:, 0], t_end=max(2000.0, settings.t_end))
        out["attractor"] = attractor.as_dict()
    if args.save:
        np.savez(
            args.save,
            t=sim.t,
            **dict(zip(names(model), sim.y)),
            Fn=sim.normal_force,
            friction=sim.friction,
        )
        out["saved"] = args.save
    if args.png:
        from ..figure import save

        def draw(axes):
            sim.plot(axes[0])
            sim.plot(axes[1], kind="friction")

        title = f"Eq. (4), {model!r}: {rate_column(model)} and the friction loop"
        save(draw, args.png, title, panels=2)
    if args.json:
        print(json.dumps(text.jsonable(named(out))))
    else:
        print(text.simulation(sim, out, args.modulation))
        if attractor is not None:
            print(f"attractor: {attractor!r}: {attractor.evidence}")
        if args.save:
            print(f"samples written to {args.save}")
        if args.png:
            print(f"drawn to {args.png}")
    return 0 if sim.status == "done" else 2
