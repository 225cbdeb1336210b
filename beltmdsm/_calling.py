"""One way of calling the analyses: the model first, then what is varied, then keywords.

Every public function takes the model first (``floquet_band(model, "Vb", 1, 8)``) and
names each keyword in its signature, so that a misspelt keyword fails in a type
checker and at run time (issue 37). `public` wraps such a function; for one release it
keeps the old spellings working, with one `DeprecationWarning` line per call naming the
new spelling of each:

* the model after the range (``floquet_band("Vb", 1, 8, model)``): the varied
  parameter is a string, so a first positional argument that is a string is the old
  order;
* model parameters and options as keywords (``simulate(Vb=4)``): they go to the model,
  ``Model(Vb=4)`` or ``model.replace(Vb=4)``;
* renamed keywords (``lo``/``hi`` for a range, ``points`` for a resolution).

Any other keyword is a `TypeError` with "did you mean" over the function's own
keywords and the model's parameters and options.
"""

from __future__ import annotations

import difflib
import functools
import inspect
import warnings
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any, Generic, ParamSpec, Protocol, TypeVar, overload

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .model import Model

P = ParamSpec("P")
R = TypeVar("R", covariant=True)
F = TypeVar("F")

#: A renamed keyword: its new name, and how the old value becomes new keywords (given
#: the old value and the other keywords of the call).
Rename = tuple[str, Callable[[Any, Mapping[str, Any]], dict[str, Any]]]


def rename(new: str) -> Rename:
    """The keyword is now called ``new``, with the same value."""
    return new, lambda value, _: {new: value}


class Ranged(Protocol, Generic[P, R]):
    """``f(model, param, lo, hi, ...)`` that also takes ``f(param, lo, hi, model, ...)``."""

    @overload
    def __call__(self, *args: P.args, **kwargs: P.kwargs) -> R: ...
    @overload
    def __call__(
        self,
        param: str,
        lo: float,
        hi: float,
        model: Model | Mapping[str, Any] | None = None,
        /,
        **kw: Any,
    ) -> R: ...


class Valued(Protocol, Generic[P, R]):
    """``f(model, param, values, ...)`` that also takes ``f(param, values, model, ...)``."""

    @overload
    def __call__(self, *args: P.args, **kwargs: P.kwargs) -> R: ...
    @overload
    def __call__(
        self,
        param: str,
        values: ArrayLike,
        model: Model | Mapping[str, Any] | None = None,
        /,
        **kw: Any,
    ) -> R: ...


class Mapped(Protocol, Generic[P, R]):
    """``f(model, x, x_lo, x_hi, y, y_lo, y_hi, ...)`` that also takes the model last."""

    @overload
    def __call__(self, *args: P.args, **kwargs: P.kwargs) -> R: ...
    @overload
    def __call__(
        self,
        x: str,
        x_from: float,
        x_to: float,
        y: str,
        y_from: float,
        y_to: float,
        model: Model | Mapping[str, Any] | None = None,
        /,
        **kw: Any,
    ) -> R: ...


def _deprecated(message: str) -> None:
    # stacklevel 3: the line that called the public function, not this wrapper
    warnings.warn(message, DeprecationWarning, stacklevel=3)


def _model_names() -> tuple[str, ...]:
    from .model import MODEL_PARAMETERS, OPTIONS

    return (*MODEL_PARAMETERS, *OPTIONS)


def unexpected(function: str, name: str, own: tuple[str, ...]) -> TypeError:
    """The error of an unknown keyword, with "did you mean" over the function's own
    keywords (``own``) and the model's parameters and options."""
    model = _model_names()
    close = difflib.get_close_matches(name, (*own, *model), n=1, cutoff=0.6)
    hint = ""
    if close and close[0] in own:
        hint = f"; did you mean {close[0]!r}?"
    elif close:
        hint = (
            f"; did you mean the model parameter {close[0]!r} "
            f"(Model({close[0]}=...) or model.replace({close[0]}=...))?"
        )
    return TypeError(f"{function}() got an unexpected keyword argument {name!r}{hint}")


def _with(model: Any, params: dict[str, Any]) -> Any:
    """``model`` with ``params``: a `Model` replaced, a mapping (or None) merged, so
    that the function still sees which parameters were given (``sweep``'s swept one)."""
    from .model import Model, as_model

    if isinstance(model, Model):
        return model.replace(**params)
    if model is None or isinstance(model, Mapping):
        return {**(model or {}), **params}
    return as_model(model, **params)  # refused there, naming the type


def _paper_only(name: str, model: Any) -> None:
    """Refuse another registered model than the paper's (``Model(model=...)``) in one
    line naming the model and what it lacks, for a function that runs the paper's only."""
    from .errors import Unsupported
    from .model import PAPER, Model, as_model

    if isinstance(model, Mapping) and model.get("model", PAPER) != PAPER:
        model = as_model(model)
    if isinstance(model, Model) and model.model != PAPER:
        raise Unsupported(model.refusal(name))


def _wrap(
    function: Callable[..., Any],
    old_order: tuple[str, ...],
    renamed: Mapping[str, Rename],
    hints: Mapping[str, str],
    models: bool = False,
) -> Callable[..., Any]:
    name = function.__name__
    parameters = inspect.signature(function).parameters
    own = tuple(k for k, p in parameters.items() if p.kind is not p.VAR_KEYWORD)
    first = next(iter(parameters))  # the model

    @functools.wraps(function)
    def call(*args: Any, **kw: Any) -> Any:
        notes = []  # what of the call is spelt as before: one warning line for all
        if old_order and args and isinstance(args[0], str):
            n = len(old_order)
            if len(args) > n + 1:
                raise TypeError(f"{name}() takes {n + 1} positional arguments")
            if len(args) > n:
                if first in kw:
                    raise TypeError(f"{name}() got the model twice (positional and {first}=)")
                kw[first] = args[n]
            given = ", ".join(old_order)
            notes.append(f"{name}({given}, model): pass the model first, {name}(model, {given})")
            args = (kw.pop(first, None), *args[:n])
        elif old_order and not args and first not in kw:
            kw[first] = None  # the model was optional when it came last
        extra = [k for k in kw if k not in own]
        model_names = _model_names() if extra else ()
        for key in extra:
            if key in hints:
                raise TypeError(f"{name}() {hints[key]}")
            if key not in renamed and key not in model_names:
                raise unexpected(name, key, own)
        old = [k for k in extra if k in renamed]
        if old:
            new = ", ".join(f"{renamed[k][0]}=" for k in old)
            notes.append(f"{name}({'=..., '.join(old)}=...): use {new}")
        moved = {k: kw.pop(k) for k in extra if k not in renamed}
        if moved:
            listed = ", ".join(f"{k}={v!r}" for k, v in moved.items())
            notes.append(
                f"{name}({listed}): pass the parameters in the model, "
                f"Model({listed}) or model.replace({listed})"
            )
        if notes:
            _deprecated("deprecated, and gone in the next release: " + "; ".join(notes))
        for key in old:
            for k, v in renamed[key][1](kw.pop(key), kw).items():
                if k in kw:
                    raise TypeError(f"{name}() got {k} twice (as {k}= and {key}=)")
                kw[k] = v
        if moved:
            if args:
                args = (_with(args[0], moved), *args[1:])
            else:
                kw[first] = _with(kw.get(first), moved)
        if not models:
            _paper_only(name, args[0] if args else kw.get(first))
        return function(*args, **kw)

    return call


def public(
    *,
    renamed: Mapping[str, Rename] | None = None,
    hints: Mapping[str, str] | None = None,
    models: bool = False,
) -> Callable[[Callable[P, F]], Callable[P, F]]:
    """A public function with the model first and only its own keywords, that takes
    the model's parameters as keywords (deprecated), ``renamed`` keywords (deprecated)
    and refuses any other keyword with "did you mean" (``hints``: a keyword's own
    message, ``simulate(start=...)``). Without ``models`` it runs the paper's model
    only and refuses another (``Model(model="belt_1dof")``) in one line, naming what
    the model lacks (`beltmdsm.model.OtherModel.capabilities`)."""

    def decorate(function: Callable[P, F]) -> Callable[P, F]:
        return _wrap(function, (), renamed or {}, hints or {}, models)  # type: ignore[return-value]

    return decorate


def ranged(
    *, renamed: Mapping[str, Rename] | None = None, models: bool = False
) -> Callable[[Callable[P, F]], Ranged[P, F]]:
    """`public`, also taking the old order ``f(param, lo, hi, model, ...)``."""

    def decorate(function: Callable[P, F]) -> Ranged[P, F]:
        order = ("param", "lo", "hi")
        return _wrap(function, order, renamed or {}, {}, models)  # type: ignore[return-value]

    return decorate


def valued(
    *, renamed: Mapping[str, Rename] | None = None, models: bool = False
) -> Callable[[Callable[P, F]], Valued[P, F]]:
    """`public`, also taking the old order ``f(param, values, model, ...)``."""

    def decorate(function: Callable[P, F]) -> Valued[P, F]:
        order = ("param", "values")
        return _wrap(function, order, renamed or {}, {}, models)  # type: ignore[return-value]

    return decorate


def mapped(
    *, renamed: Mapping[str, Rename] | None = None, models: bool = False
) -> Callable[[Callable[P, F]], Mapped[P, F]]:
    """`public`, also taking the old order ``f(x, x_lo, x_hi, y, y_lo, y_hi, model, ...)``."""

    def decorate(function: Callable[P, F]) -> Mapped[P, F]:
        order = ("x", "x_lo", "x_hi", "y", "y_lo", "y_hi")
        return _wrap(function, order, renamed or {}, {}, models)  # type: ignore[return-value]

    return decorate
