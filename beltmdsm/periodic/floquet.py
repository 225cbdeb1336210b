"""Exact stability of the forced periodic response: Floquet multipliers with saltation matrices.

The MDSM and the paper's analysis (Sects. 4.2-4.3) linearise about a slow equilibrium
that stands for the response of period ``T = 2 pi / Omega``; the exact counterpart is
the Floquet stability of that periodic response (docs/modelling.md#what-unstable-means).
`floquet` computes it: the response by shooting on the period map
(`beltmdsm.periodic.shooting.periodic_response`), by one of two engines that the facts
of the model's laws choose (``beltmdsm.generated.capabilities``,
`beltmdsm.periodic.engines.engine_of`), never by assumption:

* ``closed_form`` (`beltmdsm.periodic.closed_form.ClosedFormMap`), where the slip-mode
  friction is free of the tangential state and the normal equation too (Coulomb
  friction): the tangential map on the cached normal orbit, closed-form state
  transitions and saltation matrices, the normal block's multipliers apart;
* ``general`` (`beltmdsm.periodic.general_map.GeneralMap`), every law (Stribeck
  friction): the full state shot with the event-driven integrator, the monodromy by
  the variational equations with the generated Jacobians of the modes and the
  saltation matrices (`beltmdsm.periodic.variational`; Leine and Nijmeijer 2004).

The results say which (``engine``); where both apply they agree to 1e-9.

* **Phase-locked responses** (``periods = k > 1``): the multipliers are those of the
  ``k``-fold map (the eigenvalues of the product of the ``k`` one-period Jacobians,
  and on the closed-form path the normal block's to the power ``k``).
* **Without excitation** (`beltmdsm.excitation.is_autonomous`): the self-excited cycle's
  (`beltmdsm.periodic.cycle`), with ``autonomous`` set, its multipliers without the
  trivial one (along the flow, reported as ``trivial_multiplier``) and a multiplier 0
  for a stick phase.
* **Grazing.** A switch reached with a vanishing rate
  (`beltmdsm.periodic.margins.GRAZING_RATIO`) is reported as grazing, and no
  multiplier is returned for it.

* **The error floor.** The monodromy is a product of the propagators of the run's
  steps, each good to about the orbits' tolerance ``RTOL``
  (`beltmdsm.periodic.base.RTOL`) of the largest transition it carries; over a period
  of ``T`` the steps number about ``T`` times the model's fastest rate
  (`beltmdsm.settings.fastest_rate`), and their errors add, unamplified where the flow
  contracts. A multiplier below ``floor = FLOOR_FACTOR RTOL (1 + T rate)
  max(1, |mu|_max)`` is not resolved: it is reported as below the floor
  (``below_floor``; the text prints ``|mu| < floor``, and a growth rate whose
  multiplier is below it is ``growth rate < ln(floor) / (k T)``), not as a number.
  At ``Omega = 0.001`` the normal block's multiplier came out 2.98e-7 where it is
  ``exp(-0.225 T) = 1e-614``.

`floquet` reports the multipliers, the largest modulus, the growth rate per unit time
``log|mu| / (k T)``, the frequency of the critical pair ``|arg mu| / (k T)`` (to
compare with omega1; it is defined modulo ``2 pi / (k T)``) and the verdict. The
ranges of a parameter where the response is unstable are `beltmdsm.continuation.band`'s.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from .._calling import public
from .._tables import DataFrame
from ..integrate.switching import Mode
from ..model import Backend, Model, as_model
from ..settings import fastest_rate
from .base import RTOL, Engine
from .response import PeriodicResponse
from .shooting import FORWARD_PERIODS, periodic_response

__all__ = [
    "Floquet",
    "floquet",
    "FLOOR_FACTOR",
]

#: The error of the multipliers per ``RTOL (1 + T rate)`` (module docstring): measured
#: at most 8.4 over the base set at Omega = 0.001 to 0.05 (closed-form path, normal
#: block against its exact ``exp(lambda T)``; at Omega = 0.001 its 2.98e-7 against
#: 0), rounded up to 64.
FLOOR_FACTOR = 64.0


@dataclass(kw_only=True)
class Floquet:
    """Floquet multipliers of the periodic response and what they say.

    ``multipliers`` are those of the ``k``-fold map (``k = response.periods``): on the
    closed-form path the tangential pair, then the normal pair; on the general path
    the four eigenvalues of the whole monodromy, by decreasing modulus (no pair is
    singled out where nothing says the blocks decouple). NaN where the response
    grazes (``grazing`` is then set and ``stable`` is None). For a self-excited cycle
    (``autonomous``) the multipliers are the three of its Poincare map, without the
    trivial one along the flow (``trivial_multiplier``, 1 to the accuracy of the
    orbit); a stick phase makes one 0. Built by `floquet`, or from a response by
    `Floquet.of`.

    Attributes
    ----------
    multipliers : ndarray of complex
        Of the ``k``-fold map (4; 3 for a cycle).
    max_abs_multiplier : float
        The largest modulus, ``|mu|_max``.
    growth_rate : float
        ``log |mu|_max / (k T)`` [1/s]: negative where the response is stable.
    frequency : float
        ``|arg mu| / (k T)`` of the multiplier of largest modulus [rad/s], defined
        modulo ``2 pi / (k T)`` (to compare with omega1).
    stable : bool or None
        ``|mu|_max < 1``; None where the response grazes.
    n_reversals, n_sticks : int
        Reversals of the relative velocity and stick phases over the ``k`` periods.
    grazing : dict or None
        ``{"t", "surface", "ratio"}`` of a switch reached with a vanishing rate.
    period : float
        ``k T`` [s] (a cycle's own period).
    response : PeriodicResponse
        The response the multipliers belong to.
    autonomous : bool
        A self-excited cycle of a model without excitation.
    trivial_multiplier : complex or None
        A cycle's multiplier along the flow.
    floor : float
        The multipliers' error floor (module docstring, `FLOOR_FACTOR`): a multiplier
        below it is not resolved (``below_floor``; ``growth_bound`` where the largest
        is). 0.0 for a cycle (its multipliers are `beltmdsm.periodic.cycle`'s).

    See Also
    --------
    floquet : computes it.
    beltmdsm.periodic.response.PeriodicResponse : the orbit and its monodromy.
    beltmdsm.continuation.band.floquet_band : where along a parameter it is unstable.

    Examples
    --------
    >>> from beltmdsm import floquet
    >>> f = floquet(Model(Vb=12.0))
    >>> f.verdict, f.engine, round(f.max_abs_multiplier, 3), round(f.growth_rate, 3)
    ('stable', 'closed_form', 0.855, -0.1)
    >>> f.n_reversals, f.n_sticks, f.response.periods
    (0, 0, 1)
    >>> sorted(f.as_dict())[:4]
    ['autonomous', 'below_floor', 'engine', 'floor']
    """

    multipliers: np.ndarray
    max_abs_multiplier: float
    growth_rate: float
    frequency: float
    stable: bool | None
    n_reversals: int
    n_sticks: int
    grazing: dict | None
    period: float
    response: PeriodicResponse = field(repr=False)
    autonomous: bool = False
    trivial_multiplier: complex | None = None
    floor: float = 0.0

    @property
    def below_floor(self) -> np.ndarray:
        """Which multipliers lie below the error floor (``floor``): not resolved."""
        return np.abs(self.multipliers) < self.floor

    @property
    def growth_bound(self) -> float | None:
        """``ln(floor) / (k T)`` where even the largest multiplier is below the floor
        (the growth rate is below it, no number), else None."""
        if not self.max_abs_multiplier < self.floor:
            return None
        return math.log(self.floor) / self.period

    @classmethod
    def of(cls, resp: PeriodicResponse) -> Floquet:
        """The multipliers of a periodic response and what they say.

        Parameters
        ----------
        resp : PeriodicResponse
            A forced response (`beltmdsm.periodic.shooting.periodic_response`) or a
            cycle's (`beltmdsm.periodic.response.response_of_cycle`).

        Returns
        -------
        Floquet
            NaN multipliers and ``stable`` None where the response grazes.

        Raises
        ------
        numpy.linalg.LinAlgError
            Where the monodromy holds a NaN (eigenvalues do not converge).

        See Also
        --------
        floquet : the response and its multipliers in one call.

        Examples
        --------
        >>> from beltmdsm import Floquet, periodic_response
        >>> f = Floquet.of(periodic_response(Model(Vb=5.0), periods=4))
        >>> f.verdict, f.response.periods, round(f.max_abs_multiplier, 3)
        ('stable', 4, 0.587)
        """
        if resp.autonomous:
            return cls._of_cycle(resp)
        n_rev = sum(
            1
            for _, b, a, s in resp.switches
            if s == "relative_velocity" and {b, a} == {Mode.SLIP_BACK, Mode.SLIP_FORWARD}
        )
        n_stick = sum(1 for _, _, a, _ in resp.switches if a == Mode.STICK)
        if resp.grazing is not None:
            nan = float("nan")
            return cls(
                multipliers=np.full(4, complex(nan, nan)),
                max_abs_multiplier=nan,
                growth_rate=nan,
                frequency=nan,
                stable=None,
                n_reversals=n_rev,
                n_sticks=n_stick,
                grazing=resp.grazing,
                period=resp.period,
                response=resp,
            )
        if resp.engine == "closed_form":
            mt = np.linalg.eigvals(resp.monodromy_tangential)
            mn = np.linalg.eigvals(resp.monodromy_normal)
            mu = np.concatenate([mt, mn])
        else:
            mu = np.linalg.eigvals(resp.monodromy).astype(complex)
            mu = mu[np.argsort(-np.abs(mu), kind="stable")]
        k = int(np.argmax(np.abs(mu)))
        biggest = float(abs(mu[k]))
        growth = math.log(biggest) / resp.period if biggest > 0 else -math.inf
        steps = 1.0 + resp.period * fastest_rate(resp.model)
        floor = FLOOR_FACTOR * RTOL * steps * max(1.0, biggest)
        return cls(
            multipliers=mu,
            max_abs_multiplier=biggest,
            growth_rate=growth,
            frequency=abs(float(np.angle(mu[k]))) / resp.period,
            stable=bool(biggest < 1.0),
            n_reversals=n_rev,
            n_sticks=n_stick,
            grazing=None,
            period=resp.period,
            response=resp,
            floor=floor,
        )

    @classmethod
    def _of_cycle(cls, resp: PeriodicResponse) -> Floquet:
        """`Floquet` of a self-excited cycle: its multipliers as the cycle reports them."""
        c = resp.cycle
        mu = np.asarray(c.multipliers, dtype=complex)
        biggest = float(np.max(np.abs(mu)))
        if resp.grazing is not None or not math.isfinite(biggest):
            growth = frequency = math.nan
        else:
            k = int(np.argmax(np.abs(mu)))
            growth = math.log(biggest) / c.period if biggest > 0 else -math.inf
            frequency = abs(float(np.angle(mu[k]))) / c.period
        return cls(
            multipliers=mu,
            max_abs_multiplier=biggest,
            growth_rate=growth,
            frequency=frequency,
            stable=c.stable,
            n_reversals=c.n_reversals,
            n_sticks=c.n_sticks,
            grazing=c.grazing,
            period=c.period,
            response=resp,
            autonomous=True,
            trivial_multiplier=complex(c.trivial_multiplier),
        )

    @property
    def engine(self) -> str:
        """The path that computed the response: ``"closed_form"`` or ``"general"``."""
        return self.response.engine

    @property
    def verdict(self) -> Literal["stable", "unstable", "grazing"]:
        """``"stable"``, ``"unstable"`` or ``"grazing"`` (no multiplier at a grazing orbit)."""
        if self.stable is None:
            return "grazing"
        return "stable" if self.stable else "unstable"

    def __repr__(self) -> str:
        from .._display import block, laws

        resp = self.response
        head = (
            f"Floquet({resp.model!r}; {laws(resp.model)}: {self.verdict}, "
            f"period {self.period:.6g} s ({resp.periods} T), {self.engine} path)"
        )
        if self.stable is None:
            return block(head, [f"grazing: {self.grazing}"])
        return block(
            head,
            [
                f"{self.largest_text()}, critical pair at {self.frequency:.6g} rad/s",
                f"multipliers: {self.multipliers_text()}",
                f"{self.n_reversals} reversals and {self.n_sticks} sticks per orbit",
            ],
        )

    def to_pandas(self) -> DataFrame:
        """A `pandas.DataFrame` (needs pandas) of the multipliers, one row each in the
        order of ``multipliers``: ``multiplier``, ``abs``, ``angle`` [rad] and ``rate =
        log|mu| / period`` [1/s] (`beltmdsm._tables.multiplier_frame`), and
        ``below_floor``: the modulus is under the computation's error floor (`floor`),
        so that only its bound is known.

        Examples
        --------
        >>> from beltmdsm import Model, floquet
        >>> table = floquet(Model(Vb=12.0)).to_pandas()
        >>> list(table), len(table)
        (['multiplier', 'abs', 'angle', 'rate', 'below_floor'], 4)
        >>> round(float(table["rate"].max()), 3)  # the growth rate
        -0.1
        """
        from .._tables import multiplier_frame

        table = multiplier_frame(self.multipliers, self.period)
        table["below_floor"] = self.below_floor
        return table

    def multipliers_text(self) -> str:
        """The multipliers, those below the error floor as ``|mu| < floor``."""
        return ", ".join(
            f"|mu| < {self.floor:.1e}" if low else f"{z.real:.6g}{z.imag:+.6g}j"
            for z, low in zip(self.multipliers, self.below_floor)
        )

    def largest_text(self) -> str:
        """The largest modulus and the growth rate, or the bound where below the floor."""
        bound = self.growth_bound
        if bound is not None:
            return (
                f"max |mu| below the error floor {self.floor:.1e} of the computation: "
                f"growth rate < {bound:.6g} 1/s"
            )
        return f"max |mu| = {self.max_abs_multiplier:.6g}, growth rate {self.growth_rate:.6g} 1/s"

    def as_dict(self) -> dict:
        """The JSON-able summary (the keys of ``python -m beltmdsm floquet --json``).

        ``autonomous`` says whether it is a self-excited cycle; a cycle adds the keys of
        `beltmdsm.periodic.cycle.Cycle.as_dict` (``trivial_multiplier``, ``x1_range``,
        ``velocity_range``, ``stick_time``, ``stick_collapses``, ...).
        """
        if self.autonomous:
            return {
                **self.response.cycle.as_dict(),
                "growth_rate": self.growth_rate,
                "frequency": self.frequency,
                "periods": 1,
                "engine": self.engine,
            }
        return {
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "floor": self.floor,
            "below_floor": [bool(b) for b in self.below_floor],
            "max_abs_multiplier": self.max_abs_multiplier,
            "growth_rate": None if self.growth_bound is not None else self.growth_rate,
            "growth_rate_below": self.growth_bound,
            "frequency": self.frequency,
            "stable": self.stable,
            "n_reversals": self.n_reversals,
            "n_sticks": self.n_sticks,
            "grazing": self.grazing,
            "period": self.period,
            "periods": self.response.periods,
            "state0": [float(v) for v in self.response.state0],
            "newton_iterations": self.response.iterations,
            "residual": self.response.residual,
            "engine": self.engine,
            "autonomous": False,
        }


@public(models=True)
def floquet(
    model: Model | Mapping[str, Any] | None = None,
    *,
    guess: Sequence[float] | PeriodicResponse | None = None,
    forward: int = FORWARD_PERIODS,
    backend: Backend | None = None,
    periods: int = 1,
    engine: Engine | None = None,
) -> Floquet:
    """Floquet multipliers of the periodic response of Eq. (4) (module docstring).

    The response by shooting (`beltmdsm.periodic.shooting.periodic_response`, whose
    arguments this takes), on the period map the model's laws allow; for ``periods =
    k > 1`` the response of ``k`` periods and the multipliers of the ``k``-fold map.
    Without excitation, the self-excited cycle's.

    Parameters
    ----------
    model : Model or dict, optional
        The model (default: the base set).
    guess : array_like (2,) or (4,), or PeriodicResponse, optional
        The state at phase 0 that Newton's method starts from (a neighbour on a
        branch); default the backward-sliding orbit, or for ``periods > 1`` the
        attractor of the period map iterated from rest.
    forward : int
        Periods of forward iteration where Newton's method fails (0: none).
    backend : {"python", "numba", None}
    periods : int
        ``k >= 1``: the response of ``k`` excitation periods.
    engine : {"closed_form", "general", None}
        The period map (`beltmdsm.periodic.engines.period_map`); None: the one the
        model's laws allow.
    **kw
        Parameters and options of the model (``floquet(Model(Vb=5))``).

    Returns
    -------
    Floquet

    Raises
    ------
    ValueError
        Naming the argument, as `beltmdsm.periodic.shooting.periodic_response` (a
        parameter outside its domain, an excitation without a period, a bad guess or
        engine); `beltmdsm.errors.Refused` for ``periods > MAX_SEED_PERIODS`` without a
        guess.
    beltmdsm.errors.Unsupported
        For ``engine="closed_form"`` where the model's laws lack a fact it needs.
    beltmdsm.errors.NoPeriodicResponse
        Where no periodic response is found (`beltmdsm.errors.ShorterPeriod` where the
        attractor locks at a divisor of ``periods``).

    See Also
    --------
    beltmdsm.periodic.shooting.periodic_response : the response alone.
    beltmdsm.continuation.band.floquet_band : the ranges of a parameter where it is unstable.
    beltmdsm.continuation.branch.branch : the response continued in a parameter.
    beltmdsm.multistability.responses.responses : every response at one point, locked ones too.

    Examples
    --------
    >>> from beltmdsm import floquet
    >>> f = floquet(Model(Vb=5.0))
    >>> f.verdict, round(f.max_abs_multiplier, 3), round(f.growth_rate, 3)
    ('unstable', 1.12, 0.072)
    >>> round(f.frequency, 3), round(f.period, 4)  # omega1 = 1 rad/s, T = 2 pi / 4
    (1.029, 1.5708)

    The response of 4 excitation periods, locked at ``omega1 = Omega / 4``:

    >>> f4 = floquet(Model(Vb=5.0), periods=4)
    >>> f4.verdict, f4.n_reversals, round(f4.period, 4)
    ('stable', 4, 6.2832)
    """
    model = as_model(model)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        return api.periodic_response(model, guess, periods, engine=engine)
    return Floquet.of(
        periodic_response(
            model, guess=guess, forward=forward, backend=backend, periods=periods, engine=engine
        )
    )
