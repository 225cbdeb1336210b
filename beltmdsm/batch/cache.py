"""The disk cache of sweep points: one JSON file per point, named by its key.

A point's row (`beltmdsm.batch.row.Row.as_dict`, read back by
`beltmdsm.batch.row.Row.from_dict`) is cached as a small JSON file named by
`cache_key`, a SHA-256 of what the row depends on: the model (`beltmdsm.Model.digest`:
parameters and options), the solver settings, the start state of a continued point,
the cache format, the package version and the code that computes a row (`code_hash`
over `code_files`: the modules that a row's entry module, `NUMERIC_SOURCES`, imports,
read from the sources: the generated model, the integrators, the run's summary, the
period map; not the command line, the reports or the sweep's orchestration, whose edits
change no number). No pickles are stored.

The cache is safe to share between processes and hosts (dask workers on several
machines): a file is written under a unique temporary name and renamed into place, so
a reader sees a whole file or none. A file that fails its checks (unreadable, not
UTF-8, not JSON, keys missing, another point's key or identity, a row that does not
match its checksum) is reported by name (`Problem`), recomputed and rewritten, never
served. A folder that cannot be written is refused before anything is computed
(`writable_folder`).
"""

from __future__ import annotations

import ast
import functools
import hashlib
import json
import os
import re
import uuid
from collections.abc import Iterable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from beltmdsm.generated._support import cache_root

from .._layout import SIBLINGS
from ..model import Model
from ..settings import SolverSettings

__all__ = [
    "CACHE_FORMAT",
    "NUMERIC_SOURCES",
    "CODE_PACKAGES",
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
#: The entry module of a row's computation (`beltmdsm.batch.row.run_point`). The
#: sources hashed into every key (`code_files`) are the modules that importing it
#: executes within `CODE_PACKAGES`: its imports, theirs, and so on, read from the
#: source (every ``import`` statement, a function's own included), so that no hand
#: list can leave a module out (issue 28: the period map, the variational equations
#: and the lock detection decided a row's ``resolved`` and start, and were not hashed).
NUMERIC_SOURCES = ("beltmdsm.batch.row",)
#: The packages whose modules are hashed (beltmdsm.generated among them); numpy, scipy
#: and numba enter by the package version only.
CODE_PACKAGES = ("beltmdsm",)


class CacheWarning(UserWarning):
    """A sweep cache file failed its checks; it was recomputed and rewritten.

    See Also
    --------
    Problem : what the warning says.

    Examples
    --------
    >>> issubclass(CacheWarning, UserWarning)
    True
    """


@dataclass(frozen=True)
class Problem:
    """A cache file that failed its checks: its path and what is wrong with it.

    Parameters
    ----------
    path : str
        The file.
    reason : str
        What is wrong with it (`read_cached`'s phrase).

    See Also
    --------
    CacheWarning : the warning that carries it.

    Examples
    --------
    >>> print(Problem("ab12.json", "not valid JSON"))
    sweep cache file ab12.json: not valid JSON; recomputed and rewritten
    """

    path: str
    reason: str

    def __str__(self) -> str:
        return f"sweep cache file {self.path}: {self.reason}; recomputed and rewritten"


def default_cache_dir() -> Path:
    """``sweeps`` in the folder of the package's caches (`beltmdsm.generated._support.cache_root`,
    one rule for every cache): ``$BELTMDSM_CACHE/sweeps``, else
    ``$XDG_CACHE_HOME/beltmdsm-cache/sweeps``, else ``~/.cache/beltmdsm-cache/sweeps``
    (an empty variable counts as unset).

    Returns
    -------
    pathlib.Path

    See Also
    --------
    writable_folder : the check a sweep makes of it.

    Examples
    --------
    >>> default_cache_dir().name
    'sweeps'
    """
    return Path(cache_root()) / "sweeps"


def writable_folder(folder: os.PathLike | str) -> Path:
    """``folder``, created if need be, after a test write.

    Parameters
    ----------
    folder : path

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ValueError
        Naming the folder, where it cannot be created or written (checked before a
        sweep computes anything, so that no computed point is lost).

    See Also
    --------
    default_cache_dir : the folder of a sweep's ``cache_dir="default"``.

    Examples
    --------
    >>> import os, tempfile
    >>> root = tempfile.mkdtemp()
    >>> writable_folder(os.path.join(root, "sweeps")).is_dir()
    True
    >>> open(os.path.join(root, "a_file"), "w").close()
    >>> writable_folder(os.path.join(root, "a_file", "sweeps"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: cache folder .../a_file/sweeps cannot be written (...); give another --cache-dir ...
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


def _module_file(name: str) -> Path | None:
    """The source of module ``name`` in `CODE_PACKAGES` (a package: its ``__init__.py``),
    or None (another package's, a namespace package, a name that is no module)."""
    parts = name.split(".")
    if parts[0] not in CODE_PACKAGES:
        return None
    base = _ROOT.joinpath(*parts)
    if len(parts) > 1 and parts[1] in SIBLINGS and not (_ROOT / parts[0] / parts[1]).is_dir():
        base = _ROOT.joinpath(*parts[1:])  # a source checkout: beside beltmdsm/ (_layout)
    for path in (base / "__init__.py", base.with_suffix(".py")):
        if path.is_file():
            return path
    return None


#: An import statement (``from M import (a,\n b)``, a line continued by ``\\``),
#: indented or not: each match is parsed alone (`ast`), which reads the statements of
#: a large generated module many times faster than parsing the whole module; a match
#: that does not parse is prose (a docstring's "import ...").
_IMPORT = re.compile(
    rb"^[ \t]*((?:from[ \t]+[.\w]+[ \t]+)?import[ \t]+(?:\([^)]*\)|(?:[^\n]*\\\n)*[^\n]*))",
    re.M,
)


def _imported(name: str, path: Path) -> set[str]:
    """The modules that module ``name`` (source ``path``) may import: every ``import``
    statement in it, a function's own included, with each package above a module
    (Python runs them first) and each name of ``from M import a`` that may be a
    submodule ``M.a``."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for match in _IMPORT.finditer(path.read_bytes()):
        try:
            # the match runs to the end of its line: "import a; import b" parses whole
            nodes = ast.parse(match.group(1).decode("utf-8")).body
        except (SyntaxError, UnicodeDecodeError):
            continue
        for node in nodes:
            if isinstance(node, ast.Import):
                found.update(alias.name for alias in node.names)
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = package.split(".")[: package.count(".") + 2 - node.level]
                    base = ".".join(up + ([node.module] if node.module else []))
                found.add(base)
                found.update(f"{base}.{alias.name}" for alias in node.names)
    return {".".join(m.split(".")[:i]) for m in found for i in range(1, m.count(".") + 2)}


def code_files() -> list[Path]:
    """The sources of the modules that importing `NUMERIC_SOURCES` executes within
    `CODE_PACKAGES` (the import graph, read from the sources), sorted by path (their
    hash must not depend on the order they are found in).

    Returns
    -------
    list of pathlib.Path

    See Also
    --------
    code_hash : their hash, part of every key.

    Examples
    --------
    >>> names = {path.name for path in code_files()}
    >>> parents = {path.parent.name + "/" + path.name for path in code_files()}
    >>> {"row.py", "summary.py", "hybrid.py"} <= names, "batch/sweep.py" in parents
    (True, False)
    """
    seen: dict[str, Path] = {}
    # an entry and the packages above it, which Python imports first
    todo = [e.rsplit(".", k)[0] for e in NUMERIC_SOURCES for k in range(e.count(".") + 1)]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        path = _module_file(name)
        if path is None:
            continue
        seen[name] = path
        todo += sorted(_imported(name, path) - set(seen))
    return sorted(set(seen.values()))


@functools.cache
def code_hash() -> str:
    """SHA-256 over the path and bytes of every file of `code_files` (once per process).

    Part of `cache_key`: a change of the generated model or of the integrator gives
    new keys, so that no stale result is served.

    Returns
    -------
    str
        64 hexadecimal digits.

    See Also
    --------
    code_files : the files hashed.

    Examples
    --------
    >>> len(code_hash()), code_hash() == code_hash()
    (64, True)
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
    """The installed version of beltmdsm, else the version in ``pyproject.toml``.

    Returns
    -------
    str

    See Also
    --------
    cache_key : which it enters.

    Examples
    --------
    >>> isinstance(package_version(), str)
    True
    """
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

    Parameters
    ----------
    model : Model
        The point's model.
    settings : SolverSettings
        Its solver settings.
    modulation : bool
        Whether its row holds the modulation columns.
    continuation : {None, "up", "down"}
        The direction of a continued sweep.
    y0 : sequence of float, optional
        A continued point's start state.
    start : {"rest", "periodic"}
        Where a point that is not continued starts.

    Returns
    -------
    dict
        Plain JSON values: the model's `Model.as_dict`, ``settings``, ``modulation``,
        and ``start``, ``continuation`` and ``y0`` where they apply.

    See Also
    --------
    cache_key : its key.

    Examples
    --------
    >>> from beltmdsm import Model, SolverSettings
    >>> ident = identity(Model(Vb=4.0), SolverSettings(t_end=40.0))
    >>> sorted(ident)
    ['contact', 'friction', 'modulation', 'params', 'settings', 'tension']
    >>> "continuation" in identity(Model(Vb=4.0), SolverSettings(), continuation="up")
    True
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
    """SHA-256 of a point's `identity`, the cache format, the version and the code.

    Parameters
    ----------
    ident : dict
        The point's `identity`.

    Returns
    -------
    str
        64 hexadecimal digits, the name of the point's file.

    See Also
    --------
    identity : what it hashes besides the code.

    Examples
    --------
    >>> from beltmdsm import Model, SolverSettings
    >>> ident = identity(Model(Vb=4.0), SolverSettings(t_end=40.0))
    >>> key = cache_key(ident)
    >>> len(key), key == cache_key(identity(Model(Vb=4), SolverSettings(t_end=40)))
    (64, True)
    >>> key == cache_key(identity(Model(Vb=4.5), SolverSettings(t_end=40.0)))
    False
    """
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

    Parameters
    ----------
    path : path
        The point's file.
    ident : dict
        The point's `identity`: the file must hold the same.
    columns : iterable of str
        The columns the row must hold.

    Returns
    -------
    (row, problem)
        ``row`` (a dict) and ``None`` for a valid file; ``None`` and what is wrong
        (a short phrase) for a file that cannot be read, is not UTF-8 or not JSON,
        lacks a key or one of ``columns``, belongs to another point, or whose row
        does not match its checksum; ``(None, None)`` for no file.

    See Also
    --------
    write_cached : writes the file (its Examples read one back).
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

    Parameters
    ----------
    path : path
        The point's file, named by its `cache_key`.
    ident : dict
        The point's `identity`, stored to be checked on reading.
    row : dict
        The point's row (`beltmdsm.batch.row.Row.as_dict`).

    See Also
    --------
    read_cached : reads it back, checked.

    Examples
    --------
    >>> import os, tempfile
    >>> from beltmdsm import Model, SolverSettings
    >>> ident = identity(Model(Vb=4.0), SolverSettings(t_end=40.0))
    >>> path = os.path.join(tempfile.mkdtemp(), cache_key(ident) + ".json")
    >>> write_cached(path, ident, {"regime": "stick_slip"})
    >>> read_cached(path, ident, ["regime"])
    ({'regime': 'stick_slip'}, None)
    >>> read_cached(path, ident, ["regime", "resolved"])
    (None, 'its row lacks resolved')
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
