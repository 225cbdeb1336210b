"""Budgets for the symbolic steps that may not terminate.

Some of SymPy's algorithms decide a question by a search whose length depends on the
law: Risch's algorithm on a rational law's average (minutes and tens of GB), `solve`
on the forced damping of a cubic law (hours). A derivation that must finish for every
law a user writes runs each such step through `within`: in a forked worker process,
under a CPU-time budget (`SECONDS`, the environment's ``BELTMDSM_DERIVE_SECONDS``) and a
memory budget (`MEMORY_MB`, ``BELTMDSM_DERIVE_MEMORY_MB``, on top of the address space
the derivation holds already: ``RLIMIT_AS`` in the worker). A worker past its budget
is killed, and `within` raises `OverBudget`; the caller then takes the numeric path the
package has for laws without a closed form (a quadrature printed as a Gauss-Legendre
rule, roots found at run time) and records why, in the words of `OverBudget.reason`,
in ``generated/capabilities.py`` or in the refusal of the generated function.

The time budget is CPU time (``RLIMIT_CPU`` in the worker): the wall clock of a busy
shared machine runs several times faster than a step's CPU clock, and a budget in wall
time would make the generated code depend on the load (the wall clock ends only a
worker that used almost no CPU time in `WALL_FACTOR` times its budget: one that stopped).

A worker is a ``fork`` of the derivation: it starts with SymPy's caches and every
derived expression, and sends back one picklable result (tens of ms for the fork and
the pipe; tests/derive/test_budget.py prints it). ``BELTMDSM_DERIVE_LOG=1`` prints each
step's CPU and wall time on stderr.

**What is written does not depend on the machine.** A CPU-time budget still depends on
the machine's speed and load (caches, frequency, a neighbour's hyperthread): a step that
takes 18 s of a 20 s budget finishes in one run and not in the next. So each budgeted
decision is recorded, in ``generated/_budget.py`` (`render_record`), and read back by the
next derivation and by ``python -m derive --check`` (`use_record`): a step recorded past
its budget is not run again (its fallback is taken at once, which also keeps a law's
hopeless searches out of every later derivation), a step recorded as finished is run
with `SAFETY` times its budget, so that a slower or busier machine reproduces it. A
step is keyed by its name and a digest of its inputs (the law's expressions): a law
that changes is decided afresh, and the record then differs, which ``--check`` reports.
Raising ``BELTMDSM_DERIVE_SECONDS`` above a recorded budget decides its steps afresh.

A step may also end without an answer because SymPy implements no method for it
(`NotImplementedError`, such as `solve` on a transcendental equation with several
generators): that is `Unimplemented`, which the caller treats as it treats a step
past its budget (`Undecided` is either), with a reason in the package's words.
"""

from __future__ import annotations

import ast
import hashlib
import math
import multiprocessing
import os
import resource
import signal
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

__all__ = [
    "SECONDS",
    "MEMORY_MB",
    "SAFETY",
    "RECORD",
    "Undecided",
    "OverBudget",
    "Unimplemented",
    "NoClosedForm",
    "within",
    "reason",
    "in_worker",
    "use_record",
    "render_record",
]


def _setting(name: str, default: float) -> float:
    value = os.environ.get(name, "")
    try:
        number = float(value) if value else default
    except ValueError:
        raise ValueError(
            f"{name} must be a number of {'s' if 'SECONDS' in name else 'MB'}; got {value!r}"
        ) from None
    if not number > 0:
        raise ValueError(f"{name} must be > 0; got {value!r}")
    return number


#: The time budget of one step, in seconds.
SECONDS = _setting("BELTMDSM_DERIVE_SECONDS", 20.0)
#: The memory a step may add to the derivation's address space, in MB.
MEMORY_MB = _setting("BELTMDSM_DERIVE_MEMORY_MB", 1536.0)

#: The wall-clock safety net of a step, in multiples of its CPU budget: a worker that used
#: no CPU time for that long has stopped computing (the CPU budget is the one that ends a
#: long search; a worker that a busy machine starves is waited for).
WALL_FACTOR = 10
#: A step recorded as finished within its budget runs again under this many times the
#: budget (CPU time and memory): a slower or busier machine still reproduces it.
SAFETY = 5
#: The record's file name in generated/.
RECORD = "_budget.py"

_IN_WORKER = False


class Undecided(Exception):
    """A step without an answer; ``reason`` says why, in the package's words."""

    reason: str = "undecided"


class OverBudget(Undecided):
    """A step that did not finish within its budget (time or memory)."""

    def __init__(self, what: str, seconds: float, memory: bool = False):
        self.what, self.seconds, self.memory = what, seconds, memory
        super().__init__(f"{what}: {reason(seconds, memory)}")

    @property
    def reason(self) -> str:
        """``no closed form found within the budget of N s`` (or of its memory)."""
        return reason(self.seconds, self.memory)


class Unimplemented(Undecided):
    """A step for which SymPy implements no method (it raised `NotImplementedError`)."""

    reason = "SymPy implements no method for it"

    def __init__(self, what: str):
        self.what = what
        super().__init__(f"{what}: {self.reason}")


@dataclass(frozen=True)
class NoClosedForm:
    """A derivation's answer where a step ran past its budget: why there is no closed form
    (the code generator turns it into a refusal that names the law and the budget)."""

    reason: str


def reason(seconds: float | None = None, memory: bool = False) -> str:
    """The words a capability fact or a refusal records for a step past its budget."""
    if memory:
        return f"no closed form found within the memory budget of {MEMORY_MB:g} MB"
    seconds = SECONDS if seconds is None else seconds
    return f"no closed form found within the budget of {seconds:g} s of CPU time"


def in_worker() -> bool:
    """Whether this process is a budget's worker (a nested step then runs in it directly)."""
    return _IN_WORKER


def _address_space() -> int:
    """The bytes of address space this process holds now (Linux; 0 where unknown)."""
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[0]) * resource.getpagesize()
    except (OSError, ValueError, IndexError):
        return 0


def _work(conn, fn, args, seconds, memory_bytes):
    global _IN_WORKER
    _IN_WORKER = True
    # CPU time, not wall time: on a shared machine the wall clock runs several times
    # faster than a busy process's CPU clock, and the budget must not depend on the load.
    # Past the soft limit the kernel sends SIGXCPU, whose default action ends the worker.
    cpu = math.ceil(seconds)
    try:
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 1))
        if memory_bytes:
            resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
    except (ValueError, OSError):  # a platform without the limit: the wall clock's remains
        pass
    try:
        conn.send(("done", fn(*args)))
    except MemoryError:
        conn.send(("memory", None))
    except NotImplementedError:
        conn.send(("unimplemented", None))
    except BaseException as err:  # noqa: BLE001 (handed to the caller, raised there)
        try:
            conn.send(("raised", err))
        except Exception:  # noqa: BLE001 (an exception that does not pickle)
            conn.send(("raised", RuntimeError(f"{type(err).__name__}: {err}")))
    finally:
        conn.close()


# The record of decisions ----------------------------------------------------------------

#: ``{(what, digest): outcome}`` read from a record (`use_record`); outcome ``"done"`` or
#: ``("time", seconds)`` or ``("memory", megabytes)``.
_RECORDED: dict = {}
#: The decisions of this derivation, in the same form (`render_record`).
_DECIDED: dict = {}
#: ``(returned, value or exception)`` of the steps that finished in this derivation: a
#: step met again (the same unforced root for each contact law) is not computed twice.
_VALUES: dict = {}


def _text(x) -> str:
    """A deterministic text of a step's inputs (SymPy's `srepr` for its expressions)."""
    if isinstance(x, (tuple, list)):
        return "(" + ", ".join(map(_text, x)) + ")"
    if hasattr(x, "func") and hasattr(x, "args"):  # a SymPy object
        from sympy import srepr  # sympy is loaded already wherever a step runs

        return srepr(x)
    return repr(x)


def _key(what: str, inputs) -> tuple[str, str]:
    return what, hashlib.sha256(_text(inputs).encode()).hexdigest()[:16]


def use_record(path: Path | None) -> None:
    """Read the decisions recorded in ``path`` (a ``generated/_budget.py``; None or a missing
    file: none) and start a new record."""
    _RECORDED.clear()
    _DECIDED.clear()
    _VALUES.clear()
    if path is None or not Path(path).is_file():
        return
    tree = ast.parse(Path(path).read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and node.targets[0].id == "DECISIONS":
            _RECORDED.update(ast.literal_eval(node.value))


def render_record(header: str) -> str:
    """The text of ``generated/_budget.py``: this derivation's decisions, sorted."""
    lines = [
        header + '"""The budgeted steps of the derivation and how each ended (derive/budget.py).',
        "",
        "Read back by the next ``python -m derive`` and by ``--check``: a step recorded past its",
        "budget takes its fallback without running; one recorded ``done`` runs again. Keys are",
        "the step and a digest of its inputs; values ``done``, ``(time, seconds)`` or",
        '``(memory, megabytes)``. Importing it imports nothing."""',
        "",
        "DECISIONS = {",
    ]
    for key in sorted(_DECIDED):
        lines.append(f"    {key!r}: {_DECIDED[key]!r},")
    return "\n".join(lines) + "\n}\n"


def within(what: str, fn: Callable, *args, seconds: float | None = None, inputs=None):
    """``fn(*args)``, computed in a forked worker under the time and memory budgets.

    Parameters
    ----------
    what : str
        The step, for `OverBudget`'s message and the record.
    fn, args
        A function of the derivation and its arguments; the result must pickle.
    seconds : float, optional
        The time budget; default `SECONDS`.
    inputs : optional
        What the result depends on, for the record's key (default ``args``): the law's
        expressions where ``args`` name it only.

    Raises
    ------
    OverBudget
        If the worker did not answer within ``seconds``, or ran out of its memory, or the
        record says so.
    Unimplemented
        If ``fn`` raised `NotImplementedError`.
    Exception
        Whatever else ``fn`` raised, raised again here.
    """
    seconds = SECONDS if seconds is None else seconds
    if _IN_WORKER or "fork" not in multiprocessing.get_all_start_methods():
        try:
            return fn(*args)  # nested, or no fork (Windows): the step runs here, unbudgeted
        except NotImplementedError:
            raise Unimplemented(what) from None
    key = _key(what, args if inputs is None else inputs)
    if key in _VALUES:  # the same step with the same inputs, decided in this derivation
        finished, value = _VALUES[key]
        if not finished:
            raise value
        return value
    recorded = _DECIDED.get(key, _RECORDED.get(key))
    if recorded is not None and recorded != "done":
        kind, amount = recorded
        if kind == "memory" or amount >= seconds:  # a larger budget decides afresh
            _DECIDED[key] = recorded
            raise OverBudget(what, amount, memory=kind == "memory")
    safety = SAFETY if recorded == "done" else 1
    try:
        value = _run(what, fn, args, seconds, safety)
    except OverBudget as over:
        _DECIDED[key] = ("memory", MEMORY_MB) if over.memory else ("time", seconds)
        raise OverBudget(what, seconds, over.memory) from None
    except Exception as err:  # what fn raised: the same every time
        _DECIDED[key], _VALUES[key] = "done", (False, err)
        raise
    _DECIDED[key], _VALUES[key] = "done", (True, value)
    return value


def _cpu_of(pid: int) -> float | None:
    """The CPU seconds process ``pid`` has used (Linux's /proc; None where unknown)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


def _answers(receive, pid: int, limit: float) -> bool:
    """Whether the worker answers: its CPU limit ends a long computation; the wall clock
    ends only a worker that stopped computing (no CPU time in `WALL_FACTOR` times its
    budget of wall time). A worker that a busy machine starves of CPU (7% of a core on a
    shared machine: a 20 s step takes minutes) is waited for, or its outcome would depend
    on the load."""
    last = _cpu_of(pid)
    while not receive.poll(WALL_FACTOR * limit):
        now = _cpu_of(pid)
        if now is None or last is None or now - last < 0.01 * limit:
            return False
        last = now
    return True


def _run(what: str, fn: Callable, args, seconds: float, safety: float):
    """`within`'s worker: ``fn(*args)`` under ``safety`` times the budgets."""
    used = _address_space()
    memory_bytes = used + int(safety * MEMORY_MB * 2**20) if used else 0
    hard = resource.getrlimit(resource.RLIMIT_AS)[1]
    if memory_bytes and hard != resource.RLIM_INFINITY:
        memory_bytes = min(memory_bytes, hard)
    limit = safety * seconds
    start, cpu = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
    ctx = multiprocessing.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)
    worker = ctx.Process(target=_work, args=(send, fn, args, limit, memory_bytes), daemon=True)
    worker.start()
    send.close()
    try:
        if not _answers(receive, worker.pid, limit):  # a worker that waits, not computes
            raise OverBudget(what, seconds)
        try:
            status, value = receive.recv()
        except EOFError:  # the worker died without a word
            worker.join()
            if worker.exitcode == -signal.SIGXCPU:
                raise OverBudget(what, seconds) from None
            raise OverBudget(what, seconds, memory=True) from None
    finally:
        if worker.is_alive():
            worker.kill()
        worker.join()
        receive.close()
        if os.environ.get("BELTMDSM_DERIVE_LOG"):
            now = resource.getrusage(resource.RUSAGE_CHILDREN)
            used_cpu = now.ru_utime + now.ru_stime - cpu.ru_utime - cpu.ru_stime
            print(
                f"  budget: {what}: {used_cpu:.1f} s of CPU time, "
                f"{time.perf_counter() - start:.1f} s wall",
                file=sys.stderr,
            )
    if status == "memory":
        raise OverBudget(what, seconds, memory=True)
    if status == "unimplemented":
        raise Unimplemented(what)
    if status == "raised":
        raise value
    return value
