"""The registry of laws: friction, contact and tension laws, one entry each.

Every derivation in `derive/` and every generated module takes its laws from here:
the model (`beltmdsm.derive.model`) builds Eq. (4) from the chosen entries, the code
generator writes one variant per choice (``friction=``, ``contact=``, ``tension=``)
and copies the choice lists, their documentation and the laws' parameters into
``generated/parameters.py``. Adding a law is adding one entry with `register`
(docs/extending.md); nothing else is edited.

An entry holds the law's expression, as a function of the parameter symbols (the
dict ``P`` of `beltmdsm.derive.model`) and its arguments, its parameters (rows of the
parameter table, with domain, unit, base value and description), the paper's
equations it reproduces and its documentation:

* a **friction law** (`FrictionLaw`) gives the friction coefficient ``mu(s)`` as a
  function of the sliding speed ``s = |Vr| >= 0``, ``Vr = X1' - Vb``. The framework
  applies the direction: the friction force per unit mass is ``-mu(|Vr|) sgn(Vr) F``
  while slipping (Eqs. 2-3), and at ``Vr = 0`` the set-valued sign bounds the
  holding force by the static bound ``mu_st``, the stick cone
  ``|a_free| <= mu_st F``: the law's ``static`` where it gives one (``static_kinetic``:
  ``mu_s`` above the kinetic ``mu_k`` of slip), else ``mu(0)`` (``mu_s`` for
  ``coulomb`` and ``stribeck``);
* a **contact law** (`ContactLaw`) gives the normal force per unit mass in contact,
  ``F(X2, X2')`` for ``X2 > 0`` (zero in flight is the framework's, Eq. 1);
* a **tension law** (`TensionLaw`) maps that force to the one that acts: Eq. (1) as
  printed, or a contact that cannot pull.

A parameter belongs to the laws that list it. Two laws may list the same name where
it means the same (the same unit, domain, base value and description: one row of the
parameter table, ``mu_k`` of ``stribeck`` and ``static_kinetic``); `register` refuses
a name whose row would differ.

The first entry of each option is its default: ``coulomb``, ``hertz_damp``,
``allowed``, which give the paper's model.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

import sympy as sp

from .lawcheck import check
from .parameters import MODEL, Parameter

__all__ = [
    "Law",
    "FrictionLaw",
    "ContactLaw",
    "TensionLaw",
    "OPTIONS",
    "LAWS",
    "register",
    "choices",
    "default",
    "get",
    "parameter_table",
    "law_parameters",
    "owners",
]


@dataclass(frozen=True)
class Law:
    """What every entry of the registry has.

    Attributes
    ----------
    name : str
        The choice's value (``friction="stribeck"``).
    summary : str
        One line, for ``--help``, the site's laws page (written at build from
        ``OPTION_DOCS``, docs/_ext/beltmdsm_site.py) and ``OPTION_DOCS``.
    doc : str
        The longer documentation: what the law models and where it comes from.
    equations : str
        The paper's equations the law reproduces (``"Eq. (3)"``), or how it relates
        to them.
    parameters : tuple of Parameter
        The law's own parameters (their ``law`` field is filled in by `register`).
    """

    name: str
    summary: str
    doc: str
    equations: str
    parameters: tuple[Parameter, ...] = ()


@dataclass(frozen=True)
class FrictionLaw(Law):
    """A friction law: ``coefficient(P, s)`` is ``mu(s)`` at sliding speed ``s = |Vr|``.

    ``P`` maps parameter names to their SymPy symbols, ``s`` is a nonnegative
    symbol. The framework multiplies by ``-sgn(Vr) F`` while slipping and bounds
    stick by ``static(P)``, the static bound, where the law gives one (a static
    coefficient above the kinetic one: ``static_kinetic``), else by ``mu(0)``.
    ``coefficient`` is then the slip law only: ``mu(0)`` is its limit as ``s -> 0+``.
    """

    coefficient: Callable[[Mapping[str, sp.Symbol], sp.Expr], sp.Expr] = None
    static: Callable[[Mapping[str, sp.Symbol]], sp.Expr] | None = None


@dataclass(frozen=True)
class ContactLaw(Law):
    """A contact law: ``force(P, X2, Y2)`` is the normal force per unit mass in contact.

    ``X2 > 0`` is the penetration and ``Y2 = X2'``; the framework sets the force to
    zero in flight and applies the tension law.
    """

    force: Callable[[Mapping[str, sp.Symbol], sp.Expr, sp.Expr], sp.Expr] = None


@dataclass(frozen=True)
class TensionLaw(Law):
    """A tension law: ``acting(F)`` is the force that acts where the contact law gives ``F``."""

    acting: Callable[[sp.Expr], sp.Expr] = None


#: The fields of a parameter that two laws sharing its name must agree on.
_MEANING = ("unit", "base", "domain", "description", "default_from", "derived_unit")

#: The options, in the order in which generated tables key them.
OPTIONS = ("friction", "contact", "tension")
_KIND = {"friction": FrictionLaw, "contact": ContactLaw, "tension": TensionLaw}

#: option -> choice -> law, in registration order (the default first).
LAWS: dict[str, dict[str, Law]] = {option: {} for option in OPTIONS}


def register(option: str, law: Law) -> Law:
    """Add ``law`` to the registry under ``option``; return it with its parameters' owner set.

    A parameter name in the table already is shared where it means the same: a
    law's parameter (not one of the model's own) with the same unit, base value,
    domain and description; the table keeps one row, owned by the first law that
    listed it (`owners` gives every law that lists it).

    Raises
    ------
    ValueError
        For an unknown option, a law of the wrong kind, a name taken already, or a
        parameter name of the table whose row differs (naming the fields), or that is
        one of the model's own; `beltmdsm.derive.lawcheck.UnsupportedLaw` (a ValueError) for a
        construct the framework cannot take (docs/extending.md).
    """
    if option not in _KIND:
        raise ValueError(f"option must be one of {OPTIONS}; got {option!r}")
    if not isinstance(law, _KIND[option]):
        raise ValueError(f"a {option} law must be a {_KIND[option].__name__}; got {law!r}")
    if law.name in LAWS[option]:
        raise ValueError(f"{option} law {law.name!r} is registered already")
    table = {p.name: p for p in parameter_table()}
    clash = {}
    for p in law.parameters:
        row = table.get(p.name)
        if row is None:
            continue
        if row.law is None:
            clash[p.name] = "one of the model's own parameters"
            continue
        differ = [f for f in _MEANING if getattr(row, f) != getattr(p, f)]
        if differ:
            clash[p.name] = f"{row.law[1]!r} gives it another {', '.join(differ)}"
    if clash:
        why = "; ".join(f"{name}: {text}" for name, text in sorted(clash.items()))
        raise ValueError(
            f"{option} law {law.name!r}: parameter names taken already with another meaning ({why})"
        )
    check(option, law, parameter_table() + law.parameters)
    owned = tuple(replace(p, law=(option, law.name)) for p in law.parameters)
    law = replace(law, parameters=owned)
    LAWS[option][law.name] = law
    return law


def choices(option: str) -> tuple[str, ...]:
    """The registered choices of ``option``, the default first."""
    return tuple(LAWS[option])


def default(option: str) -> str:
    """The default choice of ``option`` (the first registered)."""
    return choices(option)[0]


def get(option: str, name: str) -> Law:
    """The law ``name`` of ``option``.

    Raises
    ------
    ValueError
        Naming the option and its choices, for an unknown name.
    """
    try:
        return LAWS[option][name]
    except KeyError:
        raise ValueError(f"{option} must be one of {choices(option)}; got {name!r}") from None


def law_parameters() -> tuple[Parameter, ...]:
    """The parameters of every registered law, in registry order, each name once (a
    shared one with its first owner)."""
    seen, out = set(), []
    for option in OPTIONS:
        for law in LAWS[option].values():
            for p in law.parameters:
                if p.name not in seen:
                    seen.add(p.name)
                    out.append(p)
    return tuple(out)


def owners(name: str) -> tuple[tuple[str, str], ...]:
    """``(option, choice)`` of every registered law that lists the parameter ``name``."""
    return tuple(
        (option, law.name)
        for option in OPTIONS
        for law in LAWS[option].values()
        if any(p.name == name for p in law.parameters)
    )


def parameter_table() -> tuple[Parameter, ...]:
    """The full parameter table: the model's own parameters, then the laws'."""
    return MODEL + law_parameters()


# The shipped laws ----------------------------------------------------------------------

#: The kinetic coefficient, one parameter of two laws (`register`: a shared name).
_MU_K = Parameter(
    "mu_k",
    "1",
    0.25,
    "nonnegative",
    "kinetic friction coefficient: mu while slipping (static_kinetic), "
    "the limit at high |Vr| (stribeck)",
)

register(
    "friction",
    FrictionLaw(
        "coulomb",
        "Coulomb friction: mu(|Vr|) = mu_s, static equal to kinetic",
        "The paper's law, Eq. (3): the friction force is mu_s F_n against the "
        "relative velocity while slipping, and at most mu_s F_n while sticking.",
        "Eq. (3)",
        coefficient=lambda P, s: P["mu_s"],
    ),
)
register(
    "friction",
    FrictionLaw(
        "stribeck",
        "Stribeck friction: mu(|Vr|) = mu_k + (mu_s - mu_k) exp(-|Vr|/v_s)",
        "The coefficient falls from the static mu_s at rest to the kinetic mu_k at "
        "speeds well above the Stribeck velocity v_s, the law most studies of "
        "friction-induced vibration use; mu_s bounds stick. With mu_k = mu_s it is "
        "Coulomb's law of Eq. (3). Falling with speed, it is not monotone in Vr "
        "(derive/contraction.py) and acts as a negative damping of steady sliding.",
        "Eq. (3) for mu_k = mu_s; not in the paper otherwise",
        (
            _MU_K,
            Parameter(
                "v_s",
                "m/s",
                1.0,
                "positive",
                "Stribeck velocity: the speed over which mu falls from mu_s towards mu_k",
            ),
        ),
        coefficient=lambda P, s: P["mu_k"] + (P["mu_s"] - P["mu_k"]) * sp.exp(-s / P["v_s"]),
    ),
)
register(
    "friction",
    FrictionLaw(
        "static_kinetic",
        "Static above kinetic: stick held up to mu_s F, slip at mu_k F < mu_s F",
        "The classical stick-slip law: the friction force is mu_k F_n against the "
        "relative velocity while slipping, at any speed, and holds the mass while "
        "sticking up to the static mu_s F_n (its static bound, FrictionLaw.static). "
        "For mu_k < mu_s the signed friction falls by a jump at Vr = 0 (not "
        "monotone, derive/contraction.py): steady sliding, linearly stable, may "
        "coexist with a stick-slip cycle. With mu_k = mu_s it is Coulomb's law of "
        "Eq. (3); mu_k > mu_s (a static bound below the kinetic coefficient) is "
        "outside the law and refused where a model is built.",
        "Eq. (3) for mu_k = mu_s; Eq. (3) with mu_k while slipping otherwise",
        (_MU_K,),
        coefficient=lambda P, s: P["mu_k"],
        static=lambda P: P["mu_s"],
    ),
)
register(
    "contact",
    ContactLaw(
        "hertz_damp",
        "Hertz-Damp: (omega2^2 + 2 beta2 omega2 X2') X2^(3/2)",
        "The paper's contact law, Eq. (1): a Hertzian stiffness with a damping "
        "proportional to the same power of the penetration; beta2 and omega2 are the "
        "starred quantities of Eq. (4).",
        "Eq. (1)",
        force=lambda P, X2, Y2: (
            (P["omega2"] ** 2 + 2 * P["beta2"] * P["omega2"] * Y2) * X2 ** sp.Rational(3, 2)
        ),
    ),
)
register(
    "contact",
    ContactLaw(
        "kelvin_voigt",
        "Kelvin-Voigt: omega2^2 X2 + 2 beta2 omega2 X2' (linear)",
        "The linear spring and dashpot of Fig. 16: beta2 is the ordinary damping "
        "ratio and omega2 the natural frequency of the normal direction.",
        "Fig. 16",
        force=lambda P, X2, Y2: P["omega2"] ** 2 * X2 + 2 * P["beta2"] * P["omega2"] * Y2,
    ),
)
register(
    "contact",
    ContactLaw(
        "hunt_crossley",
        "Hunt-Crossley: omega2^2 X2^n_h + 2 beta2 omega2 X2^n_h X2'",
        "A power-law contact whose damping scales with the same power of the "
        "penetration as the stiffness; the exponent n_h is carried symbolically "
        "through every derivation (n_h = 3/2 is Hertz-Damp, Eq. 1; n_h = 1 has a "
        "linear stiffness but, unlike Kelvin-Voigt, a damping that vanishes with the "
        "penetration).",
        "Eq. (1) for n_h = 3/2",
        (Parameter("n_h", "1", 1.5, "positive", "Hunt-Crossley exponent (Hertz-Damp: 3/2)"),),
        force=lambda P, X2, Y2: (
            (P["omega2"] ** 2 + 2 * P["beta2"] * P["omega2"] * Y2) * X2 ** P["n_h"]
        ),
    ),
)
register(
    "tension",
    TensionLaw(
        "allowed",
        "Eq. (1) as printed: tensile where its damping term outweighs its stiffness term",
        "The contact force of the contact law as it is, negative (pulling the mass "
        "into the belt) where the damping term outweighs the stiffness term "
        "(docs/modelling.md#tension).",
        "Eq. (1)",
        acting=lambda F: F,
    ),
)
register(
    "tension",
    TensionLaw(
        "clipped",
        "max(F, 0): a contact that cannot pull (the surfaces separate)",
        "Where the contact law would pull, the surfaces separate and no force acts "
        "(docs/modelling.md#tension). The clipped force is continuous where F "
        "crosses zero: a kink of the vector field, not a jump.",
        "Eq. (1) with the force clipped at zero",
        acting=lambda F: sp.Piecewise((F, F > 0), (0, True)),
    ),
)
