"""``floquet``: the periodic response by shooting and its Floquet multipliers."""

from __future__ import annotations

import argparse
import json

from .. import generic
from ..flags import json_parent, model_from, model_parent, periods_parent
from ..models import named
from ..running import register


def add(commands, name: str) -> None:
    register(
        commands,
        name,
        run,
        [model_parent(), periods_parent(), json_parent()],
        models=generic.floquet,
        help="Floquet multipliers of the periodic response",
        description="The periodic response of Eq. (4) by shooting and its Floquet "
        "multipliers, with saltation matrices at the switches "
        "(beltmdsm/periodic/floquet.py); --periods K: the response of K excitation "
        "periods, by shooting on the K-fold period map (an attractor locked at a divisor d of K "
        "is reported as the dT response it is). Without excitation (--alpha 0) "
        "the self-excited cycle, its period found by shooting with a phase condition "
        "(beltmdsm/periodic/cycle.py); --json then says autonomous: true and gives "
        "the trivial multiplier apart.",
    )


def run(args: argparse.Namespace) -> int:
    from ...errors import ShorterPeriod
    from ...periodic.floquet import floquet
    from .. import text

    model = model_from(args)
    try:
        f = floquet(model, periods=args.periods)
    except ShorterPeriod as err:
        # an attractor locked at a divisor d of K is K T-periodic too: its d T response
        f = floquet(model, periods=err.periods)
    out = f.as_dict()
    x1_range, velocity_range = f.response.ranges()
    out["x1_range"], out["velocity_range"] = list(x1_range), list(velocity_range)
    # an attractor locked at a divisor d of K is K T-periodic too: its d T response
    # is what is reported ("periods": d), and the request is kept beside it
    out["periods_asked"] = args.periods
    out.update(f.response.model.as_dict())
    out["switches"] = [
        {"t": t, "before": b.name.lower(), "after": a.name.lower(), "surface": s}
        for t, b, a, s in f.response.switches
    ]
    if args.json:
        print(json.dumps(text.jsonable(named(out))))
    else:
        got = f.response.periods
        if got != args.periods:
            print(
                f"the response of {args.periods} periods is the {got}T response: the period "
                f"map from rest locks at {got} {'period' if got == 1 else 'periods'}, and "
                f"its orbit repeats every {args.periods} T too"
            )
        print(text.floquet(f))
    return 0
