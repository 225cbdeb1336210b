"""The Hopf point of steady sliding: where a self-excited cycle is born.

Without excitation, Eq. (4) has the equilibrium of steady sliding (Eq. 9,
`beltmdsm.generated.unforced.equilibrium`), and its Jacobian ``J^0``
(`beltmdsm.generated.unforced.jacobian_at_equilibrium`) is block triangular: its eigenvalues
are a tangential pair and a normal pair, each the roots of a quadratic, in closed form
(`beltmdsm.generated.unforced.eigenvalues`, derived by SymPy from the chosen laws). A Hopf point
in a parameter ``p`` is a value where one complex pair crosses the imaginary axis:
its real part changes sign while its imaginary part stays away from 0 (a real pair
that crosses 0 is a fold of equilibria, not a Hopf point, and is not reported).

`hopf_points` scans ``[lo, hi]`` on a grid (`SCAN_POINTS`, one vectorised call of the
closed form) for a sign change of the real part of either pair, and places each root
by Brent's method to `HOPF_TOL`; at the root it gives the crossing frequency
``omega = Im lambda``, the eigenvector ``v`` of ``J^0`` for ``i omega`` (the null
vector of ``J^0 - i omega I``), and the transversality ``d Re lambda / dp`` (central
differences of the closed form). Two crossings closer than the grid's spacing are
missed (they cancel in the sign test); `SCAN_POINTS` is chosen so that the shipped
laws have none that close in their domains.

The small cycle near a Hopf point is ``x_eq + eps Re(v e^{i omega t})`` to first
order, with period ``2 pi / omega``; it exists on one side of ``p_H``: where steady
sliding is unstable (supercritical) or where it is stable (subcritical). Which one is
decided by the branch of cycles (`beltmdsm.cycles.branch`), not here.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from beltmdsm.generated import unforced

from ..errors import NoHopfPoint  # defined there (issue 38): one hierarchy
from ..model import MODEL_PARAMETERS, Model

__all__ = [
    "HopfPoint",
    "NoHopfPoint",
    "hopf_point",
    "hopf_points",
    "eigenvalues_over",
    "HOPF_TOL",
    "SCAN_POINTS",
]

#: Hopf points are placed to this in the parameter (Brent's method's ``xtol``).
HOPF_TOL = 1e-10
#: Grid of the scan for sign changes.
SCAN_POINTS = 401
#: A pair is complex at a crossing when its imaginary part exceeds this share of
#: ``|lambda|`` (a real pair crossing 0 is a fold of equilibria).
_COMPLEX_SHARE = 1e-8
#: The pairs of `beltmdsm.generated.unforced.eigenvalues`, in its order.
PAIRS = ("tangential", "normal")


@dataclass(frozen=True)
class HopfPoint:
    """Where a complex pair of the eigenvalues of steady sliding crosses the imaginary axis.

    Attributes
    ----------
    param : str
    value : float
        ``p_H``.
    accuracy : float
        A bound of the error of ``value`` (Brent's bracket).
    pair : str
        ``"tangential"`` or ``"normal"``: which pair of `beltmdsm.generated.unforced.eigenvalues`.
    frequency : float
        ``omega_H = Im lambda`` at ``p_H`` [rad/s]; the small cycle's period is
        ``2 pi / omega_H``.
    eigenvalue : complex
        At ``p_H`` (real part zero to the accuracy).
    eigenvector : ndarray (4,) complex
        Of ``J^0`` for ``i omega_H``: unit 2-norm, its largest component real positive.
    transversality : float
        ``d Re lambda / dp`` at ``p_H``; positive: steady sliding is unstable above
        ``p_H``.
    equilibrium : ndarray (4,)
        Steady sliding at ``p_H`` (Eq. 9).
    model : Model
        At ``p_H``.

    See Also
    --------
    beltmdsm.cycles.hopf.hopf_points : Finds them.
    beltmdsm.cycles.branch.hopf_cycle : The small cycle born there.

    Examples
    --------
    Stribeck friction: the falling friction coefficient undoes the tangential damping
    at ``Vb = 1.9957``, where the tangential pair crosses at ``omega1 = 1`` rad/s;
    steady sliding is unstable below (slower belt, steeper fall):

    >>> h = hopf_point(Model(friction="stribeck", alpha=0.0), "Vb", 0.5, 5.0)
    >>> round(h.value, 4), h.pair, round(h.frequency, 6), round(h.period, 4)
    (1.9957, 'tangential', 1.0, 6.2832)
    >>> h.unstable_side, round(h.transversality, 4), h.accuracy
    ('below', -0.1, 1e-10)
    """

    param: str
    value: float
    accuracy: float
    pair: str
    frequency: float
    eigenvalue: complex
    eigenvector: NDArray[np.complex128] = field(repr=False)
    transversality: float
    equilibrium: NDArray[np.float64] = field(repr=False)
    model: Model = field(repr=False)

    @property
    def period(self) -> float:
        """``2 pi / omega_H`` [s]."""
        return 2 * math.pi / self.frequency

    @property
    def unstable_side(self) -> str:
        """``"above"`` or ``"below"``: where steady sliding is unstable near ``p_H``."""
        return "above" if self.transversality > 0 else "below"

    def as_dict(self) -> dict:
        """For JSON: ``param``, ``value``, ``accuracy``, ``pair``, ``frequency``,
        ``period``, ``transversality``, ``unstable_side``, ``eigenvector`` (pairs of
        real and imaginary parts), ``equilibrium``."""
        return {
            "param": self.param,
            "value": self.value,
            "accuracy": self.accuracy,
            "pair": self.pair,
            "frequency": self.frequency,
            "period": self.period,
            "transversality": self.transversality,
            "unstable_side": self.unstable_side,
            "eigenvector": [[float(z.real), float(z.imag)] for z in self.eigenvector],
            "equilibrium": [float(v) for v in self.equilibrium],
        }


def eigenvalues_over(model: Model, param: str, values) -> NDArray[np.complex128]:
    """``(len(values), 4)`` eigenvalues of ``J^0`` with ``param`` at ``values`` (one call).

    Parameters
    ----------
    model : Model
        The other parameters and the options.
    param : str
        A model parameter.
    values : array_like
        Its values.

    Returns
    -------
    numpy.ndarray, shape (len(values), 4)
        The tangential pair, then the normal pair, at each value.

    See Also
    --------
    beltmdsm.cycles.hopf.hopf_points : Scans them for a crossing.

    Examples
    --------
    Under Coulomb friction the tangential pair is that of the damped oscillator,
    ``-beta1 omega1 +- i omega1 sqrt(1 - beta1^2) = -0.1 +- 0.995 i``; under Stribeck
    friction at ``Vb = 1.5`` it has crossed into the right half plane:

    >>> lam = eigenvalues_over(Model(alpha=0.0), "Vb", [1.5, 3.0])
    >>> np.round(lam[:, 0], 4).tolist()
    [(-0.1+0.995j), (-0.1+0.995j)]
    >>> lam = eigenvalues_over(Model(friction="stribeck", alpha=0.0), "Vb", [1.5, 3.0])
    >>> np.round(lam[:, 0], 4).tolist()
    [(0.0642+0.9979j), (-0.0634+0.998j)]
    """
    kw = model.arguments(unforced.eigenvalues)
    kw[param] = np.asarray(values, dtype=float)
    return np.asarray(unforced.eigenvalues(**kw)).reshape(-1, 4)


def _real_part(lam: NDArray[np.complex128], pair: int) -> NDArray[np.float64]:
    """The largest real part of a pair: continuous where the pair turns real."""
    return np.max(lam[:, 2 * pair : 2 * pair + 2].real, axis=1)


def hopf_points(model: Model, param: str, lo: float, hi: float) -> list[HopfPoint]:
    """Every Hopf point of steady sliding in ``param`` over ``[lo, hi]``, in increasing order.

    Parameters
    ----------
    model : Model
        The other parameters and the options (its value of ``param`` is not used).
    param : str
        A model parameter.
    lo, hi : float
        The range, inside the parameter's domain.

    Returns
    -------
    list of HopfPoint
        Possibly empty.

    Raises
    ------
    ValueError
        For an unknown parameter or a bad range (naming it).

    See Also
    --------
    beltmdsm.cycles.hopf.hopf_point : The lowest one, or a refusal.
    beltmdsm.cycles.hopf.eigenvalues_over : The eigenvalues scanned.

    Examples
    --------
    >>> model = Model(friction="stribeck", alpha=0.0)
    >>> [round(h.value, 4) for h in hopf_points(model, "Vb", 0.5, 5.0)]
    [1.9957]
    >>> hopf_points(model, "Vb", 3.0, 5.0)
    []
    >>> hopf_points(model, "Vb", -1.0, 5.0)
    Traceback (most recent call last):
    ...
    ValueError: parameter 'Vb' must be >= 0; got -1.0
    """
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo}, {hi}]")
    model.replace(**{param: lo}), model.replace(**{param: hi})  # the domain, named
    if param != "Vb" and model["Vb"] <= 0:
        raise ValueError("steady sliding needs a moving belt: Vb must be > 0 for a Hopf point")
    grid = np.linspace(lo, hi, SCAN_POINTS)
    lam = eigenvalues_over(model, param, grid)
    found = []
    for k, name in enumerate(PAIRS):
        re = _real_part(lam, k)
        for i in np.flatnonzero(np.sign(re[:-1]) * np.sign(re[1:]) <= 0):
            if re[i] == 0 and i > 0:  # a zero on the grid is found from the left
                continue

            def f(v, k=k):
                return float(_real_part(eigenvalues_over(model, param, [v]), k)[0])

            a, b = grid[i], grid[i + 1]
            # Brent's method halves a bracket at worst every other step: enough steps
            # for any bracket down to HOPF_TOL (a range up to 1e300 takes ~2000)
            n = 2 * math.ceil(math.log2(max((b - a) / HOPF_TOL, 2.0))) + 100
            value = (
                a
                if re[i] == 0
                else b
                if re[i + 1] == 0
                else brentq(f, a, b, xtol=HOPF_TOL, maxiter=n)
            )
            accuracy = (b - a) if re[i] == 0 else HOPF_TOL
            point = _at(model, param, float(value), k, name, accuracy, (lo, hi))
            if point is not None:
                found.append(point)
    return sorted(found, key=lambda h: h.value)


def hopf_point(model: Model, param: str, lo: float, hi: float) -> HopfPoint:
    """The Hopf point of steady sliding in ``param`` over ``[lo, hi]`` (the lowest, if several).

    Parameters
    ----------
    model, param, lo, hi
        As for `hopf_points`.

    Returns
    -------
    HopfPoint
        The lowest in the range.

    Raises
    ------
    NoHopfPoint
        Where no complex pair crosses the imaginary axis in the range, naming the
        real parts at its ends.
    ValueError
        For an unknown parameter or a bad range.

    See Also
    --------
    beltmdsm.cycles.hopf.hopf_points : Every one in the range.

    Examples
    --------
    >>> h = hopf_point(Model(friction="stribeck", alpha=0.0), "Vb", 0.5, 5.0)
    >>> round(h.value, 4), round(abs(h.eigenvalue.real), 9)
    (1.9957, 0.0)
    """
    found = hopf_points(model, param, lo, hi)
    if found:
        return found[0]
    lam = eigenvalues_over(model, param, [lo, hi])
    ends = ", ".join(
        f"{name} pair {_real_part(lam, k)[0]:+.3g} to {_real_part(lam, k)[1]:+.3g}"
        for k, name in enumerate(PAIRS)
    )
    raise NoHopfPoint(
        f"no Hopf point of steady sliding for {param} in [{lo:g}, {hi:g}] "
        f"({model.friction} friction, {model.contact} contact): no complex pair of the "
        f"unforced eigenvalues (beltmdsm.generated.unforced.eigenvalues) crosses the imaginary "
        f"axis; largest real parts {ends}"
    )


def _at(model, param, value, k, name, accuracy, bounds):
    """The `HopfPoint` at a located crossing of pair ``k``; None where the pair is real."""
    lam = eigenvalues_over(model, param, [value])[0, 2 * k : 2 * k + 2]
    top = lam[np.argmax(lam.imag)]
    if not abs(top.imag) > _COMPLEX_SHARE * max(abs(top), 1e-300):
        return None
    at = model.replace(**{param: value})
    J = np.asarray(
        unforced.jacobian_at_equilibrium(**at.arguments(unforced.jacobian_at_equilibrium))
    )
    omega = float(top.imag)
    v = np.linalg.svd(J.reshape(4, 4) - 1j * omega * np.eye(4))[2][-1].conj()
    v = v / np.linalg.norm(v)
    big = v[np.argmax(np.abs(v))]
    v = v * (abs(big) / big)
    h = 1e-5 * max(1.0, abs(value))
    a, b = max(value - h, bounds[0]), min(value + h, bounds[1])  # inside the domain
    re = _real_part(eigenvalues_over(model, param, [a, b]), k)
    eq = np.array([float(x) for x in unforced.equilibrium(**at.arguments(unforced.equilibrium))])
    return HopfPoint(
        param,
        value,
        float(accuracy),
        name,
        omega,
        complex(top),
        v,
        float((re[1] - re[0]) / (b - a)),
        eq,
        at,
    )
