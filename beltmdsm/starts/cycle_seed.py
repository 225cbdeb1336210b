"""The seed of a self-excited cycle: a run off unstable steady sliding, read on the section.

`seed_cycle` gives `beltmdsm.periodic.cycle.cycle` its first guess where none is
given: the state on the section (the extremum of ``X1'`` of largest ``|Vr|``,
`beltmdsm.periodic.cycle`) and the period, from a run of the autonomous model that
starts at steady sliding (the unforced equilibrium, Eq. 9) moved along its unstable
direction and goes on until its returns to the section repeat. `require_autonomous`
and `section_direction` are the checks and the orientation both share.

One of the starting states of `beltmdsm.starts`, at the layer of the periodic orbits
(tests/test_layers.py): `beltmdsm.periodic.cycle` shoots from it, so it imports nothing
above them. It was ``beltmdsm.periodic.cycle_seed`` and ``beltmdsm.cycles.seed`` before;
those paths still import (issue 38).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from beltmdsm.generated import unforced

from .._calling import public
from ..errors import NoPeriodicResponse
from ..excitation import initial_state, is_autonomous
from ..integrate.switching import SURFACE_INDEX, Mode, Switching
from ..model import Backend, Model, as_model
from ..periodic.cycle_returns import run_from, section_returns, stick_slip_start
from ..settings import SETTLE_TOL

__all__ = [
    "seed_cycle",
    "require_autonomous",
    "section_direction",
    "unstable_pair",
    "stick_end",
    "SEED_AMPLITUDE",
    "SEED_PERIODS",
    "SETTLE_TOL",
]

#: The seed's perturbation of steady sliding along its unstable direction: the
#: velocity ``X1'`` moved by this fraction of ``|Vb|``.
SEED_AMPLITUDE = 1e-2
#: The seed's run lasts at most this many periods of the unstable pair
#: (``2 pi / Im lambda``), in chunks of 10 periods doubling up to `_SEED_CHUNK` (a cycle
#: reached early is read early); a run of 300 s costs about
#: 15 ms compiled, so the bound is generous: from `SEED_AMPLITUDE` at a growth rate of
#: 0.01 1/s (Vb = 1.9, next to the Hopf point of the base Stribeck set) the cycle is
#: reached in about 80 periods.
SEED_PERIODS = 3000
_SEED_CHUNK = 50
#: The seed's run has decayed to steady sliding when ``X1'`` varies by less than this
#: fraction of ``|Vb|`` over a chunk: far above the run's rounding (its tolerance, 1e-10,
#: leaves X1' a floor of a few 1e-9), and a cycle that small exists only within about
#: 1e-12 of a Hopf point (its amplitude grows like the square root of the distance).
_DECAYED = 1e-6
#: Samples per period of the unstable pair when the seed's run is searched for the section.
_SECTION_SAMPLES = 64
#: Extrema of the seed's run within this fraction of the orbit's velocity range of
#: the deepest one count as the section (the others are lesser extrema of the cycle).
_DEEP = 1e-3


def require_autonomous(model: Model, analysis: str = "a self-excited cycle") -> None:
    """Raise ValueError (one line) unless the model has no excitation and a moving belt.

    Parameters
    ----------
    model : Model
        The model.
    analysis : str
        The analysis that asks, named in the message.

    Raises
    ------
    ValueError
        For a forced model (its periodic responses have the excitation's period).
    beltmdsm.errors.NoPeriodicResponse
        At ``Vb = 0``: nothing feeds a self-excited cycle.

    See Also
    --------
    beltmdsm.excitation.is_autonomous : Whether the model is forced.

    Examples
    --------
    >>> require_autonomous(Model(alpha=0.0, Vb=1.5))
    >>> try:
    ...     require_autonomous(Model(), "demo")
    ... except ValueError as refusal:
    ...     print(refusal)
    demo: the model is forced (alpha_t Omega_t or alpha_n Omega_n is not zero): ...
    >>> try:
    ...     require_autonomous(Model(alpha=0.0, Vb=0.0), "demo")
    ... except NoPeriodicResponse as refusal:
    ...     print(refusal)
    no self-excited cycle at Vb = 0: the belt is at rest and nothing feeds one (demo)
    """
    if not is_autonomous(model):
        raise ValueError(
            f"{analysis}: the model is forced (alpha_t Omega_t or alpha_n Omega_n is not "
            "zero): its periodic responses have the excitation's period "
            "(beltmdsm.periodic.shooting.periodic_response)"
        )
    if model["Vb"] == 0:
        raise NoPeriodicResponse(
            f"no self-excited cycle at Vb = 0: the belt is at rest and nothing feeds one "
            f"({analysis})"
        )


def section_direction(model: Model) -> int:
    """``sgn(Vr)`` while sliding steadily, ``-sgn(Vb)``: the slip mode code of the section.

    The section is the extremum of ``X1'`` on this side: a minimum for ``Vb > 0``.

    Parameters
    ----------
    model : Model
        The model.

    Returns
    -------
    int
        -1 (slip back) for ``Vb > 0``, else 1.

    See Also
    --------
    beltmdsm.starts.cycle_seed.stick_end : The edge of the friction cone on this side.

    Examples
    --------
    >>> section_direction(Model(alpha=0.0, Vb=1.5)), section_direction(Model(alpha=0.0, Vb=0.0))
    (-1, 1)
    """
    return -1 if model["Vb"] > 0 else 1


def unstable_pair(model: Model) -> tuple[complex, NDArray[np.complex128]]:
    """The eigenvalue of steady sliding with the largest real part and its eigenvector.

    Parameters
    ----------
    model : Model
        Without excitation.

    Returns
    -------
    eigenvalue : complex
        Of `beltmdsm.generated.unforced.jacobian_at_equilibrium`.
    eigenvector : numpy.ndarray, shape (4,), complex
        Unit 2-norm (numpy's normalisation).

    See Also
    --------
    beltmdsm.cycles.hopf.eigenvalues_over : The closed-form eigenvalues.

    Examples
    --------
    Stribeck friction at ``Vb = 1.5``, below its Hopf point (1.9957): the tangential
    pair grows at 0.0642 1/s, and its eigenvector has no normal component (``J^0`` is
    block triangular):

    >>> lam, v = unstable_pair(Model(friction="stribeck", alpha=0.0, Vb=1.5))
    >>> round(lam.real, 4), round(abs(lam.imag), 4), np.round(np.abs(v[2:]), 12).tolist()
    (0.0642, 0.9979, [0.0, 0.0])
    """
    J = np.array(
        unforced.jacobian_at_equilibrium(**model.arguments(unforced.jacobian_at_equilibrium)),
        dtype=float,
    ).reshape(4, 4)
    lam, V = np.linalg.eig(J)
    k = int(np.argmax(lam.real))
    return complex(lam[k]), V[:, k]


@public(models=True)
def seed_cycle(
    model: Model | Mapping[str, Any],
    *,
    t_end: float | None = None,
    perturbation: ArrayLike | None = None,
    backend: Backend | None = None,
) -> tuple[NDArray[np.float64], float]:
    """A state on the section and a period estimate, from a run off steady sliding.

    The run starts at the unforced equilibrium (Eq. 9) moved by ``perturbation``, or
    where none is given along the real part of the eigenvector of the most unstable
    eigenvalue of steady sliding (`beltmdsm.generated.unforced.jacobian_at_equilibrium`), its
    velocity by `SEED_AMPLITUDE` of ``|Vb|``. Where steady sliding is stable and no
    perturbation is given, the run starts where a stick ends instead (`stick_end`):
    every stick-slip cycle passes there, so a stick-slip cycle that coexists with
    stable sliding is found (it is superstable: one slip phase later the run is on it),
    and where none does the run decays. Once the run sticks, the cycle is the run from
    that stick end to the next (`beltmdsm.periodic.cycle_returns.stick_slip_start`: one state,
    the least period); a chunk spent sticking has not decayed. Otherwise the run goes
    on in chunks until its returns to the section (module docstring) repeat to
    `SETTLE_TOL`; the period is the time between the last two returns that match
    (several turns where the cycle has several extrema of the same depth; `cycle`
    shortens a multiple of the least period).

    Another registered model than the paper's (``Model(model="belt_1dof")``) is seeded
    by the generic runtime (`beltmdsm.oscillator.cycle_seed`): a run of ``t_end``
    seconds (200 by default) off steady sliding, moved along its least stable direction
    (or by ``perturbation``) and then from the stick state over it, read at a stick end
    (its period the time over the sticks until they repeat) or at its least slip speed;
    the state has the model's ``2n`` states, and ``backend`` (the paper's integrators')
    is refused.

    Parameters
    ----------
    model : Model or dict
        Without excitation.
    t_end : float, optional
        The longest run [s]; default `SEED_PERIODS` periods of the unstable pair.
    perturbation : array_like (4,), optional
        The start's offset from the equilibrium (a cycle that coexists with stable
        steady sliding is reached only from far enough).
    backend : {"python", "numba", None}

    Returns
    -------
    state : ndarray (4,)
    period : float

    Raises
    ------
    ValueError
        For a forced model, a perturbation that is not 4 finite numbers, ``t_end <= 0``.
    NoPeriodicResponse
        Naming why: steady sliding is stable and no perturbation is given (a run from it
        decays to it), the run decays to steady sliding, stops, or does not settle on
        a cycle within ``t_end``.

    See Also
    --------
    beltmdsm.periodic.cycle.cycle : the cycle itself, by shooting from this seed.
    beltmdsm.cycles.hopf.hopf_point : where steady sliding loses stability.

    Examples
    --------
    A run off unstable steady sliding under Stribeck friction settles on the stick-slip
    cycle; `cycle` then shoots it exactly from the seed:

    >>> from beltmdsm import Model, cycle, seed_cycle
    >>> model = Model(friction="stribeck", alpha=0.0, Vb=1.5)
    >>> state, period = seed_cycle(model)
    >>> state.shape, round(period, 1)
    ((4,), 6.7)
    >>> round(cycle(model, guess=state, period=period).period, 3)
    6.654
    """
    model = as_model(model)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        return api.seed_cycle(model, t_end, perturbation, backend=backend)
    require_autonomous(model, "seed_cycle")
    vb = float(model["Vb"])
    lam, vec = unstable_pair(model)
    omega = abs(lam.imag) if abs(lam.imag) > 0 else float(model["omega1"])
    turn = 2 * math.pi / omega
    if t_end is None:
        t_end = SEED_PERIODS * turn
    if not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0; got {t_end!r}")
    x0 = initial_state(model)
    if perturbation is None and lam.real <= 0:
        stable = (
            f"no self-excited cycle from the equilibrium: steady sliding is stable at "
            f"Vb={vb:g} (largest real part of its eigenvalues {lam.real:.3g} 1/s), a run "
            "from it decays to it"
        )
        y = stick_end(model)
        if y is None:
            raise NoPeriodicResponse(f"{stable}; and no stick can end (an empty friction cone)")
        try:
            return _settle(model, y, "the end of a stick", t_end, turn, backend)
        except NoPeriodicResponse as err:
            why = str(err).replace("no self-excited cycle from the end of a stick: ", "")
            raise NoPeriodicResponse(
                f"{stable}; nor from the end of a stick (X1 at the friction limit, X1' = Vb): {why}"
            ) from None
    if perturbation is None:
        v = np.real(vec)
        if abs(v[1]) < 1e-3 * np.max(np.abs(v)):
            v = np.imag(vec)
        y = x0 + SEED_AMPLITUDE * abs(vb) * v / abs(v[1])
        start = f"the equilibrium perturbed along its unstable direction (lambda = {lam:.4g})"
    else:
        offset = np.array(perturbation, dtype=float).ravel()
        if offset.size != 4 or not np.all(np.isfinite(offset)):
            raise ValueError(f"perturbation must be 4 finite numbers; got {perturbation!r}")
        y = x0 + offset
        start = "the equilibrium perturbed as given"
    return _settle(model, y, start, t_end, turn, backend)


def stick_end(model: Model) -> NDArray[np.float64] | None:
    """The state where a stick ends: ``X1' = Vb``, ``X1`` at the edge of the friction cone
    on the section's side (the mass leaves against the belt's motion), the normal
    motion at its equilibrium. None where the cone has no such edge.

    The edge's switching function (`beltmdsm.generated.hybrid.surfaces`, ``stick_back`` for
    ``Vb > 0``) is affine in ``X1`` (the spring's force); its root is found by two
    secant steps and checked.

    Parameters
    ----------
    model : Model
        The model.

    Returns
    -------
    numpy.ndarray or None
        ``[X1, X1', X2, X2']``, or None.

    See Also
    --------
    beltmdsm.starts.cycle_seed.seed_cycle : Starts there where steady sliding is stable.

    Examples
    --------
    At ``Vb = 1.5`` the spring and the damper moving with the belt pull the mass
    back with ``omega1^2 X1 + 2 beta1 omega1 Vb``, held by ``mu_s g``: the stick ends at
    ``X1 = (0.4 x 9.81 - 2 x 0.1 x 1.5) / 1 = 3.624``:

    >>> [round(float(v), 4) for v in stick_end(Model(friction="stribeck", alpha=0.0, Vb=1.5))]
    [3.624, 1.5, 11.5474, 0.0]
    """
    sw = Switching(model)
    index = SURFACE_INDEX["stick_back" if section_direction(model) < 0 else "stick_forward"]
    y = initial_state(model)
    y[1] = model["Vb"]

    def edge(x1):
        return float(sw.surfaces(0.0, x1, *y[1:])[index])

    a, b = float(y[0]), float(y[0]) + 1.0
    fa, fb = edge(a), edge(b)
    for _ in range(2):
        if fb == fa:
            return None
        a, fa, b = b, fb, b - fb * (b - a) / (fb - fa)
        fb = edge(b)
    if not abs(fb) <= 1e-9 * (1.0 + float(sw.scales(0.0, b, *y[1:])[index])):
        return None
    y[0] = b
    return y


def _settle(model, y, start, t_end, turn, backend):
    """Run from ``y`` until the returns to the section repeat: ``(state, period)``.

    A run that sticks is on the stick-slip cycle through the stick end, if any
    (`beltmdsm.periodic.cycle_returns.stick_slip_start`): that cycle is shot from there, at its
    least period. A chunk spent sticking has ``X1'`` at the belt's speed throughout:
    it has not decayed to steady sliding.
    """
    vb = float(model["Vb"])
    x0 = initial_state(model)
    sw = Switching(model)
    d = section_direction(model)
    chunk = 10 * turn
    t, returns, first_amplitude, tried_stick = 0.0, [], None, False
    while t < t_end:
        t1 = min(t + chunk, t_end)
        chunk = min(2 * chunk, _SEED_CHUNK * turn)
        try:
            run = run_from(model, y, t, t1, backend, 1e-10)
        except NoPeriodicResponse as err:
            why = str(err).replace("no self-excited cycle found: ", "")
            raise NoPeriodicResponse(f"no self-excited cycle from {start}: {why}") from None
        tr = run.trajectory
        stuck = tr.time_in_modes(t, t1)[Mode.STICK] > 0
        if stuck and not tried_stick:
            tried_stick = True
            end = stick_end(model)
            found = None if end is None else stick_slip_start(model, end, d, t_end, backend)
            if found is not None:
                return found
        amplitude = _velocity_spread(tr, turn)
        if first_amplitude is None:
            first_amplitude = amplitude
        if amplitude <= _DECAYED * abs(vb) and not stuck:
            raise NoPeriodicResponse(
                f"no self-excited cycle from {start}: the run decays to steady sliding at "
                f"Vb={vb:g} (X1' varies by {amplitude:.1e} m/s at t = {t1:g} s)"
            )
        spans = [(seg.t0, seg.t1, seg.mode) for seg in tr.segments]
        returns += section_returns(sw, tr.state, spans, d, turn / _SECTION_SAMPLES)
        found = _settled(returns, amplitude, x0)
        if found is not None:
            return found
        t, y = t1, tr.state(np.array([t1]))[:, 0]
    trend = (
        "; its amplitude shrinks: it decays towards steady sliding"
        if amplitude < 0.5 * first_amplitude
        else ""
    )
    raise NoPeriodicResponse(
        f"no self-excited cycle from {start}: the run does not settle on a cycle in "
        f"{t_end:g} s (its returns to the section do not repeat to {SETTLE_TOL:g}){trend}"
    )


def _velocity_spread(tr, turn):
    """How much ``X1'`` varies over a run (sampled)."""
    t0 = tr.segments[0].t0
    t = np.linspace(t0, tr.t_end, int((tr.t_end - t0) / turn * 16) + 2)
    v = tr.state(t)[1]
    return float(np.max(v) - np.min(v))


def _settled(returns, amplitude, equilibrium):
    """``(state, period)`` where the last deepest return repeats an earlier one, else None.

    The deepest returns are those within `_DEEP` of the velocity's ``amplitude`` of the
    deepest of the last 20 (a cycle's lesser extrema of ``X1'`` are not its section).
    """
    recent = returns[-20:]
    if len(recent) < 2:
        return None
    top = max(r[2] for r in recent)
    deep = [r for r in recent if r[2] >= top - _DEEP * amplitude]
    t_last, x_last, _ = deep[-1]
    scale = float(np.max(np.abs(x_last - equilibrium)))
    for t_prev, x_prev, _ in reversed(deep[-9:-1]):
        if float(np.max(np.abs(x_last - x_prev))) <= SETTLE_TOL * scale:
            return x_last, float(t_last - t_prev)
    return None
