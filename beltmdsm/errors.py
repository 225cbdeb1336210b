"""The named failures of the package that are not bad values of one argument.

A bad value (a parameter outside its domain, a setting that is not a number) is a
`ValueError` naming it, raised where it is checked. The failures here say more; they
form one hierarchy under `BeltmdsmError`, and each keeps its builtin base, so that an
``except ValueError`` written for one still catches it:

* `Refused` (a `ValueError`): a request that the package refuses before computing
  anything, because what it asks for cannot be answered from what it would compute
  (a sampling step that aliases the excitation into the omega1 band, a tolerance
  below the rounding of a range) or would cost more than a stated bound (memory,
  grid points). It names the settings it refuses (``names``), so that the command
  line can name its flags.
* `Unsupported` (a `ValueError`): an analysis that the chosen laws do not allow,
  naming the law and the missing property.
* `NoHopfPoint` (a `ValueError`): no pair of steady sliding's eigenvalues crosses the
  imaginary axis in the range given.
* `StepTooSmall` (an `ArithmeticError`): an integrator cannot go on at the
  tolerances given.
* `NoPeriodicResponse` (a `RuntimeError`): no periodic response is found;
  `ShorterPeriod`, one of them: the response of ``k`` periods asked for is one of a
  divisor of ``k`` periods.

The command line reports each in one line, exit status 2 (`beltmdsm.cli.flags`).
`NotApplicable` (a `ValueError`: the superposition's closed forms do not exist for a
model) and `NoEdge` (a `RuntimeError`: no margin closes where a response is lost) are
and `NoPrediction` (a `ValueError`: an analysis that gives no prediction) are raised and
caught inside the package; they are here so that every failure has one home.

Every class is defined here, and this module imports nothing of beltmdsm (only the
standard library): it is the lowest layer of the package (tests/test_layers.py), below
``beltmdsm.generated``, whose modules raise `Unsupported` too and import it from here
(``beltmdsm.generated._support``, written from derive/codegen/templates/_support.py),
so that one class of one name catches a refusal of either layer. The classes are also
importable from the modules that raised them before (`beltmdsm.model`,
`beltmdsm.continuation.edges`, `beltmdsm.integrate.superposition`,
`beltmdsm.cycles.hopf`, ``beltmdsm.generated._support``): the same objects.
`NoPeriodicResponse` is imported from here alone (it was defined in
``beltmdsm.periodic.periodmap``, now cut by concept).

Three names that sound alike are three things: `Refused` (this module: a request
refused before anything is computed), `NoPrediction` (this module: an analysis of
`beltmdsm.prediction` that has no answer, caught there and reported as its reason) and
``beltmdsm.derive.codegen.NoVariant`` (derive/: a variant of a generated function that
does not exist, written as the table entry ``beltmdsm.generated._support.NoVariant``,
on which the function raises `Unsupported`).

Examples
--------
One ``except`` catches every named failure; each is still its builtin kind:

>>> from beltmdsm import Model
>>> from beltmdsm.errors import BeltmdsmError, Unsupported
>>> from beltmdsm.model import require
>>> try:
...     require(Model(friction="stribeck"), "friction_monotone", "this analysis")
... except BeltmdsmError as err:
...     print(type(err).__name__, isinstance(err, ValueError))
...     print(err)
Unsupported True
this analysis: friction='stribeck': dmu/d|Vr| ... the coefficient falls with the sliding speed ...
"""

from __future__ import annotations

__all__ = [
    "BeltmdsmError",
    "Refused",
    "Unsupported",
    "NoHopfPoint",
    "NoPrediction",
    "StepTooSmall",
    "NoPeriodicResponse",
    "ShorterPeriod",
    "NotApplicable",
    "NoEdge",
]


class BeltmdsmError(Exception):
    """The base of every named failure of beltmdsm and of its generated modules.

    Each failure also keeps its builtin base (`ValueError`, ...), so that an ``except``
    written for that still catches it.

    See Also
    --------
    beltmdsm.errors : the failures, each a subclass of this one.

    Examples
    --------
    >>> from beltmdsm.errors import BeltmdsmError, Refused, StepTooSmall, Unsupported
    >>> all(issubclass(e, BeltmdsmError) for e in (Refused, StepTooSmall, Unsupported))
    True
    """


class Unsupported(BeltmdsmError, ValueError):
    """A choice of laws without a property that the function needs.

    The message is one line naming the law and the missing property (from
    ``beltmdsm.generated.capabilities``): the function refuses rather than computing with
    the physics of another law. ``beltmdsm.generated._support.Unsupported``, which the
    generated functions raise, and ``beltmdsm.model.Unsupported`` are this class.

    See Also
    --------
    beltmdsm.generated.capabilities : the facts each choice of laws has, and why not.

    Examples
    --------
    Stribeck friction has no closed-form critical belt speed (its effective friction
    is a quadrature), so the closed form refuses and says what to use instead:

    >>> from beltmdsm.errors import Unsupported
    >>> from beltmdsm.generated import stability
    >>> from beltmdsm.generated.parameters import BASE
    >>> params = {**BASE, "mu_k": 0.2, "v_s": 1.0}
    >>> try:
    ...     stability.critical_belt_speed(**params, friction="stribeck")
    ... except Unsupported as err:
    ...     print(isinstance(err, ValueError), "no closed-form critical belt speed" in str(err))
    True True
    """


class NoHopfPoint(BeltmdsmError, ValueError):
    """No complex pair of steady sliding crosses the imaginary axis in the range.

    A `ValueError`: the range given holds no Hopf point to start a branch of
    self-excited cycles from.

    See Also
    --------
    beltmdsm.cycles.hopf.hopf_point : Raises it.

    Examples
    --------
    Under Coulomb friction the tangential pair of steady sliding is the damped
    oscillator's, ``-0.1 +- 0.995 i``, whatever the belt speed: no Hopf point.

    >>> from beltmdsm import Model
    >>> from beltmdsm.cycles.hopf import hopf_point
    >>> try:
    ...     hopf_point(Model(alpha=0.0), "Vb", 0.5, 5.0)
    ... except NoHopfPoint as refusal:
    ...     print(isinstance(refusal, BeltmdsmError), str(refusal)[:38])
    True no Hopf point of steady sliding for Vb
    """


class NoPrediction(BeltmdsmError, ValueError):
    """An analysis of `beltmdsm.prediction.predict` that gives no prediction, with why.

    Raised and caught inside the package: the analysis' list is then None and the
    message its reason (``Prediction.reasons``).

    Parameters
    ----------
    message : str
        Why the analysis has no answer (the law and the assumption).

    See Also
    --------
    beltmdsm.prediction.prediction.Prediction : ``reasons`` holds the message.

    Examples
    --------
    >>> from beltmdsm.errors import NoPrediction
    >>> issubclass(NoPrediction, ValueError) and issubclass(NoPrediction, BeltmdsmError)
    True
    """


class Refused(BeltmdsmError, ValueError):
    """A request refused before anything is computed, with the bound it exceeds.

    Parameters
    ----------
    message : str
        What is refused, the bound and where it is stated.
    *names : str
        The settings or arguments refused, by their Python names (``"dt"``,
        ``"t_end"``, ``"tol"``, ``"points"``).

    Attributes
    ----------
    names : tuple of str
        ``names``: the command line names its flags from them.

    See Also
    --------
    beltmdsm.errors.Unsupported : an analysis that the chosen laws do not allow.

    Examples
    --------
    A sampling step that would alias the excitation's harmonics into the omega1 band:

    >>> from beltmdsm import Model, simulate
    >>> from beltmdsm.errors import Refused
    >>> try:
    ...     simulate(Model(Vb=5), dt=0.7, t_end=50)
    ... except Refused as err:
    ...     print(err.names, err)
    ('dt',) dt = 0.7 s samples up to pi/dt = 4.488 rad/s, below 8 x Omega_t = 32 rad/s: ...

    It survives pickling (a refusal raised in a worker process arrives whole):

    >>> import pickle
    >>> pickle.loads(pickle.dumps(Refused("too many points", "points"))).names
    ('points',)
    """

    def __init__(self, message: str, *names: str) -> None:
        super().__init__(message)
        self.names = names

    def __reduce__(self) -> tuple[type, tuple[str, ...]]:
        # rebuilt with its names (the default passes only ``args``): a refusal raised in
        # a worker process of an executor arrives whole
        return (type(self), (str(self), *self.names))


class StepTooSmall(BeltmdsmError, ArithmeticError):
    """An integrator's step fell below what the rounding of the time allows.

    The tolerances are too loose for the switches to be located (the state drifts
    across a switching surface between steps) or too tight for the field there.

    Parameters
    ----------
    message : str
        Where the step fell, and how far.
    rtol, atol : float
        The tolerances of the run (kept as attributes of the same names).

    See Also
    --------
    beltmdsm.settings.SolverSettings : where the tolerances are set.

    Examples
    --------
    >>> import pickle
    >>> from beltmdsm.errors import BeltmdsmError, StepTooSmall
    >>> err = StepTooSmall("the step fell below 1e-14 s at t = 3.2 s", 1e-10, 1e-10)
    >>> isinstance(err, ArithmeticError) and isinstance(err, BeltmdsmError)
    True
    >>> again = pickle.loads(pickle.dumps(err))
    >>> str(again), again.rtol, again.atol
    ('the step fell below 1e-14 s at t = 3.2 s', 1e-10, 1e-10)
    """

    def __init__(self, message: str, rtol: float, atol: float) -> None:
        super().__init__(message)
        self.rtol, self.atol = rtol, atol

    def __reduce__(self) -> tuple[type, tuple[str, float, float]]:
        return (type(self), (str(self), self.rtol, self.atol))


class NoPeriodicResponse(BeltmdsmError, RuntimeError):
    """No periodic response is found (Newton's method and forward iteration fail).

    Parameters
    ----------
    message : str
        Where and why the search failed.

    See Also
    --------
    beltmdsm.periodic.floquet.floquet : raises it where there is no periodic response.
    beltmdsm.multistability.responses.responses : lists the seeds that failed with it.

    Examples
    --------
    >>> from beltmdsm.errors import BeltmdsmError, NoPeriodicResponse
    >>> try:
    ...     raise NoPeriodicResponse("Newton's method did not converge at Vb = 9")
    ... except RuntimeError as err:
    ...     print(isinstance(err, BeltmdsmError), err)
    True Newton's method did not converge at Vb = 9
    """


class ShorterPeriod(NoPeriodicResponse):
    """No response of minimal period ``asked`` periods: the attractor is a response of
    ``periods``, a divisor of it (its orbit repeats after ``asked`` periods too, but is
    not a new response). ``periodic_response(..., periods=periods)`` computes it
    (``floquet --periods K`` reports it so).

    Parameters
    ----------
    asked : int
        The periods asked for.
    periods : int
        The periods of the response found, a divisor of ``asked``.
    how : str
        How it was found (the message goes on with ``periods``).

    Attributes
    ----------
    asked, periods, how : int, int, str
        The arguments, for a caller that goes on with ``periods``.

    See Also
    --------
    beltmdsm.errors.NoPeriodicResponse : The failure this one refines.

    Examples
    --------
    A period-1 response also repeats after 2 periods; asked for period 2, the
    message says which ``periods`` computes it:

    >>> error = ShorterPeriod(2, 1, "the fixed point of the map has")
    >>> print(error)  # doctest: +NORMALIZE_WHITESPACE
    no response of minimal period 2 periods found: the fixed point of the map has
    1 period, whose orbit repeats after 2 too (periods=1 computes it)
    >>> error.periods, isinstance(error, NoPeriodicResponse)
    (1, True)
    """

    def __init__(self, asked: int, periods: int, how: str) -> None:
        super().__init__(
            f"no response of minimal period {_periods(asked)} found: {how} "
            f"{_periods(periods)}, whose orbit repeats after {asked} too "
            f"(periods={periods} computes it)"
        )
        self.asked, self.periods, self.how = asked, periods, how

    def __reduce__(self) -> tuple[type, tuple[int, int, str]]:
        # rebuilt from what built it (the default passes the message alone, which this
        # __init__ does not take: raised in a worker process it did not arrive)
        return (type(self), (self.asked, self.periods, self.how))


def _periods(k: int) -> str:
    return "1 period" if k == 1 else f"{k} periods"


class NotApplicable(BeltmdsmError, ValueError):
    """The superposition's closed forms do not exist for this model (the reason).

    Raised and caught inside the package: a run then takes the general integrator.

    Parameters
    ----------
    message : str
        Why the closed forms do not exist.

    See Also
    --------
    beltmdsm.settings.SolverSettings : ``solver="superposition"`` falls back to "events".

    Examples
    --------
    >>> from beltmdsm.errors import NotApplicable
    >>> issubclass(NotApplicable, ValueError)
    True
    """


class NoEdge(BeltmdsmError, RuntimeError):
    """No margin of the response closes towards where it is no longer found.

    Raised and caught inside the package: the end of a response is then reported
    unclassified.

    Parameters
    ----------
    message : str
        Which margins were tried.

    See Also
    --------
    beltmdsm.continuation.band.floquet_band : labels each end by the margin that closes.

    Examples
    --------
    >>> from beltmdsm.errors import NoEdge
    >>> issubclass(NoEdge, RuntimeError)
    True
    """
