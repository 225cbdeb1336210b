"""The forced analyses of a model other than the paper's (``--model NAME`` with an
excitation amplitude): ``branch`` (its forced response continued), ``floquet-band`` and
``floquet-map`` (`beltmdsm.continuation.oscillator_branch`,
`beltmdsm.continuation.oscillator_band`). A model without excitation: ``branch`` keeps
its steady sliding and self-excited cycles (`beltmdsm.cli.generic.branch`), the band
and the map refuse in one line naming what is missing (`beltmdsm.cli.models.refusal`).
Their JSON names the model and its states.
"""

from __future__ import annotations

import argparse
import json

from ..model import Model
from .flags import range_from
from .models import refusal, refuse_flags, system_from

__all__ = ["branch", "floquet_band", "floquet_map", "model_of"]


def model_of(
    args: argparse.Namespace,
    names: tuple[str, ...],
    swept: tuple[str, ...] = (),
    ranges: tuple[tuple[float, float], ...] = (),
) -> Model:
    """The `Model` of ``--model`` and the flags (checked by `system_from`); ``names`` (the
    walked parameters) that the model lacks, or ``swept`` ones given as fixed ones too:
    exit 2. Where the flags leave the model without excitation, the swept parameters
    take the middle of their ranges (``ranges``, in the order of ``swept``): the band
    and the map walk the range, and an excitation amplitude that is swept (``--param
    alpha_t``) excites the model there, though no flag may set it."""
    for name in swept:
        if getattr(args, name, None) is not None:
            args.parser.error(f"argument --{name}: {name} is the parameter walked; drop --{name}")
    system = system_from(args)
    for name in names:
        if name not in system.params:
            args.parser.error(
                f"argument --{'param' if args.command != 'floquet-map' else 'x/--y'}: not a "
                f"parameter of model {system.name!r} ({', '.join(system.params)}); got {name}"
            )
    if ranges and system.excitation_period() is None:
        system = system.replace(**{n: 0.5 * (lo + hi) for n, (lo, hi) in zip(swept, ranges)})
    if system.excitation_period() is None:
        args.parser.error(refusal(args))
    return Model(model=system.name, friction=system.friction, **system._given)


def _print(args, result) -> None:
    from .text import jsonable

    print(json.dumps(jsonable(result.as_dict())) if args.json else repr(result))


def branch(args: argparse.Namespace) -> int:
    """``branch --model NAME`` with excitation: the forced response continued in
    ``--param`` over ``[--from, --to]`` from the flags' value."""
    from ..branches import branch as run

    lo, hi = range_from(args)
    model = model_of(args, (args.param,))
    found = run(model, periods=args.periods, param=args.param, lo=lo, hi=hi)
    if args.png:
        from .figure import save

        save(lambda ax: found.plot(ax), args.png, f"branch in {found.param} ({found.model!r})")
    _print(args, found)
    return 0


def floquet_band(args: argparse.Namespace) -> int:
    """``floquet-band --model NAME``: the band of the forced response."""
    from ..continuation.band import floquet_band as run

    refuse_flags(args, ("png",))
    lo, hi = range_from(args)
    model = model_of(args, (args.param,), (args.param,), ((lo, hi),))
    band = run(
        model, args.param, lo, hi, points=args.points, tol=args.tol,
        periods=args.periods,
    )  # fmt: skip
    _print(args, band)
    return 0


def floquet_map(args: argparse.Namespace) -> int:
    """``floquet-map --model NAME``: a band on every row of ``--y``."""
    from ..continuation.floquet_map import floquet_map as run

    refuse_flags(args, ("png",))
    if args.x == args.y:
        args.parser.error(f"argument --y: must differ from --x ({args.x})")
    (x_lo, x_hi), (y_lo, y_hi) = range_from(args, "x"), range_from(args, "y")
    model = model_of(args, (args.x, args.y), (args.x, args.y), ((x_lo, x_hi), (y_lo, y_hi)))
    result = run(
        model, args.x, x_lo, x_hi, args.y, y_lo, y_hi,
        points=args.rows,
    )  # fmt: skip
    _print(args, result)
    return 0
