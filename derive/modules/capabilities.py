"""What each combination of laws allows: the spec of generated/capabilities.py."""

from __future__ import annotations

from .. import capabilities as cap
from ..codegen import ModuleSpec

__all__ = ["build"]


def build() -> ModuleSpec:
    """The structural facts of each combination of laws, as data (derive/capabilities.py)."""
    table = cap.capabilities()
    return ModuleSpec(
        "capabilities",
        """What each combination of laws allows: facts SymPy decided (derive/capabilities.py).

``CAPABILITIES[(friction, contact, tension)][fact] = (holds, reason)``: ``holds`` a
bool, ``reason`` one line naming the law and the property. ``FACTS`` are the fact
names, ``FACT_DOCS`` say what each means and which analysis relies on it. An
analysis checks the facts it needs and either takes a general path or refuses with
the reason, never computing with the physics of another law.
""",
        (),
        (
            ("FACTS", tuple(cap.FACTS), "The facts, in the order of every entry."),
            ("FACT_DOCS", dict(cap.FACTS), "What each fact means and which analysis needs it."),
            ("CAPABILITIES", table, "(friction, contact, tension) -> fact -> (holds, reason)."),
        ),
        mp=False,
    )
