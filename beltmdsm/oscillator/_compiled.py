"""One mode of a hybrid run, to its first switch, compiled by numba with a model's kernels.

`beltmdsm.oscillator.hybrid.flow` chooses the modes and applies the switches in Python
(a few hundred per run); between them, the plain-Python integrator spends about a
millisecond a step in numpy's small-array overheads. Here the same method (DOP853 with
SciPy's step-size control, the coefficients of ``beltmdsm.generated.tableau``), the same
surfaces (`beltmdsm.oscillator.hybrid`) and the same search for the first crossing
(the guard at the step's Chebyshev-Lobatto points, its polynomial and error model of
`beltmdsm.oscillator._dips` for a fall between them, then the Illinois method of
`beltmdsm.integrate._roots`; in stick, the two sides of the cone integrated beside the
state) run as one numba function, with the model's kernels compiled into it.

The kernels are the module's plain functions: each is compiled by numba with every
function it calls (its globals and closure cells) compiled too. The compiled module is
written to the private cache folder and cached on disk by numba, once per model module
and friction law (its name holds a digest of the sources): made at the first run as the
paper's integrators are (`beltmdsm.integrate._background`: plain Python while a child
process compiles it, unless ``backend="numba"`` asks for it at once; about a minute on a
loaded 2-core machine, then loaded in a second or two). A module whose kernels numba
cannot compile runs in plain Python, said once (`CompileWarning`);
benchmarks/bench_oscillator.py prints cold and warm times.
"""

from __future__ import annotations

import functools
import importlib
import importlib.util
import inspect
import math
import os
import sys
import tempfile
import types
import warnings
from pathlib import Path

import numpy as np

from beltmdsm.generated import tableau as _coef
from beltmdsm.generated._support import import_numba, user_cache

from ..integrate import _roots
from ..integrate._background import Lazy, digest, numba_installed, numba_version
from . import _dips

__all__ = ["advance", "CompileWarning"]

_NS = _coef.N_STAGES
_NX = _coef.N_STAGES_EXTENDED
_NP = _coef.INTERPOLATOR_POWER
_A = np.ascontiguousarray(_coef.A, dtype=float)
_B = np.ascontiguousarray(_coef.B, dtype=float)
_C = np.ascontiguousarray(_coef.C, dtype=float)
_E3 = np.ascontiguousarray(_coef.E3, dtype=float)
_E5 = np.ascontiguousarray(_coef.E5, dtype=float)
_D = np.ascontiguousarray(_coef.D, dtype=float)
STATUS_END, STATUS_EVENT, STATUS_STEP_TOO_SMALL = 0, 1, 2


class CompileWarning(UserWarning):
    """A model's kernels that numba cannot compile: its runs take plain Python."""


# the kernels, bound as globals of the functions below (`_build`)
field = slip_velocity = slip_acceleration = holding_force = stick_limit = normal_force = None
gap = surfaces = surface_rates = None
UNILATERAL = False
#: positions in the module's SURFACES (`_source` binds the model's; -1: none)
I_FORWARD, I_BACK, I_GAP = 1, 2, -1


def _u(t, y, p, mode, j):
    """Surface ``j`` of the mode, positive inside (`beltmdsm.oscillator.guards.surfaces`)."""
    if UNILATERAL:
        if mode == 2:
            return gap(t, y, p)
        if j == 1:
            return -gap(t, y, p)
    if mode == 0:
        return stick_limit(t, y, p) - abs(holding_force(t, y, p))
    return mode * slip_velocity(t, y, p)


def _du(t, y, p, mode, j):
    """The rate of surface ``j`` of the mode along its field
    (`beltmdsm.oscillator.guards.rates`)."""
    if UNILATERAL:
        if mode == 2:
            return surface_rates(t, y, p, mode)[I_GAP]
        if j == 1:
            return -surface_rates(t, y, p, mode)[I_GAP]
    if mode == 0:
        r = surface_rates(t, y, p, mode)
        return r[I_BACK] if holding_force(t, y, p) >= 0.0 else r[I_FORWARD]
    return mode * slip_acceleration(t, y, p, mode)


def _rhs(t, y, p, mode, out):
    """The mode's field into ``out``; where ``out`` is longer (stick), the rates of the
    two sides of the cone after it (`beltmdsm.oscillator.guards.quadratures`)."""
    f = field(t, y, p, mode)
    n = f.shape[0]
    for i in range(n):
        out[i] = f[i]
    if out.shape[0] > n:
        r = surface_rates(t, y, p, mode)
        out[n] = r[I_FORWARD]
        out[n + 1] = r[I_BACK]


def _du_at(p, mode, j, F, y0, t0, h, t, tmp):
    _dense(F, y0, (t - t0) / h, tmp)
    return _du(t, tmp, p, mode, j)


def _root(p, mode, j, F, y0, t0, h, a, fa, b, fb, tmp, rate):
    """The Illinois method on the dense output: ``u`` (``rate`` False, ``fa > 0 >= fb``)
    or minus its rate (``rate`` True)."""
    side = 0
    for _ in range(200):
        if converged(a, b):
            break
        c = secant(a, fa, b, fb)
        if rate:
            fc = -_du_at(p, mode, j, F, y0, t0, h, c, tmp)
        else:
            fc = _u_at(p, mode, j, F, y0, t0, h, c, tmp)
        a, fa, b, fb, side = illinois(a, fa, b, fb, c, fc, side)
    return b


def _touch(p, mode, j, F, y0, t0, h, values, first, last, ts, tmp):
    """As `beltmdsm.oscillator.guards.touch`: the first fall to 0 between the nodes
    ``first`` and ``last`` that no node shows, or -1."""
    n = values.shape[0]
    c = np.empty(n)
    scratch = np.empty(n)
    bernstein(values, c)
    e = error(values)
    xa, xb = NODES[first], NODES[last]
    if xa > 0.0:
        split(c, xa, scratch, c)
    if xb < 1.0:
        split(c, (xb - xa) / (1.0 - xa), c, scratch)
    # depth-first, left first: at most one pending right half per level
    stack = np.empty((DEPTH + 2, n))
    lo_s = np.empty(DEPTH + 2)
    hi_s = np.empty(DEPTH + 2)
    depth_s = np.empty(DEPTH + 2, dtype=np.int64)
    for i in range(n):
        stack[0, i] = c[i]
    lo_s[0], hi_s[0], depth_s[0] = xa, xb, 0
    top = 1
    t_pos, u_pos = ts[first], values[first]
    while top > 0:
        top -= 1
        lo, hi, depth = lo_s[top], hi_s[top], depth_s[top]
        for i in range(n):
            c[i] = stack[top, i]
        if lowest(c) > e:
            continue
        if depth < DEPTH:
            mid = 0.5 * (lo + hi)
            split(c, 0.5, c, scratch)
            for i in range(n):
                stack[top, i] = scratch[i]
                stack[top + 1, i] = c[i]
            lo_s[top], hi_s[top], depth_s[top] = mid, hi, depth + 1
            lo_s[top + 1], hi_s[top + 1], depth_s[top + 1] = lo, mid, depth + 1
            top += 2
            continue
        ta = t0 + h * lo if lo > xa else ts[first]
        tb = t0 + h * hi if hi < xb else ts[last]
        ua = u_pos if ta == t_pos else _u_at(p, mode, j, F, y0, t0, h, ta, tmp)
        if ua <= 0.0:
            return _root(p, mode, j, F, y0, t0, h, t_pos, u_pos, ta, ua, tmp, False)
        ub = _u_at(p, mode, j, F, y0, t0, h, tb, tmp)
        if ub <= 0.0:
            return _root(p, mode, j, F, y0, t0, h, ta, ua, tb, ub, tmp, False)
        ra = _du_at(p, mode, j, F, y0, t0, h, ta, tmp)
        rb = _du_at(p, mode, j, F, y0, t0, h, tb, tmp)
        if ra < 0.0 <= rb:
            tm = _root(p, mode, j, F, y0, t0, h, ta, -ra, tb, -rb, tmp, True)
            um = _u_at(p, mode, j, F, y0, t0, h, tm, tmp)
            if um <= 0.0:
                return _root(p, mode, j, F, y0, t0, h, ta, ua, tm, um, tmp, False)
        t_pos, u_pos = tb, ub
    return -1.0


def _dense(F, y0, x, out):
    for i in range(y0.shape[0]):
        out[i] = 0.0
    for k in range(_NP):
        row = _NP - 1 - k
        for i in range(y0.shape[0]):
            out[i] += F[row, i]
            out[i] *= x if k % 2 == 0 else 1.0 - x
    for i in range(y0.shape[0]):
        out[i] += y0[i]


def _u_at(p, mode, j, F, y0, t0, h, t, tmp):
    _dense(F, y0, (t - t0) / h, tmp)
    return _u(t, tmp, p, mode, j)


def _crossing(p, mode, j, F, y0, t0, h, u_old, u_new, armed, tmp):
    """``(time, armed)``: the first fall of surface ``j`` to <= 0 inside the step
    (time < 0: none); as `beltmdsm.oscillator.guards.crossing`."""
    n = NODES.shape[0]
    ts = np.empty(n)
    values = np.empty(n)
    for i in range(n):
        ts[i] = t0 + h * NODES[i]
    ts[n - 1] = t0 + h
    values[0], values[n - 1] = u_old, u_new
    for i in range(1, n - 1):
        values[i] = _u_at(p, mode, j, F, y0, t0, h, ts[i], tmp)
    first = 0
    if not armed:
        first = -1
        for i in range(n):
            if values[i] > 0.0:
                first = i
                break
        if first < 0:
            return t0, False  # never inside: the field leaves through its own start surface
    last = n - 1
    fall = False
    for i in range(first + 1, n):
        if values[i] <= 0.0:
            last = i - 1
            fall = True
            break
    if last > first:
        tc = _touch(p, mode, j, F, y0, t0, h, values, first, last, ts, tmp)
        if tc >= 0.0:
            return tc, True
    if fall:
        tc = _root(p, mode, j, F, y0, t0, h, ts[last], values[last], ts[last + 1],
                   values[last + 1], tmp, False)  # fmt: skip
        return tc, True
    return -1.0, True


def advance(p, mode, n_watch, t, y, t_end, h_abs, rtol, atol, dt, t_first, k_next, out_t, out_y):
    """Integrate ``mode`` from ``(t, y)`` to ``t_end`` or its first crossing.

    ``y``: the state, then (stick) the two sides of the cone (`_rhs`). Samples at
    ``t_first + k dt`` (``k >= k_next``) are written to ``out_t``, ``out_y`` from
    ``k_next`` on (``dt <= 0``: none). Returns ``(status, t, y, hit, h_abs, k_next)``.
    """
    m = y.shape[0]
    y = y.copy()
    K = np.empty((_NX, m))
    F = np.empty((_NP, m))
    tmp = np.empty(m)
    y_new = np.empty(m)
    u_old = np.empty(n_watch)
    u_new = np.empty(n_watch)
    armed = np.empty(n_watch, dtype=np.bool_)
    for j in range(n_watch):
        u_old[j] = _u(t, y, p, mode, j)
        armed[j] = u_old[j] > 0.0
    f = np.empty(m)
    _rhs(t, y, p, mode, f)
    status, hit = STATUS_END, -1
    while t < t_end:
        rejected = False
        while True:
            min_step = 10.0 * (np.nextafter(t, np.inf) - t)
            h_abs = max(h_abs, min_step)
            t_new = min(t + h_abs, t_end)
            h = t_new - t
            if not (h > 0.0) or (h < min_step and t_new < t_end):
                status = STATUS_STEP_TOO_SMALL
                break
            for i in range(m):
                K[0, i] = f[i]
            for s in range(1, _NS):
                for i in range(m):
                    acc = 0.0
                    for r in range(s):
                        acc += _A[s, r] * K[r, i]
                    tmp[i] = y[i] + h * acc
                _rhs(t + _C[s] * h, tmp, p, mode, K[s])
            for i in range(m):
                acc = 0.0
                for r in range(_NS):
                    acc += _B[r] * K[r, i]
                y_new[i] = y[i] + h * acc
            _rhs(t_new, y_new, p, mode, K[_NS])
            e5 = 0.0
            e3 = 0.0
            for i in range(m):
                sc = atol + max(abs(y[i]), abs(y_new[i])) * rtol
                a5 = 0.0
                a3 = 0.0
                for r in range(_NS + 1):
                    a5 += _E5[r] * K[r, i]
                    a3 += _E3[r] * K[r, i]
                e5 += (a5 / sc) ** 2
                e3 += (a3 / sc) ** 2
            norm = 0.0 if e5 == 0.0 and e3 == 0.0 else h * e5 / math.sqrt((e5 + 0.01 * e3) * m)
            if not math.isfinite(norm):
                norm = math.inf
            if norm < 1.0:
                factor = 10.0 if norm == 0.0 else min(10.0, 0.9 * norm**-0.125)
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            h_abs *= max(0.2, 0.9 * norm**-0.125) if math.isfinite(norm) else 0.2
            rejected = True
        if status != STATUS_END:
            break
        for s in range(_NS + 1, _NX):
            for i in range(m):
                acc = 0.0
                for r in range(s):
                    acc += _A[s, r] * K[r, i]
                tmp[i] = y[i] + h * acc
            _rhs(t + _C[s] * h, tmp, p, mode, K[s])
        for i in range(m):
            d = y_new[i] - y[i]
            F[0, i] = d
            F[1, i] = h * K[0, i] - d
            F[2, i] = 2.0 * d - h * (K[_NS, i] + K[0, i])
            for row in range(_NP - 3):
                acc = 0.0
                for r in range(_NX):
                    acc += _D[row, r] * K[r, i]
                F[3 + row, i] = h * acc
        hit, t_hit = -1, math.inf
        for j in range(n_watch):
            u_new[j] = _u(t_new, y_new, p, mode, j)
            tc, armed[j] = _crossing(p, mode, j, F, y, t, h, u_old[j], u_new[j], armed[j], tmp)
            if tc >= 0.0 and tc < t_hit:
                hit, t_hit = j, tc
        t_stop = t_hit if hit >= 0 else t_new
        if dt > 0.0:
            while k_next < out_t.shape[0]:
                ts = t_first + dt * k_next
                if ts > t_stop:
                    break
                _dense(F, y, (ts - t) / h, tmp)
                out_t[k_next] = ts
                for i in range(out_y.shape[1]):
                    out_y[k_next, i] = tmp[i]
                k_next += 1
        if hit >= 0:
            if t_hit > t:
                _dense(F, y, (t_hit - t) / h, tmp)
                for i in range(m):
                    y[i] = tmp[i]
            t = t_hit
            status = STATUS_EVENT
            break
        t = t_new
        for i in range(m):
            y[i] = y_new[i]
            f[i] = K[_NS, i]
        for j in range(n_watch):
            u_old[j] = u_new[j]
    return status, t, y, hit, h_abs, k_next


converged, secant, illinois = _roots.converged, _roots.secant, _roots.illinois
bernstein, error, split, lowest = _dips.bernstein, _dips.error, _dips.split, _dips.lowest
NODES, DEPTH = _dips.NODES, _dips.DEPTH
_FUNCTIONS = ("_u", "_du", "_rhs", "_dense", "_u_at", "_du_at", "_root", "_touch",
              "_crossing", "advance")  # fmt: skip
_KERNELS = ("field", "slip_velocity", "slip_acceleration", "holding_force", "stick_limit",
            "normal_force", "gap", "surfaces", "surface_rates")  # fmt: skip


def _deep_jit(fn, numba, memo):
    """``fn`` compiled by numba, the functions it calls (globals, closure cells) too."""
    if fn in memo:
        return memo[fn]
    names = set(fn.__code__.co_names)
    g = dict(fn.__globals__)
    for name in names:
        if isinstance(g.get(name), types.FunctionType):
            g[name] = _deep_jit(g[name], numba, memo)
    closure = None
    if fn.__closure__:
        cells = []
        for cell in fn.__closure__:
            value = cell.cell_contents
            if isinstance(value, types.FunctionType):
                value = _deep_jit(value, numba, memo)
            cells.append(types.CellType(value))
        closure = tuple(cells)
    copy = types.FunctionType(fn.__code__, g, fn.__name__, fn.__defaults__, closure)
    memo[fn] = jitted = numba.njit(error_model="numpy")(copy)
    return jitted


def kernels_jitted(module_name: str, friction: str) -> dict:
    """The kernels of a module's law, compiled by numba (with what they call)."""
    numba = import_numba(True)
    module = importlib.import_module(module_name)
    kernels = module.kernels(friction)
    memo: dict = {}
    return {
        name: _deep_jit(getattr(kernels, name), numba, memo)
        for name in _KERNELS
        if name != "gap" or module.UNILATERAL
    }


def _source(module, friction: str, numba_version: str) -> str:
    """The text of the module that numba compiles and caches on disk."""
    index = {name: i for i, name in enumerate(module.SURFACES)}
    constants = ("_NS", "_NX", "_NP", "_A", "_B", "_C", "_E3", "_E5", "_D", "NODES", "DEPTH")
    lines = [
        f"# Written by beltmdsm/oscillator/_compiled.py (numba {numba_version}); do not edit.",
        "import math",
        "import numba",
        "import numpy as np",
        "from beltmdsm.integrate import _roots",
        f"from beltmdsm.oscillator._compiled import {', '.join(constants)}",
        "from beltmdsm.oscillator._compiled import STATUS_END, STATUS_EVENT, STATUS_STEP_TOO_SMALL",
        "from beltmdsm.oscillator._compiled import kernels_jitted",
        "converged = numba.njit(_roots.converged)",
        "secant = numba.njit(_roots.secant)",
        "illinois = numba.njit(_roots.illinois)",
        "from beltmdsm.oscillator import _dips",
        "bernstein = numba.njit(_dips.bernstein)",
        "error = numba.njit(_dips.error)",
        "split = numba.njit(_dips.split)",
        "lowest = numba.njit(_dips.lowest)",
        f"_K = kernels_jitted({module.__name__!r}, {friction!r})",
        f"UNILATERAL = {bool(module.UNILATERAL)}",
        f"I_FORWARD, I_BACK, I_GAP = {index['stick_forward']}, {index['stick_back']}, "
        f"{index.get('gap', -1)}",
    ]
    lines += [f"{name} = _K[{name!r}]" for name in _KERNELS if name != "gap" or module.UNILATERAL]
    if not module.UNILATERAL:
        lines.append("gap = None")
    for name in _FUNCTIONS:
        cache = "cache=True, " if name == "advance" else ""
        source = inspect.getsource(globals()[name]).rstrip()
        lines += ["", "", f'@numba.njit({cache}error_model="numpy")', source]
    return "\n".join(lines) + "\n"


def _load(module, friction: str, numba_version: str):
    """The compiled `advance`, from a module file in the private cache folder (numba
    caches it on disk beside it), or compiled in memory where the model's module is
    not importable by its name (a module made at run time)."""
    text = _source(module, friction, numba_version)
    files = [__file__, _roots.__file__, _dips.__file__]
    if getattr(module, "__file__", None):
        files.append(module.__file__)
    stem = f"beltmdsm_model_{module.NAME}_{friction}_" + digest(numba_version, *files)
    try:
        importable = importlib.import_module(module.__name__) is module
    except ImportError:
        importable = False
    try:
        folder = Path(user_cache("compiled")) if importable else None
    except OSError:
        folder = None
    if folder is None:
        entry = types.ModuleType(stem)
        exec(compile(text.replace("cache=True, ", ""), f"<{stem}>", "exec"), vars(entry))  # noqa: S102
        return entry.advance
    path = folder / f"{stem}.py"
    if not path.exists() or path.read_text() != text:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{stem}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "w") as fh:
                fh.write(text)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.remove(tmp)
    spec = importlib.util.spec_from_file_location(stem, path)
    entry = importlib.util.module_from_spec(spec)
    sys.modules[stem] = entry
    spec.loader.exec_module(entry)
    return entry.advance


def _make(module_name: str, friction: str, numba_version: str):
    """The dispatcher of a module's law (in this process or `_background`'s child)."""
    return _load(importlib.import_module(module_name), friction, numba_version)


@functools.cache
def _lazy(module, friction: str, foreground: bool) -> Lazy:
    version = numba_version()
    files = [__file__, _roots.__file__, _dips.__file__, module.__file__]
    stem = f"beltmdsm_model_{module.NAME}_{friction}_" + digest(version, *files)
    return Lazy((_make, (module.__name__, friction, version)), stem, None, foreground)


def _types(m: int) -> tuple:
    """Arguments of `advance`'s types, for a state of ``m``."""
    return (np.zeros(1), -1, 1, 0.0, np.zeros(m), 1.0, 0.1, 1e-10, 1e-10, 0.0, 0.0, 0,
            np.empty(0), np.empty((0, m)))  # fmt: skip


def compiled(module, friction: str, foreground: bool = False):
    """The compiled `advance` of a model module's law, or None: numba not installed, the
    module not importable by its name (made at run time), not ``foreground`` and not a
    module of the package (``beltmdsm.generated.models``), the kernels not compilable
    (said once), or, not ``foreground``, while `beltmdsm.integrate._background`'s child
    compiles it (the first run of a new model: plain Python meanwhile, the same method)."""
    if not numba_installed() or not getattr(module, "__file__", None):
        return None
    if not foreground and not module.__name__.startswith("beltmdsm."):
        # the child that compiles in the background imports the package's modules
        # only: a module of the caller's (a model typed by hand) is compiled when asked
        return None
    try:
        if importlib.import_module(module.__name__) is not module:
            return None
    except ImportError:
        return None
    lazy = _lazy(module, friction, foreground)
    try:
        return lazy.compiled(_types(len(module.STATES)))
    except Exception as err:  # noqa: BLE001 (numba's typing errors have no common base)
        _refused(module, friction, err)
        return None


@functools.cache
def _refused(module, friction, err) -> None:
    warnings.warn(
        f"model {module.NAME!r}, friction={friction!r}: numba cannot compile its kernels "
        f"({type(err).__name__}); its runs take plain Python",
        CompileWarning,
        stacklevel=4,
    )
