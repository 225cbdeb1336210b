"""The paper's unstable belt speeds: its closed forms (Eqs. 25, 28), each ``V_hat`` reading.

The paper (Sects. 4.2-4.3) linearises the slow equations with the slope ``mu_bar'`` of
Eq. (25); `beltmdsm.generated.stability.unstable_interval` gives its unstable interval in
closed form, with the model's laws. The closed forms need the law's fast average in
closed form (the capability ``closed_form_average``) and a ``V_hat`` that does not
depend on ``Vb``; where either fails (Stribeck's law) `paper_intervals` finds the same
analysis' unstable set numerically (`beltmdsm.prediction.paper_numeric`), and
`paper_reasons` says so with its grid and tolerance.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, Literal

from beltmdsm.generated import _support, friction, stability

from ..model import Model, as_model
from .paper_numeric import NO_VHAT, PAPER_XTOL, paper_numeric
from .scan import GRID_END

__all__ = [
    "paper_intervals",
    "paper_reasons",
    "PAPER_NUMERIC",
    "NUMERIC_NO_AVERAGE",
    "NUMERIC_VHAT_OF_VB",
]


def paper_intervals(
    model: Model | Mapping[str, Any] | None = None,
    *,
    convention: Literal["paper", "consistent"] = "paper",
    **kw: Any,
) -> dict[str, list[tuple[float, float]] | None]:
    """The paper's unstable interval ``(Vb_c, Vhat]`` for each ``V_hat`` reading (Eq. 25, 28).

    With the model's laws (`beltmdsm.generated.stability.unstable_interval` and
    `beltmdsm.generated.friction.vhat` get ``friction=`` and ``contact=``). Where the closed form
    does not exist (the law's fast average is no closed form, the capability
    ``closed_form_average``, Stribeck's; or ``V_hat`` depends on ``Vb``) the same
    analysis is solved numerically (`paper_numeric`).

    Parameters
    ----------
    model : Model, mapping or None
        the parameter set (or the keywords ``**kw`` it is built from)
    convention : {"paper", "consistent"}
        the sign of the effective friction in Eq. (A4): as printed, or as Eq. (4)
        implies (`beltmdsm.generated.stability.unstable_interval`, docs/modelling.md#friction-sign)

    Returns
    -------
    dict
        ``{"tangential": [(lower, upper), ...], "coupled": [...]}``; an empty interval
        (NaN from `beltmdsm.generated.stability.unstable_interval`) is ``[]``, and a reading
        without an answer is ``None``: ``V_hat`` is 0 (no excitation, where Eqs. 23-25
        have no meaning). `paper_reasons` says why, or how a numeric set was found.

    Raises
    ------
    ValueError
        For bad parameters or options (naming them).

    See Also
    --------
    paper_reasons : why a reading has no answer, or how it was found.
    beltmdsm.prediction.paper_numeric.paper_numeric : the path without closed forms.
    beltmdsm.predict : this and the consistent MDSM.

    Examples
    --------
    At the base set the tangential reading is unstable from 0 up to ``V_hat``; with
    the sign of the friction that Eq. (4) implies, nowhere:

    >>> found = paper_intervals()
    >>> {k: [(round(lo, 4), round(hi, 4)) for lo, hi in v] for k, v in found.items()}
    {'tangential': [(0.0, 8.5212)], 'coupled': [(0.0, 6.3754)]}
    >>> paper_intervals(convention="consistent")
    {'tangential': [], 'coupled': []}
    """
    return _paper(as_model(model, **kw), convention)[0]


def paper_reasons(
    model: Model | Mapping[str, Any] | None = None,
    *,
    convention: Literal["paper", "consistent"] = "paper",
    **kw: Any,
) -> dict[str, str]:
    """``{reading: why}`` for each ``V_hat`` reading whose `paper_intervals` is None
    (`NO_VHAT`, or the refusal of `beltmdsm.generated.stability.unstable_interval`) or was found
    numerically (`PAPER_NUMERIC`: why there is no closed form, the grid and the
    tolerance): one line each.

    Parameters
    ----------
    model : Model, mapping or None
        The parameter set (or the keywords ``**kw`` it is built from).
    convention : {"paper", "consistent"}
        As for `paper_intervals`.

    Returns
    -------
    dict of str
        By reading (``"tangential"``, ``"coupled"``); empty where both have closed
        forms.

    Raises
    ------
    ValueError
        For bad parameters or options (naming them).

    See Also
    --------
    paper_intervals : the intervals these reasons are about.

    Examples
    --------
    >>> paper_reasons()
    {}
    >>> print(paper_reasons(alpha=0.0)["tangential"])
    V_hat = 0 (no fast tangential motion): Eqs. (23)-(25) need V_hat > 0
    """
    return _paper(as_model(model, **kw), convention)[1]


def _vhat_depends_on_vb(model: Model, reading: str) -> bool:
    """Whether the law's ``V_hat`` takes ``Vb`` (the slope of a coefficient that varies
    in slip enters the linear response): the generated function then needs it."""
    fn = friction.vhat
    try:
        fn(model=reading, **{**model.arguments(fn), "Vb": None})
    except TypeError:
        return True
    return False


def _paper(model: Model, convention: str):
    intervals_, reasons = {}, {}
    closed = model.fact("closed_form_average")[0]
    fn = friction.vhat
    for reading in ("tangential", "coupled"):
        intervals_[reading] = None
        if not closed:
            without = NUMERIC_NO_AVERAGE.format(friction=model.friction)
        elif _vhat_depends_on_vb(model, reading):
            without = NUMERIC_VHAT_OF_VB.format(friction=model.friction)
        elif not fn(model=reading, **model.arguments(fn)) > 0:
            reasons[reading] = NO_VHAT
            continue
        else:
            interval = stability.unstable_interval
            try:
                lower, upper = (
                    float(x)
                    for x in interval(
                        convention=convention, vhat_model=reading, **model.arguments(interval)
                    )
                )
            except _support.Unsupported as err:  # no closed-form boundary for these laws
                reasons[reading] = str(err)
                continue
            # an empty interval is NaN (also (Vb_c, Vhat] with Vb_c = Vhat: mu_s = 0)
            empty = math.isnan(lower) or not lower < upper
            intervals_[reading] = [] if empty else [(lower, upper)]
            continue
        try:
            found, info = paper_numeric(model, reading=reading, convention=convention)
        except ValueError as err:
            reasons[reading] = str(err)
            continue
        intervals_[reading] = found
        note = PAPER_NUMERIC.format(without=without, reading=reading, xtol=PAPER_XTOL, **info)
        if info["reaches_top"]:
            note += "; " + GRID_END.format(end="highest", value=info["top"], side="above")
        reasons[reading] = note
    return intervals_, reasons


#: How `paper_intervals` found a set without the closed form (formatted with the reason
#: there is none, the reading and `paper_numeric`'s grid).
PAPER_NUMERIC = (
    "numeric ({without}: Eqs. (25), (28) have no closed form): Vb where "
    "beltmdsm.generated.stability.growth_rate > 0 with V_hat ({reading} reading) at each Vb, "
    "{points} points in [0, {top:.4g}] m/s, edges by brentq to {xtol:.0e} m/s (a root, "
    "or V_hat(Vb) = Vb where the slope of Eq. (25) jumps); a band narrower than "
    "{step:.2g} m/s can be missed"
)


#: The clauses of `PAPER_NUMERIC`: a law without a closed-form fast average, a V_hat
#: that depends on Vb.
NUMERIC_NO_AVERAGE = "friction={friction!r} has no closed-form fast average (closed_form_average)"


NUMERIC_VHAT_OF_VB = "V_hat depends on Vb under friction={friction!r}"
