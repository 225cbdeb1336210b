"""One way of calling the analyses: the model first, then what is varied.

`simulate`, `floquet`, `branch` and `responses` take the model first; `floquet_band`,
`coexistence`, `sweep` and `floquet_map` were written with the model after the range
(``floquet_band(param, lo, hi, model)``). `model_first` lets those take the model
first as well (``floquet_band(model, "Vb", 1, 8)``) while every old positional call
keeps working: the varied parameter is always a string, so a first positional
argument that is not one is the model. `settings_keywords` lets a function that takes
``settings=`` take the settings' fields as keywords too (``sweep(..., t_end=50)``), as
`simulate` does.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any, Generic, ParamSpec, Protocol, TypeVar, overload

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .model import Model

P = ParamSpec("P")
R = TypeVar("R", covariant=True)

_NOTE = """
    The model may also come first, as in `simulate` and `branch`:
    ``{name}(model, {order})`` is ``{name}({order}, model)``.
"""


class Ranged(Protocol, Generic[P, R]):
    """``f(param, lo, hi, model=None, ...)`` that also takes ``f(model, param, lo, hi, ...)``."""

    @overload
    def __call__(
        self,
        model: Model | Mapping[str, Any] | None,
        param: str,
        lo: float,
        hi: float,
        /,
        **kw: Any,
    ) -> R: ...
    @overload
    def __call__(self, *args: P.args, **kwargs: P.kwargs) -> R: ...


class Valued(Protocol, Generic[P, R]):
    """``f(param, values, model=None, ...)`` that also takes ``f(model, param, values, ...)``."""

    @overload
    def __call__(
        self, model: Model | Mapping[str, Any] | None, param: str, values: ArrayLike, /, **kw: Any
    ) -> R: ...
    @overload
    def __call__(self, *args: P.args, **kwargs: P.kwargs) -> R: ...


class Mapped(Protocol, Generic[P, R]):
    """``f(x, x_lo, x_hi, y, y_lo, y_hi, model=None, ...)`` that also takes the model first."""

    @overload
    def __call__(
        self,
        model: Model | Mapping[str, Any] | None,
        x: str,
        x_from: float,
        x_to: float,
        y: str,
        y_from: float,
        y_to: float,
        /,
        **kw: Any,
    ) -> R: ...
    @overload
    def __call__(self, *args: P.args, **kwargs: P.kwargs) -> R: ...


def _model_first(function: Callable[..., Any], order: str) -> Callable[..., Any]:
    @functools.wraps(function)
    def call(*args: Any, **kw: Any) -> Any:
        if args and not isinstance(args[0], str):  # the parameter's name is a string
            if "model" in kw:
                raise TypeError(f"{function.__name__}() got the model twice (first and model=)")
            return function(*args[1:], model=args[0], **kw)
        return function(*args, **kw)

    call.__doc__ = (
        (function.__doc__ or "").rstrip() + "\n" + _NOTE.format(name=function.__name__, order=order)
    )
    return call


def ranged(function: Callable[P, R]) -> Ranged[P, R]:
    """`function` (``f(param, lo, hi, model=None, ...)``), also taking the model first."""
    return _model_first(function, "param, lo, hi")  # type: ignore[return-value]


def valued(function: Callable[P, R]) -> Valued[P, R]:
    """`function` (``f(param, values, model=None, ...)``), also taking the model first."""
    return _model_first(function, "param, values")  # type: ignore[return-value]


def mapped(function: Callable[P, R]) -> Mapped[P, R]:
    """`function` (``f(x, x_from, x_to, y, y_from, y_to, model=None, ...)``), also taking
    the model first."""
    return _model_first(function, "x, x_from, x_to, y, y_from, y_to")  # type: ignore[return-value]


def settings_keywords(function: Callable[P, R]) -> Callable[P, R]:
    """`function` (taking ``settings=``), also taking its fields as keywords.

    ``f(..., t_end=50)`` is ``f(..., settings=replace(settings or SolverSettings(),
    t_end=50))``, as in `simulate`; a field given both ways is the keyword's.
    """

    @functools.wraps(function)
    def call(*args: Any, **kw: Any) -> Any:
        from .settings import SolverSettings

        names = SolverSettings.names()
        changes = {k: kw.pop(k) for k in list(kw) if k in names}
        if changes:
            base = kw.get("settings") or SolverSettings()
            kw["settings"] = SolverSettings(**{**base.__dict__, **changes})
        return function(*args, **kw)

    return call  # type: ignore[return-value]
