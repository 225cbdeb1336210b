"""No module shared by every model names the paper's states or assumes four of them
(issue 39 item 4): state names, sizes and labels come from the model
(`beltmdsm.state_names`, its generated module's ``STATES`` and ``COORDINATES``).

The scan parses each module of beltmdsm/ (ast): the code's string constants (f-strings'
parts included; docstrings and comments are not code) that name a paper state (``X1``,
``Y1``, ``X2``, ``Y2``, ``X1'``), and the literal state count 4 where it sizes or indexes
a state (``np.eye(4)``, ``reshape(4, 4)``, ``range(4)``, ``y[:4]``, ``y[4]``, a shape
``(4,)``, ``x.size == 4``). The modules allowed them are listed once, in `PAPER_ENGINE`,
each with its reason. Then the shared functions are checked on ``belt_1dof`` (states
``x, x_dot``) and ``hoffmann`` (``x, y, x_dot, y_dot``): their tables' columns, their
figures' labels and their JSON's state keys are the model's.
"""

import ast
import re
from pathlib import Path

import numpy as np
import pytest

from beltmdsm import Model, plotting, simulate, state_names
from beltmdsm._tables import STATE_COLUMNS
from beltmdsm.generated.models import load

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "beltmdsm"

#: The modules (a file, or a folder ending in "/") that may name the paper's states and
#: size arrays by its four: the paper model's own engine, which runs the paper's model
#: only (another model runs on beltmdsm/oscillator/, issue 39), with why.
PAPER_ENGINE = {
    "integrate/": "the paper's hybrid integrator (superposition, Hertz-Damp contact, its "
    "generated kernels of four states)",
    "periodic/": "the paper's periodic orbits, shooting and Floquet stability on its "
    "generated functions (another model: beltmdsm/oscillator/forced.py, cycles.py)",
    "prediction/": "the paper's linear predictions (Routh-Hurwitz of its four states)",
    "paper_reports/": "the paper's reports (its figures, its validation)",
    "attractors/lyapunov.py": "the paper's Lyapunov spectrum on its integrator (another "
    "model: beltmdsm/oscillator/lyapunov.py)",
    "attractors/self_excited.py": "the paper's self-excited attractors: its generated "
    "vector field of four arguments (another model: beltmdsm/oscillator/cycles.py)",
    "cycles/continuation.py": "the paper's cycle continuation: the paper's shooting "
    "unknowns (state, period) (another model: beltmdsm/oscillator/hopf_branch.py)",
    "cycles/hopf.py": "the paper's Hopf points: its generated eigenvalues and Jacobian "
    "(another model: beltmdsm/oscillator/equilibria.py)",
    "cycles/multiple.py": "the paper's multiple shooting on its integrator",
    "starts/cycle_seed.py": "the paper's seed of a self-excited cycle: its generated "
    "Jacobian (another model: beltmdsm/oscillator/cycles.py)",
}
#: The modules of the generic runtime (not branches.py, which dispatches to either): what
#: they import of the engine's folders is shared by every model and scanned
#: (`_generic_imports`).
GENERIC = ("oscillator/", "continuation/oscillator_", "cli/generic")
#: Literal fours that size no state, by module.
NOT_STATES = {
    "integrate/_background.py": "np.zeros((4,) * ndim): a strided stand-in array that "
    "numba types a compiled function's argument by",
}
#: A paper state's name in a string: X1, Y1, X2, Y2 (X1' included), not X10 or aX1.
NAME = re.compile(r"(?<![A-Za-z0-9_])(X1|X2|Y1|Y2)(?![0-9])")
#: The calls whose literal 4 sizes an array or a loop over the states.
SIZING = {"eye", "identity", "zeros", "empty", "ones", "full", "reshape", "range"}


def _rel(path):
    return path.relative_to(PACKAGE).as_posix()


def _generic_imports():
    """The modules of beltmdsm/ that the generic runtime (`GENERIC`) imports."""
    out = set()
    for path in PACKAGE.rglob("*.py"):
        if not _rel(path).startswith(GENERIC):
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level and node.module:
                base = path.parent
                for _ in range(node.level - 1):
                    base = base.parent
                target = base.joinpath(*node.module.split("."))
                for name in node.names:  # a submodule imported by name, or the module
                    for candidate in (target / f"{name.name}.py", target.with_suffix(".py")):
                        if candidate.is_file():
                            out.add(_rel(candidate))
                            break
    return out


SHARED_IN_ENGINE = _generic_imports()


def _allowed(path):
    rel = _rel(path)
    if rel in SHARED_IN_ENGINE and rel not in PAPER_ENGINE:
        return False
    return any(rel == a or (a.endswith("/") and rel.startswith(a)) for a in PAPER_ENGINE)


def _docstrings(tree):
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                out.add(id(body[0].value))
    return out


def _is_four(node):
    return isinstance(node, ast.Constant) and type(node.value) is int and node.value == 4


def _fours(node):
    """The literal 4s of an index, a slice or a shape (not through a sign: ``[-4:]`` counts
    back, it is no state)."""
    if _is_four(node):
        return [node]
    if isinstance(node, ast.Slice):
        return [n for part in (node.lower, node.upper) if part for n in _fours(part)]
    if isinstance(node, ast.Tuple):
        return [n for e in node.elts for n in _fours(e)]
    if isinstance(node, ast.BinOp):  # 4 * m, 4 * i + 4: blocks of four states
        return _fours(node.left) + _fours(node.right)
    return []


def findings(path):
    """``[(line, what)]``: the paper's state names and four-state sizes in ``path``'s code."""
    tree = ast.parse(path.read_text())
    docs = _docstrings(tree)
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
            if NAME.search(node.value):
                out.append((node.lineno, f"names a paper state: {node.value[:60]!r}"))
        elif isinstance(node, ast.Subscript):
            out += [(n.lineno, "indexes four states") for n in _fours(node.slice)]
        elif isinstance(node, ast.Call):
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
            args = [*node.args, *(k.value for k in node.keywords if k.arg == "shape")]
            if name in SIZING:
                out += [(n.lineno, f"sizes four states ({name})") for a in args for n in _fours(a)]
        elif isinstance(node, ast.Compare) and isinstance(node.ops[0], (ast.Eq, ast.NotEq)):
            sides = [node.left, *node.comparators]
            sized = any(isinstance(s, ast.Attribute) and s.attr in ("size", "shape") for s in sides)
            if sized and any(_fours(s) for s in sides):
                out.append((node.lineno, "compares a size with four states"))
    return out


def _shared():
    return [p for p in sorted(PACKAGE.rglob("*.py")) if not _allowed(p)]


def _engine():
    return [p for p in sorted(PACKAGE.rglob("*.py")) if _allowed(p) and "oscillator" not in p.parts]


def test_the_allowed_modules_exist():
    """Each entry of `PAPER_ENGINE` names a module or a folder of beltmdsm/ (a moved module
    leaves no stale permission)."""
    for entry in PAPER_ENGINE:
        assert (PACKAGE / entry).exists(), entry


def test_the_generic_runtime_uses_shared_modules_of_the_engines_folders():
    """What beltmdsm/oscillator/ imports of integrate/ and periodic/ (the root finders, the
    compile cache, Newton's method, the Zeno bounds) is scanned as shared, not allowed."""
    assert {"integrate/_roots.py", "periodic/newton.py"} <= SHARED_IN_ENGINE
    assert not _allowed(PACKAGE / "periodic" / "newton.py")
    assert _allowed(PACKAGE / "periodic" / "cycle.py")


@pytest.mark.parametrize("path", _engine(), ids=lambda p: p.relative_to(PACKAGE).as_posix())
def test_a_module_of_the_engine_says_it_is_the_papers(path):
    """Each module allowed the paper's states says, first thing a reader sees, that it is
    the paper model's engine and where another model runs."""
    doc = ast.get_docstring(ast.parse(path.read_text())) or ""
    assert "the paper model's engine" in " ".join(doc.split()), path


def test_the_scan_finds_what_it_looks_for(tmp_path):
    """The scan reports each kind it looks for, and not a docstring, ``[-4:]`` or ``tol / 4``."""
    path = tmp_path / "m.py"
    path.write_text(
        '"""X1 and X2 in a docstring."""\n'
        "import numpy as np\n"
        "A = {'X1': 0}\n"
        "B = f'{3} of X2'\n"
        "def f(y, tol):\n"
        "    '''Y1 in a docstring.'''\n"
        "    J = np.eye(4)\n"
        "    z = np.zeros((n, 4))\n"
        "    w = y[:4] + y[4] + y[-4:] + y[4 * m]\n"
        "    for k in range(4):\n"
        "        pass\n"
        "    return y.size == 4, tol / 4, len(y) < 4\n"
    )
    lines = [line for line, _ in findings(path)]
    assert sorted(lines) == [3, 4, 7, 8, 9, 9, 9, 10, 12]


@pytest.mark.parametrize("path", _shared(), ids=lambda p: p.relative_to(PACKAGE).as_posix())
def test_a_shared_module_takes_its_states_from_the_model(path):
    """A module outside `PAPER_ENGINE` names no paper state in its code and sizes nothing
    by four states: it reads them from the model (`beltmdsm.state_names`)."""
    found = findings(path)
    if _rel(path) in NOT_STATES:
        found = [(line, what) for line, what in found if "four states" not in what]
    assert not found, "\n".join(f"{path.name}:{line}: {what}" for line, what in found)


# ---- the shared functions name another model's states (issue 39 item 4)


def test_the_columns_are_the_models_and_the_papers_are_kept():
    """belt_1dof's and hoffmann's columns are their STATES (rates ``<q>_dot``); the
    paper's keep their names in its tables and figures (X1' for its rate Y1, a contract),
    derived from its STATES and COORDINATES."""
    assert state_names.columns("belt_1dof") == load("belt_1dof").STATES == ("x", "x_dot")
    assert state_names.columns("hoffmann") == load("hoffmann").STATES
    assert state_names.units("hoffmann") == ("m", "m", "m/s", "m/s")
    assert STATE_COLUMNS == state_names.columns() == ("X1", "X1'", "X2", "X2'")
    assert plotting.STATE == {"X1": ("m", 0), "X1'": ("m/s", 1), "X2": ("m", 2), "X2'": ("m/s", 3)}
    assert state_names.rate_column("hoffmann", 1) == "y_dot"
    assert state_names.plane("hoffmann") == ("x", "x_dot")
    with pytest.raises(ValueError, match="not a state of model 'belt_1dof' \\(x, x_dot\\)"):
        state_names.index("belt_1dof", "Y1")


@pytest.fixture(scope="module")
def runs():
    """A short run of each of the two other models (the generic runtime's trajectory)."""
    import matplotlib

    matplotlib.use("Agg")
    return {name: simulate(Model(model=name), t_end=2.0) for name in ("belt_1dof", "hoffmann")}


@pytest.mark.parametrize(
    ("name", "variable", "label", "row"),
    [
        ("belt_1dof", None, "x_dot [m/s]", 1),  # the default: the first coordinate's rate
        ("belt_1dof", "x", "x [m]", 0),
        ("hoffmann", None, "x_dot [m/s]", 2),
        ("hoffmann", "y_dot", "y_dot [m/s]", 3),
        ("hoffmann", "y", "y [m]", 1),
    ],
)
def test_a_run_of_another_model_is_drawn_with_its_states(runs, name, variable, label, row):
    """`beltmdsm.plotting.simulation` of another model's run: the axis is named by the
    model's state and its unit, and the line is that row of the run."""
    run = runs[name]
    ax = plotting.simulation(run, variable=variable)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("t [s]", label)
    assert np.array_equal(ax.lines[0].get_ydata(), run.y[row])
    assert np.array_equal(ax.lines[0].get_xdata(), run.t)


def test_a_paper_state_is_no_state_of_another_model(runs):
    """The paper's names are refused on another model's run, the model's states listed;
    the friction loop needs a run that holds the friction force (the paper's)."""
    with pytest.raises(ValueError, match='one of x, y, x_dot, y_dot; got "X1\'"'):
        plotting.simulation(runs["hoffmann"], variable="X1'")
    with pytest.raises(ValueError, match="kind='friction' needs a run"):
        plotting.simulation(runs["belt_1dof"], kind="friction")


def test_an_observable_of_another_model_is_labelled_with_its_state():
    """A branch's observable ``<state>_amplitude`` of another model names the state and
    its unit; the paper's keep theirs."""
    assert plotting.observable_label("x_dot_amplitude", "belt_1dof") == "x_dot amplitude [m/s]"
    assert plotting.observable_label("y_min", "hoffmann") == "y min [m]"
    assert plotting.observable_label("X1'_amplitude", "hoffmann") == "X1'_amplitude (recorded)"
    assert plotting.observable_label("X1'_amplitude") == "X1' amplitude [m/s]"
    assert plotting.observable_label("X1_max", Model()) == "X1 max [m]"


def test_a_basin_map_of_another_model_is_labelled_with_its_states():
    """`beltmdsm.plotting.basins` of another model's basin map: its axes are the model's
    states with their units, each attractor drawn at its state on them (the bistable
    Stribeck belt at Vb = 2.5: steady sliding and the stick-slip cycle,
    tests/beltmdsm/cli/test_model_studies_commands.py); on hoffmann's plane (y, y_dot)."""
    from beltmdsm import basins

    model = Model(model="belt_1dof", friction="stribeck", Vb=2.5)
    b = basins(model, points=2, x_lo=1.5, x_hi=3.5, y_lo=-3.0, y_hi=0.5, t_end=600.0)
    ax = plotting.basins(b)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [m]", "x_dot [m/s]")
    assert [a.kind for a in b.attractors] == ["steady_sliding", "stick_slip"]
    drawn = [(line.get_xdata()[0], line.get_ydata()[0]) for line in ax.lines]
    assert drawn == [a.state for a in b.attractors]
    b = basins(
        Model(model="hoffmann"), x="y", y="y_dot", points=2, x_lo=-0.1, x_hi=0.1, y_lo=-0.1,
        y_hi=0.1, t_end=5.0,
    )  # fmt: skip
    ax = plotting.basins(b)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("y [m]", "y_dot [m/s]")
