"""The quadrature of the generated functions whose closed form SymPy does not find.

`quad` integrates a generated integrand on composite Gauss-Legendre panels
(`QUAD_NODES`, `QUAD_WEIGHTS`; the scalar kernels loop over the same rule inline).
Reached through `beltmdsm.generated._support`.

Copied verbatim into ``generated/_quadrature.py`` by ``python -m derive``; edit the
template in ``derive/codegen/templates/`` and regenerate.
"""

import math

import numpy

#: Points per block (`quad`, `beltmdsm.generated._support.blockwise`): a chain of array
#: operations on 2**15 float64 values keeps its temporaries (256 KiB each) in cache.
BLOCK = 2**15


def _graded_gauss_legendre(nodes, levels):
    """Composite Gauss-Legendre on [-1, 1], panels halving towards both ends.

    Panel edges at ``+-(1 - 2^-j)``, ``j = 1..levels``, and 0: a function with a
    boundary layer at an end (the decay of ``exp(-|Vr|/v_s)`` from a reversal of the
    friction, where a fast average splits its period) is resolved down to a width of
    ``2^-levels`` of the interval, and the inner panels see a smooth function.
    """
    x, w = numpy.polynomial.legendre.leggauss(nodes)
    half = numpy.concatenate([[0.0], 1 - 2.0 ** -numpy.arange(1, levels + 1), [1.0]])
    edges = numpy.unique(numpy.concatenate([-half, half]))
    lo, hi = edges[:-1, None], edges[1:, None]
    return (lo + hi) / 2 + (hi - lo) / 2 * x, (hi - lo) / 2 * w


#: The quadrature rule of `quad` (and of the scalar kernels' inline loop): nodes and
#: weights on [-1, 1], 28 panels of 10 Gauss-Legendre nodes (`_graded_gauss_legendre`).
#: Against mpmath it integrates the averages of Stribeck's law to about 1e-14
#: relative for V / v_s up to 1e3 (tests/generated/test_friction.py has the error model).
_QUAD_PANELS = _graded_gauss_legendre(10, 14)
QUAD_NODES = _QUAD_PANELS[0].ravel()
QUAD_WEIGHTS = _QUAD_PANELS[1].ravel()


def quad(integrand, lo, hi, *args):
    """``integral of integrand(x, *args) dx`` from ``lo`` to ``hi``, broadcast over arrays.

    The rule of `QUAD_NODES` one panel at a time (memory of ten evaluations of the
    integrand), nodes on a leading axis; ``args`` are the integrand's other inputs,
    which set the broadcast shape with the limits. Where all the nodes at all the
    points fit in a `BLOCK`, in one evaluation: a scalar quadrature (a root-finder's
    iterate) then costs one call of the integrand instead of one a panel, 8 times
    less time.
    """
    lo, hi = numpy.asarray(lo, dtype=float), numpy.asarray(hi, dtype=float)
    shape = numpy.broadcast_shapes(lo.shape, hi.shape, *(numpy.shape(a) for a in args))
    mid, half = (lo + hi) / 2, (hi - lo) / 2
    if math.prod(shape) * QUAD_NODES.size <= BLOCK:
        x = QUAD_NODES.reshape((-1,) + (1,) * len(shape))
        values = numpy.broadcast_to(integrand(mid + half * x, *args), x.shape[:1] + shape)
        return half * numpy.tensordot(QUAD_WEIGHTS, values, axes=1)
    total = numpy.zeros(shape)
    for x, w in zip(*_QUAD_PANELS):
        x = x.reshape((-1,) + (1,) * len(shape))
        values = numpy.broadcast_to(integrand(mid + half * x, *args), x.shape[:1] + shape)
        total = total + numpy.tensordot(w, values, axes=1)
    return half * total
