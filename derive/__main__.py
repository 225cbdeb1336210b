"""``python -m derive``, from a source checkout's root: ``python -m beltmdsm``.

The command line is `beltmdsm.cli`'s, one tree (beltmdsm/cli/tree.py) whose top is the
derivation (``[--check] [--out DIR]``, ``check-paper``) and whose commands are the
runtime's. derive/ imports no runtime module: this file runs the runtime's entry point
as a program, as the shell would run ``python -m beltmdsm`` (its ``--help`` says
``python -m beltmdsm``). The package, imported by its old top-level name to find this
file, is dropped first, so that nothing of derive/ is loaded under two names.
"""

import runpy
import sys

if __package__ == "derive":
    del sys.modules["derive"]
if sys.argv[1:] == []:  # `python -m derive` regenerates; a bare `beltmdsm` prints its help
    sys.argv.append("--regenerate")
runpy.run_module("beltmdsm", run_name="__main__", alter_sys=True)
