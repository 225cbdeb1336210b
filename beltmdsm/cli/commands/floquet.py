"""``floquet``: the periodic response by shooting and its Floquet multipliers."""

from __future__ import annotations

import argparse
import json

from ..flags import json_parent, model_from, model_parent, periods_parent, register


def add(commands, name: str) -> None:
    register(
        commands,
        name,
        run,
        [model_parent(), periods_parent(), json_parent()],
        help="Floquet multipliers of the periodic response",
        description="The periodic response of Eq. (4) by shooting and its Floquet "
        "multipliers, with saltation matrices at the switches "
        "(beltmdsm/analysis/floquet.py); --periods K: the response of K excitation "
        "periods, by shooting on the K-fold period map. Without excitation (--alpha 0) "
        "the self-excited cycle, its period found by shooting with a phase condition "
        "(beltmdsm/analysis/cycles.py); --json then says autonomous: true and gives "
        "the trivial multiplier apart.",
    )


def run(args: argparse.Namespace) -> int:
    from ...analysis.floquet import floquet
    from .. import text

    f = floquet(model_from(args), periods=args.periods)
    out = f.as_dict()
    x1_range, velocity_range = f.response.ranges()
    out["x1_range"], out["velocity_range"] = list(x1_range), list(velocity_range)
    out.update(f.response.model.as_dict())
    out["switches"] = [
        {"t": t, "before": b.name.lower(), "after": a.name.lower(), "surface": s}
        for t, b, a, s in f.response.switches
    ]
    if args.json:
        print(json.dumps(text.jsonable(out)))
    else:
        print(text.floquet(f))
    return 0
