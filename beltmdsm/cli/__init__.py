"""The command line: ``beltmdsm`` (and ``python -m beltmdsm``; from a source checkout's
root, ``python -m derive``).

One argparse tree, built here (`beltmdsm.cli.tree`): its top and ``check-paper`` run
the derive commands (`beltmdsm.derive.commands`: regenerate ``generated/``,
``--check``), the runtime commands are one module per command in
`beltmdsm.cli.commands`, with the flags they share in `beltmdsm.cli.flags`, the parser
and its file types in `beltmdsm.cli.parser` and their readable text in
`beltmdsm.cli.text`.
Each command imports what it runs only when it runs, so that ``--help`` and the
start of every command stay fast; the command line imports everything, and nothing
imports it.
"""

from .tree import COMMANDS, main

__all__ = ["main", "COMMANDS"]
