"""Lyapunov exponents of the hybrid flow of Eq. (4): Benettin's method through the switches.

The tangent dynamics of a run is the one the Floquet engine already carries
(`beltmdsm.periodic.variational`): between switches the variational equation of the
mode's field (the generated Jacobian, integrated with the run's own DOP853 steps),
across every switch (stick, slip, reversal, contact loss) a jump by the saltation
matrix. Integrating the variational equations across an event without that jump
gives wrong exponents (the known failure of event callbacks in tangent-space
methods). Here the run is cut into chunks of length ``tau`` (one excitation period,
or without excitation the slowest oscillation's of steady sliding, cut so that no
direction underflows:
`chunk_length`); the monodromy ``M_k`` of each chunk acts on an
orthonormal frame ``Q``, re-orthonormalised by ``M_k Q = Q' R`` (QR), and the exponents
are the running means of ``log |R_ii|`` over the time averaged (Benettin et al. 1980).

On a periodic orbit of period ``k T`` the exponents are ``ln |mu_i| / (k T)`` of its
Floquet multipliers; on steady sliding they are the real parts of the unforced
eigenvalues (tests/beltmdsm/attractors/test_lyapunov.py checks both, a two-trajectory
separation estimate and the sum of the exponents against the mean divergence of the
field plus the switches' ``ln |det S|``).

**Stick removes a direction.** The saltation matrix into stick maps every velocity
perturbation to the belt's (``X1' = Vb`` whatever the perturbation): the chunk's
monodromy loses rank and one exponent is ``-inf`` (a Floquet multiplier 0). It is
reported as ``-inf`` (``None`` in JSON) with ``collapsed`` counting such directions,
never as the large negative number rounding would give.

**Error.** ``error`` is the largest of the standard error of the exponents over
`BLOCKS` blocks of the averaging window, the drift of the running mean (the mean over
the whole window against the mean over its second half) and ``rtol / tau``: the first
bounds the fluctuation, the second the transient left in the start, the third the
runs' tolerance, which no average removes (benchmarks/bench_lyapunov.py: errors of
6e-12 1/s on the stick orbit where the spread says 1e-14).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from tqdm import tqdm

from beltmdsm.generated import unforced

from .._calling import public
from .._tables import DataFrame
from ..arguments import number, state
from ..errors import Refused, StepTooSmall
from ..excitation import START_PERTURBATION, equilibrium_start, excitation_period, initial_state
from ..integrate.events import integrate_events
from ..integrate.switching import Mode
from ..model import Backend, Model, as_model
from ..periodic import variational
from ..settings import MAX_RUN_BYTES, SolverSettings, fastest_rate

__all__ = [
    "Lyapunov",
    "lyapunov",
    "advance",
    "chunk_length",
    "check_length",
    "BLOCKS",
    "BYTES_PER_BASE",
    "COLLAPSE",
    "PIECE",
    "RTOL",
    "SPREAD",
    "STEP",
]

#: Blocks of the averaging window whose spread estimates the error.
BLOCKS = 8
#: A diagonal entry of R below this fraction of the largest, in a chunk that enters
#: stick, is the direction that stick removed (rounding leaves about 1e-16 there).
COLLAPSE = 1e-10
#: The most ``tau`` times the fastest rate of the model (`chunk_length`).
SPREAD = 8.0
#: The longest step times the fastest rate: the step control sees the state only, and
#: at an equilibrium it would take steps on which the variational equation's order-8
#: step errs by ``(h |lambda|)^9 / 9!``, 1e-11 at 0.25.
STEP = 0.25
#: Tolerance of the runs (the monodromy carries about this relative accuracy).
RTOL = 1e-10
#: The memory the average keeps per base period (`chunk_length`): the period's
#: ``log |R_ii|``, its sample, the running means and the work arrays of `_spectrum`,
#: six rows of four floats, rounded up. A run of ``t_end`` is refused where its base
#: periods would need more than `beltmdsm.settings.MAX_RUN_BYTES` so (`check_length`).
BYTES_PER_BASE = 256
#: Base periods a plain run (the transient) is cut into: its dense output (about 21 kB
#: a simulated second at the base set) is dropped after each piece, only the state kept.
PIECE = 64
#: Chunks with the frame turning but nothing averaged, by default: the frame aligns
#: with the Lyapunov vectors at the rate of the gaps between the exponents.
_ALIGN = 20


@dataclass
class Lyapunov:
    """The Lyapunov spectrum of a run of Eq. (4).

    Attributes
    ----------
    model : Model
    exponents : ndarray (4,)
        Largest first [1/s]; ``-inf`` for a direction that stick removes.
    error : ndarray (4,)
        Error estimate of each exponent (module docstring); 0 for ``-inf``.
    t_transient : float
        Time run before the frame starts turning [s].
    t_average : float
        Length of the averaging window [s].
    tau : float
        Chunk length between re-orthonormalisations [s] (`chunk_length`).
    collapsed : int
        Directions removed by stick (exponent ``-inf``).
    switches : int
        Switches passed in the averaging window.
    running : ndarray (n, 4)
        The running means at the end of each chunk of the window.
    state : ndarray (4,)
        The state where the run ended.
    samples : ndarray (n, 4)
        The state at the end of each base period of the window (`chunk_length`): with
        excitation, the stroboscopic samples at phase 0 (`beltmdsm.attractors.classification`
        reads the attractor's kind from them).
    start_perturbation : float
        How far the default start was moved off unstable steady sliding
        (`beltmdsm.excitation.equilibrium_start`), 0.0 where it was not.

    See Also
    --------
    beltmdsm.attractors.lyapunov.lyapunov : computes it.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> spec = lyapunov(Model(Vb=5.0), t_end=60.0)  # the 4T lock, stable
    >>> spec  # doctest: +ELLIPSIS
    Lyapunov([-0.09...+-..., ...] 1/s over 32.9867 s, 20 switches, 0 collapsed)
    >>> bool(spec.largest < 0), spec.exponents.shape, sorted(spec.as_dict())[:3]
    (True, (4,), ['collapsed', 'error', 'exponents'])
    """

    model: Model = field(repr=False)
    exponents: NDArray[np.float64]
    error: NDArray[np.float64]
    t_transient: float
    t_average: float
    tau: float
    collapsed: int
    switches: int
    running: NDArray[np.float64] = field(repr=False)
    state: NDArray[np.float64] = field(repr=False)
    samples: NDArray[np.float64] = field(repr=False)
    start_perturbation: float = field(default=0.0, repr=False)

    @property
    def largest(self) -> float:
        """The largest exponent [1/s]."""
        return float(self.exponents[0])

    def __repr__(self) -> str:
        parts = ", ".join(
            "-inf" if not np.isfinite(x) else f"{x:+.4g}+-{e:.1g}"
            for x, e in zip(self.exponents, self.error)
        )
        return (
            f"Lyapunov([{parts}] 1/s over {self.t_average:g} s, "
            f"{self.switches} switches, {self.collapsed} collapsed)"
        )

    def to_pandas(self) -> DataFrame:
        """A `pandas.DataFrame` (needs pandas) of the spectrum, largest first: one row per
        exponent, ``exponent`` [1/s] (``-inf`` where stick removes a direction) and its
        ``error``.

        Examples
        --------
        >>> from beltmdsm import Model
        >>> table = lyapunov(Model(Vb=5.0), t_end=60.0).to_pandas()
        >>> list(table), len(table), bool(table["exponent"].iloc[0] < 0)
        (['exponent', 'error'], 4, True)
        """
        from .._tables import frame

        rows = {"exponent": self.exponents, "error": self.error}
        return frame(rows, list(rows))

    def as_dict(self) -> dict:
        """The spectrum as JSON-ready numbers (``-inf`` stays a float: callers map it)."""
        return {
            "exponents": [float(x) for x in self.exponents],
            "error": [float(x) for x in self.error],
            "largest": self.largest,
            "t_transient": self.t_transient,
            "t_average": self.t_average,
            "tau": self.tau,
            "collapsed": self.collapsed,
            "switches": self.switches,
            "start_perturbation": self.start_perturbation,
        }


def chunk_length(model: Model) -> tuple[float, int]:
    """The base period and the number ``n`` of chunks it is cut into: ``tau = base / n``.

    The base period is one excitation period, or without excitation the period of the
    slowest oscillation of steady sliding (`beltmdsm.generated.unforced.eigenvalues`)
    (the averages are taken over whole base periods, so that the phase of the forcing
    does not enter their spread). ``n`` is the least integer that keeps ``tau`` times
    the fastest rate (`beltmdsm.settings.fastest_rate`) within `SPREAD`: within one
    chunk the frame's directions separate by at most ``exp(2 SPREAD)`` (the exponents
    lie within the fastest rate of zero), so the smallest ``R_ii`` keeps about
    ``16 - 2 SPREAD / ln 10`` digits, 9 at `SPREAD` = 8.

    Parameters
    ----------
    model : Model
        The model whose exponents are computed.

    Returns
    -------
    base : float
        The base period [s].
    n : int
        The chunks per base period.

    See Also
    --------
    beltmdsm.attractors.lyapunov.lyapunov : Integrates the frame chunk by chunk.

    Examples
    --------
    With the defaults the base is the excitation period ``2 pi / 4``, and the
    contact's rate 5.6609 gives ``ceil(1.5708 x 5.6609 / 8) = 2`` chunks:

    >>> base, n = chunk_length(Model())
    >>> round(base, 6), n
    (1.570796, 2)
    """
    try:
        base = excitation_period(model)
    except ValueError:
        # without excitation: the period of the slowest oscillation of steady sliding
        lam = np.asarray(unforced.eigenvalues(**model.arguments(unforced.eigenvalues)))
        w = np.abs(lam.imag)[np.abs(lam.imag) > 0]
        base = 2 * math.pi / (float(w.min()) if w.size else fastest_rate(model))
    return base, max(1, math.ceil(base * fastest_rate(model) / SPREAD))


def check_length(model: Model, t_end: float, name: str = "t_end") -> None:
    """Refuse a run of ``t_end`` whose base periods the averages could not keep.

    A run keeps `BYTES_PER_BASE` bytes per base period (`chunk_length`), nothing of
    its transient's dense output (`advance`); more periods than
    `beltmdsm.settings.MAX_RUN_BYTES` holds so are refused before anything runs.

    Parameters
    ----------
    model : Model
        The model to run.
    t_end : float
        The run's length [s].
    name : str
        The argument named in the refusal.

    Raises
    ------
    beltmdsm.errors.Refused
        Naming ``name``, with the longest run that fits.

    See Also
    --------
    beltmdsm.settings.check_request : The same rule for `beltmdsm.simulation.simulate`.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> check_length(Model(), 1e5)
    >>> try:
    ...     check_length(Model(), 1e300)
    ... except Refused as refusal:
    ...     print(refusal.names, str(refusal)[:48])
    ('t_end',) t_end = 1e+300 s holds 6.37e+299 base periods of
    """
    base, _ = chunk_length(model)
    periods = t_end / base
    if periods * BYTES_PER_BASE > MAX_RUN_BYTES:
        top = base * MAX_RUN_BYTES / BYTES_PER_BASE
        raise Refused(
            f"{name} = {t_end:g} s holds {periods:.3g} base periods of {base:.4g} s, and "
            f"the averages keep {BYTES_PER_BASE} bytes a period: more than MAX_RUN_BYTES "
            f"= {MAX_RUN_BYTES / 2**30:g} GiB (beltmdsm/settings.py, "
            f"beltmdsm/attractors/lyapunov.py); shorten {name} to at most about {top:.3g} s",
            name,
        )


def advance(
    model: Model,
    y: ArrayLike,
    t0: float,
    t1: float,
    *,
    rtol: float = RTOL,
    backend: Backend | None = None,
    times: ArrayLike = (),
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The state at ``t1`` of the run from ``y`` at ``t0``, and its states at ``times``.

    The run goes in pieces of `PIECE` base periods (`chunk_length`) and keeps only the
    state between them: its memory does not grow with ``t1 - t0``.

    Parameters
    ----------
    model : Model
    y : array_like (4,)
        The state at ``t0``.
    t0, t1 : float
        The run's ends [s] (``t = 0`` is the excitation's phase 0).
    rtol : float
        Its tolerance (also its ``atol``).
    backend : {"python", "numba", None}
    times : array_like, optional
        Increasing times in ``[t0, t1]`` at which the state is wanted.

    Returns
    -------
    end : ndarray (4,)
    states : ndarray (len(times), 4)

    Raises
    ------
    beltmdsm.errors.StepTooSmall
        Where the run cannot go on at the tolerance.

    See Also
    --------
    beltmdsm.attractors.lyapunov.lyapunov : Runs its transient so.

    Examples
    --------
    Two pieces end where one run ends, to its tolerance:

    >>> from beltmdsm import Model
    >>> from beltmdsm.excitation import initial_state
    >>> m = Model(Vb=4.0)
    >>> end, at = advance(m, initial_state(m), 0.0, 250.0, times=[100.0, 250.0])
    >>> bool(np.abs(at[-1] - end).max() < 1e-12), at.shape
    (True, (2, 4))
    """
    base, _ = chunk_length(model)
    times = np.asarray(times, dtype=float)
    out = np.zeros((times.size, 4))
    y, t, k = np.array(y, dtype=float), float(t0), 0
    while t < t1:
        t_next = min(t + PIECE * base, t1)
        run = integrate_events(model, _settings(t, t_next, rtol, backend), y0=y, t0=t)
        if run.status != "done":
            raise StepTooSmall(f"the run stopped: {run.message}", rtol, rtol)
        j = k + int(np.searchsorted(times[k:], t_next, side="right"))
        if j > k:
            out[k:j] = run.trajectory.state(times[k:j]).T
        y, t, k = run.trajectory.state(np.array([t_next]))[:, 0], t_next, j
    return y, out


def _chunk(model, settings, y, t0, max_step, backend):
    """One chunk from ``t0`` to ``settings.t_end``: ``(end state, monodromy, switches)``."""
    run = integrate_events(model, settings, y0=y, t0=t0, max_step=max_step)
    if run.status != "done":
        raise StepTooSmall(
            f"lyapunov: the run stopped at t = {run.trajectory.t_end:.6g} s: {run.message}",
            settings.rtol,
            settings.atol,
        )
    m = variational.monodromy(run, backend)
    end = run.trajectory.state(np.array([run.trajectory.t_end]))[:, 0]
    return end, m.matrix, m.switches


@public(models=True)
def lyapunov(
    model: Model | Mapping[str, Any] | None = None,
    *,
    y0: ArrayLike | None = None,
    t_end: float = 1000.0,
    t_transient: float | None = None,
    rtol: float = RTOL,
    backend: Backend | None = None,
) -> Lyapunov:
    """The Lyapunov spectrum of the run from ``y0`` (module docstring).

    Parameters
    ----------
    model : Model or dict, optional
        The model, or a dict of its parameters and options (None: the base set).
    y0 : array_like (4,), optional
        The start; default as `beltmdsm.simulation.simulate`'s: the unforced equilibrium
        at rest, or without excitation where steady sliding is unstable that
        equilibrium moved by `beltmdsm.excitation.START_PERTURBATION` along its unstable
        direction (`beltmdsm.excitation.equilibrium_start`; the result's
        ``start_perturbation``): a run started exactly on it stays there, and its
        exponents would be the equilibrium's instability, not the attractor's. To
        start on the periodic response pass `beltmdsm.starts.forced.periodic_start`.
    t_end : float
        The whole run [s]: the transient, the alignment of the frame, the average.
    t_transient : float, optional
        Time run before the frame starts turning [s]; default 30 % of ``t_end``, or
        from a start moved off unstable steady sliding the time it takes to leave it,
        ``ln(1 / START_PERTURBATION) / sigma`` (``sigma`` the largest real part of its
        eigenvalues), where ``t_end`` leaves the average its ``2 BLOCKS`` periods
        after it; cut down to whole base periods (`chunk_length`).
    rtol : float
        Tolerance of the runs (also their ``atol``).
    backend : {"python", "numba", None}

    Returns
    -------
    Lyapunov

    Raises
    ------
    ValueError
        For a bad ``t_end``, ``t_transient``, ``rtol`` or ``y0``, or a window of
        fewer than ``2 * BLOCKS`` base periods (`chunk_length`).
    beltmdsm.errors.Refused
        Naming ``t_end``, for a run whose averages would not fit in memory
        (`check_length`).
    beltmdsm.errors.StepTooSmall
        Where a run cannot go on at the tolerance.

    See Also
    --------
    beltmdsm.attractors.classification.classify : Names the attractor from the spectrum.
    beltmdsm.attractors.lyapunov.chunk_length : The chunks the frame is carried over.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> spec = lyapunov(Model(alpha=0.0, Vb=1.0), t_end=200.0)
    >>> bool(spec.largest < 0)   # steady sliding, stable under Coulomb friction
    True
    """
    model = as_model(model)
    t_end = number("t_end", t_end, above=0)
    rtol = number("rtol", rtol, above=0)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        return api.lyapunov(model, y0, t_end, t_transient, rtol)
    if t_transient is not None:
        t_transient = number(
            "t_transient", t_transient, at_least=0, below=t_end, below_name="t_end"
        )
    base, cuts = chunk_length(model)
    tau = base / cuts
    check_length(model, t_end)
    moved = 0.0
    if y0 is None:
        start, moved = equilibrium_start(model)
        y0 = initial_state(model) if start is None else start
    else:
        y0 = state("y0", y0, (4,), "X1, Y1, X2, Y2")
    if t_transient is None:
        t_transient = max(0.3 * t_end, _escape(model, base, t_end) if moved else 0.0)
    t_transient = float(t_transient)
    if not (math.isfinite(t_transient) and 0 <= t_transient < t_end):
        raise ValueError(f"t_transient must be in [0, t_end); got {t_transient!r}")
    # whole base periods, so that the samples are at the excitation's phase 0
    t_transient = base * math.floor(t_transient / base + 1e-9)
    n_periods = int((t_end - t_transient) / base + 1e-9)
    n_align = min(_ALIGN, n_periods // 4)
    n_avg = n_periods - n_align
    if n_avg < 2 * BLOCKS:
        raise ValueError(
            f"t_end - t_transient = {t_end - t_transient:g} s holds {n_periods} periods of "
            f"{base:.4g} s: at least {2 * BLOCKS + n_align} are needed for the average and "
            f"its error; raise t_end"
        )
    y = y0

    # simulated time on stderr, on a terminal, once the run has taken 2 s (issue 36 item 12)
    bar = tqdm(total=t_end, desc="lyapunov", unit="s", delay=2, leave=False, disable=None,
               file=sys.stderr, bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.0f}/{total:.0f}"
               " s of simulated time [{elapsed}<{remaining}]")  # fmt: skip
    # the transient: a plain run, its phase kept (t = 0 is the excitation's phase 0)
    t = 0.0
    if t_transient > 0:
        try:
            y, _ = advance(model, y, 0.0, t_transient, rtol=rtol, backend=backend)
        except StepTooSmall as err:
            raise StepTooSmall(f"lyapunov: the transient stopped: {err}", rtol, rtol) from None
        t = t_transient
        bar.update(t)

    max_step = STEP / fastest_rate(model)
    Q = np.eye(4)
    logs = np.zeros((n_avg, 4))
    samples = np.zeros((n_avg, 4))
    collapsed = np.zeros(4, dtype=bool)
    switches = 0
    for k in range(n_periods):
        for _ in range(cuts):
            s = _settings(t, t + tau, rtol, backend)
            y, M, sw = _chunk(model, s, y, t, max_step, backend)
            t += tau
            Q, R = np.linalg.qr(M @ Q)
            if k < n_align:
                continue
            d = np.abs(np.diag(R))
            switches += len(sw)
            if any(after == Mode.STICK for _, _, after, _, _ in sw):
                collapsed |= d < COLLAPSE * d.max()
            with np.errstate(divide="ignore"):
                logs[k - n_align] += np.log(d)
        if k >= n_align:
            samples[k - n_align] = y
        bar.update(t - bar.n)
    bar.close()
    spec = _spectrum(model, logs, collapsed, base, tau, rtol, t_transient, switches, samples)
    spec.start_perturbation = moved
    return spec


def _escape(model, base, t_end):
    """The time a run started `START_PERTURBATION` off unstable steady sliding takes to
    leave it, ``ln(1 / START_PERTURBATION) / sigma`` (to a disturbance of order one),
    where ``t_end`` leaves the average its ``2 BLOCKS`` base periods after it, else 0."""
    lam = np.asarray(unforced.eigenvalues(**model.arguments(unforced.eigenvalues)))
    sigma = float(np.max(lam.real))
    t = math.log(1.0 / START_PERTURBATION) / sigma
    n = int((t_end - base * math.ceil(t / base)) / base)
    return t if n - min(_ALIGN, n // 4) >= 2 * BLOCKS else 0.0


def _settings(t0, t1, rtol, backend):
    """The settings of a run from ``t0`` to ``t1`` (its samples are not read)."""
    return SolverSettings(
        t_end=t1, rtol=rtol, atol=rtol, dt=(t1 - t0) / 50, t_discard=t0, backend=backend
    )


def _spectrum(model, logs, collapsed, base, tau, rtol, t_transient, switches, samples):
    """The exponents, their errors and running means from each period's ``sum log |R_ii|``."""
    n = logs.shape[0]
    finite = np.where(collapsed, 0.0, logs)
    running = np.cumsum(finite, axis=0) / (base * np.arange(1, n + 1))[:, None]
    mean = running[-1]
    blocks = finite[: n - n % BLOCKS].reshape(BLOCKS, -1, 4).mean(axis=1) / base
    spread = blocks.std(axis=0, ddof=1) / math.sqrt(BLOCKS)
    second = finite[n // 2 :].mean(axis=0) / base
    # the runs' tolerance bounds what no average removes: each chunk's R_ii carries
    # about rtol of relative error, rtol / tau of rate
    error = np.maximum(np.maximum(spread, np.abs(mean - second)), rtol / tau)
    exponents = np.where(collapsed, -np.inf, mean)
    error = np.where(collapsed, 0.0, error)
    order = np.argsort(-exponents, kind="stable")
    running[:, collapsed] = -np.inf
    return Lyapunov(
        model,
        exponents[order],
        error[order],
        float(t_transient),
        float(n * base),
        float(tau),
        int(collapsed.sum()),
        int(switches),
        running[:, order],
        samples[-1].copy(),
        samples,
    )
