"""``--model NAME`` on every command: the paper's model (the default) or another
registered model, run by the generic runtime (`beltmdsm.oscillator`).

`model_flag` is the parent parser of ``--model`` (choices: the registry's,
``beltmdsm.generated.models.MODELS``) and of the parameters of the other models that
the paper's flags do not name (Hoffmann's ``--k1``, ``--k_c``, ...). A command
registered with a handler for the other models (`beltmdsm.cli.running.register`'s
``models``) runs it on `system_from`'s `beltmdsm.oscillator.System`; every other command
refuses them in one line (`refusal`): never the paper's physics under another name.
"""

from __future__ import annotations

import argparse
from collections.abc import Iterable
from typing import TYPE_CHECKING

from beltmdsm.generated.models import MODELS, load
from beltmdsm.generated.parameters import DOMAIN_RULES, within
from beltmdsm.generated.parameters import PARAMETERS as _PAPER

from ..model import FORCED, LACKS, OPTIONS
from .flags import number, params_from

if TYPE_CHECKING:
    from ..model import Model
    from ..oscillator import System

__all__ = [
    "MODELS",
    "model_flag",
    "other_params",
    "system_from",
    "model_of",
    "refusal",
    "refuse_flags",
    "refuse_other_params",
    "named",
]

_PAPER_NAMES = {p["name"] for p in _PAPER}


def other_params() -> dict[str, str]:
    """The other models' parameters that are not the paper's: name -> help.

    See Also
    --------
    model_flag : makes them flags.

    Examples
    --------
    >>> sorted(other_params())[:3]
    ['F_pre', 'c1', 'c2']
    """
    found: dict[str, str] = {}
    for name in MODELS[1:]:
        module = load(name)
        for law in module.FRICTION_LAWS:
            for p in module.PARAMETERS[law]:
                if p not in _PAPER_NAMES and p not in found:
                    found[p] = f"{module.DESCRIPTIONS[p]} [{module.UNITS[p]}] (--model {name})"
    return found


def model_flag(others: bool) -> argparse.ArgumentParser:
    """Parent parser: ``--model``; with ``others``, the other models' own parameters.

    See Also
    --------
    system_from : the `beltmdsm.oscillator.System` of the flags.

    Examples
    --------
    >>> args = argparse.ArgumentParser(parents=[model_flag(True)]).parse_args(
    ...     ["--model", "hoffmann", "--k_c", "2"])
    >>> args.model, args.k_c
    ('hoffmann', 2.0)
    """
    parent = argparse.ArgumentParser(add_help=False)
    parent.add_argument(
        "--model",
        choices=MODELS,
        default=MODELS[0],
        help="the registered model (derive/models/entries.py): "
        f"{', '.join(MODELS)} (default: {MODELS[0]}); "
        + (
            f"another than {MODELS[0]} runs on the generic runtime (beltmdsm/oscillator/), "
            "with its own parameters and states"
            if others
            else f"this command runs {MODELS[0]} only and refuses another, naming what it lacks"
        ),
    )
    if others:
        group = parent.add_argument_group("parameters of the other models (--model)")
        for name, text in other_params().items():
            group.add_argument(
                f"--{name}",
                dest=name,
                type=number(),
                default=None,
                metavar="X",
                help=text.replace("%", "%%"),
            )
    return parent


def refusal(args: argparse.Namespace) -> str:
    """The one line of a command that does not run ``args.model``: what is missing (the
    model's ``ABSENT`` piece, or what the generic runtime lacks: `beltmdsm.model.LACKS`)."""
    analysis = args.command.replace("-", "_")
    module = load(args.model)
    why = LACKS.get(analysis, "the generic runtime does not run it")
    if why.startswith("ABSENT:"):
        why = module.ABSENT[why.removeprefix("ABSENT:")]
    if analysis in FORCED:  # it runs the model with excitation: say how to get one
        amplitudes = ", ".join(f"--{amplitude}" for _, amplitude, _, _ in module.EXCITATION)
        how = (
            f"set an excitation amplitude ({amplitudes})"
            if amplitudes
            else "the model has no excitation terms (derive/models/entries.py)"
        )
        return f"argument --model: {args.command} does not run model {args.model!r}: {why}: {how}"
    return (
        f"argument --model: {args.command} does not run model {args.model!r}: {why}; "
        f"it runs the paper's model only (--model {MODELS[0]})"
    )


def refuse_flags(args: argparse.Namespace, dests: Iterable[str]) -> None:
    """Exit 2 naming the first of ``dests`` given (not at its default): the paper's only."""
    for dest in dests:
        if getattr(args, dest, None) != args.parser.get_default(dest):
            flags = [a.option_strings for a in args.parser._actions if a.dest == dest]
            flag = flags[0][0] if flags and flags[0] else "--" + dest.replace("_", "-")
            args.parser.error(
                f"argument {flag}: applies to the paper's model, not to --model {args.model}"
            )


def refuse_other_params(args: argparse.Namespace) -> None:
    """Exit 2 naming a parameter of another model given to the paper's (never ignored)."""
    for name, text in other_params().items():
        if getattr(args, name, None) is not None:
            owner = text.rsplit("(--model ", 1)[1].rstrip(")")
            args.parser.error(
                f"argument --{name}: a parameter of --model {owner}, not of the paper's model"
            )


def system_from(args: argparse.Namespace) -> System:
    """The `beltmdsm.oscillator.System` of ``--model``, ``--friction`` and the parameter
    flags given (one the model lacks, or a paper option changed: exit 2, named)."""
    from ..oscillator import System

    module = load(args.model)
    refuse_flags(args, [o for o in OPTIONS if o != "friction"])
    if args.friction not in module.FRICTION_LAWS:
        args.parser.error(
            f"argument --friction: model {args.model!r} has the laws "
            f"{', '.join(module.FRICTION_LAWS)}; got {args.friction}"
        )
    given = params_from(args)
    given.update(
        {n: getattr(args, n) for n in other_params() if getattr(args, n, None) is not None}
    )
    names = module.PARAMETERS[args.friction]
    for name, value in given.items():
        if name not in names:
            args.parser.error(
                f"argument --{name}: not a parameter of model {args.model!r} with friction "
                f"{args.friction!r} ({', '.join(names)})"
            )
        domain = module.DOMAINS[name]
        if not within(domain, value):
            args.parser.error(
                f"argument --{name}: must be {DOMAIN_RULES[domain][2]}; got {value:g}"
            )
    try:
        return System(args.model, friction=args.friction, **given)
    except ValueError as err:
        args.parser.error(str(err))


def model_of(system: System) -> Model:
    """The `beltmdsm.Model` of a `System` from `system_from` (its flags checked there),
    which the public functions take: a command runs the Python API's function, one
    path for both (``responses``, ``coexistence``, ``simulate --classify``)."""
    from ..model import Model

    return Model(model=system.name, friction=system.friction, **system._given)


def named(out: dict) -> dict:
    """A command's JSON with the model it ran named first (``"model": NAME``; the
    paper's where the output does not name one)."""
    return {"model": out.get("model", MODELS[0]), **out}
