"""Where steady sliding is unstable without excitation, per friction law (`steady_sliding`).

The closed form `beltmdsm.generated.unforced.critical_belt_speed` (SymPy's root of the
tangential damping ``2 beta1 omega1 + g dmu/d|Vr|`` of the linearisation at
``|Vr| = Vb``) beside the sign change of the largest real part of
`beltmdsm.generated.unforced.eigenvalues`, and the eigenvalues of the whole Jacobian against
those of its tangential and normal blocks (the normal coupling does not move them: the
normal equation is free of the tangential state, ``one_way_coupling`` of
`beltmdsm.generated.capabilities`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from beltmdsm.generated import unforced

from ...model import Model
from .laws import VB_RANGE, Law

__all__ = ["SteadySliding", "steady_sliding"]


@dataclass(frozen=True)
class SteadySliding:
    """Where steady sliding (the unforced equilibrium, Eq. 9) is unstable (`steady_sliding`).

    The linearisation at ``Fn = g > 0`` is the same under both tension laws
    (docs/modelling.md#tension), so this has no tension law.

    Attributes
    ----------
    law : Law
    critical_speed : float
        `beltmdsm.generated.unforced.critical_belt_speed`: steady sliding is unstable for
        ``Vb`` below it; NaN where no belt speed is (Coulomb's law, ``mu_k >= mu_s``, or a
        fall too weak to beat ``2 beta1 omega1`` even at ``Vb = 0``).
    unstable : list of (lo, hi)
        ``[(0, critical_speed)]``, or empty.
    eigenvalue_speed : float
        Where the largest real part of `beltmdsm.generated.unforced.eigenvalues` changes sign in
        ``Vb`` (Brent's method from the grid's sign change); NaN without a sign change.
    vb : ndarray
        The grid [m/s].
    growth_rate : ndarray
        The largest real part of the eigenvalues on the grid [1/s].
    damping : ndarray
        The tangential damping of the linearisation, minus the ``(X1', X1')`` entry of
        `beltmdsm.generated.unforced.jacobian_at_equilibrium` (``2 beta1 omega1 + g dmu/d|Vr|`` at
        ``|Vr| = Vb``) [1/s].
    block_gap : float
        The largest distance between the eigenvalues of the whole Jacobian and those of
        its tangential and normal 2 x 2 blocks over the grid (``numpy.linalg.eigvals``):
        rounding, because the normal coupling does not change them.
    closed_form_gap : float
        The largest distance between `beltmdsm.generated.unforced.eigenvalues` and
        ``numpy.linalg.eigvals`` of the Jacobian over the grid.
    wall_s : float

    See Also
    --------
    beltmdsm.paper_reports.law_comparison.steady.steady_sliding : what builds it.

    Examples
    --------
    Under Coulomb friction steady sliding is stable at every belt speed: no critical
    speed, and the eigenvalues' largest real part never changes sign:

    >>> import numpy as np
    >>> from beltmdsm.paper_reports.law_comparison import LAWS
    >>> s = steady_sliding(LAWS["coulomb"], vb=np.linspace(0.2, 12.0, 60))
    >>> s.unstable, s.as_dict()["critical_speed"], s.as_dict()["eigenvalue_speed"]
    ([], None, None)
    >>> bool((s.growth_rate < 0).all())
    True
    """

    law: Law
    critical_speed: float
    unstable: list[tuple[float, float]]
    eigenvalue_speed: float
    vb: NDArray[np.float64] = field(repr=False)
    growth_rate: NDArray[np.float64] = field(repr=False)
    damping: NDArray[np.float64] = field(repr=False)
    block_gap: float
    closed_form_gap: float
    wall_s: float

    def as_dict(self) -> dict:
        """For JSON: the numbers, the arrays as lists."""
        return {
            "law": self.law.name,
            "critical_speed": _finite_or_none(self.critical_speed),
            "unstable": [list(r) for r in self.unstable],
            "eigenvalue_speed": _finite_or_none(self.eigenvalue_speed),
            "block_gap": self.block_gap,
            "closed_form_gap": self.closed_form_gap,
            "wall_s": self.wall_s,
        }


def _finite_or_none(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def _largest_real_part(model: Model, vb: ArrayLike) -> NDArray[np.float64]:
    args = model.arguments(unforced.eigenvalues)
    lam = unforced.eigenvalues(**{**args, "Vb": np.asarray(vb, dtype=float)})
    return np.max(np.real(lam), axis=-1)


def steady_sliding(
    law: Law,
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb: ArrayLike | None = None,
) -> SteadySliding:
    """Where steady sliding is unstable, unforced: closed form and eigenvalues (part (a)).

    Parameters
    ----------
    law : Law
    model : Model or dict, optional
        The other parameters (default: the base set); the excitation does not enter.
    vb : array_like, optional
        The grid of belt speeds (default 600 values over `VB_RANGE`).

    Returns
    -------
    SteadySliding

    See Also
    --------
    beltmdsm.paper_reports.law_comparison.forced.forced_stability : the forced response (b).

    Examples
    --------
    Stribeck's law B (``mu_k = 0.1``, ``v_s = 3`` m/s) leaves steady sliding unstable
    up to 4.77 m/s; the closed form and the eigenvalues' sign change agree, and the
    normal coupling does not move the eigenvalues:

    >>> from beltmdsm.paper_reports.law_comparison import LAWS
    >>> s = steady_sliding(LAWS["stribeck_B"])
    >>> round(s.critical_speed, 4), round(s.eigenvalue_speed, 4)
    (4.7708, 4.7708)
    >>> [(lo, round(hi, 4)) for lo, hi in s.unstable]
    [(0.0, 4.7708)]
    >>> bool(s.block_gap < 1e-12 and s.closed_form_gap < 1e-12)
    True
    """
    start = time.perf_counter()
    m = law.model(model)
    vb = np.linspace(*VB_RANGE, 600) if vb is None else np.asarray(vb, dtype=float)
    vc = float(unforced.critical_belt_speed(**m.arguments(unforced.critical_belt_speed)))
    if math.isnan(vc):
        unstable = []
    else:
        unstable = [(0.0, vc)]
    growth = _largest_real_part(m, vb)
    # the sign change of the eigenvalues' largest real part, refined by Brent's method
    changes = np.flatnonzero(np.sign(growth[:-1]) * np.sign(growth[1:]) < 0)
    speed = math.nan
    if changes.size:
        i = int(changes[0])
        speed = float(
            brentq(
                lambda v: float(_largest_real_part(m, v)), vb[i], vb[i + 1], xtol=1e-14, rtol=1e-15
            )
        )
    args = m.arguments(unforced.jacobian_at_equilibrium)
    J = np.asarray(unforced.jacobian_at_equilibrium(**{**args, "Vb": vb}), dtype=float)
    damping = -J[:, 1, 1]
    full = np.sort_complex(np.linalg.eigvals(J))
    blocks = np.sort_complex(
        np.concatenate([np.linalg.eigvals(J[:, :2, :2]), np.linalg.eigvals(J[:, 2:, 2:])], axis=1)
    )
    closed = unforced.eigenvalues(**{**m.arguments(unforced.eigenvalues), "Vb": vb})
    closed = np.sort_complex(np.asarray(closed, dtype=complex))
    return SteadySliding(
        law=law,
        critical_speed=vc,
        unstable=unstable,
        eigenvalue_speed=speed,
        vb=vb,
        growth_rate=growth,
        damping=damping,
        block_gap=float(np.max(np.abs(full - blocks))),
        closed_form_gap=float(np.max(np.abs(full - closed))),
        wall_s=time.perf_counter() - start,
    )
