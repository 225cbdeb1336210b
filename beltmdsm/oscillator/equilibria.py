"""Steady sliding of any model, its stability, and its Hopf points along a parameter.

Steady sliding is the module's ``equilibrium`` (the state where the field of its slip
mode vanishes: the mass at rest, the belt moving). Its stability is read twice from
what the derivation gives: the eigenvalues of the derived Jacobian of that slip mode
(numpy), and the derived Hurwitz determinants ``H_1..H_2n`` of its characteristic
polynomial (stable where all are positive, Routh-Hurwitz). A Hopf point along a
parameter is a root of ``H_{2n-1}`` where ``a_{2n}`` and ``H_1..H_{2n-2}`` are positive
(a complex pair on the imaginary axis), bracketed on a grid and refined by Brent's
method.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ..errors import Unsupported
from .system import System

__all__ = ["Equilibrium", "steady_sliding", "hopf_points", "no_hopf_reason"]


@dataclass(repr=False)
class Equilibrium:
    """Steady sliding of a model and its stability.

    Attributes
    ----------
    system : System
    state : ndarray (2n,)
    mode : int
        The slip mode (the sign of the slip velocity there).
    eigenvalues : ndarray (2n,) complex
        Of the derived Jacobian, by numpy, largest real part first.
    characteristic : ndarray (2n+1,)
        ``1, a_1 .. a_2n`` of ``det(lambda I - J)``, derived.
    hurwitz : ndarray (2n,)
        ``H_1 .. H_2n``, derived.
    stable : bool
        All Hurwitz determinants positive.

    See Also
    --------
    steady_sliding : makes it.

    Examples
    --------
    >>> eq = steady_sliding(System("belt_1dof", friction="stribeck", Vb=2.5))
    >>> eq  # doctest: +NORMALIZE_WHITESPACE
    Equilibrium(System('belt_1dof', friction='stribeck', Vb=2.5); x=2.57329, x_dot=0;
    stable, growth rate -0.03961)
    >>> [bool(h > 0) for h in eq.hurwitz]
    [True, True]
    """

    system: System
    state: NDArray[np.float64]
    mode: int
    eigenvalues: NDArray[np.complex128]
    characteristic: NDArray[np.float64]
    hurwitz: NDArray[np.float64]
    stable: bool

    @property
    def growth_rate(self) -> float:
        """The largest real part of the eigenvalues [1/s]."""
        return float(self.eigenvalues.real.max())

    def __repr__(self) -> str:
        word = "stable" if self.stable else "unstable"
        state = ", ".join(f"{n}={v:.6g}" for n, v in zip(self.system.states, self.state))
        return f"Equilibrium({self.system!r}; {state}; {word}, growth rate {self.growth_rate:.4g})"


def steady_sliding(system: System) -> Equilibrium:
    """Steady sliding of the model, its eigenvalues and Hurwitz determinants.

    Parameters
    ----------
    system : System

    Returns
    -------
    Equilibrium

    Raises
    ------
    Unsupported
        Where the slip velocity vanishes there (no slip mode: the belt at rest).

    See Also
    --------
    hopf_points : where it loses stability along a parameter.

    Examples
    --------
    >>> eq = steady_sliding(System("belt_1dof", friction="stribeck", Vb=1.5))
    >>> eq.stable, eq.mode, round(eq.growth_rate, 4)
    (False, -1, 0.0642)
    """
    k, p = system.kernels, system.p
    state = np.asarray(k.equilibrium(p), dtype=float)
    v = k.slip_velocity(0.0, state, p)
    if v == 0.0:
        raise Unsupported(
            f"model {system.name!r}: the slip velocity vanishes at steady sliding "
            "(Vb = 0?): it has no slip mode"
        )
    mode = 1 if v > 0.0 else -1
    J = np.asarray(k.jacobian(0.0, state, p, mode), dtype=float)
    eig = np.linalg.eigvals(J)
    eig = eig[np.argsort(-eig.real, kind="stable")]
    H = np.asarray(k.hurwitz(p), dtype=float)
    a = np.asarray(k.characteristic(p), dtype=float)
    return Equilibrium(system, state, mode, eig, a, H, bool(np.all(H > 0.0)))


def hopf_points(
    system: System, parameter: str, lo: float, hi: float, points: int = 64
) -> NDArray[np.float64]:
    """The Hopf points of steady sliding along one parameter in ``[lo, hi]``.

    Roots of the derived ``H_{2n-1}`` where ``a_{2n} > 0`` and ``H_1 .. H_{2n-2} > 0``,
    bracketed on ``points`` values and refined by Brent's method to rounding.

    Parameters
    ----------
    system : System
    parameter : str
        One of the system's parameters.
    lo, hi : float
        The range, ``lo < hi``.
    points : int
        The grid that brackets the roots (two roots closer than its spacing may be
        missed).

    Returns
    -------
    ndarray
        The Hopf points, increasing (empty where there is none).

    Raises
    ------
    ValueError
        An unknown parameter or an empty range.

    See Also
    --------
    steady_sliding : the stability at one point.

    Examples
    --------
    >>> s = System("belt_1dof", friction="stribeck")
    >>> [round(float(v), 6) for v in hopf_points(s, "Vb", 0.5, 5.0)]
    [1.99572]
    """
    if parameter not in system.params:
        raise ValueError(f"parameter={parameter!r}: not a parameter of {system!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi) or points < 2:
        raise ValueError(f"[{lo}, {hi}] with {points} points: not a range")
    k = system.kernels
    i = list(system.params).index(parameter)
    p = system.p.copy()

    def H(value):
        p[i] = value
        return np.asarray(k.hurwitz(p), dtype=float), np.asarray(k.characteristic(p), dtype=float)

    def crit(value):
        return H(value)[0][-2]

    grid = np.linspace(lo, hi, points)
    values = np.array([crit(v) for v in grid])
    roots = []
    for a, b, fa, fb in zip(grid[:-1], grid[1:], values[:-1], values[1:]):
        if fa == 0.0:
            root = a
        elif fa * fb < 0.0:
            root = brentq(crit, a, b, xtol=1e-15, rtol=1e-15)
        else:
            continue
        hurwitz, char = H(root)
        if char[-1] > 0.0 and np.all(hurwitz[:-2] > 0.0):
            roots.append(root)
    return np.array(roots)


def no_hopf_reason(system: System, parameter: str, lo: float, hi: float, points: int = 64) -> str:
    """Why steady sliding has no Hopf point in ``parameter`` over ``[lo, hi]``, in one line.

    Where its derived characteristic polynomial is the same at every value of the grid
    (to rounding), its stability does not depend on the parameter at all (under Coulomb
    friction a constant coefficient: the belt speed only moves the equilibrium); the
    line then names the parameters the polynomial does depend on, where its thresholds
    lie (Hoffmann's flutter threshold in the friction coefficient). Else it is stable,
    or unstable, over the whole range.

    Parameters
    ----------
    system : System
    parameter : str
    lo, hi : float
        The range looked in, ``lo < hi``.
    points : int
        The grid (as `hopf_points`').

    Returns
    -------
    str

    See Also
    --------
    hopf_points : the Hopf points, where there are some.

    Examples
    --------
    Under Coulomb friction Hoffmann's model has no Hopf point in the belt speed:

    >>> why = no_hopf_reason(System("hoffmann", mu_s=1.0), "Vb", 0.5, 2.0)
    >>> why.split(":")[0]
    "steady sliding's characteristic polynomial does not depend on Vb (friction 'coulomb')"
    >>> why.endswith("(its threshold in the friction coefficient mu_s)")
    True
    """
    k = system.kernels
    i = list(system.params).index(parameter)

    def coefficients(p):
        return np.asarray(k.characteristic(p), dtype=float)

    base = system.p.copy()
    a0 = coefficients(base)
    scale = float(np.abs(a0).max())

    def moved(j, value):
        q = base.copy()
        q[j] = value
        return float(np.abs(coefficients(q) - a0).max()) > 1e-13 * scale

    eq = steady_sliding(system.replace(**{parameter: float(lo)}))
    word = "stable" if eq.stable else "unstable"
    if not any(moved(i, v) for v in np.linspace(lo, hi, points)):
        names = [n for j, n in enumerate(system.params) if moved(j, base[j] * 1.01 + 1e-3)]
        laws = [n for n in system.module.PARAMETERS[system.friction] if n.startswith("mu")]
        hint = [n for n in laws if n in names]
        where = f" (its threshold in the friction coefficient {hint[0]})" if hint else ""
        return (
            f"steady sliding's characteristic polynomial does not depend on {parameter} "
            f"(friction {system.friction!r}): it is {word} at every {parameter} (growth "
            f"rate {eq.growth_rate:.6g}); its stability depends on {', '.join(names)}{where}"
        )
    end = steady_sliding(system.replace(**{parameter: float(hi)}))
    flutter = _flutter(system, parameter, eq, end)
    if flutter is not None:
        return flutter
    return (
        f"steady sliding is {word} over {parameter} in [{lo:g}, {hi:g}] (growth rate "
        f"{eq.growth_rate:.6g} to {end.growth_rate:.6g}): no Hopf point there"
    )


def _flutter(system: System, parameter: str, a: Equilibrium, b: Equilibrium) -> str | None:
    """Where steady sliding is marginal (eigenvalues on the imaginary axis: no damping)
    at one end and unstable at the other: the value where a pair leaves the axis, by
    bisection on the growth rate (a flutter: the Hurwitz determinant ``H_{2n-1}``
    vanishes on the whole marginal side, so it has no sign change to find)."""

    def tiny(eq: Equilibrium) -> float:
        return 1e-9 * (1.0 + float(np.abs(eq.eigenvalues).max()))

    if abs(a.growth_rate) <= tiny(a) < b.growth_rate:
        x0, x1 = a.system.params[parameter], b.system.params[parameter]
    elif abs(b.growth_rate) <= tiny(b) < a.growth_rate:
        x0, x1 = b.system.params[parameter], a.system.params[parameter]
    else:
        return None
    lo, hi = x0, x1  # marginal at lo, unstable at hi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        eq = steady_sliding(system.replace(**{parameter: mid}))
        if eq.growth_rate > tiny(eq):
            hi = mid
        else:
            lo = mid
    return (
        f"steady sliding is marginally stable (eigenvalues on the imaginary axis: no "
        f"damping) from {parameter} = {x0:g} to {parameter} = {hi:.12g}, "
        "where two of them meet and leave the axis (a flutter, mode coupling); no Hopf "
        "point (the Hurwitz determinant that changes sign at one vanishes on the whole "
        "marginal side)"
    )
