"""Moved (issue 38): the forced response's point and corrector are
`beltmdsm.continuation.forced` (`BranchPoint`, `ForcedProblem`), the pseudo-arclength
walk that drives it is `beltmdsm.continuation.driver`."""

from .forced import BranchPoint, ForcedProblem, _Continuation  # noqa: F401

__all__ = ["BranchPoint"]
