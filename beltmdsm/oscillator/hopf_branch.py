"""The self-excited cycles born at a Hopf point of steady sliding, followed in the
parameter to the onset of stick.

A Hopf point (`beltmdsm.oscillator.hopf_points`) gives birth to a family of pure-slip
cycles on one side of it: on the side where steady sliding is stable (subcritical: the
cycles are unstable and no run finds them) or where it is unstable (supercritical).
`hopf_branch` seeds the shooting a little way into each side, from steady sliding
moved along the real part of the critical eigenvector by amplitudes ``1 .. 0.01`` (in
units of the state's scale), with the period ``2 pi / omega`` of the critical pair;
Newton's method from a small amplitude may fall back onto the equilibrium itself,
which is rejected (a cycle must stand off it). From the first cycle found, the branch
is followed by shooting each value from the last to `stick_onset`, where the cycle
first touches ``v_r = 0``.

Where the slip mode's field is linear in the state (Coulomb friction, a constant
coefficient, with a normal force linear in the state: Hoffmann's model; the model
module's derived ``LINEAR_SLIP``, derive/models/linearity.py), the Hopf point is
degenerate: there the pure-slip cycles form a linear centre, of every amplitude up to
the one that grazes ``v_r = 0``, and off it none exists. The cycles born there stick at once: on the
unstable side the branch is one of stick-slip cycles, seeded from the grazing orbit of
the centre and followed away from the Hopf point (``degenerate``, the reason in
``note``; its onset of stick is the Hopf point itself).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import NoPeriodicResponse, Unsupported
from .cycle import Cycle
from .cycles import self_excited_cycle
from .equilibria import steady_sliding
from .hybrid import flow
from .onset import stick_onset
from .slip_shooting import _shoot_slip
from .system import System

__all__ = ["HopfBranch", "hopf_branch"]

#: Amplitudes of the seed along the critical eigenvector, in units of the state's scale.
_AMPLITUDES = (1.0, 0.3, 0.1, 0.03, 0.01)
#: How far into a side the seed is taken, as fractions of the range.
_OFFSETS = (0.01, 0.03)
#: A cycle stands off the equilibrium by more than this (relative).
_OFF = 1e-6
#: The step along the branch, as a fraction of the range, and the most steps.
_STEP, _MAX_STEPS = 0.02, 200


@dataclass(repr=False)
class HopfBranch:
    """The cycles born at one Hopf point.

    Attributes
    ----------
    hopf : float
        The parameter's value at the Hopf point.
    side : int
        +1 where the cycles lie above it, -1 below, 0 where none was found.
    cycles : list of Cycle
        Along the branch, from the seed to the onset.
    onset : Cycle or None
        The grazing cycle (``onset.system.params[param]`` the onset of stick).
    failure : str
        Why the branch or its onset was not found, if so.
    degenerate : bool
        The slip field is linear (module docstring): the cycles are stick-slip ones,
        born at the Hopf point from the grazing orbit of a linear centre.
    note : str
        Why, where ``degenerate``.

    See Also
    --------
    hopf_branch : makes it.

    Examples
    --------
    >>> b = HopfBranch("mu_s", 0.63375, 0, failure="no pure-slip cycle found near it")
    >>> b.criticality, b.onset is None, b.failure
    ('', True, 'no pure-slip cycle found near it')
    """

    param: str
    hopf: float
    side: int
    cycles: list[Cycle] = field(default_factory=list)
    onset: Cycle | None = None
    failure: str = ""
    degenerate: bool = False
    note: str = ""

    @property
    def criticality(self) -> str:
        """``"subcritical"`` where the cycles are unstable, ``"supercritical"`` where
        stable, ``"degenerate"`` at a linear centre, ``""`` where none was found."""
        if not self.cycles:
            return ""
        if self.degenerate:
            return "degenerate"
        return "supercritical" if self.cycles[0].stable else "subcritical"

    def __repr__(self) -> str:
        onset = (
            f"stick onset at {self.param} = {self.onset.system.params[self.param]:.10g}"
            if self.onset is not None
            else "stick-slip cycles from the Hopf point on (a linear centre there)"
            if self.degenerate
            else f"no stick onset ({self.failure})"
        )
        return (
            f"HopfBranch({self.param} = {self.hopf:.10g}; {self.criticality or 'no cycles'}, "
            f"{len(self.cycles)} cycles; {onset})"
        )


def _seed(system: System, param: str, value: float) -> Cycle | None:
    s = system.replace(**{param: value})
    eq = steady_sliding(s)
    w, V = np.linalg.eig(np.asarray(s.kernels.jacobian(0.0, eq.state, s.p, eq.mode)))
    pair = np.flatnonzero(np.abs(w.imag) > 1e-12)
    if not pair.size:
        return None
    i = pair[np.argmax(w.real[pair])]
    v = V[:, i].real / np.abs(V[:, i].real).max()
    scale = 1.0 + np.abs(eq.state).max()
    for a in _AMPLITUDES:
        try:
            c = self_excited_cycle(s, eq.state + a * scale * v, 2 * np.pi / abs(w[i].imag))
        except NoPeriodicResponse:
            continue
        if c.kind == "slip" and np.abs(c.state - eq.state).max() > _OFF * scale:
            return _least_speed(c)
    return None


def _least_speed(c: Cycle) -> Cycle:
    """The cycle shot again from where its slip speed is least (the section
    ``slip_acceleration = 0`` has a second point, where it is largest, which Newton's
    method may have found; `stick_onset` follows the least)."""
    k, p = c.system.kernels, c.system.p
    samples: list = []
    flow(c.system, 0.0, c.state, c.period, mode=c.mode, dt=c.period / 2000, samples=samples)
    ys = np.concatenate([y for _, y, _ in samples])
    speed = [c.mode * k.slip_velocity(0.0, y, p) for y in ys]
    tol = dict(rtol=1e-11, atol=1e-11)
    return _shoot_slip(c.system, ys[int(np.argmin(speed))], c.period, 30, tol)


def _linear_slip(system: System) -> bool:
    """Whether the slip modes' fields are affine in the state under the system's law: the
    model module's derived ``LINEAR_SLIP`` (derive/models/linearity.py); a module typed
    by hand without it is refused, never guessed."""
    flags = getattr(system.module, "LINEAR_SLIP", None)
    if flags is None:
        raise Unsupported(
            f"hopf_branch: model {system.name!r}: its module has no LINEAR_SLIP "
            "(MODEL_CONTRACT.md): whether its slip field is linear decides a degenerate "
            "Hopf point"
        )
    return bool(flags[system.friction])


def _grazing_orbit(system: System, eq) -> NDArray[np.float64]:
    """The state of the linear centre's orbit that grazes ``v_r = 0`` where its slip
    velocity is largest: steady sliding plus ``A Re(v e^{i theta})`` along the critical
    eigenvector ``v``, ``A |g . v| = |v_r|`` at steady sliding (``g`` the slip gradient)."""
    k, p = system.kernels, system.p
    w, V = np.linalg.eig(np.asarray(k.jacobian(0.0, eq.state, p, eq.mode), dtype=float))
    pair = np.flatnonzero(np.abs(w.imag) > 1e-12)
    v = V[:, pair[np.argmax(w.real[pair])]]  # the critical pair's
    g = np.asarray(k.slip_gradient(0.0, eq.state, p), dtype=float)
    gv = complex(g @ v)
    turn = -eq.mode * np.conj(gv) / abs(gv)  # v_r's swing towards 0
    amplitude = abs(k.slip_velocity(0.0, eq.state, p)) / abs(gv)
    return eq.state + amplitude * (v * turn).real


def _sticking_branch(system, param, hopf, stop) -> HopfBranch:
    """The stick-slip cycles born at a degenerate Hopf point (module docstring), from
    ``hopf`` towards ``stop`` on its unstable side."""
    side = 1 if stop > hopf else -1
    centre = steady_sliding(system.replace(**{param: hopf}))
    seed = 0.999 * (_grazing_orbit(centre.system, centre) - centre.state) + centre.state
    note = (
        f"the slip field is linear in the state (friction {system.friction!r}): at "
        f"{param} = {hopf:.10g} the pure-slip cycles form a linear centre up to the one "
        "that grazes v_r = 0, and none exists off it; the cycles born there stick"
    )
    branch = HopfBranch(param, hopf, side, degenerate=True, note=note)
    step = (stop - hopf) / 10
    last = None
    for j in range(1, 11):
        value = hopf + j * step
        try:
            last = self_excited_cycle(
                system.replace(**{param: float(value)}),
                seed if last is None else last.state,
                settle=50.0,
            )
        except NoPeriodicResponse as err:
            branch.failure = f"at {param} = {value:.10g}: {err}"
            break
        branch.cycles.append(last)
    return branch


def hopf_branch(
    system: System,
    param: str,
    hopf: float,
    span: float,
    bounds: tuple[float, float] | None = None,
) -> HopfBranch:
    """The cycles born at ``hopf`` and their stick onset (module docstring).

    Parameters
    ----------
    system : System
        Unforced.
    param : str
    hopf : float
        A Hopf point in ``param`` (`beltmdsm.oscillator.hopf_points`).
    span : float
        The length of the range looked in, > 0 (the seeds sit 1 % and 3 % of it off the
        Hopf point; the branch is stepped along by 2 % of it).
    bounds : (float, float), optional
        The range looked in: a degenerate branch (module docstring) is followed to its
        end on the Hopf point's unstable side (by default ``span`` beyond the Hopf point).

    Returns
    -------
    HopfBranch

    Examples
    --------
    The subcritical branch of the Stribeck belt (about 30 s: each cycle is shot with
    its variational equations in Python; ``branch --model belt_1dof`` in
    tests/beltmdsm/cli/test_model_flag.py runs it):

    >>> from beltmdsm.oscillator import System

    >>> b = hopf_branch(System("belt_1dof", friction="stribeck"), "Vb", 1.9957202, 4.5)
    ... # doctest: +SKIP
    >>> b.criticality, round(b.onset.system.params["Vb"], 6)  # doctest: +SKIP
    ('subcritical', 2.900393)
    """
    eq_above = steady_sliding(system.replace(**{param: hopf + 0.01 * span}))
    if _linear_slip(system):
        unstable = -1 if eq_above.stable else 1
        end = hopf + unstable * span if bounds is None else bounds[unstable > 0]
        return _sticking_branch(system, param, hopf, end)
    # the stable side first: a subcritical branch, which no run finds
    sides = (1, -1) if eq_above.stable else (-1, 1)
    for side in sides:
        for frac in _OFFSETS:
            seed = _seed(system, param, hopf + side * frac * span)
            if seed is not None:
                break
        if seed is not None:
            break
    else:
        return HopfBranch(param, hopf, 0, failure="no pure-slip cycle found near it")
    branch = HopfBranch(param, hopf, side, [seed])
    # march away from the Hopf point, each cycle shot from the last, the step halved
    # where the shooting fails (near the Hopf point the amplitude grows like the root
    # of the distance) and grown where it succeeds, until it fails at the least step
    # (past the onset the run from the last cycle switches); then the onset by the
    # secant of the least slip speed from the last cycle
    h, h_max, h_min = side * _STEP * span, side * _STEP * span, side * _STEP * span / 8
    last = seed
    for _ in range(_MAX_STEPS):
        value = last.system.params[param] + h
        try:
            last = _shoot_slip(
                last.system.replace(**{param: float(value)}), last.state, last.period, 30,
                dict(rtol=1e-11, atol=1e-11),
            )  # fmt: skip
        except NoPeriodicResponse:
            if abs(h) <= abs(h_min):
                break
            h = 0.5 * h
            continue
        branch.cycles.append(last)
        h = side * min(abs(h_max), 1.5 * abs(h))
    # the secant from a cycle a few steps back, a full step away (right at the onset
    # the least slip speed is too flat in the step to bracket it)
    back = branch.cycles[max(0, len(branch.cycles) - 4)]
    try:
        branch.onset = stick_onset(back, param, h_max)
    except NoPeriodicResponse as err:
        branch.failure = str(err)
        return branch
    branch.cycles.append(branch.onset)
    return branch
