"""What a run settles on, named: `Attractor` (the result of
`beltmdsm.attractors.classification.classify` and
`beltmdsm.attractors.classification.periodic_attractor`) and its `KINDS`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import NDArray

__all__ = ["KINDS", "Attractor"]


#: The kinds of attractor, in the order of the module docstring.
KINDS = ("periodic", "quasi_periodic", "chaotic", "equilibrium", "unclassified", "unstable")


@dataclass
class Attractor:
    """An attractor, its kind and the evidence.

    Attributes
    ----------
    kind : {"periodic", "quasi_periodic", "chaotic", "equilibrium", "unclassified", "unstable"}
    periods : int or None
        Excitation periods of a periodic attractor (minimal), or of the unstable
        periodic response an ``unstable`` run sits on.
    rotation_number : float or None
        Mean turn per period about the samples' centre [turns]; ``p / k`` where periodic.
    rotation_accuracy : float or None
        Its accuracy (quasi-periodic: module docstring; periodic: exact, 0).
    lyapunov : float
        The largest Lyapunov exponent [1/s].
    lyapunov_error : float
    exponents : ndarray (4,)
        The spectrum, largest first (``-inf`` for a direction stick removes).
    evidence : str
        Why this kind, in one sentence.
    state : ndarray (4,)
        A state on the attractor at phase 0 (the fixed point where periodic).
    points : ndarray (n, 4)
        Its stroboscopic samples.
    exponent_floor : float or None
        From Floquet multipliers (`periodic_attractor`): the bound below which the
        exponents of multipliers under the computation's error floor lie (those are
        NaN, `beltmdsm.periodic.floquet.FLOOR_FACTOR`); None where every one is resolved.

    See Also
    --------
    beltmdsm.attractors.classification.classify : names the attractor a run settles on.
    beltmdsm.attractors.classification.periodic_attractor : the fast path where it locks.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.attractors.classification import periodic_attractor
    >>> a = periodic_attractor(Model(Vb=3.88), t_end=300.0)
    >>> a  # doctest: +ELLIPSIS
    Attractor(periodic (4T), largest exponent -0.0951 +- ... 1/s, rotation -0.250000)
    >>> d = a.as_dict()
    >>> d["kind"], d["periods"], d["rotation_number"]
    ('periodic', 4, -0.25)
    """

    kind: Literal[
        "periodic", "quasi_periodic", "chaotic", "equilibrium", "unclassified", "unstable"
    ]
    periods: int | None
    rotation_number: float | None
    rotation_accuracy: float | None
    lyapunov: float
    lyapunov_error: float
    exponents: NDArray[np.float64] = field(repr=False)
    evidence: str = field(repr=False)
    state: NDArray[np.float64] = field(repr=False)
    points: NDArray[np.float64] = field(repr=False)
    exponent_floor: float | None = field(default=None, repr=False)

    def __repr__(self) -> str:
        what = self.kind + (f" ({self.periods}T)" if self.periods else "")
        rot = "" if self.rotation_number is None else f", rotation {self.rotation_number:+.6f}"
        return (
            f"Attractor({what}, largest exponent {self.lyapunov:+.3g} +- "
            f"{self.lyapunov_error:.1g} 1/s{rot})"
        )

    def as_dict(self) -> dict:
        """JSON-ready: kind, periods, rotation number, exponents and the evidence."""
        return {
            "kind": self.kind,
            "periods": self.periods,
            "rotation_number": self.rotation_number,
            "rotation_accuracy": self.rotation_accuracy,
            "lyapunov": self.lyapunov,
            "lyapunov_error": self.lyapunov_error,
            "exponents": [float(x) for x in self.exponents],
            "evidence": self.evidence,
            "state": [float(x) for x in self.state],
            "exponent_floor": self.exponent_floor,
        }
