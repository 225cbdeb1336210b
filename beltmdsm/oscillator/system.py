"""A derived model with its friction law and parameter values: what the runtime runs.

A model is a generated module, ``beltmdsm.generated.models.<name>`` (written by
``python -m derive`` from a registry entry; its interface is the model contract of
issue 39): its coordinates, states, parameters and the kernels of each friction law
(vector field per mode, Jacobian, slip velocity, holding force, stick limit, saltation
matrices, steady sliding and its Hurwitz determinants). `System` binds one to a law and
to values of its parameters, checked here once; the integrator
(`beltmdsm.oscillator.hybrid`), steady sliding (`beltmdsm.oscillator.equilibria`),
cycles (`beltmdsm.oscillator.cycles`) and forced responses
(`beltmdsm.oscillator.forced`) read the model through it alone: no state name, size or
formula is assumed.
"""

from __future__ import annotations

import difflib
import math
from types import ModuleType

import numpy as np
from numpy.typing import NDArray

from ..errors import Unsupported
from ..other_model import model_module
from ..state_names import module_units

__all__ = ["System", "load_model", "STICK", "FLIGHT"]

#: The mode codes of the contract: +-1 slip in the sign of the slip velocity.
STICK, FLIGHT = 0, 2

#: What a model module must hold (the contract's module-level data and ``kernels``).
_REQUIRED = (
    "NAME",
    "COORDINATES",
    "STATES",
    "UNILATERAL",
    "FRICTION_LAWS",
    "PARAMETERS",
    "DEFAULTS",
    "EXCITATION",
    "SURFACES",
    "kernels",
)


def load_model(model: str | ModuleType) -> ModuleType:
    """The generated module of a model, by name or as given.

    Parameters
    ----------
    model : str or module
        A registered model's name (``beltmdsm.generated.models.<name>`` is imported) or a
        module that holds the contract's names (a model typed by hand, as the tests do).

    Returns
    -------
    module

    Raises
    ------
    ValueError
        An unknown name (the registered ones listed, the closest suggested), a module
        that lacks a name of the contract, or one whose ``STATE_UNITS`` (optional: m and
        m/s without it) is not one unit string per state
        (`beltmdsm.state_names.module_units`).

    See Also
    --------
    System : binds the module to a friction law and parameter values.

    Examples
    --------
    >>> try:
    ...     load_model("no_such_model")
    ... except ValueError as err:
    ...     print(str(err).split(";")[1])
     got 'no_such_model'
    """
    if isinstance(model, str):
        module = model_module(model)
    else:
        module = model
    missing = [name for name in _REQUIRED if not hasattr(module, name)]
    if missing:
        raise ValueError(
            f"model={getattr(module, '__name__', module)!r}: the module lacks "
            f"{', '.join(missing)} of the model contract"
        )
    module_units(module)
    return module


class System:
    """A model, its friction law and the values of its parameters.

    Parameters
    ----------
    model : str or module
        A registered model's name or its module (`load_model`).
    friction : str, optional
        One of the model's ``FRICTION_LAWS``; its first one by default.
    **params : float
        Values of the parameters of the model and the law (the module's ``DEFAULTS``
        for those not given).

    Attributes
    ----------
    module : module
        The generated module.
    name, friction : str
    states, coordinates : tuple of str
        From the module (``2n`` states, ``n`` coordinates).
    units : tuple of str
        The unit of each state (the module's ``STATE_UNITS``; m and m/s without it).
    unilateral : bool
        Whether the contact can open (a flight mode).
    params : dict
        Every parameter's value, in the module's order.
    p : ndarray
        The same values, the kernels' argument.
    kernels : NamedTuple
        The module's kernels of the law.

    Raises
    ------
    ValueError
        A friction law the model does not have, an unknown parameter (the closest
        suggested) or a value that is not a finite number.

    See Also
    --------
    beltmdsm.oscillator.simulate : a run of the system.
    beltmdsm.oscillator.steady_sliding : its equilibrium and stability.

    Examples
    --------
    The generated 1-DOF belt oscillator (``beltmdsm.generated.models.belt_1dof``):

    >>> s = System("belt_1dof", friction="stribeck", Vb=1.5)
    >>> s
    System('belt_1dof', friction='stribeck', Vb=1.5)
    >>> s.states, s.params["mu_k"]
    (('x', 'x_dot'), 0.25)
    >>> System("belt_1dof", friction="stribeck", vb=1.5)
    Traceback (most recent call last):
    ...
    ValueError: vb: not a parameter of belt_1dof with friction='stribeck'; did you mean 'Vb'?
    """

    def __init__(
        self, model: str | ModuleType, friction: str | None = None, **params: float
    ) -> None:
        module = load_model(model)
        laws = tuple(module.FRICTION_LAWS)
        if friction is None:
            friction = laws[0]
        if friction not in laws:
            raise ValueError(
                f"friction={friction!r}: not a law of model {module.NAME!r} ({', '.join(laws)})"
            )
        names = tuple(module.PARAMETERS[friction])
        values = {}
        for key, value in params.items():
            if key not in names:
                hint = difflib.get_close_matches(key, names, n=1)
                hint = hint or [n for n in names if n.lower() == key.lower()]
                said = f"; did you mean {hint[0]!r}?" if hint else ""
                raise ValueError(
                    f"{key}: not a parameter of {module.NAME} with friction={friction!r}{said}"
                )
            try:
                number = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"{key}={value!r}: not a number") from None
            if not math.isfinite(number):
                raise ValueError(f"{key}={value!r}: not a finite number")
            values[key] = number
        self.module = module
        self.name: str = module.NAME
        self.friction: str = friction
        self.states: tuple[str, ...] = tuple(module.STATES)
        self.coordinates: tuple[str, ...] = tuple(module.COORDINATES)
        self.units: tuple[str, ...] = module_units(module)
        self.unilateral: bool = bool(module.UNILATERAL)
        self.params: dict[str, float] = {n: values.get(n, float(module.DEFAULTS[n])) for n in names}
        self._given = values
        self.p: NDArray[np.float64] = np.array([self.params[n] for n in names])
        self.kernels = module.kernels(friction)

    def __repr__(self) -> str:
        given = "".join(f", {k}={v!r}" for k, v in self._given.items())
        return f"System({self.name!r}, friction={self.friction!r}{given})"

    def replace(self, **params: float) -> System:
        """The same model and law with some parameters changed (checked as at first).

        Examples
        --------
        >>> System("belt_1dof", Vb=2.0).replace(Vb=3.0).params["Vb"]
        3.0
        """
        return System(self.module, self.friction, **{**self._given, **params})

    def as_dict(self, without: str | None = None) -> dict:
        """The model's part of every JSON output: ``model``, ``friction``, ``params`` (less
        ``without``, a swept parameter that the output lists per point), ``states`` and
        ``state_units`` (state -> unit).

        Examples
        --------
        >>> d = System("belt_1dof", Vb=2.0).as_dict(without="Vb")
        >>> d["model"], "Vb" in d["params"], d["states"][0], d["state_units"]
        ('belt_1dof', False, 'x', {'x': 'm', 'x_dot': 'm/s'})
        """
        params = {k: v for k, v in self.params.items() if k != without}
        return {
            "model": self.name,
            "friction": self.friction,
            "params": params,
            "states": list(self.states),
            "state_units": dict(zip(self.states, self.units)),
        }

    def excitation_period(self) -> float | None:
        """The period of the excitation, or None where every amplitude is 0 (autonomous).

        Raises
        ------
        Unsupported
            Excited terms of different frequencies (no common period assumed).
        """
        omegas = {
            abs(self.params[freq])
            for _, amp, freq, _ in self.module.EXCITATION
            if self.params[amp] != 0.0 and self.params[freq] != 0.0
        }
        if not omegas:
            return None
        if len(omegas) > 1:
            raise Unsupported(
                f"model {self.name!r}: the excitation has frequencies {sorted(omegas)}; "
                "a forced response here needs one common frequency"
            )
        return 2.0 * math.pi / omegas.pop()
