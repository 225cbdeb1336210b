"""Helper processes that end with the process that started them.

A sweep's pool workers and the child that compiles the integrators
(`beltmdsm.integrate._background`) work for one command: killed (``kill -9``, a closed
terminal), that command cannot stop them, and orphans left behind kept running for
minutes with hundreds of MB each (issue 36 item 13). Each calls `end_with_parent` when
it starts: a daemon thread that ends the process once its parent is gone.

It polls ``os.getppid()``, which changes the moment the parent dies (the orphan is
re-parented to init or a subreaper), rather than using Linux's ``PR_SET_PDEATHSIG``,
which fires when the *thread* that started the child ends, and a pool started from a
short-lived thread would lose its workers.
"""

from __future__ import annotations

import os
import threading
import time

__all__ = ["end_with_parent", "POLL_S"]

#: How often a helper process looks at its parent [s]: the time it may outlive it, plus
#: the longest compiled call it is in (a numba loop holds the interpreter until it returns).
POLL_S = 0.25


def end_with_parent(on_end=None, parent: int | None = None) -> None:
    """End this process (exit status 1, nothing flushed or joined) once its parent dies.

    Parameters
    ----------
    on_end : callable, optional
        Called first (a claim on a compile released); its failures are ignored.
    parent : int, optional
        The parent's pid as the parent knew it (default: the parent now). Given, a
        parent that died while this process was still starting ends it at once.
    """
    if parent is None:
        parent = os.getppid()

    def watch():
        while os.getppid() == parent:
            time.sleep(POLL_S)
        try:
            if on_end is not None:
                on_end()
        finally:
            os._exit(1)

    threading.Thread(target=watch, name="beltmdsm-end-with-parent", daemon=True).start()
