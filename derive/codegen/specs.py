"""What a generated module contains, as data: `FunctionSpec`, `ModuleSpec`, `NoVariant`.

`beltmdsm.derive.modules` builds these from the derivations;
`beltmdsm.derive.codegen.render` prints them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["FunctionSpec", "ModuleSpec", "NoVariant"]


@dataclass(frozen=True)
class NoVariant:
    """A variant that does not exist, and why: the generated function raises
    ``_support.Unsupported`` with ``reason`` (one line naming the law and the missing
    property) instead of computing with other physics."""

    reason: str


@dataclass(frozen=True)
class FunctionSpec:
    """One generated function.

    Attributes
    ----------
    name : str
        Public name.
    summary : str
        First docstring line.
    equations : str
        The paper's equations it implements, e.g. ``"Eq. (9)"``.
    returns : {"value", "tuple", "vector", "matrix", "roots", "growth", "stable"}
        How the outputs are assembled: one array; a tuple of arrays; an array with
        a trailing axis; a matrix with two trailing axes; the complex roots of a
        list of `Quadratic` factors along a trailing axis; the largest real part
        of those roots (`Quadratic.growth`); ``True`` where every output is
        positive (Routh-Hurwitz).
    returns_doc : str
        The ``Returns`` section body.
    variants : dict
        Outputs keyed by a tuple of option values (``()`` without options), or a
        `NoVariant`. Variants with equal outputs share one implementation.
    options : tuple of (name, choices-doc, default, description)
        Keyword options that select the variant, in the order of the keys.
    args : tuple of sympy.Symbol
        Positional (state) arguments.
    arg_docs : dict
        Description of each positional argument.
    arg_domains : dict
        ``name -> (domain, reason)`` checks for positional arguments.
    notes : str
        Extra docstring paragraph.
    vhat : bool
        The public function resolves ``Vhat`` from ``vhat_model`` (via
        ``beltmdsm.generated.friction.vhat``, with the function's law options) unless
        ``Vhat`` is passed.
    accelerate : bool
        Put the arithmetic in two kernels, numpy code run by
        ``beltmdsm.generated._support.blockwise`` and scalar code that
        ``beltmdsm.generated._support.compiled`` turns into a numba ufunc, selected by the
        ``backend=`` keyword (for one output per point: ``returns`` in ``"value"``,
        ``"growth"``, ``"stable"``).
    bind : bool
        Also generate ``bind_<name>``: the parameters checked once and bound to a
        scalar kernel (numpy variant only; ``returns`` in ``"value"``, ``"tuple"``,
        ``"vector"``, ``"matrix"``: the kernel returns a float or a flat tuple,
        row-major for a matrix).
    examples : str
        The numpydoc ``Examples`` section body of the public (numpy) function:
        doctest lines that run as written (tests/test_examples.py), printing rounded
        numbers.
    bind_examples : str
        The same for ``bind_<name>`` (with ``bind``).
    """

    name: str
    summary: str
    equations: str
    returns: str
    returns_doc: str
    variants: dict
    options: tuple = ()
    args: tuple = ()
    arg_docs: dict = field(default_factory=dict)
    arg_domains: dict = field(default_factory=dict)
    notes: str = ""
    vhat: bool = False
    accelerate: bool = False
    bind: bool = False
    examples: str = ""
    bind_examples: str = ""


@dataclass(frozen=True)
class ModuleSpec:
    """One generated module: its docstring, functions and data constants.

    ``constants`` are ``(name, value, comment)`` rows, written with ``repr`` (plain
    tuples, strings and numbers keep the output deterministic). ``mp``: whether the
    module has an mpmath variant in ``generated/mp/`` (not for a module of data).
    """

    name: str
    doc: str
    functions: tuple
    constants: tuple = ()
    mp: bool = True
