"""The one tree of commands: its top (the derivation), ``check-paper`` and the runtime
commands.

::

    beltmdsm [--check] [--out DIR]     derive everything, regenerate generated/ (or check it)
    beltmdsm check-paper               compare the paper with the derivation
    beltmdsm simulate|sweep|...        the runtime commands (`COMMANDS`)

also spelt ``python -m beltmdsm`` and, from a source checkout's root, ``python -m
derive`` (derive/__main__.py runs this program). This module builds the whole tree:
the derive commands run `beltmdsm.derive.commands` (which builds no parser), the
runtime commands their modules in `beltmdsm.cli.commands`, imported when the tree is
built (their flags); each imports what it runs only when it runs.

The runtime's commands import ``beltmdsm.generated``, which the regeneration may be
about to rewrite, or which may be broken: the regeneration and ``check-paper`` build
the tree without them (`_needs_runtime`), and where they cannot be loaded the derive
commands still work and the reason is kept in ``parser.unavailable``.

Every error in a command line is one line on stderr and exit status 2
(`beltmdsm.cli.parser.Parser`); `main` returns the exit status, which ``python -m
beltmdsm`` and the console script pass to ``sys.exit``.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections.abc import Sequence

from beltmdsm.derive import commands as derive

from .parser import Parser, UsageError, folder, writable_file, writable_folder

__all__ = ["COMMANDS", "add_commands", "build_parser", "main"]

#: The runtime commands, in the order of ``--help``, and their modules.
COMMANDS = {
    "simulate": "simulate",
    "sweep": "sweep",
    "predict": "predict",
    "floquet": "floquet",
    "floquet-band": "floquet_band",
    "responses": "responses",
    "branch": "branch",
    "coexistence": "coexistence",
    "floquet-map": "floquet_map",
    "lyapunov": "lyapunov",
    "basins": "basins",
    "basin-stability": "basin_stability",
    "validate": "validate",
    "docs": "docs",
}


def add_commands(commands: argparse._SubParsersAction) -> None:
    """Hang the runtime commands on ``commands`` (an argparse subparsers action)."""
    for name, module in COMMANDS.items():
        importlib.import_module(f"beltmdsm.cli.commands.{module}").add(commands, name)


def _paper_evidence():
    """The simulated numbers of the paper check (`beltmdsm.paper_reports.contraction_evidence`)."""
    from ..paper_reports.contraction_evidence import paper_evidence

    return paper_evidence()


def _prog() -> str:
    """How the user called the command line: ``beltmdsm`` or ``python -m beltmdsm``
    (``python -m derive`` runs ``python -m beltmdsm``, and says so)."""
    path = sys.argv[0] if sys.argv else ""
    if os.path.basename(path) == "__main__.py":
        return f"python -m {os.path.basename(os.path.dirname(path))}"
    return "beltmdsm"


#: The paper's model: the one check-paper checks (``MODELS[0]`` of beltmdsm.generated.models,
#: not imported here: check-paper's command line must not need generated/).
PAPER = "paper"


def _check_paper(args) -> int:
    """`beltmdsm.derive.commands.check_paper` of the paper's model; ``--model`` another:
    one line naming it and what it lacks (its module's ``ABSENT["paper_check"]``), exit 2."""
    if args.model != PAPER:
        from beltmdsm.generated.models import MODELS, load

        if args.model not in MODELS:
            args.parser.error(
                f"argument --model: invalid choice: {args.model!r} (choose from "
                f"{', '.join(MODELS)})"
            )
        why = load(args.model).ABSENT["paper_check"]
        args.parser.error(
            f"argument --model: check-paper does not run model {args.model!r}: {why}; "
            f"it checks the paper's model only (--model {PAPER})"
        )
    return derive.check_paper(args)


def _generate(args) -> int:
    """The top of the tree: `beltmdsm.derive.commands.generate`, its ``--out`` checked
    by writing first (not after a derivation of a minute)."""
    if args.out is not None and not args.check:
        problem = writable_folder(args.out)
        if problem:
            args.parser.error(f"argument --out: {problem}")
    return derive.generate(args)


def build_parser(prog: str | None = None, runtime: bool = True) -> Parser:
    """The command-line tree (`Parser`); with ``runtime``, the runtime commands too.

    Where they cannot be loaded (a broken ``beltmdsm.generated``), the derive commands
    still work and the reason is in ``parser.unavailable`` (else None).
    """
    parser = Parser(
        prog=prog or _prog(),
        description="Derive the model symbolically and regenerate generated/ "
        "(--regenerate, --check, --out), or run one of the commands.",
    )
    parser.add_argument(
        "--regenerate",
        action="store_true",
        help="regenerate generated/ from the derivations (a source checkout; what "
        "`python -m derive` does); without it, --check or --out, `beltmdsm` alone prints "
        "this help",
    )
    parser.add_argument(
        "--check",
        action="store_true",
        help="do not write; exit 1 and name the stale files if "
        "generated/ differs from the derivations",
    )
    parser.add_argument(
        "--out",
        type=folder,
        default=None,
        metavar="DIR",
        help="write (or check) a complete copy of generated/ in DIR instead of the "
        "package's generated/ (which only a source checkout may rewrite)",
    )
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", title="commands")
    paper = commands.add_parser(
        "check-paper",
        help="compare the paper's equations and claims with the derivation",
        description="Compare the paper's equations and claims with the derivation; write "
        "the report PAPER_CHECK.md.",
    )
    paper.add_argument(
        "--out",
        type=writable_file,
        default=None,
        metavar="FILE",
        help="the report (default: generated/PAPER_CHECK.md in a source checkout, else "
        "PAPER_CHECK.md in the current folder)",
    )
    paper.add_argument(
        "--model",
        default=PAPER,
        metavar="NAME",
        help=f"the registered model (derive/models/entries.py; default: {PAPER}): the "
        "paper's claims are its model's, so another is refused, naming what it lacks",
    )
    paper.set_defaults(run=_check_paper, evidence=_paper_evidence, parser=paper)
    parser.unavailable = None
    if runtime:
        try:
            add_commands(commands)
        except Exception as err:  # noqa: BLE001 (whatever a broken generated/ raises)
            parser.unavailable = parser.epilog = (
                f"the runtime commands cannot be loaded: {type(err).__name__}: {err}"
            )
    return parser


def _needs_runtime(argv):
    """False for the regeneration (``[--check] [--out DIR]``) and check-paper: their
    command lines must not need generated/ (check-paper's simulated rows import the
    runtime when they run)."""
    rest = list(argv)
    if "--out" in rest[:-1]:
        del rest[rest.index("--out") : rest.index("--out") + 2]
    rest = [a for a in rest if a not in ("--check", "--regenerate") and not a.startswith("--out=")]
    return not (rest == [] or rest[:1] == ["check-paper"])


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line ``argv`` (default ``sys.argv[1:]``); return the exit status.

    0: done; 1: a check failed (``--check``) or the system refused (a file, the
    network), or the reader of the output went away (``| head``, quietly); 2: a bad
    command line or parameter, or a run that could not be done, reported in one line
    on stderr.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        return _run(argv)
    except KeyboardInterrupt:
        # Ctrl-C outside a command's run (while the program starts): one line, as in it
        print("beltmdsm: interrupted", file=sys.stderr)
        return 130


def _run(argv: list[str]) -> int:
    parser = build_parser(runtime=_needs_runtime(argv))
    try:
        args = parser.parse_args(argv)
        if args.command is None and not (args.regenerate or args.check or args.out):
            parser.print_help()  # a bare `beltmdsm` derives nothing (issue 37)
            status = 0
        elif args.command is None:
            args.parser = parser
            status = _generate(args)
        else:
            if args.check:
                parser.error("--check applies to the regeneration, not to a command")
            status = args.run(args)
        sys.stdout.flush()  # a reader gone (`| head`) shows here, not at exit
        return status
    except UsageError as err:
        print(err, file=sys.stderr)
        if parser.unavailable:
            print(parser.unavailable, file=sys.stderr)
        return 2
    except BrokenPipeError:
        # the reader of the output went away (`| head`): end quietly, as the Python
        # documentation advises (the signal module's note on SIGPIPE); what is still
        # buffered goes to the null device, not to a second error at exit
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except SystemExit as done:  # --help, or a command that exits
        if done.code is None or isinstance(done.code, int):
            return done.code or 0
        print(done.code, file=sys.stderr)
        return 1
