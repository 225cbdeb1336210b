"""The parser of the command line and the argparse types of its files and folders.

`Parser` is an ``ArgumentParser`` whose errors are one line (`UsageError`);
`writable_file` and `writable_folder` check by writing, before anything is computed,
that an output can be written.
"""

from __future__ import annotations

import argparse
import os
import tempfile
from pathlib import Path
from typing import NoReturn

__all__ = ["Parser", "UsageError", "folder", "writable_file", "writable_folder"]


class UsageError(Exception):
    """A bad command line: one line for stderr (the program, ``error:`` and why)."""


class Parser(argparse.ArgumentParser):
    """An ``ArgumentParser`` whose errors are one line, raised as `UsageError`.

    argparse prints the whole usage before its error, which for the runtime
    commands is a screenful of flags; the message names the flag, and ``--help``
    shows the usage. Raising (instead of exiting) lets `main` return the status.
    """

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: error: {message} (--help for usage)")


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
