"""Another registered model than the paper's: its own parameters, checked once, and the
paper's pieces refused (issue 39).

`OtherParameters` is what `beltmdsm.model.OtherModel` (the class ``Model(model=NAME,
...)`` returns) holds of another model: its friction law and its parameters, read from
its generated module ``beltmdsm.generated.models.<NAME>`` (`model_module`:
``PARAMETERS[friction]``, ``DEFAULTS``, ``DOMAINS``) and checked once where they enter;
its repr, JSON and digest; and the refusal, in one line, of every piece of the paper's
model (the contact and tension laws, the facts of its laws, its generated functions),
so that no paper physics runs under another model's name. beltmdsm/model.py builds
``OtherModel`` from it and `beltmdsm.model.Model` (the base that dispatches to it, which
is why this module imports nothing of beltmdsm/model.py), and keeps there what needs the
paper's class or its tables: ``replace``, pickling and ``capabilities``.
"""

from __future__ import annotations

import difflib
import hashlib
import json
from collections.abc import Callable
from types import MappingProxyType, ModuleType
from typing import Any, NoReturn

from beltmdsm.generated.parameters import DOMAIN_RULES, OPTIONS, within

from .domains import real_number
from .errors import Unsupported

__all__ = ["PAPER", "OtherParameters", "model_module"]

#: The default mechanical model, ``beltmdsm.generated.models.MODELS[0]``.
PAPER = "paper"


def model_module(name: str) -> ModuleType:
    """The generated module of a registered model (ValueError naming the registered).

    Parameters
    ----------
    name : str
        A name of ``beltmdsm.generated.models.MODELS``.

    Returns
    -------
    module

    Raises
    ------
    ValueError
        For another name, the registered ones listed, the closest suggested.

    See Also
    --------
    OtherParameters : reads a model's parameters from it.

    Examples
    --------
    >>> model_module("belt_1dof").STATES
    ('x', 'x_dot')
    >>> model_module("hofman")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: model must be one of 'paper', ...; got 'hofman'; did you mean 'hoffmann'?
    """
    from beltmdsm.generated import models

    if name not in models.MODELS:
        close = difflib.get_close_matches(str(name), models.MODELS, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise ValueError(
            f"model must be one of {', '.join(map(repr, models.MODELS))}; got {name!r}{hint}"
        )
    return models.load(name)


class OtherParameters:
    """Another registered model's law and parameters, and the paper's pieces refused
    (module docstring); a base of `beltmdsm.model.OtherModel`, whose docstring has the
    examples.

    Parameters
    ----------
    model : str
        A registered model other than the paper's.
    friction : str, optional
        One of its ``FRICTION_LAWS``; its first by default.
    **kw : float
        Its parameters (``PARAMETERS[friction]``); ``None`` leaves one at its default.

    Raises
    ------
    ValueError
        Naming the parameter: an option of the paper's model, a name the model lacks
        with this law, a value that is no finite real number or outside its domain; or
        a friction law the model lacks.
    """

    __slots__ = ()

    def __init__(self, **kw: Any) -> None:
        name = kw.pop("model")
        module = model_module(name)
        laws = tuple(module.FRICTION_LAWS)
        friction = kw.pop("friction", None) or laws[0]
        if friction not in laws:
            raise ValueError(
                f"friction must be one of {', '.join(map(repr, laws))} for model "
                f"{name!r}; got {friction!r}"
            )
        names = tuple(module.PARAMETERS[friction])
        given = {}
        for key, value in kw.items():
            if key in OPTIONS:
                raise ValueError(
                    f"{key}: an option of the paper's model; model {name!r} derives its "
                    "normal force in its registry entry (derive/models/entries.py)"
                )
            if key not in names:
                raise ValueError(
                    f"{key}: not a parameter of model {name!r} with friction={friction!r} "
                    f"({', '.join(names)})"
                )
            if value is None:
                continue
            number = real_number(key, value)
            if not within(module.DOMAINS[key], number):
                rule = DOMAIN_RULES[module.DOMAINS[key]][2]
                raise ValueError(f"parameter {key!r} must be {rule}; got {number!r}")
            given[key] = number
        params = {n: given.get(n, float(module.DEFAULTS[n])) for n in names}
        setattr_ = object.__setattr__
        setattr_(self, "_given", MappingProxyType(given))
        setattr_(self, "_params", MappingProxyType(params))
        setattr_(self, "_options", MappingProxyType({"model": name, "friction": friction}))
        setattr_(self, "_pinned", ())
        setattr_(self, "_key", (name, friction, tuple(params.items())))

    @property
    def model(self) -> str:
        """The registered model's name."""
        return self._options["model"]  # type: ignore[attr-defined]

    @property
    def states(self) -> tuple[str, ...]:
        """The model's states, in its order (its module's ``STATES``)."""
        return tuple(model_module(self.model).STATES)

    @property
    def state_units(self) -> tuple[str, ...]:
        """The unit of each state, in the order of `states` (its module's ``STATE_UNITS``,
        which derive/models/ writes from the entry's units of its coordinates)."""
        return tuple(model_module(self.model).STATE_UNITS)

    def _paper_only(self, what: str) -> NoReturn:
        raise Unsupported(
            f"model {self.model!r}: {what} belongs to the paper's model; this analysis "
            f"runs the paper's model only (model={PAPER!r})"
        )

    @property
    def contact(self) -> NoReturn:
        """Refused: the contact law is the paper's model's."""
        self._paper_only("the contact law")

    @property
    def tension(self) -> NoReturn:
        """Refused: the tension law is the paper's model's."""
        self._paper_only("the tension law")

    def fact(self, name: str) -> NoReturn:
        """Refused: the facts SymPy decided are of the paper's laws."""
        self._paper_only(f"the capability {name!r} of the paper's laws")

    def arguments(self, function: Callable[..., Any]) -> NoReturn:
        """Refused: the generated functions are the paper's model's."""
        self._paper_only(f"the generated function {function.__name__}")

    def __repr__(self) -> str:
        module = model_module(self.model)
        params = self._params  # type: ignore[attr-defined]
        friction = self._options["friction"]  # type: ignore[attr-defined]
        changed = {k: v for k, v in params.items() if v != module.DEFAULTS[k]}
        args = ", ".join(f"{k}={v!r}" for k, v in changed.items())
        law = f", friction={friction!r}" if friction != module.FRICTION_LAWS[0] else ""
        return f"Model(model={self.model!r}{law}{', ' if args else ''}{args})"

    def as_dict(self) -> dict[str, Any]:
        """``{"model": NAME, "params": {...}, "friction": LAW}``, for JSON."""
        params, options = self._params, self._options  # type: ignore[attr-defined]
        return {"model": self.model, "params": dict(params), "friction": options["friction"]}

    def digest(self) -> str:
        """SHA-256 of `as_dict`: the same on every machine and run."""
        text = json.dumps(self.as_dict(), sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()
