"""What every readable text shares: JSON-able values, the bifurcation kinds, the laws."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from ...model import Model

__all__ = ["jsonable", "kind", "laws", "response_name"]


def jsonable(x: Any) -> Any:
    """``x`` with numpy scalars as Python numbers, tuples as lists and NaN or inf as None."""
    if isinstance(x, dict):
        return {k: jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, (np.floating, float)):
        return None if not np.isfinite(x) else float(x)
    if isinstance(x, (np.integer, np.bool_)):
        return x.item()
    return x


def kind(name: str, frequency: float | None = None) -> str:
    """A bifurcation kind as the text prints it (a Neimark-Sacker pair with its frequency)."""
    if name == "neimark_sacker" and frequency is not None:
        return f"neimark_sacker at {frequency:.4g} rad/s"
    return name


def laws(model: Model) -> str:
    """The model's laws and the Floquet path they take, as the headers print them."""
    from ...periodic.engines import engine_of

    return (
        f"{model.friction} friction, {model.contact}, tension {model.tension}; "
        f"{engine_of(model)} path"
    )


def response_name(periods: int) -> str:
    """``"T"``, or ``"4T"`` for a response of 4 excitation periods."""
    return "T" if periods == 1 else f"{periods}T"
