"""The normal motion of Eq. (4), once, with the tangential response to its contact force.

The normal equation of Eq. (4) contains neither ``X1``, ``X1'``, ``Vb`` nor
``mu_s``: the normal motion is fixed by the excitation alone. `NormalMotion`
integrates it once, together with ``z``, the response of the tangential oscillator
(from rest) to the contact force (`beltmdsm.generated.hybrid.response_field`), mode by mode
with located switches (loss of contact and touchdown; separation and recontact
under the clipped tension law), on the compiled DOP853 integrator of
`beltmdsm.integrate._dop853`. Every run of a sweep over ``Vb`` or ``mu_s`` reuses it
(`normal_motion` caches the last few), and `beltmdsm.integrate.superposition` builds the
tangential motion on it in closed form.

The motion is kept twice: as DOP853 dense output (exact to the integration
tolerance at any time), and sampled on a uniform grid for the superposition's scan
for switches.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import inspect
from collections import OrderedDict
from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from beltmdsm.generated import hybrid, oscillator

from ..model import Backend, Model
from ..settings import fastest_rate
from . import _compiled, _dop853
from .events import REST_STEP, check_status
from .switching import EVENT_KINDS, SURFACE_INDEX, Mode, Switching

__all__ = ["NormalMotion", "normal_motion", "normal_key", "clear_cache", "GRID_STEP"]

#: Grid of the scan for switches [s].
GRID_STEP = 0.005
_NORMAL_SURFACES = ("penetration", "contact_force")
#: How many normal motions `normal_motion` keeps.
_KEPT = 4
#: The friction law of the surface kernels that the normal motion binds (the generated
#: kernels' default). It watches the normal surfaces alone (penetration, contact force),
#: whose rows of the generated ``surfaces`` and ``surface_rates`` are the same under
#: every friction law (the normal equation is free of friction; tests/beltmdsm/integrate/
#: test_normal_kernels.py compares them bit for bit): bound with one law, its compiled
#: integrator is one per contact law, not one per friction and contact law (about 12 s of
#: compiling each with a cold cache).
NORMAL_FRICTION = inspect.signature(hybrid.bind_surface_rates).parameters["friction"].default


def normal_key(model: Model) -> tuple:
    """What the normal motion, ``z`` and the excitation response of ``model`` depend on.

    The parameters that the generated response field (the normal equation with the
    tangential response to its force) and the tangential excitation response take,
    as the generated code declares them, with the contact and tension laws: ``Vb``
    and ``mu_s`` are not among them, so a sweep over either shares one normal motion.

    Parameters
    ----------
    model : Model
        The model.

    Returns
    -------
    tuple
        The model's options, then ``(name, value)`` of each parameter the normal
        motion depends on, sorted by name.

    See Also
    --------
    beltmdsm.integrate.normal.normal_motion : Keeps normal motions by this key.

    Examples
    --------
    >>> key = normal_key(Model(Vb=1.5))
    >>> key[:3], [name for name, _ in key[3]][:4]
    (('coulomb', 'hertz_damp', 'allowed'), ['Omega_n', 'Omega_t', 'alpha_n', 'alpha_t'])
    >>> key == normal_key(Model(Vb=3.0, mu_s=0.3)), key == normal_key(Model(alpha_n=1.0))
    (True, False)
    """
    p = model.params
    names = _normal_names(model)
    return (*model.options.values(), tuple((k, float(p[k])) for k in names))


#: The parameter names of `normal_key` by the laws (`_normal_names`).
_NAMES: dict[tuple, tuple[str, ...]] = {}


def _normal_names(model):
    """The parameter names of `normal_key`: those the generated kernels declare. They
    depend on the contact law only (the variant bound), not on the values: found once
    per law, so that a continuation's trial points do not bind kernels to build a key."""
    laws = tuple(model.options.items())
    names = _NAMES.get(laws)
    if names is None:
        field, exc = hybrid.bind_response_field, oscillator.bind_excitation_response
        used = field(backend="python", **model.arguments(field)).params
        used |= exc(backend="python", **model.arguments(exc)).params
        names = _NAMES[laws] = tuple(sorted(used))
    return names


class NormalMotion:
    """The normal motion, ``z`` and the excitation response, from ``t = 0`` to ``t_end``.

    Attributes
    ----------
    switch_t : float array
        Times of the normal switches (the segment boundaries), with 0 and t_end.
    switch_mode : list of Mode
        The normal mode of each segment: ``Mode.SLIP_BACK`` stands for contact
        (the contact modes share the normal field), ``FLIGHT`` or ``SEPARATED``.
    switch_kind, switch_surface : list of str
        The event kind of each switch (`beltmdsm.integrate.switching.EVENT_KINDS`) and the
        surface crossed.
    t_steps, h_steps, y_steps, F_steps : arrays
        The DOP853 steps of all segments (state ``(z, z', X2, X2')``).
    grid : float array (n,)
        Uniform times, ``GRID_STEP`` apart (the segment boundaries added).
    on_grid : float array (6, n)
        ``z, z', X2, X2'`` and the excitation response ``zf, zf'`` at ``grid``.

    Parameters
    ----------
    model : Model
        The model (its normal motion does not depend on ``Vb`` or ``mu_s``).
    t_end : float
        The end [s].
    rtol, atol : float
        The integrator's tolerances.
    y0_normal : iterable of float
        The normal start ``X2, X2'``.
    backend : {"numba", "python"}, optional
        The kernels; None: numba if installed.
    grid_step : float
        The step of ``grid`` [s].

    Raises
    ------
    beltmdsm.errors.StepTooSmall
        Where the integrator fails (`beltmdsm.integrate.events.check_status`).

    See Also
    --------
    beltmdsm.integrate.normal.normal_motion : The same, kept for reuse.
    beltmdsm.integrate.superposition.Superposition : Builds the tangential motion on it.

    Examples
    --------
    A normal excitation of ``alpha_n = 8`` lifts the mass off the belt: contact and
    flight alternate, each switch a lift-off or a touchdown.

    >>> from beltmdsm.excitation import initial_state
    >>> model = Model(Vb=1.5, alpha_n=8.0)
    >>> y0 = initial_state(model)
    >>> motion = NormalMotion(model, 3.0, 1e-10, 1e-10, y0[2:], backend="python")
    >>> [round(float(t), 4) for t in motion.switch_t]
    [0.0, 0.7236, 1.5773, 2.4522, 2.8034, 3.0]
    >>> motion.switch_kind
    ['lift_off', 'touch_down', 'lift_off', 'touch_down']
    >>> [mode.name for mode in motion.switch_mode][:2]
    ['SLIP_BACK', 'FLIGHT']
    """

    def __init__(
        self,
        model: Model,
        t_end: float,
        rtol: float,
        atol: float,
        y0_normal: Iterable[float],
        backend: Backend | None = None,
        grid_step: float = GRID_STEP,
    ) -> None:
        self.model, self.t_end = model, float(t_end)
        field = hybrid.bind_response_field(
            backend=_compiled.scalar_backend(backend),
            **model.arguments(hybrid.bind_response_field),
        )
        sw = Switching(model)
        surfaces, rates = (
            bind(backend="python", **{**model.arguments(bind), "friction": NORMAL_FRICTION})
            for bind in (hybrid.bind_surfaces, hybrid.bind_surface_rates)
        )
        advance = _compiled.advance("response_field", model, backend, friction=NORMAL_FRICTION)
        guards = {}
        for mode in (Mode.SLIP_BACK, Mode.FLIGHT, Mode.SEPARATED):
            rows = [
                (SURFACE_INDEX[s], float(d), target)
                for s, d, target in sw.guards.get(mode, ((), (), ()))[2]
                if s in _NORMAL_SURFACES
            ]
            guards[mode] = (
                np.array([r[0] for r in rows], dtype=np.int64),
                np.array([r[1] for r in rows]),
                [r[2] for r in rows],
            )
        t, y = 0.0, np.array([0.0, 0.0, *y0_normal], dtype=float)
        mode = self._normal_mode(sw, t, y, entering=y[2] > 0 or (y[2] == 0 and y[3] > 0))
        switch_t, switch_mode, switch_kind, switch_surface, steps = [0.0], [mode], [], [], []
        h_next, n_steps = 0.0, 0
        while t < self.t_end:
            watch, dirs, targets = guards[mode]
            (code, n, ts, hs, ys, Fs, t_stop, y_stop, hit, h_next) = advance(
                field.args,
                surfaces.args,
                rates.args,
                float(mode),
                watch,
                dirs,
                t,
                y,
                self.t_end,
                h_next,
                rtol,
                atol,
                # at rest the steps grew without bound and amplified the rounding (to
                # 1e-9 m by t = 200 s at Vb = 0: a held mass then slipped; issue 36
                # item 11), as events.py found
                REST_STEP / fastest_rate(model),
                _dop853.MAX_STEPS - n_steps,
            )
            check_status(code, t_stop, "in the normal motion", rtol, atol)
            n_steps += n
            if n:
                steps.append((ts, hs, ys, Fs))
            t, y = float(t_stop), np.array(y_stop)
            if code == _dop853.STATUS_END:
                break
            target = targets[hit]
            if target in (hybrid.DECIDE_CONTACT,):
                mode = self._normal_mode(sw, t, y, entering=True)
            else:
                mode = Mode[target.upper()]
            surface = hybrid.SURFACES[watch[hit]]
            if surface == "penetration":
                y[2] = 0.0
            switch_t.append(t)
            switch_mode.append(mode)
            switch_kind.append(EVENT_KINDS[(surface, int(dirs[hit]))])
            switch_surface.append(surface)
        switch_t.append(self.t_end)
        self.switch_t = np.array(switch_t)
        self.switch_mode = switch_mode
        self.switch_kind = switch_kind
        self.switch_surface = switch_surface
        self.t_steps = np.concatenate([s[0] for s in steps])
        self.h_steps = np.concatenate([s[1] for s in steps])
        self.y_steps = np.concatenate([s[2] for s in steps])
        self.F_steps = np.concatenate([s[3] for s in steps])
        n_grid = int(np.ceil(self.t_end / grid_step - 1e-9))
        grid = np.union1d(np.linspace(0.0, self.t_end, n_grid + 1), self.switch_t)
        self.grid = grid
        exc = oscillator.bind_excitation_response
        zf, vf = exc(backend="python", **model.arguments(exc)).array(grid)
        self.on_grid = np.vstack([self.evaluate(grid), zf, vf])

    def _normal_mode(self, sw, t, y, entering):
        """Contact (coded SLIP_BACK) or the free mode of a normal state."""
        if not entering:
            return Mode.FLIGHT
        if sw.tension == "clipped" and sw.pulls(t, y):
            return Mode.SEPARATED
        return Mode.SLIP_BACK

    def evaluate(self, t: ArrayLike) -> NDArray[np.float64]:
        """``(z, z', X2, X2')`` at the times ``t`` from the dense output, shape (4, n)."""
        return _dop853.evaluate(self.t_steps, self.h_steps, self.y_steps, self.F_steps, t)

    def at(self, t: float) -> NDArray[np.float64]:
        """``(z, z', X2, X2')`` at one time: the dense output of the step holding ``t``."""
        # the period maps of a Floquet band call this thousands of times: the compiled
        # loop of `evaluate` (bit-identical) costs a seventh of the Python one
        fast = _dop853._evaluate_compiled()
        if fast is not None:
            out = np.empty((4, 1))
            fast(self.t_steps, self.h_steps, self.y_steps, self.F_steps, np.array([t]), out)
            return out[:, 0]
        k = max(int(np.searchsorted(self.t_steps, t, side="right")) - 1, 0)
        F = self.F_steps[k]
        x = (t - self.t_steps[k]) / self.h_steps[k]
        y = F[-1].copy()
        for j in range(1, F.shape[0]):
            y *= x if j % 2 else 1.0 - x
            y += F[-1 - j]
        y *= x if F.shape[0] % 2 else 1.0 - x
        return y + self.y_steps[k]

    def segment_at(self, t: float) -> int:
        """Index of the normal segment that holds ``t`` (the later one at a switch)."""
        return min(
            int(np.searchsorted(self.switch_t, t, side="right")) - 1, len(self.switch_mode) - 1
        )


_KEEP: OrderedDict = OrderedDict()


def normal_motion(
    model: Model,
    t_end: float,
    rtol: float,
    atol: float,
    y0_normal: Iterable[float],
    backend: Backend | None = None,
) -> NormalMotion:
    """The `NormalMotion` of ``model`` (the last few are kept, by `normal_key`).

    ``mu_s`` and ``Vb`` do not enter the normal motion or ``z``: a sweep over either
    reuses one.

    Parameters
    ----------
    model, t_end, rtol, atol, y0_normal, backend
        As for `NormalMotion`.

    Returns
    -------
    NormalMotion
        The one kept for these arguments, or a new one.

    See Also
    --------
    beltmdsm.integrate.normal.normal_key : What the motion depends on.
    beltmdsm.integrate.normal.clear_cache : Forgets the kept ones.

    Examples
    --------
    Runs at two belt speeds share one normal motion:

    >>> from beltmdsm.excitation import initial_state
    >>> model = Model(Vb=1.5)
    >>> y0 = initial_state(model)[2:]
    >>> first = normal_motion(model, 2.0, 1e-10, 1e-10, y0, backend="python")
    >>> first is normal_motion(model.replace(Vb=3.0), 2.0, 1e-10, 1e-10, y0, backend="python")
    True
    """
    key = (
        (normal_key(model), fastest_rate(model)),  # the steps' bound (NormalMotion)
        float(t_end),
        float(rtol),
        float(atol),
        tuple(float(v) for v in y0_normal),
        backend,
    )
    if key in _KEEP:
        _KEEP.move_to_end(key)
        return _KEEP[key]
    motion = NormalMotion(model, *key[1:5], backend)
    _KEEP[key] = motion
    if len(_KEEP) > _KEPT:
        _KEEP.popitem(last=False)
    return motion


def clear_cache() -> None:
    """Forget the normal motions kept for the last parameter sets.

    See Also
    --------
    beltmdsm.integrate.normal.normal_motion : Keeps them.

    Examples
    --------
    >>> from beltmdsm.excitation import initial_state
    >>> model = Model(Vb=1.5)
    >>> y0 = initial_state(model)[2:]
    >>> first = normal_motion(model, 2.0, 1e-10, 1e-10, y0, backend="python")
    >>> clear_cache()
    >>> first is normal_motion(model, 2.0, 1e-10, 1e-10, y0, backend="python")
    False
    """
    _KEEP.clear()
