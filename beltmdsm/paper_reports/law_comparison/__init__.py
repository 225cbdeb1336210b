"""Friction that falls with speed: the research answer of issue 19, item 8.

With Stribeck friction, ``mu(Vr) = mu_k + (mu_s - mu_k) exp(-|Vr|/v_s)``, beside Coulomb's,
unforced and at the base excitation, under both tension laws (``allowed``: Eq. (1) as
printed, the contact can pull; ``clipped``: ``max(F, 0)``), this package computes

(a) where steady sliding is unstable (`steady_sliding`): the closed form
    `beltmdsm.generated.unforced.critical_belt_speed` (SymPy's root of the tangential damping
    ``2 beta1 omega1 + g dmu/d|Vr|`` of the linearisation at ``|Vr| = Vb``) beside the
    sign change of the largest real part of `beltmdsm.generated.unforced.eigenvalues`, and the
    eigenvalues of the whole Jacobian against those of its tangential and normal blocks
    (the normal coupling does not move them: the normal equation is free of the
    tangential state, ``one_way_coupling`` of `beltmdsm.generated.capabilities`);
(b) where the ``T``-periodic forced response is unstable (`forced_stability`: the Floquet
    band of `beltmdsm.continuation.band.floquet_band` over ``Vb``, its labelled edges and the
    growth rate ``log max|mu| / T`` at every evaluated value);
(c) where runs from rest show the ``omega1`` vibration (`runs_from_rest`: the
    ``omega1_peak_present`` of `beltmdsm.simulation.simulate`'s summaries on a grid);
(d) the answer (`answer`): whether a self-excited vibration exists without tension once
    friction falls with speed, and where the excitation stabilises or destabilises
    steady sliding (the question of Thomsen and of Michaux et al. that the paper's
    introduction cites);
(e) the growth rates of (a) and (b) against ``Vb`` for the figure of
    notebooks/stribeck_research.ipynb.

`compare` does all of it for the laws of `LAWS` and both tension laws, timing each
expensive call; docs/stribeck.md reports the numbers. No physics is typed here: every
formula comes from generated/ (tests/beltmdsm/test_physics_in_derive_only.py), and the
tests (tests/beltmdsm/paper_reports/test_law_comparison.py) check each reported number against
an independent reference.

Modules, one concept each: `beltmdsm.paper_reports.law_comparison.laws` (the laws, tension
laws, belt speeds and starts compared), `.steady` (a), `.forced` (b), `.runs` (c),
`.comparison` (d, and `compare`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from .comparison import Answer, LawComparison, answer, compare
from .forced import ForcedStability, forced_stability
from .laws import FORCED_STARTS, LAWS, RUN_SETTINGS, STARTS, TENSIONS, VB_RANGE, Law
from .runs import RunScan, runs_from_rest
from .steady import SteadySliding, steady_sliding

__all__ = [
    "Law",
    "LAWS",
    "TENSIONS",
    "VB_RANGE",
    "STARTS",
    "FORCED_STARTS",
    "RUN_SETTINGS",
    "SteadySliding",
    "ForcedStability",
    "RunScan",
    "Answer",
    "LawComparison",
    "steady_sliding",
    "forced_stability",
    "runs_from_rest",
    "answer",
    "compare",
]
