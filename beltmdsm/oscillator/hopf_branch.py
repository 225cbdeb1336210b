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
is walked away from the Hopf point on the one continuation driver
(`beltmdsm.continuation.driver`, the problem
`beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem`): by pseudo-arclength,
so that it passes a fold of cycles, with the folds, period doublings and
Neimark-Sacker points of the cycles' multipliers located on the way (``special``), to
the onset of stick, where the cycle first touches ``v_r = 0``.

This module sits above the continuation layer (tests/test_layers.py): it drives the
driver.

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

from ..continuation.driver import walk
from ..continuation.oscillator_cycle import OscillatorCycleProblem
from ..errors import NoPeriodicResponse, Unsupported
from .cycle import Cycle
from .cycles import self_excited_cycle
from .equilibria import steady_sliding
from .slip_shooting import least_speed
from .system import System

__all__ = ["HopfBranch", "hopf_branch"]

#: Amplitudes of the seed along the critical eigenvector, in units of the state's scale.
_AMPLITUDES = (1.0, 0.3, 0.1, 0.03, 0.01)
#: How far into a side the seed is taken, as fractions of the range.
_OFFSETS = (0.01, 0.03)
#: A cycle stands off the equilibrium by more than this (relative).
_OFF = 1e-6
#: The walk's range: this many times ``span`` either side of the Hopf point.
_REACH = 4.0


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
    special : list of SpecialPoint
        The special points of the walk along the branch
        (`beltmdsm.continuation.oscillator_cycle.DETECTS`), its end last.
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
    special: list = field(default_factory=list)
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
            return least_speed(c)
    return None


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
        Hopf point; the walk's range reaches `_REACH` times it either side).
    bounds : (float, float), optional
        The range looked in: a degenerate branch (module docstring) is followed to its
        end on the Hopf point's unstable side (by default ``span`` beyond the Hopf point).

    Returns
    -------
    HopfBranch

    Examples
    --------
    The subcritical branch of Hoffmann's model under Stribeck's law, walked to its stick
    onset:

    >>> from beltmdsm.oscillator import System, hopf_points
    >>> s = System("hoffmann", friction="stribeck")
    >>> b = hopf_branch(s, "Vb", float(hopf_points(s, "Vb", 0.2, 8.0)[0]), 0.1)
    >>> b.criticality, [(p.kind, round(p.value, 6)) for p in b.special]
    ('subcritical', [('stick_onset', 0.9689)])

    The Stribeck belt's (about 7 s of CPU: each cycle is run with its variational
    equations in Python; ``branch --model belt_1dof`` in
    tests/beltmdsm/cli/test_model_flag.py runs it):

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
    # walk away from the Hopf point on the driver, to the stick onset (or a fold, the
    # range's end, a failure); the cycles as the shooting reports them
    value = seed.system.params[param]
    sx = 1.0 + float(np.abs(seed.state).max())
    problem = OscillatorCycleProblem(
        seed.system, param, seed.mode, hopf - _REACH * span, hopf + _REACH * span, sx,
        seed.period,
    )  # fmt: skip
    try:
        first, tangent = problem.start(seed.state, seed.period, value, side)
    except NoPeriodicResponse as err:
        branch.failure = f"the first cycle does not correct: {err}"
        return branch
    points, special = problem.finish(*walk(problem, first, tangent))
    branch.cycles += [p.cycle() for p in points[1:]]
    branch.special = special
    if special[-1].kind == "stick_onset":
        branch.onset = branch.cycles[-1]
    else:
        branch.failure = f"no stick onset: the walk ends ({special[-1].kind}: {special[-1].detail})"
    return branch
