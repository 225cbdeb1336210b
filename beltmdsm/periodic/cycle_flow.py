"""The flow of the unforced Eq. (4) over a free time, for the continuation of cycles.

A self-excited cycle of period ``T`` through ``x`` is a zero of ``phi_T(x; p) - x``,
``phi`` the flow of the hybrid system (the event-driven run of
`beltmdsm.integrate.events` at the period maps' tolerance
`beltmdsm.periodic.base.RTOL`), closed by a phase condition. `CycleFlow` gives
what the continuation of such a zero needs at ``(x, T, p)``: the end state, its
Jacobian in ``x`` (the monodromy by the variational equations and the saltation
matrices, `beltmdsm.periodic.variational`), in ``T`` (the field at the end) and in
``p`` (central differences), and the phase condition.

**Phase condition.** A Poincare section: the extremum of the coordinate ``k`` (``X1'``
for a tangential cycle), ``h(x) = f_k(x) = 0`` with ``f`` the field of the mode at
``x``, taken where ``x_k`` is smallest (the predictor starts there). For a cycle
around steady sliding the smallest ``X1'`` lies in backward slip, away from every
switch, so the section is crossed transversally (``dh/dt = f_k' > 0``) also on
stick-slip cycles; its gradient is taken by central differences of the field.

`orbit_observables` reads a run over one period: the extremes of ``X1`` and ``X1'``
(each refined by Brent's method on the dense output), the stick phases and the
reversals of the relative velocity.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import minimize_scalar

from ..errors import NoPeriodicResponse, StepTooSmall
from ..excitation import is_autonomous
from ..integrate.events import integrate_events
from ..integrate.switching import Mode, Switching
from ..integrate.trajectory import Run
from ..model import Backend, Model
from ..settings import SolverSettings
from . import variational
from .base import RTOL
from .cycle_returns import rest_step

__all__ = ["CycleFlow", "FlowImage", "Observables", "orbit_observables", "split_multipliers"]

#: Relative step of the central differences in the parameter (as
#: `beltmdsm.periodic.family.MapFamily`) and in the state (the section's gradient).
P_STEP = 1e-6
X_STEP = 1e-6
#: Samples of a period before the extremes are refined.
_SAMPLES = 256


def split_multipliers(M, f) -> tuple[complex, NDArray[np.complex128]]:
    """``(trivial, others)``: the trivial multiplier of a cycle's monodromy ``M``, the one
    whose eigenvector is closest in direction to the field ``f`` on the section (as
    `beltmdsm.periodic.cycle` picks it: near a Hopf point another multiplier lies
    as close to 1), and the others by decreasing modulus.

    Parameters
    ----------
    M : numpy.ndarray, shape (4, 4)
        The monodromy of a cycle.
    f : numpy.ndarray, shape (4,)
        The field at the cycle's state on the section.

    Returns
    -------
    trivial : complex
        The multiplier of the flow's direction (1 up to the error of the cycle).
    others : numpy.ndarray, complex
        The rest, by decreasing modulus.

    See Also
    --------
    beltmdsm.periodic.cycle_flow.CycleFlow.image : The monodromy and the field.

    Examples
    --------
    Along a shear that keeps the flow's direction ``f = e_1`` the trivial multiplier is
    1, although another one (0.999) lies closer to 1 than the largest of the rest:

    >>> M = np.array([[1.0, 0.5], [0.0, 0.999]])
    >>> trivial, others = split_multipliers(M, np.array([1.0, 0.0]))
    >>> trivial, np.round(others, 6).tolist()
    ((1+0j), [(0.999+0j)])
    """
    mu, V = np.linalg.eig(M)
    cosines = np.abs(np.conj(V).T @ (f / np.linalg.norm(f))) / np.linalg.norm(V, axis=0)
    k = int(np.argmax(cosines))
    others = np.delete(mu.astype(complex), k)
    return complex(mu[k]), others[np.argsort(-np.abs(others), kind="stable")]


@dataclass
class FlowImage:
    """The end of a run of length ``T`` from ``x``: ``phi``, ``d phi/dx`` and ``f(phi)``.

    Attributes
    ----------
    state : numpy.ndarray, shape (4,)
        ``phi_T(x; p)``.
    monodromy : numpy.ndarray, shape (4, 4), or None
        ``d phi/dx`` (None where not asked for).
    field : numpy.ndarray, shape (4,)
        The field at ``state``.
    run : Run
        The run itself.

    See Also
    --------
    beltmdsm.periodic.cycle_flow.CycleFlow.image : Returns it.

    Examples
    --------
    The stick-slip cycle of Stribeck friction at ``Vb = 1.5`` (period 6.654 s) closes
    on itself; its stick phase forgets the velocity's perturbation, so a change of
    ``X1`` comes back unchanged and one of ``X1'`` comes back as one of ``X1`` alone
    (the first two columns of the monodromy, in modulus):

    >>> from beltmdsm.model import Model
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> image = flow.image(x, 6.654341995080, 1.5)
    >>> bool(np.abs(image.state - x).max() < 1e-9)
    True
    >>> np.round(np.abs(image.monodromy[:, :2]), 3).tolist()
    [[1.0, 0.765], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]]
    """

    state: NDArray[np.float64]
    monodromy: NDArray[np.float64] | None
    field: NDArray[np.float64]
    run: Run = field(repr=False)


@dataclass(frozen=True)
class Observables:
    """What a cycle's orbit shows over one period.

    ``x1_range``, ``velocity_range``: [min, max] of ``X1`` and ``X1'``;
    ``max_relative_velocity``: the largest ``Vr = X1' - Vb`` (0 where the mass sticks:
    ``X1' = Vb`` holds exactly while sticking); ``amplitude``: half the range of
    ``X1'``; ``n_sticks``, ``n_reversals``: stick phases and direct crossings of
    ``Vr = 0``; ``stick_time``: the time stuck per period [s].

    See Also
    --------
    beltmdsm.periodic.cycle_flow.orbit_observables : Reads them from a run.

    Examples
    --------
    On the stick-slip cycle at ``Vb = 1.5`` the fastest the mass moves is the belt's
    speed, while stuck (1.52 s of the 6.654 s period):

    >>> from beltmdsm.model import Model
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> seen = orbit_observables(flow.run(x, 6.654341995080, 1.5), 1.5)
    >>> [round(v, 4) for v in seen.velocity_range], seen.max_relative_velocity
    ([-2.0338, 1.5], 0.0)
    >>> seen.n_sticks, seen.n_reversals, round(seen.stick_time, 3)
    (1, 0, 1.52)
    """

    x1_range: tuple[float, float]
    velocity_range: tuple[float, float]
    max_relative_velocity: float
    amplitude: float
    n_sticks: int
    n_reversals: int
    stick_time: float = 0.0


def _extreme(tr, T, i, sign):
    """The extremum of coordinate ``i`` (``sign`` 1: max, -1: min), refined by Brent."""
    t = np.linspace(0.0, T, _SAMPLES + 1)
    y = sign * tr.state(t)[i]
    j = int(np.argmax(y))
    a, b = t[max(j - 1, 0)], t[min(j + 1, _SAMPLES)]
    best = float(y[j])
    if b > a:
        r = minimize_scalar(
            lambda s: -sign * tr.state(np.array([s]))[i, 0],
            bounds=(a, b),
            method="bounded",
            options={"xatol": 1e-10 * max(T, 1.0)},
        )
        best = max(best, -float(r.fun))
    return sign * best


def orbit_observables(run: Run, Vb: float) -> Observables:
    """The `Observables` of a run over one period of a cycle.

    Parameters
    ----------
    run : Run
        A run over one period, from ``t = 0``.
    Vb : float
        The belt speed.

    Returns
    -------
    Observables
        The extremes refined on the dense output, the stick phases and reversals.

    See Also
    --------
    beltmdsm.periodic.cycle_flow.Observables : What it reads.

    Examples
    --------
    The stick-slip cycle at ``Vb = 1.5``: ``X1`` spans 0.81 to 4.88, half the range of
    ``X1'`` is ``(1.5 + 2.0338) / 2``:

    >>> from beltmdsm.model import Model
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> seen = orbit_observables(flow.run(x, 6.654341995080, 1.5), 1.5)
    >>> [round(v, 4) for v in seen.x1_range], round(seen.amplitude, 4)
    ([0.8117, 4.8822], 1.7669)
    """
    tr = run.trajectory
    T = tr.t_end
    x1 = (_extreme(tr, T, 0, -1), _extreme(tr, T, 0, 1))
    v = (_extreme(tr, T, 1, -1), _extreme(tr, T, 1, 1))
    n_sticks = sum(1 for _, _, new in run.events if Mode(int(new)) == Mode.STICK)
    n_rev = sum(
        1 for _, kind, new in run.events if kind == "vr_zero" and Mode(int(new)) != Mode.STICK
    )
    max_vr = 0.0 if n_sticks and v[1] <= Vb else v[1] - Vb
    stuck = float(tr.time_in_modes(0.0, T)[Mode.STICK])
    return Observables(x1, v, float(max_vr), 0.5 * (v[1] - v[0]), n_sticks, n_rev, stuck)


class CycleFlow:
    """The flow of one model in one parameter, with the phase condition on coordinate ``k``.

    Parameters
    ----------
    model : Model
        Without excitation (`autonomous`).
    param : str
    k : int
        The coordinate whose smallest value is the section (1: ``X1'``).
    backend : {"python", "numba", None}
        The kernels; None: numba if installed.

    Raises
    ------
    ValueError
        For a model with excitation.

    See Also
    --------
    beltmdsm.cycles.continuation.Continuation : Continues cycles on it.
    beltmdsm.periodic.cycle_flow.FlowImage : What `image` returns.

    Examples
    --------
    The stick-slip cycle at ``Vb = 1.5`` lies on the section (the minimum of ``X1'``:
    its rate is 0 there) and has multipliers 1 (the flow's direction) and 0.2236:

    >>> from beltmdsm.model import Model
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> round(abs(flow.section(x, 1.5)), 9)
    0.0
    >>> image = flow.image(x, 6.654341995080, 1.5)
    >>> trivial, others = split_multipliers(image.monodromy, image.field)
    >>> round(abs(trivial), 6), round(float(abs(others[0])), 4)
    (1.0, 0.2236)
    >>> CycleFlow(Model(), "Vb")
    Traceback (most recent call last):
    ...
    ValueError: a cycle's flow needs a model without excitation (alpha = 0)
    """

    _KEPT = 8

    def __init__(self, model: Model, param: str, k: int = 1, backend: Backend | None = None):
        if not is_autonomous(model):
            raise ValueError("a cycle's flow needs a model without excitation (alpha = 0)")
        self.model, self.param, self.k, self.backend = model, param, int(k), backend
        self._at: dict = {}

    def at(self, p: float) -> tuple[Model, Switching]:
        """The model and its switching rules at ``param = p`` (the last few kept)."""
        p = float(p)
        if p not in self._at:
            if len(self._at) >= self._KEPT:
                self._at.pop(next(iter(self._at)))
            try:
                model = self.model.replace(**{self.param: p})
            except ValueError as err:  # outside the parameter's domain
                raise NoPeriodicResponse(f"{self.param} = {p:g}: {err}") from None
            self._at[p] = (model, Switching(model))
        return self._at[p]

    def field(self, p: float, x, mode: Mode | None = None) -> NDArray[np.float64]:
        """The field at ``x`` in ``mode`` (default: the mode of ``x``)."""
        _, sw = self.at(p)
        mode = sw.initial_mode(0.0, x) if mode is None else mode
        return np.array(sw.field(0.0, *x, float(mode)), dtype=float)

    def run(self, x, T: float, p: float) -> Run:
        """The run of length ``T`` from ``x`` (raises NoPeriodicResponse where it fails)."""
        if not (np.isfinite(T) and T > 0) or not np.all(np.isfinite(x)):
            raise NoPeriodicResponse(f"no run from a period {T:g} or a state {x}")
        model, _ = self.at(p)
        settings = SolverSettings(
            t_end=float(T), rtol=RTOL, atol=RTOL, dt=T / 50, t_discard=0.0, backend=self.backend
        )
        try:
            run = integrate_events(
                model, settings, y0=np.array(x, dtype=float), max_step=rest_step(model)
            )
        except StepTooSmall as err:
            raise NoPeriodicResponse(f"cycle's flow: {err}") from None
        if run.status != "done":
            raise NoPeriodicResponse(f"cycle's flow: {run.message}")
        return run

    def image(self, x, T: float, p: float, monodromy: bool = True) -> FlowImage:
        """``phi_T(x; p)``, its Jacobian in ``x`` (``monodromy``) and the field there."""
        run = self.run(x, T, p)
        tr = run.trajectory
        end = tr.state(np.array([T]))[:, 0]
        M = variational.monodromy(run, self.backend).matrix if monodromy else None
        f = self.field(p, end, Mode(int(tr.mode(np.array([T]))[0])))
        return FlowImage(end, M, f, run)

    def largest_vr(self, x, T: float, p: float) -> float:
        """The largest ``Vr = X1' - Vb`` over the run of length ``T`` from ``x``."""
        run = self.run(x, T, p)
        return _extreme(run.trajectory, T, 1, 1) - self.at(p)[0]["Vb"]

    def p_column(self, x, T: float, p: float) -> NDArray[np.float64]:
        """``d phi/dp`` and ``dh/dp`` at ``(x, T, p)`` (5,), central differences."""
        h = P_STEP * max(1.0, abs(p))
        up = self.image(x, T, p + h, monodromy=False).state
        try:
            down, width = self.image(x, T, p - h, monodromy=False).state, 2 * h
            h_down = self.section(x, p - h)
        except NoPeriodicResponse:  # at the edge of the domain: one-sided
            down, width, h_down = self.image(x, T, p, monodromy=False).state, h, self.section(x, p)
        dh = (self.section(x, p + h) - h_down) / width
        return np.append((up - down) / width, dh)

    def section(self, x, p: float) -> float:
        """The phase condition ``h(x) = f_k(x)`` (the field of the mode at ``x``)."""
        return float(self.field(p, x)[self.k])

    def section_gradient(self, x, p: float) -> NDArray[np.float64]:
        """``dh/dx`` by central differences in the mode of ``x``."""
        _, sw = self.at(p)
        mode = sw.initial_mode(0.0, x)
        g = np.empty(4)
        for i in range(4):
            d = X_STEP * max(1.0, abs(float(x[i])))
            e = np.zeros(4)
            e[i] = d
            g[i] = (self.field(p, x + e, mode)[self.k] - self.field(p, x - e, mode)[self.k]) / (
                2 * d
            )
        return g
