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
* `NoPeriodicResponse` (a `RuntimeError`): no periodic response is found.

The command line reports each in one line, exit status 2 (`beltmdsm.cli.flags`).
`NotApplicable` (a `ValueError`: the superposition's closed forms do not exist for a
model) and `NoEdge` (a `RuntimeError`: no margin closes where a response is lost) are
raised and caught inside the package; they are here so that every failure has one home.

`BeltmdsmError` and `Unsupported` are defined in ``beltmdsm.generated._support`` and re-exported
here (the same classes): the generated modules raise `Unsupported` and cannot import
beltmdsm (the layers point derive -> generated -> beltmdsm), and one class of one name
is what ``except Unsupported`` needs to catch a refusal of either layer. The classes
are also importable from the modules that raised them before (`beltmdsm.model`,
`beltmdsm.periodic.periodmap`, `beltmdsm.periodic.floquet`, `beltmdsm.continuation.edges`,
`beltmdsm.integrate.superposition`): the same objects.
"""

from __future__ import annotations

from beltmdsm.generated._support import BeltmdsmError, Unsupported

__all__ = [
    "BeltmdsmError",
    "Refused",
    "Unsupported",
    "StepTooSmall",
    "NoPeriodicResponse",
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
    ``rtol`` and ``atol`` are the tolerances of the run.
    """

    def __init__(self, message: str, rtol: float, atol: float) -> None:
        super().__init__(message)
        self.rtol, self.atol = rtol, atol

    def __reduce__(self) -> tuple[type, tuple[str, float, float]]:
        return (type(self), (str(self), self.rtol, self.atol))


class NoPeriodicResponse(BeltmdsmError, RuntimeError):
    """No periodic response is found (Newton's method and forward iteration fail)."""


class NotApplicable(BeltmdsmError, ValueError):
    """The superposition's closed forms do not exist for this model (the reason)."""


class NoEdge(BeltmdsmError, RuntimeError):
    """No margin of the response closes towards where it is no longer found."""
