"""The integrators bound to their generated kernels: plain Python, or compiled by numba.

`beltmdsm.integrate._dop853` (one mode, stopping at switches) and
`beltmdsm.integrate._switch_scan` (the scan of the closed-form tangential motion) call the
generated scalar kernels (`beltmdsm.generated.hybrid`, `beltmdsm.generated.oscillator`)
through module globals
(``_field_kernel``, ``_surface_kernel``, ...). This module binds them:

* in plain Python, as copies of the integrators' functions whose globals hold the
  kernels (`advance`, `scan` with ``backend="python"``);
* compiled, as a small module per integrator and kernel set, written to a cache
  folder: the integrators' source with the kernels as numba-compiled globals, cached
  on disk by numba, in a private folder (`beltmdsm.generated._support.user_cache`); where none
  can be made, compiled in memory, every run (said once). Made at the first call
  (`beltmdsm.integrate._background.Lazy`): where numba's cache does not hold it yet,
  the plain-Python copy runs (the same numbers) while a child process compiles it,
  unless ``backend="numba"`` asks for the compiled code at once.

Two properties of numba's disk cache shape the compiled form: a signature that holds
a kernel passed as an argument (a dispatcher object) cannot be saved in a process
where an earlier one's dispatcher no longer exists, and a cached function is
invalidated by a change of its own source file only, not of what it calls. So the
compiled functions take numbers, tuples and arrays only, and the module's file name
holds a hash of every source it depends on (the generated kernels, the integrators,
this file, numba's version): regenerating a kernel or changing an integrator compiles
afresh, and nothing stale is served.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import inspect
import os
import sys
import tempfile
import types
import warnings
from pathlib import Path

from beltmdsm.generated import _support, hybrid, oscillator
from beltmdsm.generated._support import CacheFolderWarning, import_numba, user_cache

from ..model import Backend, Model
from . import _background, _dop853, _roots, _switch_scan

__all__ = ["advance", "scan"]

#: The modules whose sources key the compiled modules (read from their files, wherever
#: the package is: beltmdsm.generated sits beside beltmdsm/ in a source checkout).
_SOURCES = (hybrid, oscillator, _support, _dop853, _switch_scan, _roots)
_FIELDS = {"vector_field": hybrid.bind_vector_field, "response_field": hybrid.bind_response_field}
#: The integrators: their module, their functions (the entry point last), their kernels,
#: and the functions of other modules they call (compiled beside them).
_ADVANCE = (
    _dop853,
    (
        "_rhs",
        "_dense",
        "_initial_step",
        "_inside",
        "_rates",
        "_surface_at",
        "_refine",
        "_dip",
        "_first_crossing",
        "advance",
    ),
    ("_field_kernel", "_surface_kernel", "_rate_kernel"),
    (_roots.converged, _roots.secant, _roots.illinois, _roots.golden),
)
_SCAN = (
    _switch_scan,
    ("tangential_state", "_normal_at", "_inside_at", "_refine", "_dip", "scan"),
    ("_state_kernel", "_exc_kernel", "_surface_kernel", "_rate_kernel"),
    (_dop853._dense, _roots.converged, _roots.secant, _roots.illinois, _roots.golden),
)


def _kernel(bind, model, **laws):
    """The plain-Python scalar kernel that the generated ``bind`` chooses for the model's
    laws (the variant of its options), or for ``laws`` in place of some of them (those
    that ``bind`` declares): bound once per laws, since the kernel does not depend on
    the parameters' values (a period map is built at every value of a band)."""
    key = (bind, tuple({**model.options, **laws}.items()))
    kernel = _KERNELS.get(key)
    if kernel is None:
        arguments = model.arguments(bind)
        arguments.update((k, v) for k, v in laws.items() if k in arguments)
        kernel = _KERNELS[key] = bind(backend="python", **arguments).kernel
    return kernel


#: `_kernel` by the bind function and the model's laws.
_KERNELS: dict = {}


def advance(field: str, model: Model, backend: Backend | None = None, **laws: str):
    """`beltmdsm.integrate._dop853.advance` on the ``field`` ("vector_field" or
    "response_field") of the model's laws: ``f(fa, sa, ra, mode, watch, dirs, t0, y0,
    t_end, h0, rtol, atol, max_step, max_steps)``.

    ``backend``: "python", "numba" or None (numba if installed). ``laws``: laws in place
    of the model's for the surfaces and their rates (``friction=``: the normal motion,
    `beltmdsm.integrate.normal.NORMAL_FRICTION`, watches surfaces that no friction law
    enters, so that one compiled integrator serves every friction law). The arguments
    ``sa`` and ``ra`` are then those of the kernels bound with these laws.
    """
    kernels = (
        _kernel(_FIELDS[field], model),
        _kernel(hybrid.bind_surfaces, model, **laws),
        _kernel(hybrid.bind_surface_rates, model, **laws),
    )
    return _bound(_ADVANCE, kernels, _name("advance", kernels), backend)


def scan(model: Model, backend: Backend | None = None):
    """`beltmdsm.integrate._switch_scan.scan` for the model's laws: ``f(mode, stick, sgn,
    watch, dirs, t0, tc, start, Vb, grid, on_grid, ts, hs, ys, Fs, state_a, exc_a, surf_a,
    rate_a)``."""
    kernels = (
        _kernel(oscillator.bind_tangential_state, model),
        _kernel(oscillator.bind_excitation_response, model),
        _kernel(hybrid.bind_surfaces, model),
        _kernel(hybrid.bind_surface_rates, model),
    )
    return _bound(_SCAN, kernels, _name("scan", kernels), backend)


def _name(which, kernels):
    """The name of a compiled integrator: its first kernel and a digest of them all. A
    name per kernel set, since the module of that name holds the kernels it compiles:
    two sets under one name rewrote each other's module, and numba then compiled it
    afresh (about 12 s) each time the other set came (the normal motion under two
    friction laws did, before the friction law was taken out of it)."""
    names = ",".join(k.__name__ for k in kernels)
    return f"{which}_{kernels[0].__name__}_{hashlib.sha256(names.encode()).hexdigest()[:8]}"


def _bound(integrator, kernels, name, backend):
    if backend == "numba":
        import_numba(True)
    elif backend == "python" or not _background.numba_installed():
        return _python(integrator, kernels)
    return _lazy(integrator, kernels, name, backend == "numba")


#: The integrators by name, for the child that compiles them (`beltmdsm.integrate._background`).
_INTEGRATORS = {"advance": _ADVANCE, "scan": _SCAN}


@functools.cache
def _lazy(integrator, kernels, name, foreground):
    """The compiled entry point, made at its first call (`_background.Lazy`): loaded from
    numba's cache, or run as plain Python while a child compiles it (``foreground``:
    compiled at once, as ``backend="numba"`` asks)."""
    which = next(k for k, v in _INTEGRATORS.items() if v is integrator)
    version = _background.numba_version()
    stem = f"beltmdsm_{name}_{_digest(version)}"
    spec = (_compiled_entry, (which, kernels, name, version))
    return _background.Lazy(spec, stem, _python(integrator, kernels), foreground)


def _compiled_entry(which, kernels, name, numba_version):
    """`_compiled` by the integrator's name (picklable: the child makes it so)."""
    return _compiled(_INTEGRATORS[which], kernels, name, numba_version)


@functools.cache
def _python(integrator, kernels):
    """Copies of the integrator's functions, with the kernels as their globals."""
    module, functions, globals_, _ = integrator
    namespace = dict(vars(module))
    namespace.update(zip(globals_, kernels))
    for fn in functions:
        original = getattr(module, fn)
        namespace[fn] = types.FunctionType(original.__code__, namespace, fn, original.__defaults__)
    return namespace[functions[-1]]


@functools.cache
def _digest(numba_version):
    files = (*_SOURCES, sys.modules[__name__], _background)
    return _background.digest(numba_version, *(module.__file__ for module in files))


def scalar_backend(backend: Backend | None) -> Backend:
    """The backend of a bound kernel that Python calls (`beltmdsm.generated._support.bind`):
    plain Python unless numba is asked for by name. From Python, a numba kernel's
    dispatch costs about what the Python evaluation does (4 against 6 us,
    `beltmdsm.integrate.switching`), and it would import numba (about a second) and
    compile or load the kernel (0.4 to 1.4 s each when the cache is cold)."""
    return "numba" if backend == "numba" else "python"


@functools.cache
def _compiled(integrator, kernels, name, numba_version):
    """The compiled entry point: a module written from the integrator's source."""
    module, functions, globals_, helpers = integrator
    constants = [
        n
        for n, v in vars(module).items()
        if not n.startswith("__")
        and n not in functions
        and n not in globals_
        and not callable(v)
        and not isinstance(v, types.ModuleType)
    ]
    lines = [
        f"# Written by beltmdsm/integrate/_compiled.py (numba {numba_version}); do not edit.",
        "import math",
        "import numba",
        "import numpy as np",
        f"from {module.__name__} import {', '.join(constants)}",
    ]
    # numba reads a global array at a run-time index with one load, a global tuple
    # through a switch over its entries: the Runge-Kutta tables, indexed in loops,
    # become arrays (the same numbers)
    lines += [f"{n} = np.array({n})" for n in constants if isinstance(vars(module)[n], tuple)]
    for helper in helpers:
        called = helper.__name__
        lines += [
            f"from {helper.__module__} import {called} as _{called}_python",
            f'{called} = numba.njit(error_model="numpy")(_{called}_python)',
        ]
    for glob, kernel in zip(globals_, kernels):
        lines += [
            f"from {kernel.__module__} import {kernel.__name__}",
            f'{glob} = numba.njit(error_model="numpy")({kernel.__name__})',
        ]
    for fn in functions:
        decorator = (
            '@numba.njit(cache=True, error_model="numpy")'
            if fn == functions[-1]
            else '@numba.njit(error_model="numpy")'
        )
        lines += ["", "", decorator, inspect.getsource(getattr(module, fn)).rstrip()]
    text = "\n".join(lines) + "\n"
    stem = f"beltmdsm_{name}_{_digest(numba_version)}"
    folder = _folder()
    if folder is None:
        # no private folder: compiled in memory, for this process only
        entry = types.ModuleType(stem)
        sys.modules[stem] = entry
        code = text.replace("numba.njit(cache=True,", "numba.njit(cache=False,")
        exec(compile(code, f"<{stem}>", "exec"), vars(entry))  # noqa: S102 (our own source)
        return getattr(entry, functions[-1])
    path = folder / f"{stem}.py"
    if not path.exists() or path.read_text() != text:
        # a unique temporary name per process and thread, renamed into place
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
    return getattr(entry, functions[-1])


@functools.cache
def _folder() -> Path | None:
    """The private folder of the compiled modules (`beltmdsm.generated._support.user_cache`),
    or None where none can be made: said once (a
    `beltmdsm.generated._support.CacheFolderWarning`, unless
    `beltmdsm.generated._support.import_numba` said it for numba's cache)."""
    try:
        return Path(user_cache("compiled"))
    except OSError as err:
        if not _support.DISK_CACHE:
            return None  # said once already, by import_numba
        warnings.warn(
            f"{err}; the compiled integrators are not cached (compiled again in every run)",
            CacheFolderWarning,
            stacklevel=4,
        )
        return None
