"""The disk cache of sweep points: one JSON file per point, named by its key.

A point's summary row is cached as a small JSON file named by `cache_key`, a SHA-256 of
what the row depends on: the model (`beltmdsm.Model.digest`: parameters and options),
the solver settings, the start state of a continued point, the cache format, the
package version and the code that computes a row (`code_hash` over `NUMERIC_SOURCES`:
the generated model, the integrators, the run's summary; not the command line, the
reports or this file's neighbours, whose edits change no number). No pickles are
stored.

The cache is safe to share between processes and hosts (dask workers on several
machines): a file is written under a unique temporary name and renamed into place, so
a reader sees a whole file or none. A file that fails its checks (unreadable, not
UTF-8, not JSON, keys missing, another point's key or identity, a row that does not
match its checksum) is reported by name (`Problem`), recomputed and rewritten, never
served. A folder that cannot be written is refused before anything is computed
(`writable_folder`).
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import uuid
from collections.abc import Iterable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from ..model import Model
from ..settings import SolverSettings

__all__ = [
    "CACHE_FORMAT",
    "NUMERIC_SOURCES",
    "CacheWarning",
    "Problem",
    "default_cache_dir",
    "writable_folder",
    "code_files",
    "code_hash",
    "package_version",
    "identity",
    "cache_key",
    "read_cached",
    "write_cached",
]

CACHE_FORMAT = "beltmdsm-sweep-4"
_PACKAGE = Path(__file__).resolve().parents[1]
_ROOT = _PACKAGE.parent
#: The sources a cached row is computed by, relative to the folder that holds the
#: packages: the generated model, the model and settings, the integrators, the run
#: and its summary, and the analyses a row may hold (modulation; Floquet for a start
#: on the periodic response).
NUMERIC_SOURCES = (
    "generated",
    "beltmdsm/model.py",
    "beltmdsm/settings.py",
    "beltmdsm/integrate",
    "beltmdsm/simulation.py",
    "beltmdsm/analysis/summary.py",
    "beltmdsm/analysis/spectra.py",
    "beltmdsm/analysis/modulation.py",
    "beltmdsm/analysis/floquet.py",
    "beltmdsm/studies/row.py",
)


class CacheWarning(UserWarning):
    """A sweep cache file failed its checks; it was recomputed and rewritten."""


@dataclass(frozen=True)
class Problem:
    """A cache file that failed its checks: its path and what is wrong with it."""

    path: str
    reason: str

    def __str__(self) -> str:
        return f"sweep cache file {self.path}: {self.reason}; recomputed and rewritten"


def default_cache_dir() -> Path:
    """``$BELTMDSM_CACHE`` or ``~/.cache/beltmdsm/sweeps``."""
    return Path(os.environ.get("BELTMDSM_CACHE", Path.home() / ".cache" / "beltmdsm" / "sweeps"))


def writable_folder(folder: os.PathLike | str) -> Path:
    """``folder``, created if need be, after a test write.

    Raises
    ------
    ValueError
        Naming the folder, where it cannot be created or written (checked before a
        sweep computes anything, so that no computed point is lost).
    """
    folder = Path(folder)
    probe = folder / f".probe-{uuid.uuid4().hex}"
    try:
        folder.mkdir(parents=True, exist_ok=True)
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as err:
        raise ValueError(
            f"cache folder {folder} cannot be written ({err.strerror or err}); "
            "give another --cache-dir or --no-cache"
        ) from None
    return folder


def code_files() -> list[Path]:
    """The files of `NUMERIC_SOURCES`, sorted (their hash must not depend on the file
    system's order)."""
    out = []
    for rel in NUMERIC_SOURCES:
        path = _ROOT / rel
        out += sorted(path.rglob("*.py")) if path.is_dir() else [path]
    return out


@functools.cache
def code_hash() -> str:
    """SHA-256 over the path and bytes of every file of `code_files` (once per process).

    Part of `cache_key`: a change of the generated model or of the integrator gives
    new keys, so that no stale result is served.
    """
    digest = hashlib.sha256()
    for path in code_files():
        data = path.read_bytes()
        name = path.relative_to(_ROOT).as_posix().encode()
        # lengths first, so that no two file sets can hash the same byte stream
        digest.update(b"%d:%s%d:" % (len(name), name, len(data)))
        digest.update(data)
    return digest.hexdigest()


@functools.cache
def package_version() -> str:
    """The installed version of beltmdsm, else the version in ``pyproject.toml``."""
    from importlib import metadata

    try:
        return metadata.version("beltmdsm")
    except metadata.PackageNotFoundError:
        pass
    import re

    text = (_ROOT / "pyproject.toml").read_text()
    return re.search(r'^version\s*=\s*"([^"]+)"', text, re.M).group(1)


def identity(
    model: Model,
    settings: SolverSettings,
    modulation: bool = False,
    *,
    continuation: str | None = None,
    y0: Iterable[float] | None = None,
    start: str = "rest",
) -> dict[str, Any]:
    """What a point's result depends on, besides the code: keys and checks the cache.

    A continued point (``continuation`` "up" or "down") is another run than the
    point from rest: its direction and its start state ``y0`` (None: from rest)
    belong to it; so does the start on the periodic response (``start``).
    """
    ident = {
        **model.as_dict(),
        "settings": asdict(settings),
        "modulation": bool(modulation),
    }
    if start != "rest":
        ident["start"] = start
    if continuation is not None:
        ident["continuation"] = continuation
        ident["y0"] = None if y0 is None else [float(x) for x in y0]
    return ident


def cache_key(ident: dict[str, Any]) -> str:
    """SHA-256 of a point's `identity`, the cache format, the version and the code."""
    blob = json.dumps(
        {
            "format": CACHE_FORMAT,
            **ident,
            "version": package_version(),
            "code": code_hash(),
        },
        sort_keys=True,
    )
    return hashlib.sha256(blob.encode()).hexdigest()


def _checksum(row):
    return hashlib.sha256(json.dumps(row, sort_keys=True).encode()).hexdigest()


def read_cached(
    path: os.PathLike | str, ident: dict[str, Any], columns: Iterable[str]
) -> tuple[dict[str, Any] | None, str | None]:
    """The row stored at ``path`` for the point ``ident``, after checking the file.

    Returns
    -------
    (row, problem)
        ``row`` (a dict) and ``None`` for a valid file; ``None`` and what is wrong
        (a short phrase) for a file that cannot be read, is not UTF-8 or not JSON,
        lacks a key or one of ``columns``, belongs to another point, or whose row
        does not match its checksum; ``(None, None)`` for no file.
    """
    path = Path(path)
    try:
        data = json.loads(path.read_bytes().decode("utf-8"))
    except FileNotFoundError:
        return None, None
    except OSError as err:
        return None, f"cannot be read ({err.strerror or err})"
    except UnicodeDecodeError as err:
        return None, f"not UTF-8 text ({err.reason} at byte {err.start})"
    except ValueError as err:
        return None, f"not valid JSON ({err})"
    missing = [
        k for k in ("key", *ident, "row", "checksum") if not isinstance(data, dict) or k not in data
    ]
    if missing:
        return None, f"missing {', '.join(missing)}"
    if data["key"] != path.stem:
        return None, f"holds the key {str(data['key'])[:12]}..., not its name's"
    stored = {k: v for k, v in data.items() if k not in ("key", "row", "checksum")}
    if stored != ident:
        return None, "holds another point's parameters or settings"
    row = data["row"]
    if not isinstance(row, dict) or data["checksum"] != _checksum(row):
        return None, "its row does not match its checksum"
    absent = [name for name in columns if name not in row]
    if absent:
        return None, f"its row lacks {', '.join(absent)}"
    return row, None


def write_cached(path: os.PathLike | str, ident: dict[str, Any], row: dict[str, Any]) -> None:
    """Write a point's file through a unique temporary file and a rename.

    The temporary name holds a random UUID, unique across processes and hosts that
    share the folder; ``os.replace`` is atomic, so a reader (or a writer of the
    same point) never sees a partial file.
    """
    path = Path(path)
    text = json.dumps({"key": path.stem, **ident, "row": row, "checksum": _checksum(row)})
    tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex}.tmp")
    try:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
