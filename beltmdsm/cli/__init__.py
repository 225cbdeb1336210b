"""The command line: ``beltmdsm`` (and ``python -m beltmdsm``, ``python -m derive``).

One argparse tree: the top of it and the derive commands (regenerate ``generated/``,
``--check``, ``check-paper``) are `beltmdsm.derive.cli`'s; this package hangs the runtime
commands on it, one module per command in `beltmdsm.cli.commands`, with the flags
they share in `beltmdsm.cli.flags` and their readable text in `beltmdsm.cli.text`.
Each command imports what it runs only when it runs, so that ``--help`` and the
start of every command stay fast; the command line imports everything, and nothing
imports it.
"""

from .tree import COMMANDS, main

__all__ = ["main", "COMMANDS"]
