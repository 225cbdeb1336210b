"""Predicted unstable belt speeds: the paper's analysis and a consistent MDSM, side by side.

`predict` runs the paper's closed forms (`beltmdsm.prediction.paper`, or its numeric
path, `beltmdsm.prediction.paper_numeric`) for both ``V_hat`` readings and the
consistent MDSM (`beltmdsm.prediction.scan`), and returns their unstable ``Vb``
intervals as a `Prediction`, with a reason wherever an analysis has no answer or
assumed something.

The tension law (`predict`'s ``tension=``, docs/modelling.md#tension): the paper's
analyses linearise at the equilibrium, where the contact force is ``g > 0``, so
their closed forms are the same under both laws. The consistent MDSM takes a
harmonic fast normal force ``g + N1 sin``; with ``tension="clipped"`` and
``N1 >= g`` the clip ``max(F, 0)`` cuts it off and it is no longer harmonic, so that
analysis gives no prediction (`CLIPPED_MDSM`) rather than the allowed law's.

A friction law with a static bound of its own (``static_kinetic``: stick held up to
``mu_s F``, slip at ``mu_k F``): every analysis here linearises sliding and averages the
slip law over a fast motion that passes ``Vr = 0`` without sticking, so it takes the
kinetic coefficient and the static bound enters none of them. Their verdicts are
local: where the static bound exceeds the kinetic coefficient a stick-slip cycle can
coexist with stable sliding, and `predict` says so in each analysis' note
(`STATIC_BOUND`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from beltmdsm.generated.parameters import STATIC_BOUNDS

from .._calling import public, rename
from ..arguments import number
from ..errors import NoPrediction
from ..model import OPTION_DEFAULTS, Model, as_model
from .mdsm import _linear, _linear_without_reversal, clip_acts
from .paper import _paper
from .scan import GRID_END, _check_grid, _check_points, grid_note, unstable_intervals
from .sliding import _unforced_note

__all__ = [
    "predict",
    "Prediction",
    "NO_EXCITATION",
    "NO_FAST_MOTION",
    "CLIPPED_MDSM",
    "CLIPPED_MDSM_INACTIVE",
    "CLIPPED_PAPER",
    "STATIC_BOUND",
]


#: Why an analysis gives no prediction, or none of its usual kind.
NO_EXCITATION = (
    "no fast tangential motion: without tangential excitation, and none passed "
    "on by friction from the normal one, the averaged friction is friction of "
    "constant direction and coefficient with slope 0, so no belt speed is unstable"
)


#: The note on the consistent MDSM without fast motion, for a coefficient that
#: varies in slip (formatted with the law).
NO_FAST_MOTION = (
    "no fast tangential motion: the slow damping is the unforced equilibrium's, "
    "2 beta1 omega1 + g dmu/d|Vr| at |Vr| = Vb (beltmdsm.generated.unforced), which varies "
    "with Vb under friction={friction!r}"
)


#: Why the consistent MDSM gives no prediction under the clipped tension law
#: (formatted with the amplitude ``N1`` of the fast normal force and ``g``).
CLIPPED_MDSM = (
    "tension='clipped': the harmonic balance of the consistent MDSM assumes a "
    "harmonic fast normal force g + N1 sin(Omega t + psi), and with N1 = {N1:.4g} "
    ">= g = {g:.4g} the clip max(F, 0) cuts it off wherever it would pull, which "
    "makes it non-harmonic; no prediction (the allowed law's would be silently "
    "wrong)"
)


#: The note on the consistent MDSM where the clip does not act on its fast normal force.
CLIPPED_MDSM_INACTIVE = (
    "tension='clipped': the linear fast normal force g + N1 sin stays "
    "positive (N1 = {N1:.4g} < g = {g:.4g}), so the clip does not act on "
    "it and the harmonic balance is the same as under 'allowed'"
)


#: The note on every analysis under a friction law with a static bound of its own
#: (``beltmdsm.generated.parameters.STATIC_BOUNDS``; formatted with the law and both bounds).
STATIC_BOUND = (
    "friction={friction!r}: averaged is the slip law (mu(0) = {rest}) over a fast "
    "motion that passes Vr = 0 without sticking; the static bound {static} bounds "
    "stick only, so a belt speed found stable here does not exclude a stick-slip "
    "cycle beside stable sliding (friction_monotone fails where {rest} < {static})"
)


#: The note on the paper's closed forms under the clipped tension law.
CLIPPED_PAPER = (
    "tension='clipped': the same as under 'allowed', since the analysis "
    "linearises at the equilibrium, where the contact force g > 0 does not pull"
)


@dataclass(frozen=True)
class Prediction:
    """The predicted unstable ``Vb`` intervals of each analysis (``predict --json`` keys).

    Parameters
    ----------
    paper_tangential_vhat, paper_coupled_vhat : list of (float, float) or None
        The paper's unstable intervals with the tangential and the coupled reading of
        ``V_hat`` (`beltmdsm.prediction.paper.paper_intervals`), in m/s; None where
        that analysis has no answer.
    consistent_mdsm : list of (float, float) or None
        The consistent MDSM's unstable intervals
        (`beltmdsm.prediction.scan.unstable_intervals`); None where it has no answer.
    reasons : dict of str
        For an analysis, the sentence that says why it has no answer, why its list is
        empty, or what it assumed (no excitation, the tension law, a numeric path).
    tension, contact, friction : str
        The model's laws.

    Attributes
    ----------
    ANALYSES : tuple of str
        The three analyses, in the order they are printed.

    See Also
    --------
    beltmdsm.predict : what returns it.
    beltmdsm.cli.text : how ``beltmdsm predict`` prints it.

    Examples
    --------
    >>> from beltmdsm import predict
    >>> result = predict(Model(Omega_n=7.0), points=20)  # two excitation frequencies
    >>> result.consistent_mdsm is None
    True
    >>> print(result.reasons["consistent_mdsm"])
    the harmonic balance needs one excitation frequency: Omega_t = 4.0 != Omega_n = 7.0
    >>> [(round(lo, 3), round(hi, 3)) for lo, hi in result.paper_tangential_vhat]
    [(0.0, 8.521)]
    >>> sorted(result.as_dict())  # doctest: +NORMALIZE_WHITESPACE
    ['consistent_mdsm', 'contact', 'friction', 'paper_coupled_vhat',
     'paper_tangential_vhat', 'reasons', 'tension']
    """

    paper_tangential_vhat: list[tuple[float, float]] | None
    paper_coupled_vhat: list[tuple[float, float]] | None
    consistent_mdsm: list[tuple[float, float]] | None
    reasons: dict[str, str] = field(default_factory=dict)
    tension: str = OPTION_DEFAULTS["tension"]
    contact: str = OPTION_DEFAULTS["contact"]
    friction: str = OPTION_DEFAULTS["friction"]

    #: The analyses, in the order they are printed.
    ANALYSES = ("paper_tangential_vhat", "paper_coupled_vhat", "consistent_mdsm")

    def as_dict(self) -> dict[str, Any]:
        """The prediction as plain values by field name (``predict --json``)."""
        return asdict(self)

    def __repr__(self) -> str:
        from .._display import block, intervals

        lines = []
        for name in self.ANALYSES:
            found = getattr(self, name)
            if found is None:
                lines.append(f"{name}: no prediction ({self.reasons.get(name, '')})")
            else:
                note = " (a note in reasons)" if name in self.reasons else ""
                lines.append(f"{name}: unstable Vb in {intervals(found)}{note}")
        head = f"Prediction({self.friction} friction, {self.contact}, tension {self.tension})"
        return block(head, lines)


@public(renamed={"vb_max": rename("hi")})
def predict(
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb: ArrayLike | None = None,
    points: int | np.integer = 400,
    progress: bool = False,
    hi: float | None = None,
) -> Prediction:
    """Both analyses' predicted unstable ``Vb`` intervals.

    Parameters
    ----------
    model : Model or dict, optional
        The parameters and the laws (default: the base set). Under
        ``tension="clipped"`` (docs/modelling.md#tension) the paper's closed forms do
        not change (a note in ``reasons`` says why); the consistent MDSM has no
        prediction where the clip cuts its fast normal force (`clip_acts`,
        `CLIPPED_MDSM`) and a note where it does not.
    vb : array_like, optional
        The consistent MDSM's grid of belt speeds (`unstable_intervals`; default:
        ``points`` speeds up to past the onset of friction reversal).
    points : int
        The size of the default grid (2 to `MAX_VB_POINTS`).
    progress : bool
        Show a progress bar on stderr once the grid takes more than 2 s.
    hi : float, optional
        The top of the default grid instead of its own (``vb_max=`` before:
        deprecated). Where a band of the
        consistent MDSM reaches the lowest point of the grid above 0, ``reasons``
        says that it may extend below; where ``hi`` makes the grid coarser than
        the default's, what it cannot resolve (`grid_note`); where the law's unforced
        critical belt speed has no closed form, that its edges were found
        numerically (`unforced_edges`).

    Returns
    -------
    Prediction
        The unstable intervals of the paper's analysis (both ``V_hat`` readings) and
        of the consistent MDSM, each None where that analysis has no answer, with the
        reasons.

    Raises
    ------
    ValueError
        For bad parameters, a bad option or a bad grid (naming them).
    beltmdsm.errors.Refused
        For more than `MAX_VB_POINTS` points (a ValueError too).

    See Also
    --------
    beltmdsm.prediction.paper.paper_intervals : the paper's intervals alone.
    beltmdsm.prediction.scan.unstable_intervals : the consistent MDSM's, with its table.
    beltmdsm.floquet_band : the exact answer, from the Floquet multipliers.

    Examples
    --------
    The base set: the paper's analysis (as printed, tangential ``V_hat``) predicts
    instability from 0 up to 8.52 m/s, the consistent MDSM between 4.68 and 6.38 m/s.

    >>> from beltmdsm import predict
    >>> result = predict(points=20)
    >>> result
    Prediction(coulomb friction, hertz_damp, tension allowed)
      paper_tangential_vhat: unstable Vb in [0, 8.52122]
      paper_coupled_vhat: unstable Vb in [0, 6.37537]
      consistent_mdsm: unstable Vb in [4.68158, 6.37537]
    >>> for name in result.ANALYSES:
    ...     print(name, [(round(lo, 3), round(hi, 3)) for lo, hi in getattr(result, name)])
    paper_tangential_vhat [(0.0, 8.521)]
    paper_coupled_vhat [(0.0, 6.375)]
    consistent_mdsm [(4.682, 6.375)]

    Without excitation there is no fast motion, and each analysis says so:

    >>> quiet = predict(Model(alpha=0.0), points=20)
    >>> quiet.consistent_mdsm, quiet.paper_tangential_vhat
    ([], None)
    >>> print(quiet.reasons["paper_tangential_vhat"])
    V_hat = 0 (no fast tangential motion): Eqs. (23)-(25) need V_hat > 0
    """
    model = as_model(model)
    p, tension = model.params, model.tension
    _check_points(points)
    vb_max = None if hi is None else number("hi", hi, above=0)
    if vb is not None:
        vb = _check_grid(vb)
    reasons = {}
    clipped = False
    if tension == "clipped" and p["Omega_t"] == p["Omega_n"]:
        # (with two frequencies the harmonic balance is refused for that reason below)
        clipped, N1 = clip_acts(model)
        note = (CLIPPED_MDSM if clipped else CLIPPED_MDSM_INACTIVE).format(N1=N1, g=p["g"])
    try:
        if clipped:
            raise NoPrediction(note)
        consistent, table = unstable_intervals(
            model, vb=vb, points=points, progress=progress, vb_max=vb_max
        )
    except (RuntimeError, ValueError) as err:  # NoPrediction is a ValueError
        # the parameters and the grid are checked above: a ValueError left is the
        # analysis' own limit (one excitation frequency, laws whose normal motion
        # depends on the tangential one: beltmdsm.model.Unsupported); a RuntimeError a
        # harmonic balance that did not converge
        consistent, reasons["consistent_mdsm"] = None, str(err)
    else:
        if _linear(model)[0] == 0:
            reasons["consistent_mdsm"] = (
                NO_EXCITATION
                if _linear_without_reversal(model)
                else NO_FAST_MOTION.format(friction=model.friction)
            )
        ends = []
        if not _linear_without_reversal(model):
            ends.append(_unforced_note(model))
        if vb is None and vb_max is not None:
            ends.append(grid_note(model, vb_max=vb_max, points=int(points)))
        if table["Vb"].size:
            lowest, highest = float(table["Vb"][0]), float(table["Vb"][-1])
            if lowest > 0 and any(lo == lowest for lo, _ in consistent):
                ends.append(GRID_END.format(end="lowest", value=lowest, side="below"))
            if any(hi == highest for _, hi in consistent):
                ends.append(GRID_END.format(end="highest", value=highest, side="above"))
        if any(ends):
            reasons["consistent_mdsm"] = "; ".join(
                r for r in (reasons.get("consistent_mdsm"), *ends) if r
            )
        if tension == "clipped":
            reasons["consistent_mdsm"] = "; ".join(
                r for r in (reasons.get("consistent_mdsm"), note) if r
            )
    paper, why = _paper(model, "paper")
    for key, reading in (
        ("paper_tangential_vhat", "tangential"),
        ("paper_coupled_vhat", "coupled"),
    ):
        note = why.get(reading)
        if tension == "clipped" and paper[reading] is not None:
            note = "; ".join(r for r in (note, CLIPPED_PAPER) if r)
        if note:
            reasons[key] = note
    if model.friction in STATIC_BOUNDS:
        static, rest = STATIC_BOUNDS[model.friction]
        text = STATIC_BOUND.format(friction=model.friction, static=static, rest=rest)
        for key in Prediction.ANALYSES:
            reasons[key] = "; ".join(r for r in (reasons.get(key), text) if r)
    return Prediction(
        paper["tangential"],
        paper["coupled"],
        consistent,
        reasons,
        tension,
        model.contact,
        model.friction,
    )
