"""A model as a registry entry: `Oscillator`, its `Contact` and its `Excitation` terms.

A friction oscillator is ``M q'' + C q' + K q = Q(q, q', t) + Q_n + d F_f``: generalized
coordinates ``q`` (n >= 1), mass, damping and stiffness matrices (or explicit
accelerations), other generalized forces ``Q`` (constant loads, nonlinear springs), the
excitation terms, and exactly one frictional contact. The contact has

* a **slip velocity** ``v_r = w . q' - Vb``, a linear form of the velocities minus the
  belt speed (``Vb``, a parameter of every model);
* a **friction direction** ``d``, the generalized force of a unit friction force along
  the contact (``d = w`` by default: the virtual work of the friction force);
* a **normal force** ``N``: the registry's contact law on a normal coordinate (a
  penetration, positive in contact; the contact is *unilateral* and the mass may fly),
  or an expression of the state, the parameters and time (*bilateral*: a preload, a
  spring force, a constant load).

The friction force is ``F_f = -mu(|v_r|) sgn(v_r) N`` while slipping (any friction law
of the registry, `beltmdsm.derive.laws`) and the holding force of the stick constraint
``v_r = 0`` while sticking, derived in `beltmdsm.derive.models.hybrid`.

The entries are data: the matrices and forces are functions of the parameter symbols
``P`` (a dict by name) and of dicts of the coordinates ``q``, their rates ``v`` (by
coordinate name) and the time ``t``; `check` refuses an entry the derivation cannot
take, in one line naming what is wrong.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from ..parameters import Parameter
from .dimensions import LENGTH, rate_unit

__all__ = ["Excitation", "Contact", "Oscillator"]

#: The target of an excitation term acting on a bilateral contact's normal force.
NORMAL = "normal"


@dataclass(frozen=True)
class Excitation:
    """One harmonic excitation term, ``sign * A * W^2 * sin(W t + phase)``.

    The paper's form (Eq. 4; Figs. 14-15): ``A`` is the amplitude of a base motion,
    ``A W^2`` the force per unit mass it implies.

    Attributes
    ----------
    target : str
        The coordinate whose equation it enters (a generalized force), or ``"normal"``:
        it adds to a bilateral contact's normal force (a modulated load).
    amplitude, frequency, phase : str
        Names of the parameters ``A``, ``W`` and ``phase``.
    sign : {1, -1}
        The term's sign (the paper's normal excitation is ``-alpha_n Omega_n^2 sin``).

    See Also
    --------
    Oscillator : the model that lists its terms.

    Examples
    --------
    >>> from beltmdsm.derive.models import get
    >>> [(x.target, x.amplitude, x.sign) for x in get("paper").excitation]
    [('X1', 'alpha_t', 1), ('X2', 'alpha_n', -1)]
    """

    target: str
    amplitude: str
    frequency: str
    phase: str
    sign: int = 1


@dataclass(frozen=True)
class Contact:
    """The one frictional contact of a model.

    Attributes
    ----------
    slip : callable
        ``slip(P)``: the coefficients ``w`` of the velocities, a dict by coordinate name
        (missing: 0), free of the state: ``v_r = w . q' - Vb``.
    normal : str or callable
        A coordinate name: the penetration, positive in contact, whose normal force is
        the contact law ``law`` (unilateral; the force acts as ``-N`` on that
        coordinate and vanishes in flight). Or ``normal(P, q, v, t)``: the normal force
        as an expression (bilateral: never flight; its effect on the motion is part of
        the model's matrices and forces).
    law : str
        A contact law of the registry (unilateral contacts only).
    direction : callable or None
        ``direction(P)``: the generalized friction direction ``d``, a dict by
        coordinate name; None: ``d = w``.

    See Also
    --------
    Oscillator : the model that has it.

    Examples
    --------
    >>> from beltmdsm.derive.models import get
    >>> get("paper").contact.unilateral, get("hoffmann").contact.unilateral
    (True, False)
    """

    slip: Callable[[Mapping], Mapping]
    normal: str | Callable
    law: str = "hertz_damp"
    direction: Callable[[Mapping], Mapping] | None = None

    @property
    def unilateral(self) -> bool:
        """Whether the normal force is a contact law on a coordinate (flight exists)."""
        return isinstance(self.normal, str)


@dataclass(frozen=True)
class Oscillator:
    """A friction oscillator, the entry of ``register("model", ...)``.

    Attributes
    ----------
    name : str
        The model's name (``model="belt_1dof"``), a Python identifier.
    summary : str
        One line, for ``--help`` and the reference page.
    doc : str
        What it models and where it comes from (the equations as read).
    coordinates : tuple of str
        The generalized coordinates ``q``, n >= 1.
    parameters : tuple of Parameter
        The model's own parameters (``Vb`` among them); the friction law brings its own.
    contact : Contact
        The frictional contact.
    mass, damping, stiffness : callable or None
        ``f(P)``: n x n nested lists; None: identity (mass) or zero.
    forces : callable or None
        ``forces(P, q, v, t)``: other generalized forces, a dict by coordinate name.
    accelerations : callable or None
        ``accelerations(P, q, v, t)``: the accelerations without contact and friction, a
        dict by coordinate name, in place of the matrices and forces (unit mass).
    excitation : tuple of Excitation
        The harmonic excitation terms.
    rates : tuple of str or None
        Names of the velocities (None: ``<q>_dot``).
    states : tuple of str or None
        The order of the state vector, coordinates and rates by name (None: the
        coordinates, then their rates).
    friction_laws : tuple of str or None
        The friction laws generated for it (None: every registered law).
    units : mapping or None
        The unit of a coordinate, by name: ``"rad"`` for an angle, ``"1"`` for a
        dimensionless modal amplitude, any unit string; a coordinate not named is a
        length in ``"m"``. Its rate is in the coordinate's unit per second
        (`beltmdsm.derive.models.dimensions.rate_unit`); the slip form's coefficients
        must make ``v_r`` a speed in the unit of ``Vb`` (a lever arm: ``v_r = r
        theta' - Vb``), checked where the units are readable
        (`beltmdsm.derive.models.dimensions`).

    See Also
    --------
    beltmdsm.derive.models.register : adds an entry (docs/howto/own_model.md).

    Examples
    --------
    >>> from beltmdsm.derive.models import get
    >>> hoffmann = get("hoffmann")
    >>> hoffmann.coordinates, hoffmann.state_names
    (('x', 'y'), ('x', 'y', 'x_dot', 'y_dot'))
    >>> hoffmann.state_units
    ('m', 'm', 'm/s', 'm/s')
    """

    name: str
    summary: str
    doc: str
    coordinates: tuple[str, ...]
    parameters: tuple[Parameter, ...]
    contact: Contact
    mass: Callable | None = None
    damping: Callable | None = None
    stiffness: Callable | None = None
    forces: Callable | None = None
    accelerations: Callable | None = None
    excitation: tuple[Excitation, ...] = ()
    rates: tuple[str, ...] | None = None
    states: tuple[str, ...] | None = None
    friction_laws: tuple[str, ...] | None = None
    # a mapping is not hashable: the entry's hash (the derivation's cache key) leaves it
    # out; equality keeps it
    units: Mapping[str, str] | None = field(default=None, hash=False)

    @property
    def rate_names(self) -> tuple[str, ...]:
        """The names of the velocities, one per coordinate."""
        return self.rates or tuple(f"{q}_dot" for q in self.coordinates)

    @property
    def state_names(self) -> tuple[str, ...]:
        """The state vector's names, in order."""
        return self.states or (*self.coordinates, *self.rate_names)

    @property
    def coordinate_units(self) -> tuple[str, ...]:
        """The unit of each coordinate, in order (``"m"`` where `units` names none)."""
        given = self.units or {}
        return tuple(given.get(q, LENGTH) for q in self.coordinates)

    @property
    def state_units(self) -> tuple[str, ...]:
        """The unit of each state, in the order of `state_names` (a rate's: its
        coordinate's per second)."""
        of = dict(zip(self.coordinates, self.coordinate_units))
        of.update((r, rate_unit(of[q])) for q, r in zip(self.coordinates, self.rate_names))
        return tuple(of[s] for s in self.state_names)
