"""Issue 38, items 3 and 4: studies/ cut by role, the old paths kept, names that explain
themselves, and one hierarchy of failures defined in beltmdsm/errors.py."""

import ast
import importlib
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import beltmdsm
from beltmdsm import errors
from beltmdsm._moved import MOVED

ROOT = Path(__file__).resolve().parents[2]


def _fresh(code):
    """Run ``code`` in a new interpreter (no module imported yet), DeprecationWarnings
    shown; its stdout and stderr."""
    done = subprocess.run(
        [sys.executable, "-W", "always::DeprecationWarning", "-c", code],
        capture_output=True, text=True, cwd=ROOT, timeout=120,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    return done.stdout, done.stderr


@pytest.mark.parametrize("old, new", sorted(MOVED.items()))
def test_an_old_path_is_the_new_module_and_says_where_it_went(old, new):
    out, err = _fresh(
        f"import importlib, sys; o = importlib.import_module({old!r}); "
        f"print(o is sys.modules[{new!r}], o.__name__)"
    )
    assert out.split() == ["True", new]
    assert f"{old} moved to {new} (issue 38); import it from there" in err


def test_a_moved_packages_submodule_is_loaded_once():
    """``beltmdsm.studies.validation.cases`` is ``beltmdsm.paper_reports.validation.cases``
    (not a second copy with its own classes)."""
    out, _ = _fresh(
        "from beltmdsm.studies.validation.cases import Case\n"
        "from beltmdsm.studies.validation import validate\n"
        "import beltmdsm.paper_reports.validation.cases as new, sys\n"
        "print(Case is new.Case, validate.__module__,"
        " sorted(m for m in sys.modules if m.startswith('beltmdsm.paper_reports.validation.c')))"
    )
    assert out.split(" ", 2)[:2] == ["True", "beltmdsm.paper_reports.validation.run"]
    assert "'beltmdsm.paper_reports.validation.cases'" in out


def test_studies_still_names_its_modules():
    out, err = _fresh("import beltmdsm.studies as s; print(s.sweep.__name__, s.seeds.__name__)")
    assert out.split() == ["beltmdsm.batch.sweep", "beltmdsm.starts.forced"]
    assert "beltmdsm.studies.seeds moved to beltmdsm.starts.forced" in err
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        importlib.import_module("beltmdsm.studies").nothing  # noqa: B018


def test_the_starting_states_are_one_package_without_an_arrow_up():
    """Issue 38 item 3: studies/seeds.py, cycles/seed.py and periodic/start.py are one
    place, `beltmdsm.starts`, whose modules sit at their own layers: a self-excited
    cycle's seed (which `beltmdsm.periodic.cycle` shoots from) loads no simulation, and
    the package gives every name of both as before."""
    out, _ = _fresh(
        "import sys, beltmdsm.periodic.cycle, beltmdsm.starts.cycle_seed as seed\n"
        "print(seed.__name__, 'beltmdsm.simulation' in sys.modules,"
        " 'beltmdsm.starts.forced' in sys.modules)\n"
        "import beltmdsm.starts as starts, beltmdsm.starts.forced as forced\n"
        "print(all(getattr(starts, n) is getattr(forced, n) for n in forced.__all__),"
        " all(getattr(starts, n) is getattr(seed, n) for n in seed.__all__),"
        " sorted(set(dir(starts))) == sorted(set(forced.__all__) | set(seed.__all__)))"
    )
    assert out.split() == ["beltmdsm.starts.cycle_seed", "False", "False", "True", "True", "True"]
    for old in ("beltmdsm/starts.py", "beltmdsm/periodic/cycle_seed.py",
                "beltmdsm/cycles/seed.py"):  # fmt: skip
        assert not (ROOT / old).exists(), old


def test_the_public_names_come_from_their_new_homes():
    homes = {
        "sweep": "beltmdsm.batch.sweep",
        "responses": "beltmdsm.multistability.responses",
        "coexistence": "beltmdsm.multistability.coexistence",
        "basins": "beltmdsm.basin.basins",
        "validate": "beltmdsm.paper_reports.validation.run",
        "periodic_start": "beltmdsm.starts.forced",
        "seed_cycle": "beltmdsm.starts.cycle_seed",
    }
    for name, module in homes.items():
        assert getattr(beltmdsm, name).__module__ == module, name
    # a subpackage named like a public function would shadow it once imported
    importlib.import_module("beltmdsm.basin.basins")
    assert callable(beltmdsm.basins)


@pytest.mark.parametrize(
    "path",
    [
        "beltmdsm/basin/basins.py",
        "beltmdsm/multistability/coexistence.py",
        "beltmdsm/attractors/classification.py",
        "beltmdsm/attractors/self_excited.py",
    ],
)
def test_the_split_modules_are_under_500_lines(path):
    """They were 735, 700, 701 and 670 lines."""
    assert len((ROOT / path).read_text().splitlines()) < 500


def test_the_old_look_alike_names_are_gone():
    for path in ("beltmdsm/attractors/landing.py", "beltmdsm/integrate/_superpose.py",
                 "beltmdsm/studies/evidence.py", "beltmdsm/studies/overlay.py",
                 "beltmdsm/periodic/start.py", "beltmdsm/studies/seeds.py"):  # fmt: skip
        assert not (ROOT / path).exists(), path
    for path in (ROOT / "beltmdsm/paper_reports/law_comparison").glob("*.py"):
        assert "Item 8" not in path.read_text(), path


def test_the_root_failures_are_defined_in_errors_which_imports_nothing_of_beltmdsm():
    from beltmdsm.generated import _support

    assert errors.BeltmdsmError.__module__ == errors.Unsupported.__module__ == "beltmdsm.errors"
    assert _support.Unsupported is errors.Unsupported
    assert _support.BeltmdsmError is errors.BeltmdsmError
    tree = ast.parse((ROOT / "beltmdsm/errors.py").read_text())
    imported = {
        (n.module or "") if isinstance(n, ast.ImportFrom) else a.name
        for n in ast.walk(tree)
        if isinstance(n, (ast.Import, ast.ImportFrom))
        for a in n.names
    }
    assert imported == {"__future__"}


def test_no_hopf_point_and_no_prediction_join_the_hierarchy():
    from beltmdsm import Model
    from beltmdsm.cycles import hopf

    assert hopf.NoHopfPoint is errors.NoHopfPoint
    with pytest.raises(errors.BeltmdsmError, match="no Hopf point") as caught:
        hopf.hopf_point(Model(alpha=0.0), "Vb", 0.5, 5.0)
    assert isinstance(caught.value, ValueError)
    assert issubclass(errors.NoPrediction, errors.BeltmdsmError)
    assert issubclass(errors.NoPrediction, ValueError)
    source = (ROOT / "beltmdsm/prediction/prediction.py").read_text()
    assert "_Refused" not in source and "NoPrediction(" in source


def test_refused_refusal_and_the_table_entry_have_names_apart():
    """`Refused` is the runtime's refusal of a request, alone; the generated table entry
    of a variant that does not exist and derive's spec of it are `NoVariant`."""
    from beltmdsm.derive import codegen
    from beltmdsm.generated import _support

    assert not hasattr(_support, "Refused") and not hasattr(codegen, "Refusal")
    assert isinstance(_support.NoVariant("why"), _support.NoVariant)
    assert codegen.NoVariant("why").reason == "why"
    assert issubclass(errors.Refused, errors.BeltmdsmError)


def test_warnings_filter_is_left_as_found():
    """The finder warns through `warnings`; it installs no filter of its own."""
    before = list(warnings.filters)
    importlib.import_module("beltmdsm._moved").install()
    assert warnings.filters == before


def _imported(path, package):
    """The absolute module names ``path`` imports from (relative ones resolved)."""
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            yield from (a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[: len(parts) - node.level + 1])
                source = f"{base}.{node.module}" if node.module else base
            else:
                source = node.module or ""
            yield source
            yield from (f"{source}.{a.name}" for a in node.names)


#: The tests whose subject is the old paths themselves.
CHECKS_OLD_PATHS = {Path(__file__).name, "test_moved_paths.py"}


def test_nothing_of_the_package_imports_an_old_path():
    """The old paths are for users: the package, its tests and benchmarks use the new ones
    (an old one would warn, and hide a layer from tests/test_layers.py)."""
    old = []
    for folder in ("beltmdsm", "tests", "benchmarks", "notebooks"):
        for path in sorted((ROOT / folder).rglob("*.py")):
            rel = path.relative_to(ROOT)
            if rel.parts[:2] == ("beltmdsm", "studies") or path.name in CHECKS_OLD_PATHS:
                continue
            parts = rel.with_suffix("").parts
            package = ".".join(parts if path.name == "__init__.py" else parts[:-1])
            for name in _imported(path, package):
                if any(name == k or name.startswith(k + ".") for k in MOVED):
                    old.append(f"{rel}: {name}")
    assert not old, old
