"""The model: a complete, checked parameter set and its options (Eqs. 1-4, 9).

`Model` is the value every analysis of the package takes: the model options (`OPTIONS`:
the friction, contact and tension laws of the registry, derive/laws.py, as
``beltmdsm.generated.parameters`` lists them), held as a mapping of named options so that a new
option or law is added, not wired, and the parameters of Eq. (4) with the chosen
laws (the paper's base set, ``beltmdsm.generated.parameters.BASE``, updated by what the caller
gives, with the per-direction excitation filled in from ``alpha`` and ``Omega`` as
Eq. (4) has it; a law's own parameters, ``mu_k`` of Stribeck's friction, belong to
the model only where that law is chosen). It is checked once, when it is built,
against the one domain table (``beltmdsm.generated.parameters.DOMAINS``); it is frozen and
hashable, and `Model.digest` keys the sweep cache. The public functions of the
package take a `Model` or the keywords it is built from (`as_model`), convert once at
the boundary and pass the `Model` down; nothing inside checks a parameter again.
`Model.replace` checks only what it changes (with what follows it and the
constraints that involve it). `Model.arguments` gives a generated function the
keywords it takes: every parameter and the options it declares, marked as checked
(``beltmdsm.generated._support.CHECKED``), so that the function does not check them again.

`require` (beltmdsm/facts.py) is how an analysis checks a structural fact of the chosen
laws that SymPy decided (``beltmdsm.generated.capabilities``); the checks of one value
(`is_real`, `check_domain`) are beltmdsm/domains.py's, and another registered model's
parameters (`OtherModel`) beltmdsm/other_model.py's: all re-exported here.

What a model's excitation implies (its start, its period, whether there is any) is
`beltmdsm.excitation`'s.
"""

from __future__ import annotations

import functools
import hashlib
import inspect
import json
from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import Any, Literal

from beltmdsm.generated import parameters as _table
from beltmdsm.generated._support import CHECKED
from beltmdsm.generated.parameters import (
    BASE,
    DEFAULT_FROM,
    DEFAULTS,
    DOMAINS,
    KNOWN,
    PARAMETERS,
)

# beltmdsm.generated._support's class (beltmdsm.errors): one class of one name, so that
# ``except Unsupported`` catches a refusal of the generated modules too
from .domains import check_domain, is_real, real_number
from .errors import Unsupported
from .facts import require
from .other_model import PAPER, OtherParameters, model_module

__all__ = [
    "Model",
    "OtherModel",
    "PAPER",
    "GENERIC",
    "as_model",
    "OPTIONS",
    "OPTION_DEFAULTS",
    "OPTION_DOCS",
    "FRICTIONS",
    "CONTACTS",
    "TENSIONS",
    "Friction",
    "Contact",
    "Tension",
    "Backend",
    "MODEL_PARAMETERS",
    "LAW_OF",
    "LAW_OWNERS",
    "Unsupported",
    "require",
    "check_domain",
    "is_real",
]

#: The model options and their choices, the default first (the registry of laws,
#: derive/laws.py, through ``beltmdsm.generated.parameters``).
OPTIONS: Mapping[str, tuple[str, ...]] = MappingProxyType(dict(_table.OPTIONS))
OPTION_DEFAULTS: Mapping[str, str] = MappingProxyType(dict(_table.OPTION_DEFAULTS))
#: Option -> choice -> one line, for the command line's help and the site's laws page.
OPTION_DOCS: Mapping[str, Mapping[str, str]] = MappingProxyType(dict(_table.OPTION_DOCS))
FRICTIONS, CONTACTS, TENSIONS = _table.FRICTION_LAWS, _table.CONTACT_LAWS, _table.TENSION_LAWS
#: Annotation types of the options, built from the registry's choices, and of the
#: backends of the bound kernels (None: numba if installed).
Friction = Literal[FRICTIONS]
Contact = Literal[CONTACTS]
Tension = Literal[TENSIONS]
Backend = Literal["python", "numba"]
#: The parameters a model may have: every parameter of the table but ``Vhat``, which
#: is an input of the MDSM's effective friction (Eq. 23), not of Eq. (4).
MODEL_PARAMETERS = tuple(name for name in DOMAINS if name != "Vhat")
#: A law's own parameter -> the ``(option, choice)`` of the first law that lists it.
LAW_OF: Mapping[str, tuple[str, str]] = MappingProxyType(
    {p["name"]: tuple(p["law"]) for p in PARAMETERS if p["law"] is not None}
)
#: A law's own parameter -> every ``(option, choice)`` whose law lists it (a name that
#: laws share where it means the same, ``mu_k`` of ``stribeck`` and ``static_kinetic``).
LAW_OWNERS: Mapping[str, tuple[tuple[str, str], ...]] = MappingProxyType(
    {
        name: tuple(key for key, names in _table.LAW_PARAMETERS.items() if name in names)
        for name in LAW_OF
    }
)


#: The public analyses (``beltmdsm.<name>``) that take a model.
ANALYSES = (
    "simulate", "periodic_response", "floquet", "periodic_start", "cycle", "seed_cycle",
    "floquet_band", "branch", "floquet_map", "responses", "coexistence", "lyapunov",
    "classify", "basins", "basin_stability", "predict", "validate", "sweep",
)  # fmt: skip
#: Those the generic runtime (beltmdsm/oscillator/) runs for any registered model.
GENERIC = (
    "simulate", "periodic_response", "floquet", "cycle", "sweep", "lyapunov", "basins",
    "branch", "floquet_band", "floquet_map", "responses", "coexistence", "classify",
    "periodic_start", "basin_stability", "seed_cycle",
)  # fmt: skip
#: Those of `GENERIC` that follow a forced response: they run another model where one
#: of its excitation amplitudes is not 0 (`OtherModel.capabilities`).
FORCED = ("branch", "floquet_band", "floquet_map")
#: Why the generic runtime does not run the others: the paper's own piece (a key of a
#: model module's ``ABSENT``) or what beltmdsm/oscillator/ lacks.
LACKS: Mapping[str, str] = MappingProxyType(
    {
        "predict": "ABSENT:mdsm",
        "validate": "ABSENT:paper_check",
        # `FORCED`: why a model without excitation is refused (`OtherModel.capabilities`
        # adds how to excite it, or that its entry has no excitation terms)
        "floquet_band": "beltmdsm.oscillator has no band of unstable responses over a range "
        "without excitation",
        "branch": "beltmdsm.oscillator has no continuation through folds of a response "
        "without excitation (`branch --model` continues steady sliding and its "
        "self-excited cycles)",
        "floquet_map": "beltmdsm.oscillator has no two-parameter map of the response's "
        "stability without excitation",
    }
)


def _owned(name: str, options: Mapping[str, str]) -> bool:
    """Whether parameter ``name`` is part of a model with these options: a model
    parameter, or one of a chosen law's own."""
    return name not in LAW_OWNERS or any(options.get(o) == c for o, c in LAW_OWNERS[name])


def _check(name: str, value: float) -> None:
    """Raise ValueError naming ``name`` where ``value`` is outside its domain."""
    problem = check_domain(name, value)
    if problem:
        raise ValueError(f"parameter {name!r} {problem}; got {value!r}")


def _check_static(friction: str, params: Mapping[str, float]) -> None:
    """Raise ValueError where the friction law's static bound is below its slip
    coefficient at rest (``beltmdsm.generated.parameters.static_shortfall``)."""
    excess = _table.static_shortfall(friction, **params)
    if excess > 0:
        static, rest = _table.STATIC_BOUNDS[friction]
        raise ValueError(
            f"friction={friction!r}: its slip coefficient at rest {rest} "
            f"exceeds its static bound {static} by {excess:.6g}: stick would hold less "
            f"than slip does; choose {rest} <= {static}"
        )


class Model:
    """A complete, checked parameter set of Eq. (4) and the model options.

    Parameters
    ----------
    **kw
        Model parameters by name (``beltmdsm.generated.parameters``; missing ones take the
        base set, ``None`` leaves one at its default) and options (`OPTIONS`:
        ``friction="stribeck"``, ``contact="kelvin_voigt"``, ``tension="clipped"``).
        A law's own parameter (`LAW_OF`) is part of the model where its law is
        chosen; elsewhere it may only be given at its base value (``**BASE`` serves
        every law), and is then left out.

    Two models are equal (same hash, same `digest`) where their parameters and
    options are and `replace` treats them alike: ``Model(alpha=3, alpha_t=3)`` is
    not ``Model(alpha=3)``, since ``replace(alpha=1)`` keeps ``alpha_t = 3`` in the
    first only. ``-0.0`` is taken as ``0.0``.

    Raises
    ------
    ValueError
        Naming the parameter or option: an unknown name, a value that is not a real
        number (a bool, a string, an array), NaN, infinite or outside its domain, an
        unknown choice of an option, a value for a parameter of a law not chosen
        (it would be ignored), or a friction law's static bound below its slip
        coefficient at rest (``beltmdsm.generated.parameters.static_shortfall``: ``mu_k > mu_s``
        under ``static_kinetic``).

    See Also
    --------
    beltmdsm.model.as_model : The model a public function's arguments describe.
    beltmdsm.model.check_domain : The domain check of one parameter.

    Examples
    --------
    >>> m = Model(Vb=5, tension="clipped")
    >>> m["Vb"], m.tension, m["alpha_t"]
    (5.0, 'clipped', 2.0)
    >>> m.replace(Vb=6) == Model(Vb=6, tension="clipped")
    True
    """

    __slots__ = ("_given", "_params", "_options", "_pinned", "_key")

    def __new__(cls, **kw: Any) -> Model:
        # another registered model (issue 39) is an `OtherModel`: its own parameters,
        # run by the generic runtime
        if cls is Model and kw.get("model", PAPER) != PAPER:
            return object.__new__(OtherModel)
        return object.__new__(cls)

    def __init__(self, **kw: Any) -> None:
        if kw.pop("model", PAPER) != PAPER:
            raise ValueError(f"model must be {PAPER!r} here")  # OtherModel's, by __new__
        given, options = {}, dict(OPTION_DEFAULTS)
        for name, value in kw.items():
            if name in OPTIONS:
                if value not in OPTIONS[name]:
                    raise ValueError(
                        f"{name} must be one of {', '.join(map(repr, OPTIONS[name]))}; "
                        f"got {value!r}"
                    )
                options[name] = value
            elif name == "Vhat":
                raise ValueError(
                    "Vhat is an input of the effective friction of Eq. (23) "
                    "(beltmdsm.generated.stability, beltmdsm.generated.friction), not a "
                    "parameter of the model"
                )
            elif name not in KNOWN:
                raise ValueError(
                    f"unknown parameter {name!r}; known: {', '.join(MODEL_PARAMETERS)}; "
                    f"options: {', '.join(OPTIONS)}"
                )
            elif value is not None:
                given[name] = real_number(name, value)
        for name in [n for n in given if not _owned(n, options)]:
            if given.pop(name) != BASE.get(name):
                by = LAW_OWNERS[name]
                option = by[0][0]
                laws_ = " or ".join(f"{c!r}" for _, c in by)
                choose = " or ".join(f"{o}={c!r}" for o, c in by)
                raise ValueError(
                    f"parameter {name!r} belongs to the {option} law {laws_}, not "
                    f"chosen ({option}={options[option]!r}); choose {choose}"
                )
        params = {k: v for k, v in BASE.items() if _owned(k, options)}
        params.update(given)
        params.pop("Vhat", None)
        for name, value in DEFAULTS.items():
            params.setdefault(name, value)
        for name, source in DEFAULT_FROM.items():
            params.setdefault(name, params[source])
        for name, value in params.items():
            _check(name, value)
        _check_static(options["friction"], params)
        ordered = {name: params[name] for name in MODEL_PARAMETERS if name in params}
        self._set(given, ordered, options)

    def _set(self, given: dict[str, float], ordered: dict[str, float], options: dict) -> None:
        """Hold a checked parameter set (``ordered``: in the table's order)."""
        setattr_ = object.__setattr__
        setattr_(self, "_given", MappingProxyType(given))
        setattr_(self, "_params", MappingProxyType(ordered))
        setattr_(self, "_options", MappingProxyType(options))
        # a parameter that follows another (alpha_t follows alpha) and was given keeps
        # its value under replace(): it belongs to the model's identity, else two equal
        # models would differ after the same replace()
        pinned = tuple(sorted(name for name in DEFAULT_FROM if name in given))
        setattr_(self, "_pinned", pinned)
        setattr_(self, "_key", (tuple(ordered.items()), tuple(sorted(options.items())), pinned))

    @classmethod
    def from_mapping(cls, mapping: Mapping[str, Any] | None, **kw: Any) -> Model:
        """A model from a mapping of parameters and options, updated by ``kw``."""
        if mapping is not None and not isinstance(mapping, Mapping):
            raise ValueError(f"params must be a dict of parameters; got {type(mapping).__name__}")
        return cls(**{**(mapping or {}), **kw})

    def replace(self, **kw: Any) -> Model:
        """A new model with some parameters or options changed.

        The parameters given when this model was built stay given; the others
        follow their defaults (``alpha_t`` follows ``alpha`` unless it was given).
        A law's own parameters go with the law where another is chosen. Where only
        parameters of this model change, only they are checked (with the
        parameters that follow them and the constraints that involve them,
        ``beltmdsm.generated.parameters.STATIC_PARAMETERS``): the rest were checked when
        this model was built. An option change builds and checks the model whole.

        Parameters
        ----------
        **kw
            Parameters and options, as `Model` takes them.

        Returns
        -------
        Model

        Raises
        ------
        ValueError
            Naming the parameter or option, as `Model` does.

        See Also
        --------
        beltmdsm.model.Model, beltmdsm.model.as_model

        Examples
        --------
        >>> m = Model(Vb=5)
        >>> m.replace(alpha=3)["alpha_t"], m.replace(alpha=3).replace(Vb=6)["Vb"]
        (3.0, 6.0)
        >>> m.replace(Vb=-1)
        Traceback (most recent call last):
        ...
        ValueError: parameter 'Vb' must be >= 0; got -1.0
        """
        if not all(k in self._params and v is not None for k, v in kw.items()):
            # an option, a parameter of another law, None (back to the default), an
            # unknown name: built and checked whole
            options = {**self._options, **{k: v for k, v in kw.items() if k in OPTIONS}}
            given = {k: v for k, v in self._given.items() if _owned(k, options)}
            return Model(**{**given, **options, **kw})
        # parameters of this model only: the changed ones are checked, with those that
        # follow them (alpha_t follows alpha unless given) and the constraints that
        # involve them; the rest were checked when this model was built
        changed = {k: real_number(k, v) for k, v in kw.items()}
        given = {**self._given, **changed}
        for name, source in DEFAULT_FROM.items():
            if source in changed and name not in given:
                changed[name] = changed[source]
        for name, value in changed.items():
            _check(name, value)
        params = {**self._params, **changed}
        if not changed.keys().isdisjoint(_table.STATIC_PARAMETERS.get(self.friction, ())):
            _check_static(self.friction, params)
        new = object.__new__(Model)
        new._set(given, params, dict(self._options))
        return new

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError("Model is immutable; use replace()")

    def __reduce__(self):
        # pickled as what it was built from (process pools, dask workers)
        return (_rebuild, (dict(self._given), dict(self._options)))

    @property
    def params(self) -> Mapping[str, float]:
        """Every parameter of Eq. (4), in the order of the parameter table."""
        return self._params

    @property
    def model(self) -> str:
        """The registered mechanical model (``generated/models/``): the paper's here."""
        return PAPER

    @property
    def capabilities(self) -> Mapping[str, tuple[bool, str]]:
        """Public analysis -> ``(runs, why not)``: every one runs the paper's model."""
        return MappingProxyType({name: (True, "") for name in ANALYSES})

    @property
    def options(self) -> Mapping[str, str]:
        """The model options (`OPTIONS`)."""
        return self._options

    @property
    def friction(self) -> Friction:
        return self._options["friction"]

    @property
    def contact(self) -> Contact:
        return self._options["contact"]

    @property
    def tension(self) -> Tension:
        return self._options["tension"]

    def __getitem__(self, name: str) -> float:
        return self._params[name]

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Model) and self._key == other._key

    def __hash__(self) -> int:
        return hash(self._key)

    def __repr__(self) -> str:
        changed = {k: v for k, v in self._params.items() if BASE.get(k) != v}
        for name, source in DEFAULT_FROM.items():
            if name in self._pinned:
                changed[name] = self._params[name]  # given: part of the identity
            elif changed.get(name) == self._params[source]:
                del changed[name]
        for name, value in DEFAULTS.items():
            if changed.get(name) == value:
                del changed[name]
        options = {k: v for k, v in self._options.items() if OPTION_DEFAULTS[k] != v}
        args = [f"{k}={v!r}" for k, v in {**changed, **options}.items()]
        return f"Model({', '.join(args)})"

    def fact(self, name: str) -> tuple[bool, str]:
        """``(holds, reason)``: a capability of this model's laws that SymPy decided
        (``beltmdsm.generated.capabilities``; ``name`` one of its ``FACTS``)."""
        from beltmdsm.generated.capabilities import CAPABILITIES

        return CAPABILITIES[(self.friction, self.contact, self.tension)][name]

    def arguments(self, function: Callable[..., Any]) -> dict[str, Any]:
        """The keywords a generated function takes of this model: the options it declares
        (``friction=``, ``contact=``, ...), every parameter (the generated functions
        accept every known parameter) and, under ``beltmdsm.generated._support.CHECKED``, the
        parameters as this model checked them: the function does not check them again.
        A value put in the place of one (``{**m.arguments(f), "Vb": grid}``) is checked.
        """
        options = {k: self._options[k] for k in _declared_options(function)}
        return {**options, **self._params, CHECKED: self._params}

    def as_dict(self) -> dict[str, Any]:
        """``{"params": {...}, <option>: <choice>, ...}``, for JSON."""
        return {"params": dict(self._params), **self._options}

    def digest(self) -> str:
        """SHA-256 of the parameters, the options and the parameters that follow
        another but were given (``alpha_t`` given: `replace` keeps it): the same on
        every machine and run, equal exactly where the models are."""
        text = json.dumps(
            {"params": self._params.copy(), **self._options, "pinned": list(self._pinned)},
            sort_keys=True,
        )
        return hashlib.sha256(text.encode()).hexdigest()


class OtherModel(OtherParameters, Model):
    """A registered model other than the paper's, with its friction law and parameters.

    Made by ``Model(model=NAME, ...)``: the model's own parameters (its generated module
    ``beltmdsm.generated.models.<NAME>``: ``PARAMETERS[friction]``, ``DEFAULTS``,
    ``DOMAINS``), checked once (`beltmdsm.other_model.OtherParameters`, which holds them
    and refuses the paper's pieces). The analyses of `GENERIC` run it on the generic
    runtime (beltmdsm/oscillator/); the others refuse it in one line naming the model
    and what it lacks (`capabilities`). The paper's options (contact, tension) and its
    generated functions (`Model.arguments`, `Model.fact`) are not its: asked for, they
    refuse, so that no paper physics runs under another model's name.

    Examples
    --------
    >>> m = Model(model="belt_1dof", friction="stribeck", Vb=1.5)
    >>> m, m.model, m["mu_k"]
    (Model(model='belt_1dof', friction='stribeck', Vb=1.5), 'belt_1dof', 0.25)
    >>> m.capabilities["predict"][0], m.capabilities["simulate"][0]
    (False, True)
    >>> Model(model="belt_1dof", k1=2.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: k1: not a parameter of model 'belt_1dof' with friction='coulomb' (beta1, ...)
    """

    __slots__ = ()

    def replace(self, **kw: Any) -> Model:
        """The same model with some parameters changed, or another law or model (a law's
        parameters that the new law lacks are dropped)."""
        options = {**self._options, **{k: kw.pop(k) for k in ("model", "friction") if k in kw}}
        if options["model"] != self.model:
            return Model(**options, **kw)
        names = model_module(self.model).PARAMETERS[options["friction"]]
        given = {k: v for k, v in self._given.items() if k in names}
        return Model(**options, **{**given, **kw})

    def __reduce__(self):
        return (_rebuild_other, (dict(self._given), dict(self._options)))

    @property
    def capabilities(self) -> Mapping[str, tuple[bool, str]]:
        """Public analysis -> ``(runs, why not)`` for this model at these parameters: the
        forced analyses (`FORCED`) run where an excitation amplitude is not 0."""
        module = model_module(self.model)
        excited = any(self._params.get(amplitude) for _, amplitude, _, _ in module.EXCITATION)
        out = {}
        for name in ANALYSES:
            runs = name in GENERIC and (excited or name not in FORCED)
            why = "" if runs else LACKS.get(name, "")
            if why.startswith("ABSENT:"):
                why = module.ABSENT[why.removeprefix("ABSENT:")]
            elif name in FORCED and not runs:
                why += (
                    ": set an excitation amplitude"
                    if module.EXCITATION
                    else ": the model has no excitation terms (derive/models/entries.py)"
                )
            out[name] = (runs, why)
        return MappingProxyType(out)

    def refusal(self, analysis: str) -> str:
        """The one line of an analysis that does not run this model: one of `GENERIC`
        refused for its parameters (`FORCED` without excitation) says how to run it, any
        other that it runs the paper's model only."""
        why = f"{analysis}: model {self.model!r}: {self.capabilities[analysis][1]}"
        return (
            why
            if analysis in GENERIC
            else f"{why}; it runs the paper's model only (model={PAPER!r})"
        )


def _rebuild_other(given: dict[str, float], options: dict[str, str]) -> Model:
    return Model(**options, **given)


@functools.cache
def _declared_options(function: Callable[..., Any]) -> tuple[str, ...]:
    """The model options among a function's keyword-only parameters."""
    kinds = inspect.signature(function).parameters.items()
    return tuple(name for name, p in kinds if p.kind is p.KEYWORD_ONLY and name in OPTIONS)


def _rebuild(given: dict[str, float], options: dict[str, str]) -> Model:
    return Model(**given, **options)


def as_model(model: Model | Mapping[str, Any] | None = None, **kw: Any) -> Model:
    """The `Model` that a public function's arguments describe (the boundary check).

    A `Model` is passed through as it is (``kw`` replaces some of its entries); a
    mapping of parameters and options, or keywords, build one.

    Parameters
    ----------
    model : Model or Mapping or None
        A model, a mapping of parameters and options, or None for the defaults.
    **kw
        Parameters and options that replace or add to ``model``'s.

    Returns
    -------
    Model
        The checked model.

    Raises
    ------
    ValueError
        For an unknown name or a value outside its domain, naming the parameter.

    See Also
    --------
    beltmdsm.model.Model : The checked parameter set.

    Examples
    --------
    >>> as_model({"Vb": 2})["Vb"], as_model(Model(), Vb=3)["Vb"]
    (2.0, 3.0)
    >>> as_model(Vb=-1)
    Traceback (most recent call last):
    ...
    ValueError: parameter 'Vb' must be >= 0; got -1...
    """
    if isinstance(model, Model):
        return model.replace(**kw) if kw else model
    return Model.from_mapping(model, **kw)
