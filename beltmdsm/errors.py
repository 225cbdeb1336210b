"""The named failures of the package that are not bad values of one argument.

A bad value (a parameter outside its domain, a setting that is not a number) is a
`ValueError` naming it, raised where it is checked. The failures here say more:

* `Refused` (a `ValueError`): a request that the package refuses before computing
  anything, because what it asks for cannot be answered from what it would compute
  (a sampling step that aliases the excitation into the omega1 band, a tolerance
  below the rounding of a range) or would cost more than a stated bound (memory,
  grid points). It names the settings it refuses (``names``), so that the command
  line can name its flags.
* `StepTooSmall` (an `ArithmeticError`): an integrator cannot go on at the
  tolerances given.

`beltmdsm.analysis.floquet.NoPeriodicResponse` (a `RuntimeError`) is the third: no
periodic response is found. The command line reports each in one line, exit status 2
(`beltmdsm.cli.flags`).
"""

from __future__ import annotations

__all__ = ["Refused", "StepTooSmall"]


class Refused(ValueError):
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


class StepTooSmall(ArithmeticError):
    """An integrator's step fell below what the rounding of the time allows.

    The tolerances are too loose for the switches to be located (the state drifts
    across a switching surface between steps) or too tight for the field there.
    ``rtol`` and ``atol`` are the tolerances of the run.
    """

    def __init__(self, message: str, rtol: float, atol: float) -> None:
        super().__init__(message)
        self.rtol, self.atol = rtol, atol
