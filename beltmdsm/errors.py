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
* `StepTooSmall` (an `ArithmeticError`): an integrator cannot go on at the
  tolerances given.
* `NoPeriodicResponse` (a `RuntimeError`): no periodic response is found;
  `ShorterPeriod`, one of them: the response of ``k`` periods asked for is one of a
  divisor of ``k`` periods.

The command line reports each in one line, exit status 2 (`beltmdsm.cli.flags`).
`NotApplicable` (a `ValueError`: the superposition's closed forms do not exist for a
model) and `NoEdge` (a `RuntimeError`: no margin closes where a response is lost) are
raised and caught inside the package; they are here so that every failure has one home.

`BeltmdsmError` and `Unsupported` are defined in ``beltmdsm.generated._support`` and re-exported
here (the same classes): the generated modules raise `Unsupported` and cannot import
beltmdsm (the layers point derive -> generated -> beltmdsm), and one class of one name
is what ``except Unsupported`` needs to catch a refusal of either layer. The classes
are also importable from the modules that raised them before (`beltmdsm.model`,
`beltmdsm.continuation.edges`, `beltmdsm.integrate.superposition`): the same objects.
`NoPeriodicResponse` is imported from here alone (it was defined in
``beltmdsm.periodic.periodmap``, now cut by concept).

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

from beltmdsm.generated._support import BeltmdsmError, Unsupported

__all__ = [
    "BeltmdsmError",
    "Refused",
    "Unsupported",
    "StepTooSmall",
    "NoPeriodicResponse",
    "ShorterPeriod",
    "NotApplicable",
    "NoEdge",
]


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
