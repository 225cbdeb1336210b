"""``python -m beltmdsm ARGV`` run in the test's own process, for the tests whose point is
what a command prints and returns, not the process around it.

A subprocess pays an interpreter, the imports and numba's cache load (one to three
seconds a call) for what `beltmdsm.cli.main` does in the test's process with
everything already loaded. What a real process adds (exit by a signal, Ctrl-C, a hang
bounded by a timeout, memory measured, the program's start, ``-W error``) stays with
the tests that run one.

`cli` returns what `subprocess.run` returns (``returncode``, ``stdout``, ``stderr``):

* the program's name in messages is ``python -m beltmdsm``, as beltmdsm/__main__.py
  runs it (``sys.argv[0]``);
* Python's warnings go to stderr under Python's default filters, as they would in a
  program (pytest would otherwise record them and leave stderr empty);
* ``env``: variables set (a value) or removed (None) for the call, then restored.
"""

from __future__ import annotations

import contextlib
import io
import os
import subprocess
import sys
import warnings
from pathlib import Path
from unittest import mock

ROOT = Path(__file__).resolve().parents[1]
#: Python's default warning filters (without -W or PYTHONWARNINGS), most specific first.
_DEFAULT_FILTERS = (
    ("ignore", ResourceWarning),
    ("ignore", ImportWarning),
    ("ignore", PendingDeprecationWarning),
    ("ignore", DeprecationWarning),
)


def _show(message, category, filename, lineno, file=None, line=None):
    sys.stderr.write(warnings.formatwarning(message, category, filename, lineno, line))


def cli(*argv: str, env: dict | None = None) -> subprocess.CompletedProcess:
    """``python -m beltmdsm *argv`` through `beltmdsm.cli.main` in this process."""
    from beltmdsm.cli import main

    out, err = io.StringIO(), io.StringIO()
    changes = {k: v for k, v in (env or {}).items() if v is not None}
    removed = [k for k, v in (env or {}).items() if v is None]
    with contextlib.ExitStack() as stack:
        stack.enter_context(mock.patch.dict(os.environ, changes))  # restored at exit
        for key in removed:
            os.environ.pop(key, None)
        stack.enter_context(
            mock.patch.object(sys, "argv", [str(ROOT / "beltmdsm" / "__main__.py"), *argv])
        )
        stack.enter_context(warnings.catch_warnings())
        warnings.resetwarnings()
        warnings.simplefilter("default")
        for action, category in reversed(_DEFAULT_FILTERS):
            warnings.filterwarnings(action, category=category)
        warnings.filterwarnings("default", category=DeprecationWarning, module="__main__")
        warnings.showwarning = _show
        stack.enter_context(contextlib.redirect_stdout(out))
        stack.enter_context(contextlib.redirect_stderr(err))
        code = main(list(argv))
    return subprocess.CompletedProcess(
        ["python", "-m", "beltmdsm", *argv], code, out.getvalue(), err.getvalue()
    )


def once(monkeypatch, module, name: str) -> None:
    """Replace ``module.name``, a function that a command imports when it runs, for the
    rest of the test by one that computes each distinct call once (``progress`` aside).

    A test that reads a command's text and then its ``--json`` pays one computation; the
    command's own code, from the flags to the text, runs each time, and the function's
    result depends on its arguments alone.
    """
    real = getattr(module, name)
    kept = {}

    def compute_once(*args, **kwargs):
        key = (args, tuple(sorted((k, v) for k, v in kwargs.items() if k != "progress")))
        if key not in kept:
            kept[key] = real(*args, **kwargs)
        return kept[key]

    monkeypatch.setattr(module, name, compute_once)
