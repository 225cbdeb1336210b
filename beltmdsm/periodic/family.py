"""The period maps of one parameter's values, and the map's derivative in that parameter.

`MapFamily` is what a continuation in one parameter reads (`beltmdsm.continuation.branch`,
`beltmdsm.continuation.band`, `beltmdsm.continuation.floquet_map`): the map at each value
(`beltmdsm.periodic.engines.period_map`, the last few kept) and ``dP/d param`` by
central differences that keep the orbit's switch structure.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import NoPeriodicResponse
from ..model import Backend, Model
from ..settings import check_finite
from .base import PeriodMap
from .engines import period_map

__all__ = [
    "MapFamily",
]


class MapFamily:
    """The ``k``-fold period maps of one parameter's values, the others fixed.

    Parameters
    ----------
    model : Model
        The other parameters and the options.
    param : str
        The model parameter that varies.
    periods : int
    backend : {"python", "numba", None}

    ``family(value)`` is the `period_map` at ``param = value`` (the last few are
    kept); ``family.derivative(x, value)`` is ``dP/d param`` at ``x`` by central
    differences (relative step `DERIVATIVE_STEP`: a truncation error of about its
    square and a rounding error of about ``1e-12 / step`` relative, 1e-6, which slows
    Newton's method on a bordered system by nothing measurable). Both sides must keep
    the switch structure of ``x``'s image: close to a tangency the step shrinks by
    tens until they do.

    Raises
    ------
    ValueError
        For ``param`` not a model parameter; `beltmdsm.errors.Refused` for a model
        whose start is beyond floating point (`beltmdsm.settings.check_finite`).

    See Also
    --------
    beltmdsm.continuation.branch.branch : the continuation that reads it.
    beltmdsm.periodic.engines.period_map : one map.

    Examples
    --------
    >>> import numpy as np
    >>> from beltmdsm import Model, periodic_response
    >>> r = periodic_response(Model(Vb=5.0))
    >>> family = MapFamily(r.model, "Vb")
    >>> family(5.0).periods, np.round(family.derivative(r.shooting_state, 5.0), 3)
    (1, array([-0.629, -0.225]))
    """

    DERIVATIVE_STEP = 1e-6
    _SMALLEST_STEP = 1e-11
    _KEPT = 8

    def __init__(
        self, model: Model, param: str, periods: int = 1, backend: Backend | None = None
    ) -> None:
        if param not in model.params:
            raise ValueError(f"param must be a model parameter; got {param!r}")
        check_finite(model)
        self.model, self.param = model, param
        self.periods, self.backend = int(periods), backend
        self._maps: dict = {}

    def __call__(self, value: float) -> PeriodMap:
        """The map at ``param = value`` (raises NoPeriodicResponse outside its domain)."""
        value = float(value)
        if value not in self._maps:
            if len(self._maps) >= self._KEPT:
                self._maps.pop(next(iter(self._maps)))
            try:
                model = self.model.replace(**{self.param: value})
            except ValueError as err:  # a value outside the parameter's domain
                raise NoPeriodicResponse(f"{self.param} = {value:g}: {err}") from None
            self._maps[value] = period_map(model, self.periods, self.backend, check=False)
        return self._maps[value]

    def any_map(self, value: float) -> PeriodMap:
        """The map bound last, or the map at ``value`` where none is kept: for what
        does not depend on ``param`` (it saves a binding)."""
        return next(reversed(self._maps.values())) if self._maps else self(value)

    def derivative(
        self, x: ArrayLike, value: float, structure: tuple | None = None
    ) -> NDArray[np.float64]:
        """``dP/d param`` at the shooting state ``x`` by central differences.

        ``structure``: the `beltmdsm.periodic.base.signature` of the image at ``x``
        (computed if not given), which both sides must keep.
        """
        x = np.asarray(x, dtype=float)
        if structure is None:
            structure = self(value)(x).signature
        h = self.DERIVATIVE_STEP * max(1.0, abs(float(value)))
        while True:
            up = self(value + h)(x)
            try:
                down, width = self(value - h)(x), 2 * h
            except NoPeriodicResponse:  # at the edge of the domain: one-sided
                down, width = self(value)(x), h
            if (up.signature == structure and down.signature == structure) or (
                h < self._SMALLEST_STEP * max(1.0, abs(float(value)))
            ):
                return (up.state - down.state) / width
            h *= 0.1
