"""The public API as a type checker and a user's ``except`` see it (issue 30, item 2).

* mypy reads ``typing_check/uses_public_api.py`` (a study on the lazily exported names
  of ``beltmdsm``) with ``--disallow-any-expr``: no expression there is ``Any``, and
  each ``reveal_type`` names the class the call returns;
* the package ships ``py.typed`` and has a ``__version__``;
* the failures form one hierarchy under `BeltmdsmError`, each keeping its builtin
  base, one class of each name wherever it is imported from.
"""

import ast
import importlib
import importlib.metadata
import os
import pickle
import re
import subprocess
import sys
from pathlib import Path

import pytest

import beltmdsm
from beltmdsm import errors

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = Path(__file__).parent / "typing_check" / "uses_public_api.py"


def _as_installed(folder):
    """``folder/beltmdsm`` laid out as the wheel installs it, of links to this checkout:
    beltmdsm/'s files with generated/ and derive/ inside. A type checker reads files,
    not import hooks: in the checkout it cannot find ``beltmdsm.generated``, which
    beltmdsm/_layout.py maps beside beltmdsm/ when Python imports it."""
    package = folder / "beltmdsm"
    package.mkdir()
    for entry in (ROOT / "beltmdsm").iterdir():
        if entry.name != "__pycache__":
            (package / entry.name).symlink_to(entry)
    for name in ("generated", "derive"):
        (package / name).symlink_to(ROOT / name, target_is_directory=True)
    return folder


def test_the_public_api_has_no_any_for_mypy(tmp_path):
    pytest.importorskip("mypy", reason="mypy is in the test extra (pyproject.toml)")
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--follow-imports=silent", "--disallow-any-expr",
         "--no-incremental", "--cache-dir=/dev/null", "--python-version=3.10", str(SCRIPT)],
        capture_output=True, text=True, cwd=_as_installed(tmp_path), timeout=300,
        env={k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MYPYPATH")},
    )  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    revealed = re.findall(r'Revealed type is "([^"]+)"', done.stdout)
    assert revealed == [
        "beltmdsm.model.Model",
        "beltmdsm.simulation.Simulation",
        "beltmdsm.run.summary.Summary",
        "beltmdsm.periodic.floquet.Floquet",
        "beltmdsm.continuation.band_result.Band",  # the model first
        "beltmdsm.continuation.band_result.Band",  # the model last, as before
        "beltmdsm.continuation.branch_result.Branch",  # branch_parts.py before issue 38
        "beltmdsm.multistability.coexistence_result.Coexistence",  # split (issue 38)
        "beltmdsm.batch.sweep.Sweep",
        "beltmdsm.continuation.map_result.FloquetMap",
        "beltmdsm.periodic.cycle.Cycle",  # moved from cycles/cycle.py (issue 38)
        "beltmdsm.attractors.lyapunov.Lyapunov",
        "beltmdsm.attractors.attractor.Attractor",
        "beltmdsm.basin.basins_result.Basins",
        "beltmdsm.attractors.lyapunov.Lyapunov",  # a dict for the model (issue 37)
        "beltmdsm.continuation.band_result.Band",
    ]


def test_the_stub_names_every_lazy_export_from_its_module():
    stub = ast.parse((ROOT / "beltmdsm" / "__init__.pyi").read_text())
    imported = {
        a.name: node.module.removeprefix("beltmdsm.").lstrip(".")
        for node in stub.body
        if isinstance(node, ast.ImportFrom)
        for a in node.names
    }
    listed = next(
        ast.literal_eval(n.value)
        for n in stub.body
        if isinstance(n, ast.Assign) and n.targets[0].id == "__all__"
    )
    assert imported == beltmdsm._API
    assert listed == beltmdsm.__all__ == list(beltmdsm._API)


def test_the_package_is_typed_and_versioned():
    assert (ROOT / "beltmdsm" / "py.typed").is_file()
    assert beltmdsm.__version__ == importlib.metadata.version("beltmdsm")
    assert "__version__" in dir(beltmdsm)
    with pytest.raises(AttributeError, match="no attribute 'simlate'"):
        beltmdsm.simlate  # noqa: B018


FAILURES = {
    "Refused": ValueError,
    "Unsupported": ValueError,
    "StepTooSmall": ArithmeticError,
    "NoPeriodicResponse": RuntimeError,
    "ShorterPeriod": RuntimeError,
    "NotApplicable": ValueError,
    "NoEdge": RuntimeError,
}
#: The modules that defined a failure before beltmdsm.errors held them all.
OLD_HOMES = {
    "Unsupported": ["beltmdsm.model", "beltmdsm.generated._support"],
    "NoEdge": ["beltmdsm.continuation.edges"],
    "NotApplicable": ["beltmdsm.integrate.superposition"],
    "StepTooSmall": ["beltmdsm.integrate.events"],
}


@pytest.mark.parametrize("name", FAILURES)
def test_one_hierarchy_one_class_per_name(name):
    cls = getattr(errors, name)
    assert issubclass(cls, errors.BeltmdsmError) and issubclass(cls, FAILURES[name])
    for module in OLD_HOMES.get(name, []):
        assert getattr(importlib.import_module(module), name) is cls, module
    if name in beltmdsm.__all__:
        assert getattr(beltmdsm, name) is cls


def test_a_refusal_of_the_generated_modules_is_beltmdsm_unsupported():
    from beltmdsm.generated import oscillator
    from beltmdsm.model import Model

    p = Model(friction="stribeck").params
    with pytest.raises(beltmdsm.Unsupported, match="stribeck"):
        oscillator.bind_tangential_state(friction="stribeck", **p)


def test_failures_pickle_with_what_they_carry():
    refused = pickle.loads(pickle.dumps(errors.Refused("too many points", "points", "tol")))
    assert (str(refused), refused.names) == ("too many points", ("points", "tol"))
    step = pickle.loads(pickle.dumps(errors.StepTooSmall("stuck", 1e-9, 1e-12)))
    assert (str(step), step.rtol, step.atol) == ("stuck", 1e-9, 1e-12)
    # raised by periodic_response(periods=k) in a worker of an executor, it arrives whole
    shorter = errors.ShorterPeriod(8, 4, "the period map iterated from rest locks at")
    back = pickle.loads(pickle.dumps(shorter))
    assert (type(back), str(back), back.asked, back.periods) == (
        errors.ShorterPeriod,
        str(shorter),
        8,
        4,
    )
    assert "locks at 4 periods, whose orbit repeats after 8 too" in str(back)


@pytest.mark.slow
def test_mypy_reads_the_types_of_the_readmes_editable_install(tmp_path):
    """Issue 37: under the README's ``pip install -e . --config-settings
    editable_mode=strict`` mypy finds the package (with a plain ``-e .`` setuptools maps
    it by an import hook that mypy cannot follow: "Cannot find implementation", Any)."""
    import shutil
    import site
    import venv

    pytest.importorskip("mypy", reason="mypy is in the test extra (pyproject.toml)")
    readme = (ROOT / "README.md").read_text()
    assert "pip install -e . --config-settings editable_mode=strict" in readme
    listed = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=ROOT, capture_output=True, check=True,
    ).stdout.decode().split("\0")  # fmt: skip
    source = tmp_path / "source"  # a copy: the strict mode writes build/ beside it
    for rel in filter(None, listed):
        if (ROOT / rel).is_file():
            (source / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / rel, source / rel)
    venv.create(tmp_path / "env", with_pip=False)
    python = tmp_path / "env" / "bin" / "python"
    env_site = Path(
        subprocess.run(
            [python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"],
            capture_output=True, text=True, check=True,
        ).stdout.strip()
    )  # fmt: skip
    # this environment's dependencies as plain paths (its .pth files stay unread)
    (env_site / "dependencies.pth").write_text("\n".join(site.getsitepackages()) + "\n")
    install = subprocess.run(
        [sys.executable, "-m", "pip", "--python", python, "install", "-q", "--no-deps", "-e",
         source, "--config-settings", "editable_mode=strict"],
        capture_output=True, text=True,
    )  # fmt: skip
    if install.returncode and "setuptools" in install.stderr:
        pytest.skip("pip cannot fetch setuptools to build the install (no package index)")
    assert install.returncode == 0, install.stderr
    script = tmp_path / "study.py"
    script.write_text("import beltmdsm\nreveal_type(beltmdsm.floquet(beltmdsm.Model()))\n")
    done = subprocess.run(
        [python, "-m", "mypy", "--no-incremental", "--cache-dir=/dev/null", str(script)],
        capture_output=True, text=True, cwd=tmp_path, timeout=300,
        env={k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MYPYPATH")},
    )  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    assert 'Revealed type is "beltmdsm.periodic.floquet.Floquet"' in done.stdout


def test_every_analysis_that_takes_a_model_is_a_top_level_name_with_its_docs_entry():
    """``beltmdsm.model.ANALYSES`` names ``beltmdsm.<name>``: each is one (issue 39;
    ``basin_stability`` was listed there but reachable only as
    ``beltmdsm.basin.basin_stability.basin_stability``), and the reference's API page,
    written from ``__all__`` by docs/_ext/beltmdsm_site.py, has its entry."""
    import importlib.util

    from beltmdsm.basin import basin_stability as home
    from beltmdsm.model import ANALYSES

    missing = [name for name in ANALYSES if name not in beltmdsm.__all__]
    assert missing == []
    assert beltmdsm.basin_stability is home.basin_stability
    assert beltmdsm.BasinStability is home.BasinStability
    with pytest.raises(TypeError, match="did you mean 'samples'"):
        beltmdsm.basin_stability(beltmdsm.Model(), samlpes=3)
    spec = importlib.util.spec_from_file_location(
        "beltmdsm_site", ROOT / "docs" / "_ext" / "beltmdsm_site.py"
    )
    site = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(site)
    page = site.api_page()
    section = page.split("``beltmdsm.basin.basin_stability``\n")[1].split("\n``")[0]
    assert "   basin_stability\n" in section and "   BasinStability\n" in section
