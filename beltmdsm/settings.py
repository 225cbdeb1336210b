"""How a run is computed: `SolverSettings`, the integrators' options and limits.

The settings are checked once, when they are built, and normalised (every number a
float), so that equal settings key the sweep cache equally whether they came from
the command line or from Python. `check_request` checks them against a model before
a run computes anything: the sampling must resolve the model's frequencies
(`NYQUIST_MULTIPLE`) and the run must fit in `MAX_RUN_BYTES` of memory (`run_bytes`).
"""

from __future__ import annotations

import functools
import inspect
import math
from dataclasses import dataclass, fields
from typing import Literal

import numpy as np

from beltmdsm.generated import unforced
from beltmdsm.generated._support import CHECKED

from .errors import Refused
from .model import Backend, Model, is_real
from .state_names import columns

__all__ = [
    "SolverSettings",
    "SOLVERS",
    "METHODS",
    "CONTACT_LOSS",
    "MAX_SAMPLES",
    "MAX_POINTS",
    "MAX_RTOL",
    "DEFAULT_T_END",
    "NYQUIST_MULTIPLE",
    "BYTES_PER_PERIOD",
    "BYTES_PER_SAMPLE",
    "MAX_RUN_BYTES",
    "MAX_VB_POINTS",
    "MAX_BAND_POINTS",
    "MAX_SEED_POINTS",
    "SETTLE_TOL",
    "MAX_MAP_ROWS",
    "MIN_TOL_ULPS",
    "fastest_rate",
    "run_bytes",
    "check_request",
    "check_finite",
    "with_fields",
    "Solver",
    "Method",
    "ContactLoss",
]

#: The choices of the settings' fields, as types.
Solver = Literal["events", "superposition"]
Method = Literal["DOP853"]
ContactLoss = Literal["continue", "stop"]

#: The integrators: `beltmdsm.integrate.events` and `beltmdsm.integrate.superposition`.
SOLVERS = ("events", "superposition")
#: The integration methods of the integrators (`beltmdsm.integrate._dop853`), by name
#: (the name keys the sweep cache).
METHODS = ("DOP853",)
#: What a run does on loss of contact: go on in flight, or stop.
CONTACT_LOSS = ("continue", "stop")
#: Most samples in a run's time series (``t_end / dt``): each costs 7 floats in the
#: returned arrays, so this caps them near 0.6 GB, and an absurd request fails before
#: anything is allocated.
MAX_SAMPLES = 10**7
#: Most points of one sweep (`beltmdsm.batch.sweep`). A sweep of 10^6 runs of a second
#: each is eleven days on one core; a larger one is a mistake (a step of 1e-15), refused
#: before anything is allocated.
MAX_POINTS = 10**6
#: The loosest relative tolerance a run accepts. DOP853 keeps each step's estimated error
#: below ``atol + rtol |y|``, and that estimate (the difference of two embedded
#: solutions, the leading term of an expansion in the step) bounds the error only while
#: the error is small against the state. Above a tenth of the state not one significant
#: digit is kept, and the sign of a switching function (``Vr``, the stick limits), which
#: decides the mode, is not determined by the step: such a run cannot be resolved, and
#: it failed wherever the integrator met it (rtol = 0.5 and 1 ended with the step below
#: the rounding of the time at t = 181.7 s and 5.96 s, and the superposition with a
#: bounded normal step ran rtol = 1 to "done" with a meaningless energy balance). At
#: rtol = 0.1 a run still has a digit, and its energy balance says whether it closes.
MAX_RTOL = 0.1
DEFAULT_T_END = 1000.0


@dataclass(frozen=True)
class SolverSettings:
    """How a run is computed; part of the cache key of a sweep.

    Frozen and checked once, when made: every field is validated here, so a run
    never sees a bad setting.

    Parameters
    ----------
    solver : {"events", "superposition"}
        "events" (the default; `beltmdsm.integrate.events`, the compiled DOP853
        integrator on each mode: the general one, and the faster) or "superposition"
        (`beltmdsm.integrate.superposition`: the normal equation once, the tangential
        one by superposition; it falls back to "events" where it does not apply).
    method : {"DOP853"}
        The Runge-Kutta method (the only one).
    rtol, atol : float
        The integrator's relative and absolute tolerances, > 0; ``rtol`` at most
        `MAX_RTOL` (a looser one keeps no significant digit).
    t_end : float
        The duration of a run [s] (default `DEFAULT_T_END`).
    t_discard : float or None
        Start of the steady window [s]; ``None`` means 30 % of ``t_end``.
    dt : float
        Sampling step of the returned time series [s].
    on_contact_loss : {"continue", "stop"}
        At a loss of contact, go on (flight) or stop the run there.
    backend : {"numba", "python", None}
        "numba" (compiled), "python" or None (numba if installed).

    Attributes
    ----------
    window_start : float
        Where the steady window starts [s]: ``t_discard``, or 30 % of ``t_end``.

    Raises
    ------
    ValueError
        Naming the field, for a bad value or settings that do not fit together (more
        than `MAX_SAMPLES` samples, a steady window that starts after ``t_end``).

    See Also
    --------
    beltmdsm.simulation.simulate : a run with these settings (its keywords are the fields too).
    beltmdsm.batch.sweep.sweep : runs over a parameter; the settings are in the cache key.

    Examples
    --------
    >>> from beltmdsm import SolverSettings
    >>> s = SolverSettings(t_end=50.0, rtol=1e-8, atol=1e-8)
    >>> s.solver, s.t_end, s.window_start
    ('events', 50.0, 15.0)
    >>> SolverSettings(dt=0)
    Traceback (most recent call last):
    ValueError: dt must be a finite number > 0; got 0
    """

    solver: Solver = "events"
    method: Method = "DOP853"
    rtol: float = 1e-10
    atol: float = 1e-10
    t_end: float = DEFAULT_T_END
    t_discard: float | None = None
    dt: float = 0.02
    on_contact_loss: ContactLoss = "continue"
    backend: Backend | None = None

    def __post_init__(self) -> None:
        for name, choices in (
            ("solver", SOLVERS),
            ("method", METHODS),
            ("on_contact_loss", CONTACT_LOSS),
            ("backend", (None, "numba", "python")),
        ):
            if getattr(self, name) not in choices:
                raise ValueError(
                    f"{name} must be one of {', '.join(map(repr, choices))}; "
                    f"got {getattr(self, name)!r}"
                )
        for name in ("rtol", "atol", "t_end", "dt"):
            value = getattr(self, name)
            if not (is_real(value) and math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a finite number > 0; got {value!r}")
            object.__setattr__(self, name, float(value))
        if self.rtol > MAX_RTOL:
            raise Refused(
                f"rtol must be <= MAX_RTOL = {MAX_RTOL:g} (beltmdsm/settings.py): a "
                "looser relative tolerance keeps no significant digit of a step, so the "
                f"sign of a switching function is not resolved; got {self.rtol:g}",
                "rtol",
            )
        if self.t_discard is not None:
            if not (is_real(self.t_discard) and math.isfinite(self.t_discard)):
                raise ValueError(
                    f"t_discard must be None or a finite number; got {self.t_discard!r}"
                )
            object.__setattr__(self, "t_discard", float(self.t_discard))
        if self.t_end / self.dt > MAX_SAMPLES:
            raise ValueError(
                f"t_end / dt = {self.t_end / self.dt:.3g} samples is more than "
                f"MAX_SAMPLES = {MAX_SAMPLES:.0e} (beltmdsm/settings.py); "
                "shorten t_end or sample with a larger dt"
            )
        if not 0 <= self.window_start < self.t_end - 20 * self.dt:
            start = (
                "the default t_discard (0.3 t_end)"
                if self.t_discard is None
                else f"t_discard ({self.t_discard:g})"
            )
            raise ValueError(
                f"t_discard must be >= 0 and leave a steady window of 20 samples of dt "
                f"({self.dt:g}) before t_end ({self.t_end:g}); {start} leaves "
                f"{max(self.t_end - self.window_start, 0):g} s"
            )

    @property
    def window_start(self) -> float:
        return 0.3 * self.t_end if self.t_discard is None else float(self.t_discard)

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The field names (keywords that `beltmdsm.simulate` passes to the settings)."""
        return tuple(f.name for f in fields(cls))


#: The sampling step ``dt`` must give a Nyquist frequency ``pi / dt`` of at least this
#: multiple of the fastest of ``Omega_t``, ``Omega_n`` and ``omega1``. The velocity X1'
#: has a kink at every switch (the friction jumps at a reversal, a stick, a loss of
#: contact), so its harmonics fall off only as 1/k^2, and a harmonic above the Nyquist
#: frequency folds back onto the spectrum: at ``--dt 0.7`` (``pi/dt = 1.1 Omega``)
#: 2 Omega lands in the omega1 band and reads as a peak. With ``pi/dt >= 8 w`` only
#: harmonics above about ``2 x 8 - 1.25 = 14.75`` times the fastest line fold into the
#: omega1 band, and they carry less than 1/14.75^2 = 0.5 % of the fundamental, half
#: the criterion of a present peak (`beltmdsm.run.summary.PEAK_PRESENT_RATIO`).
#: Measured over the 16 cases of `beltmdsm.paper_reports.validation.CASES` at Vb = 0.5, 2,
#: 4, 6, 10 and 16 m/s (600 s runs): against a reference sampled at dt = 0.005 s, the
#: omega1 peak moves by at most 32 % of the present threshold at ``pi/dt = 4 w``, 11 %
#: at 6 w, 5.8 % at 8 w and 3.7 % at 10 w (the rest is the window's own leakage). The
#: default dt = 0.02 s passes up to w = 19.6 rad/s (every case of the paper: Omega up
#: to 10, omega1 up to 12).
NYQUIST_MULTIPLE = 8.0
#: The memory a run holds, per period ``2 pi / w`` of its fastest rate ``w``
#: (`fastest_rate`) at rtol = atol = 1e-10: the integrators keep every step's dense
#: output (DOP853: about 280 bytes a step in arrays) until the run is summarised, and
#: the summary's quadrature and samples add to it. Measured as the growth of the peak
#: resident memory between runs of 10^4 s and 4 x 10^4 s (dt = 0.05 s): 41 kB per
#: period at the base set (events; Vb = 4), 53 kB at Omega = 10 (Vb = 1, stick-slip),
#: 28 kB at omega1 = 12, and with the superposition solver 59, 40 and 28 kB; rounded up
#: to 64 KiB. A tighter tolerance takes more steps, as ``tol^(-1/8)`` (DOP853 is of
#: order 8).
BYTES_PER_PERIOD = 64 * 1024
#: The memory of one sample of a run's time series and of the summary's work on it
#: (7 floats kept, the steady window's spectra): measured 77-104 bytes a sample
#: (5 x 10^4 to 5 x 10^6 samples), rounded up.
BYTES_PER_SAMPLE = 128
#: The largest run `check_request` accepts, by `run_bytes`: 4 GiB, so that a sweep
#: with a worker per core of a small machine fits in its memory. At the base set and
#: the default tolerances this is about 7 x 10^4 s of simulated time.
MAX_RUN_BYTES = 4 * 2**30
#: Most belt speeds of one grid of `beltmdsm.prediction.scan` (``points``, or the
#: size of ``vb``): the harmonic
#: balance takes 1.3 to 2 ms a point (measured at the base set: 400 points in 0.8 s,
#: 4000 in 5.2 s, 30000 in 60 s with the other core busy), so 10^5 points take two to
#: three minutes (with a progress bar); a larger grid resolves nothing that the
#: refinement of every edge to 1e-10 m/s does not already. Under a friction law whose
#: fast average is a quadrature (Stribeck's) a point takes about 6 ms (2000 points in
#: 12 s), 10^5 points ten minutes.
MAX_VB_POINTS = 10**5
#: Most grid points of `beltmdsm.continuation.band.floquet_band`: a point takes about 2 ms
#: (6 ms where no periodic response is found; measured at the base set over Vb in
#: [1, 9]), so 10^4 points take 20 s to a minute.
MAX_BAND_POINTS = 10**4
#: Most seeds' grid points of `beltmdsm.multistability.coexistence.coexistence` (its range
#: over ``step``): a point is a shooting, a 600 s run from rest and two continued
#: ladders, 0.5 to 2 s (measured at the base set over Vb in [3, 5]), so 10^3 points
#: take ten to thirty minutes; a smaller step is a mistake (``--step 1e-6``: millions
#: of points, memory growing for hours), refused before anything is computed.
MAX_SEED_POINTS = 10**3
#: Most rows of `beltmdsm.continuation.floquet_map.floquet_map`: a row whose curves are
#: continued takes a few ms, one with a band (every ``check_every`` rows, and where a
#: curve is lost) a second or more, so 10^4 rows take minutes.
MAX_MAP_ROWS = 10**4
#: `beltmdsm.continuation.band.floquet_band`'s ``tol`` must span this many ulps of the
#: larger end of the range: below, the midpoint of a bracket rounds to one of its ends
#: and the bisection stops shrinking it.
MIN_TOL_ULPS = 64


#: A self-excited cycle's seed run has settled when its returns to the section repeat
#: to within this, relative to their distance from steady sliding (a run that decays to
#: steady sliding returns by a fixed share of that distance, and never settles):
#: Newton's method converges from there. The paper's seed
#: (`beltmdsm.starts.cycle_seed`) and another model's (`beltmdsm.oscillator.cycle_seed`).
SETTLE_TOL = 1e-6


# a model is immutable and hashable; the runtime asks this for the same model at every
# run, shooting and bound (tens of thousands of times in one study, each an eigenvalue
# solve)
@functools.lru_cache(maxsize=1024)
def fastest_rate(model: Model) -> float:
    """The fastest rate of the model [rad/s or 1/s], which sets an integrator's steps.

    The largest of the excitation frequencies ``Omega_t``, ``Omega_n``, ``omega1`` and
    the moduli of the unforced eigenvalues at the equilibrium
    (`beltmdsm.generated.unforced.eigenvalues`: the stiffness and damping of the contact).

    Parameters
    ----------
    model : Model
        The model whose rates are compared.

    Returns
    -------
    float
        The fastest rate.

    See Also
    --------
    beltmdsm.settings.run_bytes : The memory estimate this rate scales.

    Examples
    --------
    With the defaults the contact's eigenvalue of modulus 5.6609 is the fastest (the
    excitation turns at 4 rad/s); at ``Omega_t = 50`` the excitation is:

    >>> round(fastest_rate(Model()), 4), fastest_rate(Model(Omega_t=50))
    (5.6609, 50.0)
    """
    p = model.params
    names = _EIGEN_VARIANTS[(_EIGEN_FRICTION, model.contact)].names
    rate = _contact_rate(model.contact, tuple((k, p[k]) for k in names))
    return float(max(p["Omega_t"], p["Omega_n"], p["omega1"], rate))


#: The friction law of the eigenvalues `fastest_rate` reads (the generated default,
#: whatever the model's: the rates of the contact's stiffness and damping), and the
#: parameters each contact law's variant takes, as the generated code declares them.
_EIGEN_FRICTION = inspect.signature(unforced.eigenvalues).parameters["friction"].default
_EIGEN_VARIANTS = unforced._EIGENVALUES


# keyed on the parameters the eigenvalues take (not Vb, mu_s, the excitation): the
# trial points of a continuation in Vb share one solve
@functools.lru_cache(maxsize=1024)
def _contact_rate(contact: str, params: tuple[tuple[str, float], ...]) -> float:
    """The largest modulus of the unforced eigenvalues (`fastest_rate`), from the
    parameters a model checked (not checked again)."""
    given = dict(params)
    lam = np.abs(unforced.eigenvalues(contact=contact, **given, **{CHECKED: given}))
    return float(np.max(lam))


def run_bytes(model: Model, settings: SolverSettings) -> float:
    """An upper estimate of the memory a run of ``model`` with ``settings`` holds [bytes].

    ``BYTES_PER_PERIOD`` per period ``2 pi / w`` of the fastest rate (`fastest_rate`),
    scaled by ``(1e-10 / tol)^(1/8)`` for a tolerance ``tol = min(rtol, atol)`` below
    1e-10, plus ``BYTES_PER_SAMPLE`` per sample (``t_end / dt``).

    Parameters
    ----------
    model : Model
        The model to run.
    settings : SolverSettings
        Its length ``t_end``, sampling step ``dt`` and tolerances.

    Returns
    -------
    float
        The estimate in bytes.

    See Also
    --------
    beltmdsm.settings.check_request : Refuses a run above ``MAX_RUN_BYTES``.
    beltmdsm.settings.fastest_rate : The rate that sets the steps per second.

    Examples
    --------
    Both terms grow with ``t_end``: a run ten times as long holds ten times as much.

    >>> short = run_bytes(Model(), SolverSettings(t_end=100.0))
    >>> round(run_bytes(Model(), SolverSettings(t_end=1000.0)) / short, 9)
    10.0
    """
    periods = settings.t_end * fastest_rate(model) / (2 * math.pi)
    tol = min(settings.rtol, settings.atol)
    steps = max(1.0, (1e-10 / tol) ** 0.125)
    return periods * BYTES_PER_PERIOD * steps + settings.t_end / settings.dt * BYTES_PER_SAMPLE


# a model is immutable and hashable: its verdict is the same at every map, shooting and
# run that asks (a continuation builds tens of thousands of maps, most on models already
# checked: 0.3 ms each)
@functools.lru_cache(maxsize=1024)
def _overflows(model: Model) -> str | None:
    """What of the start is beyond floating point: None, or ``"X1 = inf"``, ...

    The start is the unforced equilibrium (Eq. 9) and the fields of slip back and stick;
    a state whose square overflows (the energy balance squares it) counts too.
    """
    import warnings

    from beltmdsm.generated import hybrid

    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        state = np.array(unforced.equilibrium(**model.arguments(unforced.equilibrium)), float)
        for name, value in zip(columns(model), state):
            if not math.isfinite(value):
                return f"the unforced equilibrium (Eq. 9) has {name} = {value:.3g}"
            if not math.isfinite(value * value):
                return (
                    f"the unforced equilibrium (Eq. 9) has {name} = {value:.3g}, whose "
                    "square (in the energy balance) overflows"
                )
        # the fields of the modes a start at rest on the belt can take (another mode's
        # law may be undefined there: Stribeck's forward slip at Vr < 0)
        field = hybrid.bind_vector_field(
            backend="python", **model.arguments(hybrid.bind_vector_field)
        )
        for mode in ("slip_back", "stick"):
            rate = np.array(field(0.0, *state, float(hybrid.MODE_CODES[mode])), float)
            if not np.all(np.isfinite(rate)):
                return f"the field of mode {mode} at that state is {rate.tolist()}"
    return None


def check_finite(model: Model) -> None:
    """Refuse parameters that put the start of a run beyond floating point.

    A state or rate that overflows to inf or NaN (``omega1 = 1e-200``: the equilibrium
    ``X1 = mu_s g / omega1^2``) would be integrated as NaN; the parameters responsible
    are those whose base value (``beltmdsm.generated.parameters.BASE``) makes it finite.

    Parameters
    ----------
    model : Model
        The model whose start is checked.

    Raises
    ------
    beltmdsm.errors.Refused
        Naming those parameters.

    See Also
    --------
    beltmdsm.settings.check_request : Calls this check first.

    Examples
    --------
    ``omega1 = 1e-200`` puts the equilibrium ``X1 = mu_s g / omega1^2`` at inf; the
    refusal names ``omega1``:

    >>> check_finite(Model())
    >>> try:
    ...     check_finite(Model(omega1=1e-200))
    ... except Refused as refusal:
    ...     print(refusal.names, refusal)
    ('omega1',) the unforced equilibrium (Eq. 9) has X1 = inf: beyond floating point ...
    """
    problem = _overflows(model)
    if problem is None:
        return
    from beltmdsm.generated.parameters import BASE

    names = [
        k
        for k, v in model.params.items()
        if k in BASE and v != BASE[k] and _overflows(model.replace(**{k: BASE[k]})) is None
    ]
    names = names or [k for k, v in model.params.items() if k in BASE and v != BASE[k]]
    given = ", ".join(f"{k} = {model.params[k]:g}" for k in names)
    raise Refused(
        f"{problem}: beyond floating point at {given} (the motion would be integrated "
        "as NaN); choose values whose equilibrium and forces are finite",
        *names,
    )


def check_request(model: Model, settings: SolverSettings) -> None:
    """Refuse a run that could not be read or would not fit, before it computes anything.

    Parameters
    ----------
    model : Model
        The model to run.
    settings : SolverSettings
        How it is to be run.

    Raises
    ------
    beltmdsm.errors.Refused
        Naming ``t_end`` where `run_bytes` exceeds `MAX_RUN_BYTES`, and ``dt`` where
        ``pi / dt`` is below `NYQUIST_MULTIPLE` times the fastest of ``Omega_t``,
        ``Omega_n`` and ``omega1`` (its harmonics would alias into the omega1 band).
        Naming the parameters, as `check_finite` does, where the start overflows.

    See Also
    --------
    beltmdsm.settings.run_bytes : The memory estimate checked here.
    beltmdsm.settings.check_finite : The check of the start, made first.

    Examples
    --------
    A step of 1 s samples up to pi rad/s, below 8 times ``Omega_t = 4`` rad/s; a
    run of 10^5 s would hold several GiB:

    >>> check_request(Model(), SolverSettings(t_end=10.0))
    >>> for bad in (SolverSettings(dt=1.0), SolverSettings(t_end=1e5)):
    ...     try:
    ...         check_request(Model(), bad)
    ...     except Refused as refusal:
    ...         print(refusal.names, refusal)
    ('dt',) dt = 1 s samples up to pi/dt = 3.142 rad/s, below 8 x Omega_t = 32 rad/s: ...
    ('t_end',) t_end = 100000 s would hold about 6.1 GiB ...
    """
    check_finite(model)
    need = run_bytes(model, settings)
    if need > MAX_RUN_BYTES:
        rate = fastest_rate(model)
        top = settings.t_end * MAX_RUN_BYTES / need
        raise Refused(
            f"t_end = {settings.t_end:g} s would hold about {need / 2**30:.3g} GiB "
            f"(dense output of every step: {BYTES_PER_PERIOD // 1024} KiB per period "
            f"of the fastest rate {rate:.4g} rad/s, and {BYTES_PER_SAMPLE} bytes per "
            f"sample), more than MAX_RUN_BYTES = {MAX_RUN_BYTES / 2**30:g} GiB "
            f"(beltmdsm/settings.py); shorten t_end to at most about {top:.3g} s",
            "t_end",
        )
    p = model.params
    lines = {"Omega_t": p["Omega_t"], "Omega_n": p["Omega_n"], "omega1": p["omega1"]}
    name, fastest = max(lines.items(), key=lambda kv: kv[1])
    nyquist = math.pi / settings.dt
    if nyquist < NYQUIST_MULTIPLE * fastest:
        raise Refused(
            f"dt = {settings.dt:g} s samples up to pi/dt = {nyquist:.4g} rad/s, below "
            f"{NYQUIST_MULTIPLE:g} x {name} = {NYQUIST_MULTIPLE * fastest:.4g} rad/s: the "
            "harmonics of the motion would alias into the omega1 band and read as a "
            f"peak (NYQUIST_MULTIPLE in beltmdsm/settings.py); use dt <= "
            f"{math.pi / (NYQUIST_MULTIPLE * fastest):.4g} s",
            "dt",
        )


def with_fields(settings: SolverSettings, **fields_: object) -> SolverSettings:
    """``settings`` with the fields given (not None) in place of its own: the keywords
    ``t_end=``, ``dt=``, ... of a public function that takes ``settings=`` too.

    Parameters
    ----------
    settings : SolverSettings
        The settings the caller passed (or the defaults).
    **fields_
        Fields of `SolverSettings`; None leaves one as ``settings`` has it.

    Returns
    -------
    SolverSettings
        ``settings`` itself where nothing is given, else new checked settings.

    See Also
    --------
    beltmdsm.simulation.simulate : Takes the fields as keywords.

    Examples
    --------
    >>> with_fields(SolverSettings(dt=0.05), t_end=50.0, rtol=None)
    SolverSettings(...t_end=50.0, t_discard=None, dt=0.05, ...)
    """
    changes = {k: v for k, v in fields_.items() if v is not None}
    if not changes:
        return settings
    return SolverSettings(**{**settings.__dict__, **changes})  # type: ignore[arg-type]
