"""``python -m beltmdsm`` and the ``beltmdsm`` program: the command line (`beltmdsm.cli`)."""

import gc
import sys

from .cli import main


def program() -> int:
    """`beltmdsm.cli.main`, as a program: the exit status.

    The objects left are frozen out of the collector before Python's exit, which
    otherwise traverses them in several full collections while it tears the modules
    down: about a second after a run that loaded numba and scipy, more on a busy
    machine, and most of the time a Ctrl-C took to end (issue 36 item 3). A program's
    heap is freed by its end; `main` itself, called in a process that goes on, does not.
    """
    status = main()
    gc.freeze()
    return status


if __name__ == "__main__":
    sys.exit(program())
