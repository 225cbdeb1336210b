"""The event-driven integration of any model's hybrid system, with its monodromy.

A run goes mode by mode (`beltmdsm.oscillator.system`: +-1 slip, 0 stick, 2 flight),
each integrated by DOP853 (`beltmdsm.oscillator._stepper`) until the first crossing of
a surface that ends it, located on the dense output by the Illinois method
(`beltmdsm.integrate._roots`). A touch of a guard shorter than the samples (the
start of a short stick, a brief excursion of the holding force past the static limit,
a brief take-off) is found by an error model, not by samples (`guards.touch`): the guard's
polynomial on the step and the error its values show (`beltmdsm.oscillator._dips`)
clear what cannot reach 0; where it may, the guard's minimum is bracketed by a sign
change of its rate along the mode's field: ``m slip_acceleration`` for the slip guard,
and for the others the derived ``surface_rates`` of the module's ``SURFACES``
(``stick_back`` or ``stick_forward`` by the sign of the holding force, ``gap``). In
stick the field does not see the excitation of the held direction, which moves the
holding force: the two sides of the cone (``stick_forward``,
``stick_back``) are integrated beside the state as quadratures of their rates, so that
the step-size control resolves the stick guard as it does the state.

The surfaces and the choice of the next mode are the contract's, read through the
model's kernels only:

* slip in the sign ``m`` ends where ``m v_r`` falls to 0; there the mass sticks where
  ``|holding_force| <= stick_limit``, else the slip reverses;
* stick ends where ``|holding_force|`` exceeds ``stick_limit``; the slip starts in the
  sign in which the free motion accelerates (``-sgn(holding_force)``, the friction
  then acting as the holding force did);
* where the module is ``UNILATERAL``, contact ends where ``gap`` rises through 0
  (take-off: flight) and flight ends where it falls to 0 (landing: slip in the sign of
  the slip velocity, or stick at 0 inside the friction cone).

Entering stick, the state is projected onto ``v_r = 0`` along the slip velocity's
gradient (the form is linear), so a long stick does not drift off it. Accumulating
switches (`beltmdsm.integrate.zeno`: ``ZENO_SWITCHES`` within ``ZENO_WINDOW``) on
``v_r = 0`` inside the friction cone enter stick (Filippov's sliding motion); anywhere
else the run stops with status ``"zeno"``.

With ``variational=True`` the run carries the fundamental matrix ``Phi`` (``Phi' = J
Phi``, J the mode's derived Jacobian), and at every switch multiplies it by the
module's saltation matrix: the monodromy of a periodic orbit, whose eigenvalues are
its Floquet multipliers.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import StepTooSmall
from ..integrate.zeno import ZENO_SWITCHES, ZENO_WINDOW
from ..model import Backend
from . import _compiled, _stepper, guards
from .guards import initial_mode  # public here since issue 39 (its home: guards)
from .system import STICK, System

__all__ = ["Trajectory", "simulate", "flow", "Flow", "initial_mode"]

#: Switch = (t, mode before, mode after).
Switch = tuple[float, int, int]


@dataclass(repr=False)
class Flow:
    """The end of a run from one state (what shooting needs).

    Attributes
    ----------
    t, y, mode : float, ndarray (2n,), int
        Where the run ended, in which mode.
    switches : list of (t, before, after)
    monodromy : ndarray (2n, 2n) or None
        ``d y(t) / d y(t0)`` with the saltation matrices, where asked for.
    status : str
        ``"done"``, ``"stopped"`` (the ``stop`` condition met) or ``"zeno"``.
    message : str
    """

    t: float
    y: NDArray[np.float64]
    mode: int
    switches: list[Switch]
    monodromy: NDArray[np.float64] | None
    status: str
    message: str = ""


@dataclass(repr=False)
class Trajectory:
    """A run of a model's hybrid system, sampled.

    Attributes
    ----------
    system : System
    t : ndarray (k,)
        Sample times, every ``dt`` from the start, and the end.
    y : ndarray (2n, k)
        The states, rows named by ``states``.
    modes : ndarray (k,) of int
        The mode at each sample.
    switches : list of (t, before, after)
        Every switch of mode.
    status, message : str
        ``"done"`` or ``"zeno"`` (accumulating switches outside the friction cone),
        and what happened.

    See Also
    --------
    simulate : makes it.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> run = simulate(System("belt_1dof", friction="static_kinetic", Vb=1.0), 10.0)
    >>> run  # doctest: +ELLIPSIS +NORMALIZE_WHITESPACE
    Trajectory(System('belt_1dof', ...); 501 samples of x, x_dot to t = 10 s;
    3 switches, 2 sticks; done)
    >>> run["x"].shape, sorted({int(m) for m in run.modes})
    ((501,), [-1, 0])
    """

    system: System
    t: NDArray[np.float64]
    y: NDArray[np.float64]
    modes: NDArray[np.int64]
    switches: list[Switch] = field(default_factory=list)
    status: str = "done"
    message: str = ""

    @property
    def states(self) -> tuple[str, ...]:
        return self.system.states

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        """One state's samples by its name."""
        return self.y[self.states.index(name)]

    def __repr__(self) -> str:
        sticks = sum(1 for _, _, after in self.switches if after == STICK)
        return (
            f"Trajectory({self.system!r}; {self.t.size} samples of {', '.join(self.states)} "
            f"to t = {self.t[-1]:.6g} s; {len(self.switches)} switches, {sticks} sticks; "
            f"{self.status})"
        )


def flow(
    system: System,
    t0: float,
    y0: ArrayLike,
    t_end: float,
    *,
    mode: int | None = None,
    variational: bool = False,
    stop: Callable[[Switch, int], bool] | None = None,
    dt: float | None = None,
    rtol: float = 1e-10,
    atol: float = 1e-10,
    samples: list | None = None,
    backend: Backend | None = None,
) -> Flow:
    """Run from ``(t0, y0)`` to ``t_end``, or to the first switch where ``stop(switch,
    count)`` holds (``count`` switches so far, this one included).

    ``samples``: a list to which ``(t, y, mode)`` of the samples every ``dt`` from ``t0``
    are appended, step by step (``t`` (k,), ``y`` (k, 2n)). ``backend``: "python",
    "numba" or None (numba where installed and the kernels compile); the variational
    run is plain Python.
    """
    k, p = system.kernels, system.p
    m = len(system.states)
    y = np.array(y0, dtype=float)
    t = float(t0)
    fast = None
    if backend != "python" and not variational:
        fast = _compiled.compiled(system.module, system.friction, backend == "numba")
        if fast is None and backend == "numba":
            raise ValueError(
                "backend='numba': numba is not installed, the model's module is not "
                "importable by its name, or numba cannot compile its kernels"
            )
    if fast is not None and dt is not None and math.isfinite(t_end):
        out_t = np.empty(int((t_end - t0) / dt) + 2)
        out_y = np.empty((out_t.size, m))
    else:
        out_t, out_y = np.empty(0), np.empty((0, m))
    k_next = 0
    mode = guards.initial_mode(system, t, y) if mode is None else int(mode)
    if mode == STICK:
        y = guards.to_stick(system, t, y)
    Phi = np.eye(m) if variational else None
    switches: list[Switch] = []
    recent: deque[float] = deque(maxlen=ZENO_SWITCHES)
    h_abs = 0.0
    next_sample = t if dt is not None else math.inf
    status, message = "done", ""
    while True:
        md, quad = mode, guards.quadratures(system, mode)
        if variational:

            def base(s, z, md=md):
                Pz = z[m : m + m * m].reshape(m, m)
                jac = np.asarray(k.jacobian(s, z[:m], p, md))
                return np.concatenate((k.field(s, z[:m], p, md), (jac @ Pz).ravel()))

            z = np.concatenate((y, Phi.ravel()))
        else:

            def base(s, z, md=md):
                return np.asarray(k.field(s, z[:m], p, md), dtype=float)

            z = y
        if quad:
            # the stick guard's sides as quadratures of their rates (module docstring)
            def fun(s, z, base=base, md=md, quad=quad):
                rates = np.asarray(k.surface_rates(s, z[:m], p, md), dtype=float)[quad]
                return np.concatenate((base(s, z), rates))

            z = np.concatenate((z, np.asarray(k.surfaces(t, y, p), dtype=float)[quad]))
        else:
            fun = base
        surfaces = guards.surfaces(system, mode)
        rates = guards.rates(system, mode)
        u_old = [u(t, y) for u in surfaces]
        armed = [v > 0.0 for v in u_old]
        f = fun(t, z)
        if h_abs <= 0.0 and t < t_end:
            h_abs = _stepper.initial_step(fun, t, z, f, t_end, rtol, atol, t_end - t)
        hit, t_hit = -1, math.inf
        if fast is not None:
            k_prev = k_next
            status_, t, z, hit, h_abs, k_next = fast(
                p, mode, len(surfaces), t, z, t_end, h_abs, rtol, atol,
                dt if out_t.size else 0.0, t0, k_next, out_t, out_y,
            )  # fmt: skip
            if status_ == _compiled.STATUS_STEP_TOO_SMALL:
                raise StepTooSmall(
                    f"{system.name}: the step fell below the rounding of t = {t:.9g} s "
                    f"in mode {mode}",
                    rtol,
                    atol,
                )
            if samples is not None and k_next > k_prev:
                samples.append((out_t[k_prev:k_next], out_y[k_prev:k_next], mode))
        while fast is None and t < t_end:
            try:
                st, h_abs = _stepper.step(fun, t, z, f, h_abs, t_end, rtol, atol, math.inf)
            except ArithmeticError as err:
                raise StepTooSmall(f"{system.name}: {err} in mode {mode}", rtol, atol) from None
            hit, t_hit = -1, math.inf
            for j, u in enumerate(surfaces):
                tc, armed[j] = guards.crossing(u, rates[j], st, m, u_old[j], armed[j])
                if tc is not None and tc < t_hit:
                    hit, t_hit = j, tc
            t_stop = t_hit if hit >= 0 else st.t + st.h
            if samples is not None and next_sample <= t_stop:
                k0 = round((next_sample - t0) / dt)
                k1 = math.floor((t_stop - t0) / dt + 1e-9)
                ts = t0 + dt * np.arange(k0, k1 + 1)
                ts = ts[ts <= t_stop]
                if ts.size:
                    samples.append((ts, st.many(ts)[:, :m], mode))
                    next_sample = t0 + dt * (k0 + ts.size)
            if hit >= 0:
                z = st.at(t_hit) if t_hit > st.t else st.y
                t = t_hit
                break
            t, z, f = st.t + st.h, st.y_new, st.f_new
            u_old = [u(t, z[:m]) for u in surfaces]
        t = float(t)
        y = z[:m].copy()
        if variational:
            Phi = z[m : m + m * m].reshape(m, m).copy()
        if hit < 0:
            break
        after = guards.next_mode(system, mode, hit, t, y)
        recent.append(t)
        if len(recent) == ZENO_SWITCHES and recent[-1] - recent[0] <= ZENO_WINDOW * max(
            1.0, abs(t)
        ):
            inside = abs(k.holding_force(t, y, p)) <= k.stick_limit(t, y, p)
            if hit == 0 and mode in (-1, 1, STICK) and inside:
                after = STICK  # Filippov's sliding motion: the limit of the chattering
                recent.clear()
            else:
                status = "zeno"
                message = (
                    f"{ZENO_SWITCHES} switches within {ZENO_WINDOW:g} s at t = {t:.9g} s "
                    f"(mode {mode}, surface {hit}) outside the friction cone: the run stops"
                )
                break
        if len(switches) >= ZENO_SWITCHES and all(s[0] == t for s in switches[-ZENO_SWITCHES:]):
            # the modes cycle at one instant inside the cone (outside it the rule above
            # stopped the run): no step can decide the next mode there
            if t_end - t <= rtol * max(1.0, abs(t_end)):
                break  # the time left is below the run's resolution: it ends here
            status = "zeno"
            message = (
                f"{ZENO_SWITCHES} switches at t = {t:.9g} s without the time advancing "
                f"(mode {mode} -> {after}): the run stops"
            )
            break
        if variational:
            Phi = np.asarray(k.saltation(t, y, p, mode, after)) @ Phi
        if after == STICK:
            y = guards.to_stick(system, t, y)
        switches.append((t, mode, after))
        mode = after
        if stop is not None and stop(switches[-1], len(switches)):
            status = "stopped"
            break
    if samples is not None and (not samples or samples[-1][0][-1] < t):
        samples.append((np.array([t]), y[None, :].copy(), mode))
    return Flow(t, y, mode, switches, Phi, status, message)


def simulate(
    system: System,
    t_end: float,
    y0: ArrayLike | None = None,
    *,
    dt: float = 0.02,
    rtol: float = 1e-10,
    atol: float = 1e-10,
    backend: Backend | None = None,
) -> Trajectory:
    """A run of the model's hybrid system from ``y0`` over ``[0, t_end]``.

    Parameters
    ----------
    system : System
        The model, its friction law and parameters.
    t_end : float
        The end time [s], > 0.
    y0 : array_like (2n,), optional
        The initial state in the order of ``system.states``; rest (zeros) by default.
    dt : float
        The sampling step [s], > 0.
    rtol, atol : float
        The integrator's tolerances, > 0.
    backend : {"python", "numba", None}
        None: compiled by numba where it is installed and compiles the model's kernels
        (`beltmdsm.oscillator._compiled`: cached on disk after the first run), else
        plain Python; the same method and numbers to the tolerances.

    Returns
    -------
    Trajectory

    Raises
    ------
    ValueError
        ``t_end``, ``dt``, ``rtol`` or ``atol`` not a positive number, or ``y0`` not
        ``2n`` finite numbers.
    StepTooSmall
        Where the integrator cannot go on at the tolerances.

    See Also
    --------
    beltmdsm.simulate : the paper's model, with its spectra and summary.
    beltmdsm.oscillator.self_excited_cycle : the cycle such a run settles on.

    Examples
    --------
    >>> from beltmdsm.oscillator import System, simulate
    >>> run = simulate(System("belt_1dof", friction="stribeck", Vb=1.5), t_end=40.0)
    >>> run.states, run.y.shape
    (('x', 'x_dot'), (2, 2001))
    >>> run.status, any(after == 0 for _, _, after in run.switches)  # it sticks
    ('done', True)
    """
    for name, value in (("t_end", t_end), ("dt", dt), ("rtol", rtol), ("atol", atol)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise ValueError(f"{name}={value!r}: not a positive number")
    m = len(system.states)
    if y0 is None:
        y0 = np.zeros(m)
    y0 = np.asarray(y0, dtype=float)
    if y0.shape != (m,) or not np.all(np.isfinite(y0)):
        raise ValueError(f"y0: not {m} finite numbers ({', '.join(system.states)})")
    samples: list = []
    end = flow(
        system, 0.0, y0, float(t_end), dt=float(dt), rtol=rtol, atol=atol, samples=samples,
        backend=backend,
    )  # fmt: skip
    t = np.concatenate([ts for ts, _, _ in samples])
    y = np.concatenate([ys for _, ys, _ in samples]).T
    modes = np.concatenate([np.full(ts.size, md, dtype=np.int64) for ts, _, md in samples])
    return Trajectory(system, t, y, modes, end.switches, end.status, end.message)
