"""An analysis's check of a structural fact of the chosen laws (``require``).

SymPy decides, per combination of the paper's laws, facts an analysis relies on (the
slip friction independent of the state, ...: ``beltmdsm.generated.capabilities``);
`require` raises `Unsupported` in one line, naming the analysis, the law and the missing
property, where one does not hold. `beltmdsm.model` re-exports it.
"""

from __future__ import annotations

from typing import Protocol

from .errors import Unsupported

__all__ = ["require"]


class _Laws(Protocol):
    """What `require` reads of a model (`beltmdsm.model.Model.fact`); a protocol, since
    beltmdsm/model.py imports this module."""

    def fact(self, name: str) -> tuple[bool, str]: ...


def require(model: _Laws, fact: str, analysis: str) -> None:
    """Raise `Unsupported` unless ``fact`` (``beltmdsm.generated.capabilities.FACTS``) holds.

    The message names the analysis, the law and the property, in one line:
    ``"superposition: friction='stribeck': the slip-mode friction depends on X1'"``.

    Parameters
    ----------
    model : Model
        The model the analysis is asked for.
    fact : str
        A property of the model's laws, a key of
        ``beltmdsm.generated.capabilities.FACTS``.
    analysis : str
        The analysis that needs the fact, named first in the message.

    Raises
    ------
    Unsupported
        Where the fact does not hold for the model's laws.
    KeyError
        For a fact that is not in the table.

    See Also
    --------
    beltmdsm.model.Model.fact : Whether a fact holds, and why not.

    Examples
    --------
    Coulomb's slip friction does not depend on the state; Stribeck's depends on the
    slip speed, so an analysis that needs the first fact refuses it in one line:

    >>> from beltmdsm.model import Model
    >>> require(Model(friction="coulomb"), "slip_friction_state_independent", "sketch")
    >>> try:
    ...     require(Model(friction="stribeck"), "slip_friction_state_independent", "sketch")
    ... except Unsupported as refusal:
    ...     print(refusal)
    sketch: friction='stribeck': the slip-mode friction mu(|Vr|) F depends on X1' ...
    """
    holds, reason = model.fact(fact)
    if not holds:
        raise Unsupported(f"{analysis}: {reason}")
