"""The parser of the command line and the argparse types of its files and folders.

`Parser` is an ``ArgumentParser`` whose errors are one line (`UsageError`);
`writable_file` and `writable_folder` check by writing, before anything is computed,
that an output can be written.
"""

from __future__ import annotations

import argparse
import os
import re
import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NoReturn

__all__ = [
    "Parser",
    "UsageError",
    "folder",
    "flag_names",
    "in_flags",
    "writable_file",
    "writable_folder",
]


#: A negative number as a flag's value: ``-1``, ``-0.5``, ``-.5``, ``-1e-3``, ``-2.5E+4``.
NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


class UsageError(Exception):
    """A bad command line: one line for stderr (the program, ``error:`` and why)."""


class Parser(argparse.ArgumentParser):
    """An ``ArgumentParser`` whose errors are one line, raised as `UsageError`.

    argparse prints the whole usage before its error, which for the runtime
    commands is a screenful of flags; the message names the flag, and ``--help``
    shows the usage. Raising (instead of exiting) lets `main` return the status.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        # a negative number in scientific notation is a value, not a flag
        # (``--phase_t -1e-3``): argparse's own pattern takes only ``-1`` and ``-.5``
        self._negative_number_matcher = NEGATIVE_NUMBER

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: error: {message} (--help for usage)")


def flag_names(parser: argparse.ArgumentParser, name: str) -> str:
    """The flags of ``parser`` that set the argument called ``name`` in Python, as typed
    (``points``: ``--points/--rows`` where ``--rows`` is its other spelling); ``--name``
    where the parser has no such flag."""
    flag = "--" + name.replace("_", "-")
    for action in parser._actions:
        if flag in action.option_strings or f"--{name}" in action.option_strings:
            return "/".join(o for o in action.option_strings if o.startswith("--"))
    return flag


def in_flags(message: str, parser: argparse.ArgumentParser, names: Sequence[str] = ()) -> str:
    """``message`` of a Python function with the arguments it names written as the
    flags of ``parser`` (``t_end`` as ``--t-end``): on the command line an error names
    the flags the user typed (issue 36). A name with an underscore is an argument
    wherever it stands; a plain word (``dt``, ``limit``) only where its value follows
    (``dt (0.02)``, ``limit = 12``, ``limit <= 1``), so that prose stays prose ("256
    periods of the period map"). The arguments a failure names (``names``) are the
    caller's prefix ("argument --dt:").

    Examples
    --------
    >>> p = Parser(prog="lyapunov")
    >>> _ = p.add_argument("--t-end"), p.add_argument("--t-transient"), p.add_argument("--dt")
    >>> in_flags("t_transient must be >= 0 and < t_end (100); got 500", p)
    '--t-transient must be >= 0 and < --t-end (100); got 500'
    >>> in_flags("20 samples of dt (0.02): the dt of a run", p)
    '20 samples of --dt (0.02): the dt of a run'
    """
    # a model parameter's name is the model's word ("at Vb = 3" of a sweep point), not
    # the flag's, unless the failure names it
    model = {
        a.dest
        for g in parser._action_groups
        if (g.title or "").startswith("model ")
        for a in g._group_actions
    }
    flags = {
        option.lstrip("-").replace("-", "_"): option
        for action in parser._actions
        if action.dest not in model or action.dest in names
        for option in action.option_strings
        if option.startswith("--")
    }

    def replace(match: re.Match[str]) -> str:
        word = match[1]
        flag = flags.get(word)
        if flag is None:
            return word
        valued = any(message.startswith(v, match.end()) for v in (" (", " = ", " <= ", " >= "))
        if "_" not in word and not valued:
            return word  # a plain word is prose unless its value follows
        return flag

    # not inside a name, a quotation, a path or a formula (pi/dt)
    return re.sub(r"(?<![-\w.'\"=/*])([A-Za-z]\w*)(?![\w'\"=(/])", replace, message)


def folder(s: str) -> str:
    """A folder to write into: created if missing; not an existing file."""
    if Path(s).exists() and not Path(s).is_dir():
        raise argparse.ArgumentTypeError(f"{s} exists and is not a folder")
    return s


def writable_folder(folder: str | os.PathLike) -> str | None:
    """Why ``folder`` (created if missing) cannot be written, or None: a test file of a
    unique name is created in it and removed, since ``os.access`` passes for root
    where writing fails (``/proc``)."""
    try:
        Path(folder).mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".probe-")
        os.close(fd)
        os.remove(probe)
    except OSError as err:
        return f"{folder} cannot be written ({err.strerror or err})"
    return None


def writable_file(s: str) -> str:
    """An argparse type: a file to write, checked by writing before anything is computed.

    Its folder must exist and it must not be a folder; an existing file is opened for
    appending (and left as it was), a new one is tried as a sibling temporary file,
    created and removed: ``os.access`` passes for root where writing fails, and a
    report computed for two minutes was lost at the end (issue 28).
    """
    path = Path(s)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise argparse.ArgumentTypeError(f"folder {folder} does not exist")
    if path.is_dir():
        raise argparse.ArgumentTypeError(f"{path} is a folder, not a file")
    try:
        if path.exists():
            with open(path, "ab"):
                pass
        else:
            fd, probe = tempfile.mkstemp(dir=folder, prefix=f".{path.name}.", suffix=".tmp")
            os.close(fd)
            os.remove(probe)
    except OSError as err:
        raise argparse.ArgumentTypeError(
            f"{path} cannot be written ({err.strerror or err})"
        ) from None
    return s
