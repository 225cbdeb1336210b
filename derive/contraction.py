"""Two tangential motions under one normal motion: the energy of their difference.

The normal equation of Eq. (4) contains neither ``X1``, ``X1'``, ``Vb`` nor ``mu_s``
(docs/modelling.md#model-and-units, *one-way coupling*). Two runs ``a`` and ``b``
with the same normal initial state therefore share the normal motion and with it
the contact force ``F(t)``, whatever their tangential initial states. Their
tangential equations (Eq. 4, mass-normalised)

    Xi'' + c1 Xi' + k1 Xi = f_t(t) - mu_s s_i F(t),    s_i in Sgn(Xi' - Vb),  i = a, b,

with ``c1 = 2 beta1 omega1``, ``k1 = omega1^2`` and the set-valued sign ``Sgn`` (``-1``
for ``Vr < 0``, ``[-1, 1]`` for ``Vr = 0``, ``+1`` for ``Vr > 0``: the stick mode is the
middle value, ``s = a_free / (mu_s F)``), differ by ``e = Xa - Xb``:

    e'' + c1 e' + k1 e = -mu_s F (s_a - s_b).

The excitation cancels. With the energy of the difference ``E_d = e'^2/2 + k1 e^2/2``

    dE_d/dt = -c1 e'^2 - mu_s F (s_a - s_b)(v_a - v_b),     v = X1'.

What SymPy proves (each a function returning the result; steps 1-3 in
`beltmdsm.derive.contraction_energy`, 4-6 in `beltmdsm.derive.contraction_sign`, the
conclusion here):

1. `one_way_coupling`: the normal equation of `beltmdsm.derive.dynamics.normal_rhs` is free of
   ``X1, Y1`` for both contact laws and both tension laws, so one normal motion
   serves both runs.
2. `difference_energy`, `difference_power`: ``E_d`` is the tangential part of the
   mechanical energy of `beltmdsm.derive.dynamics.energy` evaluated at the difference, and
   its rate along the two motions (accelerations of `beltmdsm.derive.dynamics.accelerations`,
   friction directions ``s_a, s_b``) is identically ``-c1 e'^2 - (f_a - f_b) F e'``
   with ``c1 = -d a_free/d X1'`` and ``f`` the signed friction coefficient of each
   run (`beltmdsm.derive.model.friction_coefficient`: ``mu_s s`` for Coulomb's law, Eq. 3),
   ``F`` the contact force of the tension law.
3. `stick_is_set_valued`: the stick field of `beltmdsm.derive.hybrid` (``Y1' = 0``) is the slip
   field at ``Vr = 0`` with ``s = a_free / (mu(0) F)``, which lies in ``[-1, 1]``
   exactly while the stick guard ``|a_free| <= mu(0) F`` holds.
4. `friction_power_sign_cases`: ``(s_a - s_b)(v_a - v_b) >= 0`` in each of the nine
   pairs of friction states (slip back, stick, slip forward for each run; stick
   with ``s`` at either end of ``[-1, 1]`` and inside it: 25 cases), by substitution of the
   state's ``Vr`` and ``s`` and SymPy's sign decision under the symbols'
   assumptions: the monotonicity of the set-valued ``Sgn``. ``v_a - v_b = Vr_a -
   Vr_b`` because both runs see the same ``Vb``.
   `monotonicity`: the friction law beyond the sign, ``sgn(Vr) mu(|Vr|)`` with
   ``mu(0) >= 0`` and ``mu' >= 0`` (Coulomb's constant ``mu_s``); it fails for
   Stribeck's law, which falls at every ``|Vr| > 0`` where ``mu_k < mu_s``, and then
   the claim does not hold (`claim` per friction law says so).
5. `clipped_force_nonnegative`: ``max(F, 0)`` of `beltmdsm.derive.model.contact_force` with
   ``tension="clipped"`` is ``>= 0`` on each branch.
6. `sign_of_friction_power`: from 4, ``mu_s >= 0`` and ``F >= 0`` the friction term
   is ``<= 0``, so ``dE_d/dt <= -c1 e'^2 <= 0``; with ``F < 0`` it is ``>= 0``
   (the converse: energy enters the difference only through friction while the
   contact pulls), and it is ``> 0`` for runs on opposite sides of ``Vr = 0``.

Conclusion (clipped tension, F >= 0 always): ``E_d`` never increases, and it
decreases strictly while ``e' != 0`` when ``beta1 > 0``.

**The convergence step is an argument in words, not a SymPy proof.** ``E_d`` is
non-increasing and bounded below, so it converges and ``int c1 e'^2 dt`` is finite.
Along a run the states and ``F`` stay bounded, so ``e''`` is bounded, ``e'`` is
uniformly continuous and (Barbalat) ``e' -> 0``; then ``|e|`` tends to a constant
``e_inf``. If ``e_inf != 0``, the difference equation forces ``k1 e = -mu_s F (s_a -
s_b)`` on average over every later window, so the friction directions differ for
a positive share of every window while the velocities coincide: both masses sit
at ``Vr = 0``, i.e. both stick, at positions ``e_inf`` apart, for all later time.
With ``Vb > 0`` a stuck mass moves with the belt, ``X1`` grows without bound and
the spring force leaves the bounded friction cone ``mu_s F``: permanent stick is
impossible, so ``e -> 0`` (LaSalle-type). The same holds for ``Vb = 0`` when the
excitation makes the mass slip in every period. Hence all tangential motions
under one normal motion converge to one. When the normal motion is periodic with
period ``T``, the shift of a tangential motion by ``T`` is again one under the same
normal motion, so the common limit is ``T``-periodic: it has spectral lines only
at multiples of ``2 pi / T`` (a line at ``omega1`` only where ``omega1`` is one of
them, as ``omega1 = 12 = 3 Omega`` of Fig. 20c). No self-excited vibration (a free
oscillation near ``omega1``, with a free phase) and no coexistence of tangential
responses are possible, for every parameter set with ``beta1 > 0`` and ``Vb > 0``.

The runtime checks this with the simulation
(beltmdsm/paper_reports/contraction_evidence.py): two runs with one normal motion, the
energy balance of their difference split by the sign of ``F``, and the sign of ``F`` at
the reversals of the friction.

Conditions, each shown by `breaking_conditions` to be needed:

* Friction non-decreasing in ``Vr`` (Coulomb's set-valued ``mu_s Sgn``). A
  coefficient ``mu_s sgn(Vr) + m(Vr)`` gives, on one slip branch,
  ``(mu(v_a) - mu(v_b))(v_a - v_b) = (m(v_a) - m(v_b))(v_a - v_b)`` (SymPy), which is
  ``m'(xi)(v_a - v_b)^2 < 0`` for a falling ``m`` by the mean value theorem (words).
  For ``m = -kappa Vr``, ``kappa > 0`` (``|mu|`` falls with ``|Vr|`` on both branches),
  SymPy gives ``dE_d/dt = -(c1 - kappa F) e'^2`` on that branch: the difference
  grows once ``kappa F > c1``, the classical falling-friction instability.
* ``beta1 > 0``: with ``beta1 = 0`` and both runs on one slip branch,
  ``dE_d/dt = 0`` identically: the difference oscillates for ever.
* One-way coupling: if ``F`` depended on the tangential state (not the case here,
  step 1), the friction term would be ``-mu_s (F_a s_a - F_b s_b) e'``, positive
  for ``s_a = s_b = -1`` and ``(F_a - F_b) e' > 0``.
* ``F >= 0``: Eq. (1) as printed (``tension="allowed"``) is negative part of the
  time (docs/modelling.md#tension), and then the converse of step 6 applies.

The argument covers tangential motions under one normal motion. Different normal
initial states may give different normal motions (the normal equation is
nonlinear); the argument says nothing about their coexistence.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from . import laws
from .contraction_energy import (
    Ya,
    Yb,
    one_way_coupling,
    power_split,
    sa,
    sb,
    stick_is_set_valued,
)
from .contraction_sign import (
    _SIGN_LAW,
    Monotonicity,
    clipped_force_nonnegative,
    friction_power_sign_cases,
    monotonicity,
    sign_of_friction_power,
)
from .model import (
    CONTACT_LAWS,
    TENSION_LAWS,
    P,
    friction_coefficient,
)

__all__ = ["Step", "ContractionClaim", "breaking_conditions", "claim"]

_FRICTION = laws.default("friction")


def breaking_conditions() -> dict[str, tuple[bool, str]]:
    """Each condition of the claim, dropped, with SymPy's result and one line of detail.

    ``"falling friction"``: friction ``mu_s s + m(Vr)`` on one slip branch; the friction
    factor reduces to ``(m(Vr_a) - m(Vr_b))(Vr_a - Vr_b)`` for a generic ``m``, and for
    ``m = -kappa Vr`` (``kappa > 0``: the coefficient falls with ``Vr``) the whole rate
    is ``-(c1 - kappa F) e'^2``: positive once ``kappa F > c1``.
    ``"beta1 = 0"``: on one slip branch ``dE_d/dt`` is identically 0.
    ``"two-way coupling"``: separate forces ``F_a = F_b + dF`` on one slip branch make the
    friction part ``mu_s dF e'`` for ``s = -1``, positive for ``dF e' > 0``.
    """
    out = {}
    split = power_split()
    de = Ya - Yb
    F, c1 = sp.Symbol("F", real=True), split.c1
    s = sp.Symbol("s", real=True)
    Vb = P["Vb"]
    # falling friction: mu(Vr) = mu_s s + m(Vr), one branch (s_a = s_b = s)
    m = sp.Function("m")
    mu_a = friction_coefficient(_SIGN_LAW, s) + m(Ya - Vb)
    mu_b = friction_coefficient(_SIGN_LAW, s) + m(Yb - Vb)
    factor = sp.expand((mu_a - mu_b) * de)
    generic = sp.expand(factor - (m(Ya - Vb) - m(Yb - Vb)) * de) == 0
    kappa = sp.Symbol("kappa", positive=True)
    linear = factor.replace(m, sp.Lambda(sp.Symbol("x"), -kappa * sp.Symbol("x")))
    d = sp.Symbol("d", positive=True)
    falls = sp.factor(linear.xreplace({Ya: Yb + d})).is_negative
    rate = -c1 * de**2 - linear * F
    closed = sp.expand(rate - (-(c1 - kappa * F) * de**2)) == 0
    Fbig = sp.Symbol("F_big", positive=True)
    grows = sp.factor(
        (-(c1 - kappa * F) * de**2).xreplace({F: (c1 + Fbig) / kappa, Ya: Yb + d})
    ).is_positive
    out["falling friction"] = (
        bool(generic and falls and closed and grows),
        (
            "(mu(Vr_a) - mu(Vr_b))(Vr_a - Vr_b) = (m(Vr_a) - m(Vr_b))"
            "(Vr_a - Vr_b) on one branch; with m = -kappa Vr it is "
            "-kappa e'^2 < 0 and dE_d/dt = -(c1 - kappa F) e'^2 > 0 "
            "once kappa F > c1"
        ),
    )
    # beta1 = 0
    zero = sp.expand(split.total.xreplace({P["beta1"]: 0, sa: s, sb: s})) == 0
    out["beta1 = 0"] = (
        bool(zero),
        ("dE_d/dt = 0 identically on one slip branch: the difference is an undamped oscillation"),
    )
    # two-way coupling: a force per run
    dF = sp.Symbol("dF", positive=True)
    mu_pos = sp.Symbol("mu_pos", positive=True)
    mu = friction_coefficient(_SIGN_LAW, -1)
    coupled = -(mu * (F + dF) - mu * F) * de
    coupled = sp.factor(coupled.xreplace({Ya: Yb + d, P["mu_s"]: mu_pos}))
    ok = coupled.is_positive and sp.expand(coupled - mu_pos * dF * d) == 0
    out["two-way coupling"] = (
        bool(ok),
        (
            "a force per run, F_a = F_b + dF, makes the "
            "friction part mu_s dF e' for s_a = s_b = -1: "
            "positive for dF, e' > 0"
        ),
    )
    return out


@dataclass(frozen=True)
class Step:
    """One step of the argument: how it is established and whether that succeeded."""

    name: str
    how: str  # "SymPy" or "words"
    proved: bool
    detail: str


@dataclass(frozen=True)
class ContractionClaim:
    """The contraction result for one friction law: statement, conditions, converse,
    its steps, and the law's monotonicity (where it fails, the claim does not hold)."""

    statement: str
    conditions: tuple[str, ...]
    converse: str
    steps: tuple[Step, ...]
    breaks: dict
    friction: str
    monotone: Monotonicity

    @property
    def proved_by_sympy(self) -> bool:
        """Whether every SymPy step succeeded (the words step is not counted)."""
        return all(s.proved for s in self.steps if s.how == "SymPy")


@cache
def claim(friction: str = _FRICTION) -> ContractionClaim:
    """Run every SymPy step (module docstring) for the friction law ``friction``.

    The steps on the set-valued sign hold for every law; the step "friction law
    non-decreasing" (`monotonicity`) decides whether the law keeps the claim: it
    fails for Stribeck's law, which falls with the sliding speed.
    """
    coupling = one_way_coupling()
    splits = {(c, tn): power_split(c, tn, friction) for c in CONTACT_LAWS for tn in TENSION_LAWS}
    cases = friction_power_sign_cases()
    stick = {c: stick_is_set_valued(c, friction) for c in CONTACT_LAWS}
    clipped = {c: clipped_force_nonnegative(c) for c in CONTACT_LAWS}
    signs = sign_of_friction_power()
    breaks = breaking_conditions()
    law = monotonicity(friction)
    n_pairs = len({(c.state_a, c.state_b) for c in cases})
    steps = (
        Step(
            "one-way coupling",
            "SymPy",
            all(coupling.values()),
            "the normal equation (beltmdsm.derive.dynamics.normal_rhs) is free of X1, X1' for "
            f"{len(coupling)} (contact, tension) combinations",
        ),
        Step(
            "difference energy and power",
            "SymPy",
            all(s.exact for s in splits.values()),
            "dE_d/dt = -c1 e'^2 - (f_a - f_b) F e' (expand to zero; f the signed "
            f"coefficient of friction={friction!r}), every contact and tension law",
        ),
        Step(
            "stick is Sgn at Vr = 0",
            "SymPy",
            all(stick.values()),
            "the stick field is the slip field at Vr = 0 with s = a_free/(mu(0) F), in "
            "[-1, 1] exactly while the stick guard holds",
        ),
        Step(
            "Sgn is monotone",
            "SymPy",
            all(c.proved for c in cases),
            f"(s_a - s_b)(Vr_a - Vr_b) >= 0 in all {len(cases)} cases ({n_pairs} pairs "
            "of slip back / stick / slip forward, stick with s = -1, inside, +1)",
        ),
        Step("friction law non-decreasing", "SymPy", law.holds, law.reason),
        Step(
            "clipped force >= 0",
            "SymPy",
            all(clipped.values()),
            "max(F, 0) of beltmdsm.derive.model.contact_force is >= 0 on each branch",
        ),
        Step(
            "sign of the friction power",
            "SymPy",
            signs["friction part = -mu_s F (s_a - s_b)(Vr_a - Vr_b)"]
            and signs["F >= 0 -> <= 0"]
            and signs["c1 e'^2 >= 0"],
            "F >= 0 and a non-decreasing law: friction part <= 0, so dE_d/dt <= -c1 e'^2 <= 0",
        ),
        Step(
            "converse (tension allowed)",
            "SymPy",
            signs["F < 0 -> >= 0"] and signs["F < 0, opposite sides -> > 0"],
            "F < 0: friction part >= 0, and > 0 while the runs slip in opposite directions",
        ),
        Step(
            "convergence",
            "words",
            True,
            "E_d non-increasing, strictly while e' != 0 (beta1 > 0); Barbalat gives "
            "e' -> 0; a persistent e needs both masses stuck e apart for all later "
            "time, impossible for Vb > 0 (a stuck mass moves with the belt and the "
            "spring force leaves the bounded cone) or when the excitation makes the "
            "mass slip; the limit of a T-periodic normal motion is T-periodic",
        ),
    )
    return ContractionClaim(
        statement=(
            "with tension clipped and a friction law non-decreasing in Vr, all "
            "tangential motions under one normal motion converge to one (the periodic "
            "response when the normal motion is periodic): no self-excited vibration "
            "and no coexistence of tangential responses, for every parameter set"
        ),
        conditions=(
            "a friction law sgn(Vr) mu(|Vr|) non-decreasing in Vr (Coulomb's mu_s Sgn: "
            "static = kinetic)",
            "beta1 > 0 (strict decay of E_d)",
            "one-way coupling: the normal equation is free of the tangential state",
            "F >= 0 (tension clipped)",
            "Vb > 0, or an excitation that makes the mass slip (no permanent stick)",
        ),
        converse=(
            "with tension allowed, dE_d/dt <= -c1 e'^2 while F >= 0; energy enters "
            "the difference only through friction while F < 0"
        ),
        steps=steps,
        breaks=breaks,
        friction=friction,
        monotone=law,
    )
