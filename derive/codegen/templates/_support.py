"""Runtime support shared by the generated modules: the one module their code calls.

Array shaping of the results, the variant tables and their dispatch (`choose`), the
accelerated backends (`blockwise`, numba's `compiled` ufuncs and `jit` kernels) and
the bound kernels (`bind`), and the failures of the generated modules
(`BeltmdsmError`, `Unsupported`, imported from `beltmdsm.errors`, where they are
defined). The argument checks (`beltmdsm.generated._checks`),
the quadrature (`beltmdsm.generated._quadrature`) and the cache folders
(`beltmdsm.generated._cache`) are modules of their own, reached through this one.

Copied verbatim into ``generated/_support.py`` by ``python -m derive``; edit the
template in ``derive/codegen/templates/`` and regenerate. Plain numpy and mpmath: importing
it never imports SymPy, nor mpmath (the mpmath variants in ``generated/mp/`` import it;
the helpers for them below import it when called), so that a program on the numpy
functions starts without it.
"""

import math

import numpy

# the root failures, defined in beltmdsm/errors.py (standard library only, the package's
# lowest layer: tests/test_layers.py) and re-exported here, so that a generated
# function's refusal and the runtime's are one class
from beltmdsm.errors import BeltmdsmError, Unsupported

from ._cache import CACHE_NAME, CacheFolderWarning, cache_root, user_cache
from ._checks import (
    CHECKED,
    _reject_unknown,
    _scalar_arguments,
    arguments,
    mp_arguments,
    mp_param,
    param,
)
from ._quadrature import BLOCK, QUAD_NODES, QUAD_WEIGHTS, quad


def shape_of(*arrays):
    """The broadcast shape of all inputs."""
    return numpy.broadcast_shapes(*(numpy.shape(a) for a in arrays))


def full(shape, value):
    """``value`` broadcast to ``shape`` as a fresh float (complex, bool) array.

    For ``shape == ()`` a numpy scalar, as numpy's ufuncs return for scalar inputs.
    """
    value = numpy.asarray(value)
    if value.dtype == bool:
        dtype = bool
    else:
        dtype = complex if numpy.iscomplexobj(value) else float
    if value.shape == shape and value.dtype == dtype:
        return value[()]
    return numpy.broadcast_to(value, shape).astype(dtype)[()]


def tuple_of(shape, *values):
    return tuple(full(shape, v) for v in values)


def matrix(shape, rows):
    """Stack a nested list of entries into an array of shape ``shape + (n, m)``."""
    return numpy.stack(
        [numpy.stack([full(shape, v) for v in row], axis=-1) for row in rows], axis=-2
    )


def vector(shape, values):
    return numpy.stack([full(shape, v) for v in values], axis=-1)


def quadratic_roots(half_p, q, disc):
    """Both roots of ``lambda^2 + 2 half_p lambda + q`` without cancellation.

    ``disc = half_p^2 - q`` is passed in from a factored closed form, so a double
    root (``disc`` near 0) loses no digits here. Real roots use the
    cancellation-free pair ``r1 = -(half_p + sign(half_p) sqrt(disc))``,
    ``r2 = q / r1``.

    Returns
    -------
    (r1, r2) : complex arrays; for complex roots ``r1`` has the positive imaginary part.
    """
    half_p, q, disc = numpy.broadcast_arrays(*(numpy.asarray(a, float) for a in (half_p, q, disc)))
    root = numpy.sqrt(numpy.abs(disc))
    real = disc >= 0
    big = -(half_p + numpy.copysign(root, half_p))
    with numpy.errstate(divide="ignore", invalid="ignore"):
        small = numpy.where(big != 0, q / big, 0.0)
    r1 = numpy.where(real, big, -half_p + 1j * root)
    r2 = numpy.where(real, small, -half_p - 1j * root)
    return r1.astype(complex), r2.astype(complex)


def mp_quadratic_roots(half_p, q, disc):
    """`quadratic_roots` for the mpmath variants."""
    import mpmath

    if disc >= 0:
        big = -(half_p + (1 if half_p >= 0 else -1) * mpmath.sqrt(disc))
        return mpmath.mpc(big), mpmath.mpc(q / big if big != 0 else 0)
    root = mpmath.sqrt(-disc)
    return mpmath.mpc(-half_p, root), mpmath.mpc(-half_p, -root)


def resolve_vhat(function, params, vhat_model, vhat, **laws):
    """``params`` with ``Vhat`` filled in from ``vhat_model`` unless it was given.

    ``laws`` are the calling function's law options (``friction=``, ``contact=``):
    ``Vhat`` is the linear response of the same model.

    Raises
    ------
    ValueError
        If both ``Vhat`` and ``vhat_model`` are given, or if the computed ``Vhat``
        is not finite (an undamped resonance of the linear response, e.g.
        ``beta1 = 0`` and ``Omega_t = omega1``).
    """
    if params.get("Vhat") is not None:
        if vhat_model is not None:
            raise ValueError(f"{function}(): give either Vhat or vhat_model, not both")
        return params
    # a bad keyword or value is the caller's to report, not the vhat() it reaches first
    _reject_unknown(function, params)
    model = "tangential" if vhat_model is None else vhat_model
    try:
        value = vhat(model=model, **laws, **params)
    except ValueError as err:
        prefix = f"{vhat.__name__}(): "
        text = str(err)
        raise ValueError(
            f"{function}(): {text[len(prefix) :]}" if text.startswith(prefix) else text
        ) from None
    # Without this the check of Vhat would blame a parameter the caller never gave
    # (the mpmath variants pass an mpf, hence the conversion).
    if not numpy.isfinite(numpy.asarray(value, dtype=float)).all():
        raise ValueError(
            f"{function}(): Vhat of vhat_model={model!r} is not finite at "
            "these parameters (an undamped resonance of the linear "
            "response); give a finite Vhat"
        )
    return {**params, "Vhat": value}


def blockwise(kernel, *args, block=BLOCK):
    """``kernel(*args)`` for array arguments, evaluated on blocks of ``block`` points.

    A generated numpy kernel is a chain of array operations, each allocating a
    temporary as large as the grid. On a large grid those fall out of cache and
    are fresh allocations (page faults); on blocks the numpy ``growth_rate`` of
    ``benchmarks/bench_stability.py`` took 10-40% less time on 10^6 points. Inputs
    broadcast as in numpy; a broadcast (not full-size) input is expanded once.
    Grids of at most ``2 * block`` points are evaluated in one call.

    Returns
    -------
    ndarray of the broadcast shape (float, complex or bool, as the kernel's).
    """
    arrays = [numpy.asarray(a) for a in args]
    shape = numpy.broadcast_shapes(*(a.shape for a in arrays))
    size = math.prod(shape)
    if size <= 2 * block:
        return kernel(*arrays)
    flat = [
        a.reshape(()) if a.size == 1 else numpy.broadcast_to(a, shape).reshape(-1) for a in arrays
    ]
    out = None
    for start in range(0, size, block):
        part = numpy.asarray(
            kernel(*(a if a.ndim == 0 else a[start : start + block] for a in flat))
        )
        if out is None:
            dtype = bool if part.dtype == bool else numpy.result_type(part.dtype, float)
            out = numpy.empty(size, dtype)
        out[start : start + block] = part
    return out.reshape(shape)


_BACKENDS = ("numpy", "numba")
_COMPILED = {}
_numba = None
#: Whether numba may cache compiled code on disk (`import_numba`): False where no
#: private cache folder can be made; the code is then compiled in every process.
DISK_CACHE = True


def import_numba(required):
    """numba, or None where it is not installed (ImportError if ``required``).

    Its on-disk cache (``cache=True``) goes to `user_cache` ``("numba")`` unless
    ``$NUMBA_CACHE_DIR`` names one: by default numba writes next to the module it
    compiles, which for an installed package is inside site-packages. Where no
    private folder can be made, numba caches nothing (`DISK_CACHE` False), said once
    (a `CacheFolderWarning`).
    """
    global _numba, DISK_CACHE
    if _numba is None:
        try:
            import numba
        except ImportError:
            numba = False
        else:
            if not numba.config.CACHE_DIR:
                try:
                    numba.config.CACHE_DIR = user_cache("numba")
                except OSError as err:
                    import warnings

                    DISK_CACHE = False
                    warnings.warn(
                        f"{err}; compiled code is not cached (compiled again in every run)",
                        CacheFolderWarning,
                        stacklevel=2,
                    )
        _numba = numba
    if _numba is False and required:
        raise ImportError(
            "backend='numba' needs numba: pip install 'beltmdsm[fast]' (or pip install numba)"
        )
    return _numba or None


def _check_backend(backend, choices):
    if backend is not None and backend not in choices:
        raise ValueError(
            f"backend must be one of {', '.join(map(repr, choices))} or None; got {backend!r}"
        )


def compiled(kernel, result, backend):
    """The scalar ``kernel`` as a numba ufunc, or ``None`` for the numpy path.

    Parameters
    ----------
    kernel : function
        A generated scalar kernel (plain Python on ``math``), float64 arguments.
    result : {"float64", "boolean"}
        Its result type.
    backend : {"numpy", "numba", None}
        ``None`` picks numba when it can be imported.

    The ufunc is compiled on first use and cached on disk by numba
    (``cache=True``), then kept here for the session.

    Raises
    ------
    ValueError
        For an unknown backend.
    ImportError
        For ``backend="numba"`` without numba installed.
    """
    _check_backend(backend, _BACKENDS)
    if backend == "numpy" or import_numba(backend == "numba") is None:
        return None
    ufunc = _COMPILED.get(kernel)
    if ufunc is None:
        signature = f"{result}({', '.join(['float64'] * kernel.__code__.co_argcount)})"
        ufunc = _numba.vectorize([signature], cache=DISK_CACHE)(kernel)
        _COMPILED[kernel] = ufunc
    return ufunc


def evaluate(variant, result, backend, *values):
    """An accelerated function's points: its numba ufunc, or its numpy kernel on blocks.

    ``values`` are the checked parameters; the hoisted roots of ``variant.prep`` are
    appended (both kernels take them as inputs).
    """
    roots = variant.prep(*values) if variant.prep is not None else ()
    kernel = compiled(variant.scalar, result, backend)
    if kernel is None:
        return blockwise(variant.impl, *values, *roots)
    # The compiled kernel may evaluate both sides of a conditional expression (a
    # select), like numpy does for a Piecewise: the side it discards may divide by 0.
    with numpy.errstate(divide="ignore", invalid="ignore"):
        return kernel(*values, *roots)


_JITTED = {}


def jit(kernel):
    """``numba.njit`` of a generated scalar kernel, compiled once per session.

    Cached on disk; floating-point errors follow numpy (a division by zero gives
    inf or NaN, as in the numpy implementation, not an exception).
    """
    fast = _JITTED.get(kernel)
    if fast is None:
        numba = import_numba(True)
        fast = _JITTED[kernel] = numba.njit(cache=DISK_CACHE, error_model="numpy")(kernel)
    return fast


class Bound:
    """A generated scalar kernel with its parameters checked and bound.

    ``bound(*state)`` is ``bound.kernel(*state, *bound.args)``. An integrator that
    compiles its own loop (numba) takes ``kernel`` and ``args`` and calls the kernel
    itself; ``params`` maps the parameter names to the bound values.
    ``bound.array(*state)`` evaluates the unchecked numpy implementation on arrays
    of states (the layout of the public function's result).
    """

    __slots__ = ("name", "kernel", "args", "params", "backend", "_impl", "_values")

    def __init__(self, name, kernel, args, params, backend, impl, values):
        self.name, self.kernel, self.args = name, kernel, args
        self.params, self.backend = params, backend
        self._impl, self._values = impl, values

    def __call__(self, *state):
        try:
            return self.kernel(*state, *self.args)
        except (ZeroDivisionError, ValueError, OverflowError):
            # plain Python raises where numpy (and the numba kernel, compiled with
            # numpy's error model) gives inf or NaN: at a singular point (undamped
            # resonance, a grazing switch) answer as the public function does
            out = numpy.asarray(self.array(*state), dtype=float).ravel()
            return float(out[0]) if out.size == 1 else tuple(float(v) for v in out)

    def array(self, *state):
        state = [numpy.asarray(x, dtype=float) for x in state]
        return self._impl(shape_of(*state), *state, *self._values)

    def __repr__(self):
        return f"<bound {self.name} ({self.backend})>"


_BIND_BACKENDS = ("python", "numba")


def bind(function, variant, params, backend):
    """`Bound` kernel of ``variant`` with ``params`` checked once (scalars only).

    Raises
    ------
    ValueError
        Naming the parameter, for a value that is not a finite scalar in its domain,
        or for an unknown backend.
    TypeError
        For an unknown keyword or a missing parameter.
    ImportError
        For ``backend="numba"`` without numba.
    """
    _check_backend(backend, _BIND_BACKENDS)
    name = f"bind_{function}"
    values = _scalar_arguments(name, variant.names, params)
    roots = tuple(float(r) for r in variant.prep(*values)) if variant.prep is not None else ()
    use_numba = backend == "numba" or (backend is None and import_numba(False) is not None)
    kernel = jit(variant.scalar) if use_numba else variant.scalar
    # the array implementation keeps numpy's floating-point semantics (inf, not an
    # exception, for a power of zero) with numpy scalars
    return Bound(
        function,
        kernel,
        values + roots,
        dict(zip(variant.names, values)),
        "numba" if use_numba else "python",
        variant.impl,
        tuple(numpy.float64(v) for v in values),
    )


class NoVariant:
    """A table entry for option values without a variant: the function raises
    `Unsupported` with ``reason`` (not `beltmdsm.errors.Refused`, a request refused by
    the runtime)."""

    __slots__ = ("reason",)

    def __init__(self, reason):
        self.reason = reason


class Variant:
    """One option variant of a generated function.

    ``impl`` is the unchecked numpy (or mpmath) implementation, ``names`` the
    parameters it takes after the positional arguments; ``scalar`` its scalar
    ``math`` twin (bound and accelerated functions) and ``prep`` the function of
    the parameters that returns the roots the scalar kernel takes (or None).
    """

    __slots__ = ("impl", "names", "scalar", "prep")

    def __init__(self, impl, names, scalar=None, prep=None):
        self.impl, self.names, self.scalar, self.prep = impl, names, scalar, prep


def choose(function, table, **options):
    """The implementation in ``table`` (keyed by tuples of option values) for ``options``.

    Raises
    ------
    ValueError
        Naming the option, if a value is not one of its choices, or naming the
        combination, if the table has no variant for it (e.g. a switch no run takes).
    Unsupported
        For a combination the function refuses, with the reason.
    """
    key = tuple(options.values())
    try:  # the common case, a known combination, without building the lists of choices
        known = key in table and not any(isinstance(v, bool) for v in key)
    except TypeError:  # an unhashable value
        known = False
    if not known:
        for position, (option, value) in enumerate(options.items()):
            choices = list(dict.fromkeys(k[position] for k in table))
            if isinstance(value, bool) or value not in choices:
                raise ValueError(
                    f"{function}(): {option} must be one of "
                    f"{', '.join(map(repr, choices))}; got {value!r}"
                )
        given = ", ".join(f"{k}={v!r}" for k, v in options.items())
        raise ValueError(f"{function}(): no variant for {given}")
    entry = table[key]
    if isinstance(entry, NoVariant):
        given = ", ".join(f"{k}={v!r}" for k, v in options.items())
        raise Unsupported(f"{function}(): not available for {given}: {entry.reason}")
    return entry


__all__ = [
    "CHECKED",
    "arguments",
    "mp_arguments",
    "param",
    "mp_param",
    "shape_of",
    "full",
    "tuple_of",
    "matrix",
    "vector",
    "quadratic_roots",
    "mp_quadratic_roots",
    "blockwise",
    "compiled",
    "evaluate",
    "jit",
    "bind",
    "Bound",
    "Variant",
    "resolve_vhat",
    "choose",
    "quad",
    "QUAD_NODES",
    "QUAD_WEIGHTS",
    "BeltmdsmError",
    "Unsupported",
    "NoVariant",
    "cache_root",
    "user_cache",
    "CacheFolderWarning",
    "CACHE_NAME",
    "import_numba",
]
