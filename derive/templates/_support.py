"""Runtime support shared by the generated modules: argument checks and array shaping.

Copied verbatim into ``generated/_support.py`` by ``python -m derive``; edit the
template in ``derive/templates/`` and regenerate. Plain numpy and mpmath: importing
it never imports SymPy.
"""
import math

import mpmath
import numpy

from .parameters import DOMAINS, KNOWN

# Each domain is a test of the smallest value; together with ``largest < inf`` it
# checks an array in two reductions and no temporary array, and NaN fails both
# (comparisons with NaN are False).
_DOMAIN_TEST = {
    "positive": (lambda lo: lo > 0, "> 0"),
    "nonnegative": (lambda lo: lo >= 0, ">= 0"),
    "real": (lambda lo: lo > -math.inf, "real"),
}


def _reject_unknown(function, extra):
    unknown = sorted(set(extra) - KNOWN)
    if unknown:
        raise TypeError(f"{function}() got unexpected keyword argument(s) "
                        f"{', '.join(map(repr, unknown))}; known parameters: "
                        f"{', '.join(sorted(KNOWN))}")


def extras(function, extra):
    """Check the parameters a function does not use; return them as arrays.

    A single dict of parameters serves every generated function: known parameters
    that a function does not use are accepted, checked like the others (a bad
    value is an error wherever it is passed) and take part in broadcasting, so
    a grid of any parameter gives outputs of the grid's shape. ``None`` (an
    optional parameter left at its default) is skipped.

    Raises
    ------
    TypeError
        For a keyword that is not a model parameter.
    """
    _reject_unknown(function, extra)
    return [param(function, k, v) for k, v in extra.items() if v is not None]


def mp_extras(function, extra):
    """`extras` for the mpmath variants (checks only)."""
    _reject_unknown(function, extra)
    for k, v in extra.items():
        if v is not None:
            mp_param(function, k, v)


def _fail(function, name, domain, why):
    return ValueError(f"{function}(): parameter {name!r} must be {why}"
                      + (f" ({domain})" if domain else ""))


def param(function, name, value, domain=None, why=None):
    """``value`` as a float array, checked against ``domain``.

    Parameters and states are finite physical numbers: an infinite input is
    refused like NaN (outputs may still be infinite, e.g. the slope of the
    effective friction at ``Vb = Vhat``).

    Raises
    ------
    ValueError
        Naming the parameter, if any element is NaN, infinite or outside the domain.
    """
    domain = domain or DOMAINS[name]
    x = numpy.asarray(value, dtype=float)
    test, text = _DOMAIN_TEST[domain]
    if x.size and not (test(x.min()) and x.max() < math.inf):
        # Tell the reasons apart only on failure, so valid input costs two reductions.
        if numpy.isnan(x).any():
            raise _fail(function, name, None, "a number, not NaN")
        if numpy.isinf(x).any():
            raise _fail(function, name, None, "finite, not inf")
        raise _fail(function, name, why, text)
    return x


def mp_param(function, name, value, domain=None, why=None):
    """`param` for the mpmath variants: a scalar ``mpf``."""
    domain = domain or DOMAINS[name]
    x = mpmath.mpf(value)
    if mpmath.isnan(x):
        raise _fail(function, name, None, "a number, not NaN")
    if mpmath.isinf(x):
        raise _fail(function, name, None, "finite, not inf")
    test, text = _DOMAIN_TEST[domain]
    if not test(x):
        raise _fail(function, name, why, text)
    return x


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
    return numpy.stack([numpy.stack([full(shape, v) for v in row], axis=-1)
                        for row in rows], axis=-2)


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
    half_p, q, disc = numpy.broadcast_arrays(*(numpy.asarray(a, float)
                                               for a in (half_p, q, disc)))
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
    if disc >= 0:
        big = -(half_p + (1 if half_p >= 0 else -1) * mpmath.sqrt(disc))
        return mpmath.mpc(big), mpmath.mpc(q / big if big != 0 else 0)
    root = mpmath.sqrt(-disc)
    return mpmath.mpc(-half_p, root), mpmath.mpc(-half_p, -root)


def quadratic_growth(half_p, q, disc):
    """Largest real part of the roots of ``lambda^2 + 2 half_p lambda + q``.

    The root nearer zero is taken as ``q / r1`` (see `quadratic_roots`) when
    ``half_p > 0``, so a slowly decaying mode next to a fast one keeps its digits.
    ``half_p = -inf`` (an infinite negative damping) gives ``+inf``.
    """
    shape = numpy.broadcast_shapes(*(numpy.shape(a) for a in (half_p, q, disc)))
    half_p, q, disc = numpy.broadcast_arrays(*(numpy.atleast_1d(numpy.asarray(a, float))
                                               for a in (half_p, q, disc)))
    # In place where possible: on large grids this function is memory-bound.
    root = numpy.sqrt(numpy.abs(disc))
    out = root - half_p                                  # the root for half_p <= 0
    with numpy.errstate(divide="ignore", invalid="ignore"):
        far = numpy.add(half_p, root, out=root)          # |larger root|, reusing root
        numpy.divide(q, numpy.negative(far, out=far), out=out, where=half_p > 0)
    numpy.negative(half_p, out=out, where=disc < 0)      # complex pair: real part
    return out.reshape(shape)


def mp_quadratic_growth(half_p, q, disc):
    """`quadratic_growth` for the mpmath variants."""
    if disc < 0:
        return -half_p
    root = mpmath.sqrt(disc)
    return q / -(half_p + root) if half_p > 0 else -half_p + root


def resolve_vhat(function, params, vhat_model, vhat, contact):
    """``params`` with ``Vhat`` filled in from ``vhat_model`` unless it was given.

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
    model = "tangential" if vhat_model is None else vhat_model
    value = vhat(model=model, contact=contact, **params)
    # Without this the check of Vhat would blame a parameter the caller never gave
    # (the mpmath variants pass an mpf, hence the conversion).
    if not numpy.isfinite(numpy.asarray(value, dtype=float)).all():
        raise ValueError(f"{function}(): Vhat of vhat_model={model!r} is not finite at "
                         "these parameters (an undamped resonance of the linear "
                         "response); give a finite Vhat")
    return {**params, "Vhat": value}


#: Points per block in `blockwise`: a chain of array operations on 2**15 float64
#: values keeps its temporaries (256 KiB each) in cache.
BLOCK = 2**15


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
    flat = [a.reshape(()) if a.size == 1 else numpy.broadcast_to(a, shape).reshape(-1)
            for a in arrays]
    out = None
    for start in range(0, size, block):
        part = numpy.asarray(kernel(*(a if a.ndim == 0 else a[start:start + block]
                                      for a in flat)))
        if out is None:
            dtype = bool if part.dtype == bool else numpy.result_type(part.dtype, float)
            out = numpy.empty(size, dtype)
        out[start:start + block] = part
    return out.reshape(shape)


_BACKENDS = ("numpy", "numba")
_COMPILED = {}
_numba = None


def _import_numba(required):
    global _numba
    if _numba is None:
        try:
            import numba
        except ImportError:
            numba = False
        _numba = numba
    if _numba is False and required:
        raise ImportError("backend='numba' needs numba: pip install 'beltmdsm[fast]' "
                          "(or pip install numba)")
    return _numba or None


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
    if backend is not None and backend not in _BACKENDS:
        raise ValueError(f"backend must be one of {', '.join(map(repr, _BACKENDS))} "
                         f"or None; got {backend!r}")
    if backend == "numpy" or _import_numba(backend == "numba") is None:
        return None
    ufunc = _COMPILED.get(kernel)
    if ufunc is None:
        signature = f"{result}({', '.join(['float64'] * kernel.__code__.co_argcount)})"
        ufunc = _numba.vectorize([signature], cache=True)(kernel)
        _COMPILED[kernel] = ufunc
    return ufunc


def choose(function, table, **options):
    """The implementation in ``table`` (keyed by tuples of option values) for ``options``.

    Raises
    ------
    ValueError
        Naming the option, if a value is not one of its choices.
    """
    for position, (option, value) in enumerate(options.items()):
        choices = list(dict.fromkeys(key[position] for key in table))
        if isinstance(value, bool) or value not in choices:
            raise ValueError(f"{function}(): {option} must be one of "
                             f"{', '.join(map(repr, choices))}; got {value!r}")
    return table[tuple(options.values())]


__all__ = ["extras", "mp_extras", "param", "mp_param", "shape_of", "full", "tuple_of",
           "matrix", "vector", "quadratic_roots", "mp_quadratic_roots", "quadratic_growth",
           "mp_quadratic_growth", "blockwise", "compiled", "resolve_vhat", "choose"]
