"""The first run: compiled integrators compiled once, in a process of their own.

numba compiles the integrators of one set of laws (`beltmdsm.integrate._compiled`) in
about 30 s of one core, once: its disk cache serves every later process. A process
that finds them not cached (a new installation, a new dask worker, CI with a fresh
``NUMBA_CACHE_DIR``) does not wait for them. It runs the same source as plain Python
(the same numbers, bit for bit: tests/beltmdsm/integrate/test_first_run.py) and hands
the compile to one child process, which fills the cache and says so by a file
(`ready`); the integrator switches to the compiled code at its first call after that.
One line on stderr says so, once.

No process outlives the command the user ran (issue 37 item 1: an orphaned compile ran
45 s after its command had returned). At its end, a process whose child still compiles
waits for it, saying so in one line, so that the run after is compiled; Ctrl-C there,
or a command ended by Ctrl-C, stops the child instead (the next run compiles again).
A parent that dies (``kill -9``) takes the child with it (`beltmdsm._processes`).

Asked for by name (``backend="numba"``), or where nothing can be cached on disk, the
compile is done in the process (`Lazy` with ``foreground``), said once too, and its
time is kept (`compile_seconds`), so that a progress bar leaves it out.

A compiled function is "ready" when a file named by its source digest (``stem``), the
Python version and numba's CPU settings stands in ``NUMBA_CACHE_DIR/beltmdsm-ready``:
in numba's cache folder, so that emptying that cache forgets it too. The check costs a
``stat``, without importing numba (1-2 s to import and start on 2 busy cores).
"""

from __future__ import annotations

import atexit
import functools
import glob
import hashlib
import importlib.util
import os
import pickle
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np

from beltmdsm.generated import _support
from beltmdsm.generated._support import cache_root, import_numba, user_cache

from .._processes import end_with_parent

__all__ = ["Lazy", "compile_seconds", "digest", "numba_installed", "numba_version", "ready"]

_ROOT = Path(__file__).resolve().parents[2]
#: How long a claim on a compile (`_claim`) holds before another process may take it
#: over (a child that was killed leaves its claim behind).
CLAIM_S = 600.0
#: The compile time quoted by the notices: what the integrators of one law set took on
#: the 2-core reference machine (issue 30: about 10 s before a first simulate, 20 s
#: more before a first floquet; 2-3 times that when its other engineers run too).
ABOUT_S = 30

_said: set = set()
#: Whether this process has asked for compiled code at once (``backend="numba"``): the
#: functions without a backend of their own (the dense output's loop) follow it.
_eager = [False]
_clock = [0.0]
_child: list = []
#: One job at a time down the child's pipe (threads of a process share the child).
_lock = threading.Lock()


def compile_seconds() -> float:
    """Seconds this process has spent making compiled code in the foreground (compiling,
    or loading it from numba's cache): the time a progress bar leaves out."""
    return _clock[0]


def numba_installed() -> bool:
    return "numba" in sys.modules or importlib.util.find_spec("numba") is not None


@functools.cache
def numba_version() -> str:
    """numba's version, from its metadata: without importing it (about a second)."""
    from importlib.metadata import version

    return version("numba")


@functools.cache
def _numba_cache() -> str | None:
    """numba's cache folder as `beltmdsm.generated._support.import_numba` sets it, without
    importing numba; None where nothing is cached on disk."""
    if not _support.DISK_CACHE:
        return None
    numba = sys.modules.get("numba")
    if numba is not None and numba.config.CACHE_DIR:
        return numba.config.CACHE_DIR
    given = os.environ.get("NUMBA_CACHE_DIR")
    if given:
        return given
    try:
        return user_cache("numba")
    except OSError:
        return None  # import_numba says so, once, when it is imported


def digest(version: str, *files: str) -> str:
    """A digest of numba's ``version`` and the ``files`` (paths, wherever the package
    is: beltmdsm.generated sits beside beltmdsm/ in a source checkout, inside it when
    installed)."""
    h = hashlib.sha256(version.encode())
    for path in files:
        h.update(Path(path).read_bytes())
    return h.hexdigest()[:20]


@functools.cache
def _marker(stem: str) -> Path | None:
    folder = _numba_cache()
    if folder is None:
        return None
    cpu = "-".join(
        os.environ.get(v, "host").replace(os.sep, "_")
        for v in ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES")
    )
    tag = f"py{sys.version_info[0]}{sys.version_info[1]}-{cpu}"
    return Path(folder) / "beltmdsm-ready" / f"{stem}-{tag}"


def ready(stem: str) -> bool:
    """Whether the compiled function ``stem`` is in numba's disk cache (said by `_mark`)."""
    marker = _marker(stem)
    return marker is not None and marker.exists()


def _mark(stem: str) -> None:
    marker = _marker(stem)
    if marker is not None:
        marker.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
        marker.touch()


def _say(kind: str, text: str) -> None:
    """``text`` on stderr, once per process and ``kind``."""
    if kind not in _said:
        _said.add(kind)
        print(f"beltmdsm: {text}", file=sys.stderr, flush=True)


def _describe(value):
    """What numba types ``value`` by, to send to the child: an array's dtype, number of
    dimensions, layout and writability (not its data), tuples entry by entry."""
    if isinstance(value, np.ndarray):
        layout = "C" if value.flags.c_contiguous else "F" if value.flags.f_contiguous else "A"
        return ("array", value.dtype.str, value.ndim, layout, bool(value.flags.writeable))
    if isinstance(value, tuple):
        return ("tuple", tuple(_describe(v) for v in value))
    return ("value", value)


def _standin(described):
    """A value that numba types as `_describe`'s ``described``."""
    kind, *rest = described
    if kind == "value":
        return rest[0]
    if kind == "tuple":
        return tuple(_standin(v) for v in rest[0])
    dtype, ndim, layout, writeable = rest
    if layout == "A":  # strided in every axis: neither C nor F contiguous
        a = np.zeros((4,) * ndim, dtype)[(slice(None, None, 2),) * ndim]
    else:
        a = np.zeros((2,) * ndim, dtype, order=layout)
    a.setflags(write=writeable)
    return a


def _compile(spec, args) -> object:
    """The compiled function of ``spec`` (``(maker, maker_args)``), compiled (or loaded
    from numba's cache) for the types of ``args``.

    A cache file that cannot be read (truncated by a full disk or a killed process:
    numba raises UnpicklingError or EOFError, in every run after) is removed and the
    function compiled afresh, said once (issue 36 item 6).
    """
    numba = import_numba(True)
    maker, maker_args = spec
    fn = maker(*maker_args)
    signature = tuple(numba.typeof(a) for a in args)
    for _ in range(MAX_UNREADABLE):
        try:
            fn.compile(signature)
            return fn
        except Exception as err:  # noqa: BLE001 (numba's loader raises what unpickling raises)
            files = _unreadable(err)
            if not files:
                raise  # not a cache file: a real failure
            for path in files:
                path.unlink(missing_ok=True)
            _say(
                "unreadable",
                f"numba's cache of the compiled integrators was unreadable ({files[0]}: "
                f"{type(err).__name__}: {err}); removed it and compiling again (~{ABOUT_S} s)",
            )
    fn.compile(signature)
    return fn


#: Unreadable cache files (each the index of one compiled function, found one per try)
#: `_compile` removes before it lets the error through.
MAX_UNREADABLE = 16


def _unreadable(err: BaseException) -> list[Path]:
    """The files of the numba cache entry whose loading raised ``err`` (its index first),
    [] where ``err`` was not raised in loading one: the entry is the loader object
    (``numba.core.caching.IndexDataCacheFile``) in the frames of the traceback."""
    tb = err.__traceback__
    while tb is not None:
        loader = tb.tb_frame.f_locals.get("self")
        if type(loader).__name__ == "IndexDataCacheFile":
            index = Path(loader._index_path)
            base = glob.escape(index.name.removesuffix(".nbi"))
            return [index, *sorted(index.parent.glob(f"{base}.*.nbc"))]
        tb = tb.tb_next
    return []


class Lazy:
    """A compiled function made at its first call: compiled code where it is cached, else
    plain Python while a child compiles it (or, ``foreground``, compiled at once).

    ``spec`` is ``(maker, args)``: ``maker(*args)`` makes the numba dispatcher (in this
    process or the child, so a module-level function); ``python`` runs the same
    numbers as plain Python; ``stem`` names the compiled code (a digest of its sources).
    """

    __slots__ = ("spec", "stem", "python", "foreground", "fn", "waiting")

    def __init__(self, spec, stem: str, python, foreground: bool = False) -> None:
        self.spec, self.stem, self.python, self.foreground = spec, stem, python, foreground
        self.fn = None
        self.waiting = False

    def __call__(self, *args):
        fn = self.fn or self.compiled(args) or self.python
        return fn(*args)

    def compiled(self, args):
        """The compiled function, or None while the child compiles it."""
        if self.fn is not None:
            return self.fn
        if self.waiting:
            if not ready(self.stem):
                return None
        elif self.foreground:
            _eager[0] = True
        elif not _eager[0] and not ready(self.stem) and _marker(self.stem) is not None:
            self.waiting = _submit(self.spec, self.stem, args)
            if self.waiting:
                return None
        folder = None if ready(self.stem) else _numba_cache()
        if folder is not None:
            _say(
                "foreground",
                f"compiling the integrator kernels once (~{ABOUT_S} s; cached in {folder})",
            )
        # loaded from numba's cache where ready (about 0.1 s; the first also starts
        # numba, about a second): timed either way, for the progress bars to leave out
        start = time.perf_counter()
        self.fn = _compile(self.spec, args)
        _clock[0] += time.perf_counter() - start
        if folder is not None:
            _mark(self.stem)
        return self.fn


_CHILD_CODE = (
    "import sys; sys.path[0] = sys.argv[1]; "
    "from beltmdsm.integrate._background import _serve; _serve(int(sys.argv[2]))"
)


def _submit(spec, stem: str, args) -> bool:
    """Hand the compile to the child (started at the first job); False where no child
    can be started (then the caller compiles)."""
    job = pickle.dumps((spec, stem, _describe(args)))
    with _lock:
        return _send(job)


def _send(job: bytes) -> bool:
    for _ in range(2):
        if not _child or _child[0].poll() is not None:
            env = dict(os.environ, NUMBA_CACHE_DIR=_numba_cache(), BELTMDSM_CACHE=cache_root())
            try:
                child = subprocess.Popen(
                    [sys.executable, "-c", _CHILD_CODE, str(_ROOT), str(os.getpid())],
                    stdin=subprocess.PIPE,
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                    env=env,
                    cwd=_ROOT,
                    # a Ctrl-C of the run does not stop the compile (_leave decides)
                    start_new_session=True,
                )
            except OSError:
                return False
            _child[:] = [child]
            atexit.register(_leave, child)
        try:
            _child[0].stdin.write(job)
            _child[0].stdin.flush()
        except OSError:  # the child ended: start another
            _child.clear()
            continue
        _say(
            "background",
            f"compiling the integrator kernels once, in the background (~{ABOUT_S} s; cached "
            f"in {_numba_cache()}); this run uses them as plain Python meanwhile (same results)",
        )
        return True
    return False


def _leave(child) -> None:
    """At this process's end: the child reads the end of its jobs, finishes them and
    ends; this process waits for that, said in one line, unless it is ending by Ctrl-C
    (`beltmdsm.cli.running` then ignores a second one) or gets one while it waits:
    then the child is stopped, and the next run compiles again."""
    try:
        child.stdin.close()
    except OSError:
        pass
    if child.poll() is not None:
        return
    if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:
        _say(
            "wait",
            "waiting for the compile of the integrator kernels to end, so that the next "
            "run is compiled (Ctrl-C stops it; the next run then compiles again)",
        )
        try:
            child.wait(timeout=CLAIM_S)
            return
        except (KeyboardInterrupt, subprocess.TimeoutExpired):
            pass
    child.terminate()
    child.wait()


def _claim(stem: str) -> Path | None:
    """A claim on compiling ``stem`` (a file made exclusively), or None where another
    process holds a fresh one."""
    marker = _marker(stem)
    marker.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
    claim = marker.with_name(marker.name + ".compiling")
    for _ in range(2):
        try:
            fd = os.open(claim, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600)
        except FileExistsError:
            try:
                holder = int(claim.read_text() or 0)
                if time.time() - claim.stat().st_mtime < CLAIM_S and _running(holder):
                    return None
                claim.unlink()  # old, or its process ended without removing it
            except (FileNotFoundError, ValueError):
                pass
            continue
        os.write(fd, str(os.getpid()).encode())
        os.close(fd)
        return claim
    return None


def _running(pid: int) -> bool:
    """Whether process ``pid`` exists (a claim's holder)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True  # exists, another user's
    return pid > 0


def _serve(parent: int) -> None:
    """The child of process ``parent``: compile each job read from stdin (until its
    end), mark it ready; end with the parent, releasing its claim."""
    held: list[Path] = []
    end_with_parent(lambda: [c.unlink(missing_ok=True) for c in held], parent)
    stdin = sys.stdin.buffer
    while True:
        try:
            spec, stem, described = pickle.load(stdin)
        except EOFError:
            return
        if ready(stem):
            continue
        claim = _claim(stem)
        if claim is None:
            continue  # another process compiles it
        held.append(claim)
        try:
            _compile(spec, _standin(described))
            _mark(stem)
        except Exception:  # noqa: BLE001 (the parent runs plain Python; the next tries again)
            pass
        finally:
            claim.unlink(missing_ok=True)
            held.remove(claim)
