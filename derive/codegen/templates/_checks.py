"""The argument checks of the generated functions: parameters and states.

Every public generated function checks its arguments once (`arguments`, `param`;
`mp_arguments`, `mp_param` for the mpmath variants, `_scalar_arguments` for a bound
kernel): ``TypeError`` for an unknown keyword or a missing parameter, ``ValueError``
naming the parameter for NaN, inf or a value outside its domain. `CHECKED` lets a
caller pass what it checked already. Reached through `beltmdsm.generated._support`.

Copied verbatim into ``generated/_checks.py`` by ``python -m derive``; edit the
template in ``derive/codegen/templates/`` and regenerate.
"""

import math

import numpy

from .parameters import DEFAULT_FROM, DEFAULTS, DOMAIN_RULES, DOMAINS, KNOWN, within

# A domain (`within`) is a test of the smallest value; together with ``largest < inf``
# it checks an array in two reductions and no temporary array, and NaN fails both
# (comparisons with NaN are False).

#: The keyword under which a caller passes the parameters it has checked already: a
#: mapping of scalar values (``beltmdsm.model.Model.arguments`` passes its own). A
#: parameter whose value *is* that checked object is not checked again; any other
#: value (one the caller put in its place, an array of a grid) is. So a model checked
#: once is not checked at every call of a generated function.
CHECKED = "_checked"


def _reject_unknown(function, extra):
    unknown = sorted(set(extra) - KNOWN - {CHECKED})
    if unknown:
        raise TypeError(
            f"{function}() got unexpected keyword argument(s) "
            f"{', '.join(map(repr, unknown))}; known parameters: "
            f"{', '.join(sorted(KNOWN))}"
        )


def _missing(function, name):
    return TypeError(f"{function}() missing required parameter {name!r}")


def _lookup(function, name, params):
    """The value of parameter ``name``: given, else its default, else its source's."""
    value = params.get(name)
    if value is None:
        if name in DEFAULTS:
            return DEFAULTS[name]
        source = DEFAULT_FROM.get(name)
        value = None if source is None else params.get(source)
        if value is None:
            raise _missing(function, source or name)
    return value


def arguments(function, names, params):
    """Check the parameters of a call once: those the variant uses, then the rest.

    Parameters
    ----------
    function : str
        Public name, for the messages.
    names : tuple of str
        The parameters the chosen implementation takes, in its order.
    params : dict
        The keywords of the call.

    Returns
    -------
    values : list of ndarray
        The checked parameters in the order of ``names`` (defaults filled in:
        ``DEFAULTS`` for the phases, ``DEFAULT_FROM`` for the per-direction
        excitation).
    extra : list of ndarray
        The other known parameters passed. A single dict of parameters serves every
        generated function: those a function does not use are accepted, checked
        like the others (a bad value is an error wherever it is passed) and take
        part in broadcasting, so a grid of any parameter gives outputs of the
        grid's shape. ``None`` (an optional parameter left at its default) is
        skipped, and so is a scalar the caller checked (`CHECKED`).

    Raises
    ------
    TypeError
        For an unknown keyword or a missing parameter.
    ValueError
        Naming the parameter, for NaN, inf or a value outside its domain.
    """
    _reject_unknown(function, params)
    checked = params.get(CHECKED) or {}
    values = []
    for n in names:
        v = _lookup(function, n, params)
        values.append(
            numpy.asarray(v, dtype=float) if _is_checked(checked, n, v) else param(function, n, v)
        )
    extra = [
        param(function, k, v)
        for k, v in params.items()
        if k not in names and k != CHECKED and v is not None and not _is_checked(checked, k, v)
    ]
    return values, extra


def _is_checked(checked, name, value):
    """Whether ``value`` is the scalar the caller checked for ``name`` (`CHECKED`):
    the same object, a float (a scalar has no shape to broadcast)."""
    return checked.get(name) is value and type(value) is float


def _scalar_arguments(function, names, params):
    """`arguments` for scalar parameters (a kernel's): floats, checked without arrays.

    Binding happens in inner loops of parameter studies (a Floquet band binds at
    every value): Python floats pass a test of their domain; anything else takes
    the checks of `arguments`, which name what is wrong.
    """
    _reject_unknown(function, params)
    checked = params.get(CHECKED) or {}
    values = []
    for n in names:
        v = _lookup(function, n, params)
        if _is_checked(checked, n, v) or (
            type(v) is float and math.isfinite(v) and within(DOMAINS[n], v)
        ):
            values.append(v)
            continue
        x = param(function, n, v)
        if x.ndim:
            raise ValueError(f"{function}(): parameter {n!r} must be a scalar; got shape {x.shape}")
        values.append(float(x))
    for k, v in params.items():
        if (
            k not in names
            and k != CHECKED
            and v is not None
            and not _is_checked(checked, k, v)
            and not (type(v) is float and math.isfinite(v) and within(DOMAINS[k], v))
        ):
            param(function, k, v)
    return tuple(values)


def mp_arguments(function, names, params):
    """`arguments` for the mpmath variants: the checked values as ``mpf``."""
    _reject_unknown(function, params)
    values = [mp_param(function, n, _lookup(function, n, params)) for n in names]
    for k, v in params.items():
        if k not in names and k != CHECKED and v is not None:
            mp_param(function, k, v)
    return values


def _fail(function, name, domain, why):
    return ValueError(
        f"{function}(): parameter {name!r} must be {why}" + (f" ({domain})" if domain else "")
    )


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
    text = DOMAIN_RULES[domain][2]
    if x.size and not (within(domain, x.min()) and x.max() < math.inf):
        # Tell the reasons apart only on failure, so valid input costs two reductions.
        if numpy.isnan(x).any():
            raise _fail(function, name, None, "a number, not NaN")
        if numpy.isinf(x).any():
            raise _fail(function, name, None, "finite, not inf")
        raise _fail(function, name, why, text)
    return x


def mp_param(function, name, value, domain=None, why=None):
    """`param` for the mpmath variants: a scalar ``mpf``."""
    import mpmath

    domain = domain or DOMAINS[name]
    x = mpmath.mpf(value)
    if mpmath.isnan(x):
        raise _fail(function, name, None, "a number, not NaN")
    if mpmath.isinf(x):
        raise _fail(function, name, None, "finite, not inf")
    text = DOMAIN_RULES[domain][2]
    if not within(domain, x):
        raise _fail(function, name, why, text)
    return x
