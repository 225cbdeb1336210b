"""How a command runs: what it raises, said in one line with an exit status, and Ctrl-C.

`register` adds a command to the one argparse tree (`beltmdsm.cli.tree`) with `_run`
around it: a bad value found while it runs is reported like a bad flag (exit 2), a
failure of the system in one line (exit 1), a warning as one line naming the program,
and Ctrl-C as one line with what was kept (exit 130), also where it lands inside
compiled code (`_Sigint`).
"""

from __future__ import annotations

import argparse
import contextlib
import signal
import sys
import warnings
from collections.abc import Callable, Sequence
from typing import Any

from ..errors import NoPeriodicResponse, StepTooSmall
from .parser import flag_names, in_flags

__all__ = ["register", "flag_of"]


def register(
    commands: argparse._SubParsersAction,
    name: str,
    run: Callable[[argparse.Namespace], int],
    parents: Sequence[argparse.ArgumentParser],
    models: Callable[[argparse.Namespace], int] | None = None,
    **kwargs: Any,
) -> argparse.ArgumentParser:
    """Add command ``name`` to ``commands`` (an argparse subparsers action), run by ``run``.

    A bad value found while it runs (a ValueError) is reported like a bad flag: one
    line naming it, exit status 2; so are a request the package refuses
    (`beltmdsm.errors.Refused`, naming the flags of the settings it refuses), an
    integrator that cannot go on at the tolerances given
    (`beltmdsm.errors.StepTooSmall`, naming ``--rtol/--atol``) and a periodic
    response that is not found (`beltmdsm.errors.NoPeriodicResponse`). The
    system refusing (an OSError): one line, exit status 1. A warning while it runs
    (a cache file recomputed) is one line on stderr, ``PROG: warning: ...``.

    Every command takes ``--model`` (`beltmdsm.cli.models`): ``run`` runs the paper's
    model, ``models`` (where given) the others; without it, another model is refused
    in one line naming the command and the model (exit 2).
    """
    from .models import model_flag

    parents = [*parents, model_flag(others=models is not None)]
    sub = commands.add_parser(name, parents=parents, **kwargs)
    sub.set_defaults(run=_run, handler=run, parser=sub, other_models=models)
    return sub


def flag_of(name: str) -> str:
    """The command-line flag of a setting or argument named in Python (``t_end``: ``--t-end``)."""
    return "--" + name.replace("_", "-")


def _run(args):
    # a warning (a cache file recomputed, ...) is one line naming the program, not
    # Python's file:line and source line
    with warnings.catch_warnings():
        warnings.showwarning = lambda message, *_, **__: print(
            f"{args.parser.prog}: warning: {message}", file=sys.stderr
        )
        return _handle(args)


def _handle(args):
    try:
        return _interrupted(args)
    except KeyboardInterrupt as err:
        # Ctrl-C: one line, what was kept (a sweep's finished points), exit status 130;
        # a second Ctrl-C while the process winds down (a pool's threads joined at exit)
        # is ignored, so that it cannot kill it half way (exit -2, or a traceback)
        with contextlib.suppress(ValueError):  # not the main thread
            signal.signal(signal.SIGINT, signal.SIG_IGN)
        print(f"{args.parser.prog}: interrupted{f' ({err})' if str(err) else ''}", file=sys.stderr)
        return 130


class _Sigint:
    """Python's own Ctrl-C handling (KeyboardInterrupt), remembering that it fired: where
    it lands inside a compiled function, numba reports "CPUDispatcher(...) returned a
    result with an exception set" as a SystemError that does not always chain the
    KeyboardInterrupt, so the chain alone cannot tell it from a real SystemError."""

    fired = False

    def __call__(self, signum, frame):
        type(self).fired = True
        signal.default_int_handler(signum, frame)


def _interrupted(args):
    """`_dispatch`, with the SystemError that numba raises where Ctrl-C lands inside a
    compiled function read as the KeyboardInterrupt it is (`_Sigint`)."""
    try:
        previous = signal.signal(signal.SIGINT, _Sigint())
    except ValueError:  # not the main thread: no handler of ours
        previous = None
    try:
        return _dispatch(args)
    except SystemError as err:
        if (
            _Sigint.fired
            or isinstance(err.__cause__, KeyboardInterrupt)
            or isinstance(err.__context__, KeyboardInterrupt)
        ):
            raise KeyboardInterrupt from None
        raise
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)


def _handler(args):
    """The command's handler of ``--model`` (the paper's, or the other models')."""
    from .models import MODELS, refusal, refuse_other_params

    if args.model == MODELS[0]:
        if args.other_models is not None:
            refuse_other_params(args)
        return args.handler
    if args.other_models is None:
        args.parser.error(refusal(args))
    return args.other_models


def _dispatch(args):
    try:
        return _handler(args)(args)
    except ValueError as err:
        names = getattr(err, "names", ())
        where = "/".join(flag_names(args.parser, n) for n in names)
        said = in_flags(str(err), args.parser, names)  # the flags, not Python's names
        args.parser.error(f"argument {where}: {said}" if where else said)
    except StepTooSmall as err:
        print(f"{args.parser.prog}: error: argument --rtol/--atol: {err}", file=sys.stderr)
        return 2
    except NoPeriodicResponse as err:
        print(f"{args.parser.prog}: error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        raise  # the reader went away (`| head`): beltmdsm.cli.tree.main ends quietly
    except OSError as err:
        print(f"{args.parser.prog}: error: {err}", file=sys.stderr)
        return 1
    except (ImportError, SyntaxError) as err:
        # generated/ broken or half written: the derive commands still work
        where = f" ({err.filename}, line {err.lineno})" if isinstance(err, SyntaxError) else ""
        print(
            f"{args.parser.prog}: error: the runtime commands cannot be loaded: "
            f"{type(err).__name__}: {err.msg if isinstance(err, SyntaxError) else err}{where}; "
            "regenerate with `python -m derive`",
            file=sys.stderr,
        )
        return 2
