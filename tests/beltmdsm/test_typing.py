"""The public API of beltmdsm is annotated, and its annotations evaluate.

For every public module of beltmdsm (modules whose name starts with ``_`` are
internals; the command line's command modules take an argparse namespace), every
function in ``__all__`` and every public method and property of a class in
``__all__`` (``__init__`` and ``__call__`` included) must annotate each parameter,
``*args`` and ``**kwargs`` too, and its return. ``typing.get_type_hints`` then
evaluates the annotations: with ``from __future__ import annotations`` they are
strings, and one naming a type the module does not import fails only there. Names a
module imports under ``if TYPE_CHECKING:`` (to keep a command's start light) count as
imported: they are what a type checker sees.
"""

import ast
import importlib
import inspect
import pkgutil
import sys
import typing

import pytest

import beltmdsm

#: Modules annotated in another change; remove a name here once its module is done.
PENDING: set[str] = set()
MODULES = sorted(
    m.name
    for m in pkgutil.walk_packages(beltmdsm.__path__, "beltmdsm.")
    if not any(part.startswith("_") for part in m.name.split("."))
    and not m.name.startswith("beltmdsm.cli.commands")
)
#: Methods of a class that belong to its public interface despite the underscores.
DUNDERS = ("__init__", "__call__")


def public_callables(module):
    """``(label, function, has_self)`` for the public API that ``module`` defines or
    re-exports from beltmdsm (objects of other packages, and of pending modules, are
    annotated where they are defined)."""
    for name in getattr(module, "__all__", ()):
        obj = getattr(module, name)
        home = getattr(obj, "__module__", "")
        if home.split(".")[0] != "beltmdsm" or home in PENDING:
            continue
        if inspect.isclass(obj):
            for attr, raw in vars(obj).items():
                if attr.startswith("_") and attr not in DUNDERS:
                    continue
                label = f"{obj.__module__}.{obj.__qualname__}.{attr}"
                if isinstance(raw, property):
                    yield label, raw.fget, True
                elif isinstance(raw, staticmethod):
                    yield label, raw.__func__, False
                elif isinstance(raw, classmethod):
                    yield label, raw.__func__, True
                elif inspect.isfunction(raw):
                    yield label, raw, True
        elif inspect.isfunction(inspect.unwrap(obj)):
            yield f"{obj.__module__}.{obj.__qualname__}", inspect.unwrap(obj), False


def type_checking_names(module):
    """The names ``module`` imports under ``if TYPE_CHECKING:``, imported now."""
    tree = ast.parse(inspect.getsource(module))
    blocks = [
        node.body
        for node in tree.body
        if isinstance(node, ast.If) and ast.unparse(node.test).endswith("TYPE_CHECKING")
    ]
    names = {"__name__": module.__name__, "__package__": module.__package__}
    for body in blocks:
        exec(compile(ast.Module(body=body, type_ignores=[]), module.__file__, "exec"), names)
    return names


@pytest.mark.parametrize("name", MODULES)
def test_public_api_is_annotated(name):
    if name in PENDING:
        pytest.skip(f"{name}: annotations pending (PENDING in tests/beltmdsm/test_typing.py)")
    module = importlib.import_module(name)
    missing = []
    for label, fn, has_self in public_callables(module):
        # a package re-exports its modules' functions: their TYPE_CHECKING names are
        # those of the module that defines them
        checking = type_checking_names(sys.modules[fn.__module__])
        params = list(inspect.signature(fn).parameters.values())
        for param in params[1:] if has_self else params:
            if param.annotation is inspect.Parameter.empty:
                missing.append(f"{label}({param.name})")
        if inspect.signature(fn).return_annotation is inspect.Signature.empty:
            missing.append(f"{label}(return)")
        try:
            typing.get_type_hints(fn, localns=checking)
        except Exception as err:  # NameError, TypeError, ...: any failure to evaluate
            missing.append(f"{label}: annotations do not evaluate ({err!r})")
    assert not missing, "\n".join(missing)


def test_option_types_match_the_checked_options():
    """The Literal types of the annotations are the sets the code checks against."""
    from beltmdsm.batch.row import STARTS, Start
    from beltmdsm.batch.sweep import CONTINUATIONS, Continuation
    from beltmdsm.model import OPTIONS, Contact, Tension

    assert typing.get_args(Contact) == OPTIONS["contact"]
    assert typing.get_args(Tension) == OPTIONS["tension"]
    assert typing.get_args(Start) == STARTS
    assert typing.get_args(Continuation) == CONTINUATIONS
