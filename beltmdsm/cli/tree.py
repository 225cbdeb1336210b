"""The tree of commands: `beltmdsm.derive.cli`'s top and derive commands, and the runtime commands.

`COMMANDS` lists the runtime commands and the module of each (`beltmdsm.cli.commands`);
`main` runs a command line. The command modules are imported when the tree is built
(their flags), and each imports what it runs only when it runs.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from beltmdsm.derive import cli as derive_cli

__all__ = ["COMMANDS", "add_commands", "main"]

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
    "validate": "validate",
    "docs": "docs",
}


def add_commands(commands: argparse._SubParsersAction) -> None:
    """Hang the runtime commands on ``commands`` (an argparse subparsers action)."""
    for name, module in COMMANDS.items():
        importlib.import_module(f"beltmdsm.cli.commands.{module}").add(commands, name)


def _paper_evidence():
    """The simulated numbers of the paper check (`beltmdsm.studies.evidence`)."""
    from ..studies.evidence import paper_evidence

    return paper_evidence()


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line ``argv`` (default ``sys.argv[1:]``); return the exit status.

    0: done; 1: a check failed or the system refused (a file); 2: a bad command line or
    parameter, or a run that could not be done, reported in one line on stderr.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        return derive_cli.main(argv, extend=add_commands, evidence=_paper_evidence)
    except KeyboardInterrupt:
        # Ctrl-C outside a command's run (while the program starts): one line, as in it
        print("beltmdsm: interrupted", file=sys.stderr)
        return 130
