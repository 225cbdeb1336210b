"""The Examples sections of the package's docstrings run and print what they say
(issue 32, item 3: doctests collected by the test run). Every module of beltmdsm/ and of
generated/ (``beltmdsm.generated``, its Examples written by derive/) whose docstrings
hold an example is found here, so a new one is checked without a list."""

import doctest
import importlib
import inspect
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: Each package and its folder in a source checkout (beltmdsm/_layout.py).
FOLDERS = {"beltmdsm": "beltmdsm", "beltmdsm.generated": "generated"}
MODULES = sorted(
    ".".join((package, *p.relative_to(ROOT / folder).with_suffix("").parts))
    for package, folder in FOLDERS.items()
    for p in (ROOT / folder).rglob("*.py")
    if ">>> " in p.read_text(encoding="utf-8")
)


def test_the_examples_are_found():
    # beltmdsm.periodic.cycle: beltmdsm.cycles.cycle before issue 38
    found = {"beltmdsm.model", "beltmdsm.periodic.cycle", "beltmdsm.basin.basins"}
    assert found | {"beltmdsm.generated.stability"} <= set(MODULES)


@pytest.mark.parametrize("name", MODULES)
def test_the_examples_run(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0, result


def _public_functions(module):
    """The functions that ``module`` defines under a public name."""
    return [
        name
        for name, obj in vars(module).items()
        if not name.startswith("_")
        and inspect.isfunction(obj)
        and obj.__module__ == module.__name__
    ]


@pytest.mark.parametrize(
    "name",
    sorted(
        f"beltmdsm.generated.{p.stem}"
        for p in (ROOT / "generated").glob("*.py")
        if not p.stem.startswith("_")
    ),
)
def test_every_generated_function_has_an_example(name):
    """derive/modules/<module>.py types them (``FunctionSpec.examples`` and
    ``bind_examples``); a new generated function needs one too."""
    module = importlib.import_module(name)
    bare = [
        f
        for f in _public_functions(module)
        if ">>> " not in (getattr(module, f).__doc__ or "").partition("Examples\n")[2]
    ]
    assert not bare, f"{name}: no Examples section for {bare}"
