"""One Dormand-Prince 8(5,3) step of any size, with its dense output.

The method, its error estimate and step-size control are those of SciPy's ``DOP853``
and of `beltmdsm.integrate._dop853` (the same coefficients,
``beltmdsm.generated.tableau``), written here for a state of any size ``m`` (a model's
``2n`` states, or those with their ``(2n)^2`` variational entries): that integrator is
compiled for the paper's four states. Plain numpy, stage by stage.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from beltmdsm.generated import tableau as _coef

__all__ = ["Step", "step", "initial_step", "dense"]

_NS = _coef.N_STAGES
_A = np.asarray(_coef.A, dtype=float)
_B = np.asarray(_coef.B, dtype=float)
_C = np.asarray(_coef.C, dtype=float)
_E3 = np.asarray(_coef.E3, dtype=float)
_E5 = np.asarray(_coef.E5, dtype=float)
_D = np.asarray(_coef.D, dtype=float)
_NX = _coef.N_STAGES_EXTENDED
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0

Field = Callable[[float, NDArray[np.float64]], NDArray[np.float64]]


class Step:
    """An accepted step ``[t, t + h]``: its end and its dense-output coefficients."""

    __slots__ = ("t", "h", "y", "y_new", "f_new", "F")

    def __init__(self, t, h, y, y_new, f_new, F):
        self.t, self.h, self.y, self.y_new, self.f_new, self.F = t, h, y, y_new, f_new, F

    def at(self, t: float) -> NDArray[np.float64]:
        """The dense output at ``t`` inside the step."""
        return dense(self.F, self.y, (t - self.t) / self.h)

    def many(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """The dense output at the times ``t`` inside the step: (len(t), m)."""
        x = ((t - self.t) / self.h)[:, None]
        out = np.zeros((t.size, self.y.size))
        for k in range(self.F.shape[0]):
            out += self.F[self.F.shape[0] - 1 - k]
            out *= x if k % 2 == 0 else 1.0 - x
        return out + self.y


def dense(F: NDArray[np.float64], y_old: NDArray[np.float64], x: float) -> NDArray[np.float64]:
    """DOP853's dense output at ``x = (t - t_old) / h`` (SciPy's Dop853DenseOutput)."""
    out = np.zeros_like(y_old)
    for k in range(F.shape[0]):
        out += F[F.shape[0] - 1 - k]
        out *= x if k % 2 == 0 else 1.0 - x
    return out + y_old


def initial_step(fun: Field, t, y, f, t_end, rtol, atol, max_step) -> float:
    """SciPy's ``select_initial_step`` (Hairer, Norsett and Wanner, Sect. II.4)."""
    sc = atol + np.abs(y) * rtol
    d0, d1 = math.sqrt(np.mean((y / sc) ** 2)), math.sqrt(np.mean((f / sc) ** 2))
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, t_end - t)
    f1 = fun(t + h0, y + h0 * f)
    d2 = math.sqrt(np.mean(((f1 - f) / sc) ** 2)) / h0
    h1 = max(1e-6, h0 * 1e-3) if max(d1, d2) <= 1e-15 else (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, max_step, t_end - t)


def step(fun: Field, t, y, f, h_abs, t_end, rtol, atol, max_step) -> tuple[Step, float]:
    """One accepted step from ``(t, y)`` (``f`` its field), at most to ``t_end``:
    the step and the size to try next. Raises ArithmeticError where the step falls
    below the rounding of ``t`` or the state is not finite."""
    m = y.size
    K = np.empty((_NX, m))
    rejected = False
    while True:
        min_step = 10.0 * (np.nextafter(t, np.inf) - t)
        h_abs = min(max(h_abs, min_step), max_step)
        t_new = min(t + h_abs, t_end)
        h = t_new - t
        if not (h > 0.0 and math.isfinite(h)) or (h < min_step and t_new < t_end):
            raise ArithmeticError(f"the step fell below {min_step:.1e} s at t = {t:.9g} s")
        K[0] = f
        try:
            # a trial step too long for a stiff field overflows: its norm is then not
            # finite and the step is rejected below, so numpy's warnings say nothing
            with np.errstate(over="ignore", invalid="ignore"):
                for s in range(1, _NS):
                    K[s] = fun(t + _C[s] * h, y + h * (_A[s, :s] @ K[:s]))
                y_new = y + h * (_B @ K[:_NS])
                K[_NS] = fun(t_new, y_new)
                sc = atol + np.maximum(np.abs(y), np.abs(y_new)) * rtol
                e5 = np.sum(((_E5 @ K[: _NS + 1]) / sc) ** 2)
                e3 = np.sum(((_E3 @ K[: _NS + 1]) / sc) ** 2)
            norm = 0.0 if e5 == 0.0 and e3 == 0.0 else h * e5 / math.sqrt((e5 + 0.01 * e3) * m)
        except OverflowError:
            # a trial step far too long for the field (an exponential law overflows)
            norm = math.inf
        if not math.isfinite(norm):
            norm = math.inf
        if norm < 1.0:
            factor = _MAX_FACTOR if norm == 0.0 else min(_MAX_FACTOR, _SAFETY * norm**-0.125)
            if rejected:
                factor = min(1.0, factor)
            break
        if h <= min_step:
            # rejected at the least step: a finite error norm too would repeat forever
            what = "the state is not finite" if not math.isfinite(norm) else "no step is accepted"
            raise ArithmeticError(f"{what} past t = {t:.9g} s")
        h_abs *= max(_MIN_FACTOR, _SAFETY * norm**-0.125) if math.isfinite(norm) else _MIN_FACTOR
        rejected = True
    for s in range(_NS + 1, _NX):
        K[s] = fun(t + _C[s] * h, y + h * (_A[s, :s] @ K[:s]))
    F = np.empty((_coef.INTERPOLATOR_POWER, m))
    dy = y_new - y
    F[0] = dy
    F[1] = h * K[0] - dy
    F[2] = 2.0 * dy - h * (K[_NS] + K[0])
    F[3:] = h * (_D @ K)
    return Step(t, h, y, y_new, K[_NS].copy(), F), h_abs * factor
