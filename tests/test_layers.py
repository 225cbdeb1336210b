"""The import graph of beltmdsm/ and of derive/ and generated/ (the packages
beltmdsm.derive and beltmdsm.generated): no cycle, one direction of layers.

Every ``import`` and ``from ... import`` counts, at module level or inside a function
(a function-local import hides a cycle from Python, not from this test), as an edge to
the package module it names (a name imported from a package is an edge to its
submodule where one exists). The layers, lowest first:

beltmdsm.derive -> beltmdsm.errors -> beltmdsm.generated -> beltmdsm.{model, settings,
intervals} ->
beltmdsm.integrate ->
beltmdsm.{periodic, oscillator} -> beltmdsm.continuation (then beltmdsm.oscillator.hopf_branch,
which drives it) -> beltmdsm.cycles ->
beltmdsm.branches -> beltmdsm.run -> beltmdsm.prediction -> beltmdsm.attractors ->
beltmdsm.simulation -> beltmdsm.starts (but beltmdsm.starts.cycle_seed, at beltmdsm.periodic's
layer) -> beltmdsm.multistability -> beltmdsm.batch ->
beltmdsm.basin -> beltmdsm.paper_reports -> beltmdsm.studies (old paths) -> beltmdsm.cli

A module imports only modules of its own layer or below, with no cycle: derive/ imports
no other beltmdsm module, generated/ none but beltmdsm.errors (the root failures, which
import nothing) (``python -m derive`` runs ``python -m
beltmdsm`` as a program, derive/__main__.py); generated/ imports nothing of derive/ (it
must run where only it is installed); beltmdsm imports derive only in its command line,
which alone builds the argparse tree (derive/ imports no argparse).
"""

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: Each package's folder in a source checkout (beltmdsm/_layout.py).
PACKAGES = {"beltmdsm.derive": "derive", "beltmdsm.generated": "generated", "beltmdsm": "beltmdsm"}
#: Layer of each module, by the longest prefix that names it.
LAYERS = {
    "beltmdsm.derive": 0,
    # the failures (issue 38): standard library only, so that the generated modules
    # raise the runtime's own `Unsupported` (one class, one hierarchy)
    "beltmdsm.errors": 0.5,
    "beltmdsm.generated": 1,
    # the templates of generated/'s support modules, copied there by derive/codegen/render.py
    # (never imported by derive/): generated/'s layer
    "beltmdsm.derive.codegen.templates": 1,
    "beltmdsm": 2,  # the package: its public names are imported lazily (importlib)
    "beltmdsm.model": 2,
    "beltmdsm.excitation": 2,
    "beltmdsm.settings": 2,
    "beltmdsm.intervals": 2,
    "beltmdsm.integrate": 3,
    # periodic orbits, then their continuation (one driver, docs/explanation/layout.md),
    # then the self-excited cycles, a problem of that driver (issue 38)
    "beltmdsm.periodic": 4.0,
    # the starting states are one package (issue 38) whose modules sit at their own
    # layers: a self-excited cycle's seed here, since beltmdsm.periodic.cycle shoots from
    # it; the forced starts (they run simulate) at beltmdsm.starts below
    "beltmdsm.starts.cycle_seed": 4.0,
    # any derived model (issue 39): its runs, cycles and forced responses, beside them
    "beltmdsm.oscillator": 4.0,
    "beltmdsm.continuation": 4.1,
    # the cycles born at a Hopf point of any model, walked on the one driver (issue 39)
    "beltmdsm.oscillator.hopf_branch": 4.15,
    "beltmdsm.cycles": 4.2,
    # the branch of any model: picks the problem above every problem (issue 38)
    "beltmdsm.branches": 4.25,
    "beltmdsm.run": 4.3,
    "beltmdsm.prediction": 4.4,
    "beltmdsm.attractors": 4.5,
    "beltmdsm.simulation": 5,
    # issue 38: studies/ cut by role. Where runs and searches start (they run simulate);
    # the responses at a point and their coexistence; the batch engine (its rows start
    # runs at the periodic start); basins (on the batch engine's cache and pool); the
    # paper's reports (on all of them); the old paths, thin re-exports
    "beltmdsm.starts": 5.1,
    "beltmdsm.multistability": 5.2,
    "beltmdsm.batch": 5.3,
    "beltmdsm.basin": 5.4,
    "beltmdsm.paper_reports": 6,
    "beltmdsm.studies": 6.5,
    "beltmdsm.cli": 7,
    "beltmdsm.__main__": 7,
}


def modules():
    """``{module name: path}`` of every module of the packages."""
    out = {}
    for package, folder in PACKAGES.items():
        for path in sorted((ROOT / folder).rglob("*.py")):
            parts = path.relative_to(ROOT / folder).with_suffix("").parts
            out[".".join((package, *parts)).removesuffix(".__init__")] = path
    return out


def _resolve(name, known):
    """The longest prefix of ``name`` that is a known module (None if none is)."""
    while name and name not in known:
        name = name.rpartition(".")[0]
    return name or None


def edges(known=None):
    """``{(importer, imported)}`` over all imports, function-local ones included."""
    known = known or modules()
    out = set()
    for module, path in known.items():
        package = module if path.name == "__init__.py" else module.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    parts = package.split(".")
                    base = ".".join(parts[: len(parts) - node.level + 1])
                    source = f"{base}.{node.module}" if node.module else base
                else:
                    source = node.module or ""
                # a name that is a submodule is an edge to it, else to the source
                targets = [
                    f"{source}.{a.name}" if f"{source}.{a.name}" in known else source
                    for a in node.names
                ]
            else:
                continue
            for target in targets:
                resolved = _resolve(target, known)
                if resolved and resolved != module:
                    out.add((module, resolved))
    return out


def _package(module):
    """The package of ``module``: beltmdsm.derive, beltmdsm.generated or beltmdsm."""
    return next(p for p in PACKAGES if module == p or module.startswith(p + "."))


def layer(module):
    return LAYERS[_resolve(module, LAYERS)]


def cycles(graph):
    """The strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]
    nodes = sorted({a for a, _ in graph} | {b for _, b in graph})
    succ = {n: sorted(b for a, b in graph if a == n) for n in nodes}

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in succ[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in nodes:
        if v not in index:
            visit(v)
    return found


def violations(graph):
    """Edges against the layer order, and the cross-package edges the rules forbid."""
    bad = []
    for a, b in sorted(graph):
        top_a, top_b = _package(a), _package(b)
        if layer(b) > layer(a):
            bad.append(f"{a} -> {b}: imports a higher layer")
        elif top_a == "beltmdsm.generated" and top_b == "beltmdsm.derive":
            bad.append(f"{a} -> {b}: generated/ must run without derive/")
        elif (
            top_a == "beltmdsm" and top_b == "beltmdsm.derive" and not a.startswith("beltmdsm.cli")
        ):
            bad.append(f"{a} -> {b}: only the command line imports derive/")
    return bad


def test_the_graph_is_read_with_function_local_imports(tmp_path):
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "__init__.py").write_text("")
    (tmp_path / "pkg" / "a.py").write_text("def f():\n    from . import b\n")
    (tmp_path / "pkg" / "b.py").write_text("from .a import f\n")
    known = {
        "pkg": tmp_path / "pkg" / "__init__.py",
        "pkg.a": tmp_path / "pkg" / "a.py",
        "pkg.b": tmp_path / "pkg" / "b.py",
    }
    graph = edges(known)
    assert graph == {("pkg.a", "pkg.b"), ("pkg.b", "pkg.a")}
    assert cycles(graph) == [["pkg.a", "pkg.b"]]


def test_a_layer_violation_is_found():
    assert violations({("beltmdsm.periodic.floquet", "beltmdsm.cli.flags")}) == [
        "beltmdsm.periodic.floquet -> beltmdsm.cli.flags: imports a higher layer"
    ]
    assert violations({("beltmdsm.derive.paper_check", "beltmdsm.simulation")})
    assert violations({("beltmdsm.simulation", "beltmdsm.derive.model")})
    assert not violations({("beltmdsm.cli.tree", "beltmdsm.derive.commands")})
    assert violations({("beltmdsm.derive.__main__", "beltmdsm.cli")})
    assert violations({("beltmdsm.generated.stability", "beltmdsm.derive.model")})


def test_every_module_has_a_layer():
    unplaced = [m for m in modules() if _resolve(m, LAYERS) is None]
    assert not unplaced, unplaced


@pytest.fixture(scope="module")
def graph():
    return edges()


def test_no_import_cycle(graph):
    assert not cycles(graph), cycles(graph)


def test_periodic_continuation_and_cycles_are_three_layers(graph):
    """periodic -> continuation -> cycles, no arrow back up (issue 38); the entry that
    picks the problem for a model (beltmdsm/branches.py) sits above all three."""
    order = ["beltmdsm.periodic", "beltmdsm.continuation", "beltmdsm.cycles", "beltmdsm.branches"]
    assert [layer(m) for m in order] == sorted({layer(m) for m in order})
    rank = {m: i for i, m in enumerate(order)}
    top = {a: next((m for m in order if a == m or a.startswith(m + ".")), None) for a, _ in graph}
    up = [
        (a, b)
        for a, b in graph
        for ta, tb in [(top[a], next((m for m in order if b == m or b.startswith(m + ".")), None))]
        if ta and tb and rank[tb] > rank[ta]
    ]
    assert not up, sorted(up)
    assert ("beltmdsm.continuation.problem", "beltmdsm.continuation.corrector") in graph


def test_imports_follow_the_layers(graph):
    bad = violations(graph)
    assert not bad, "\n".join(bad)


def test_derive_builds_no_command_line():
    """One owner of the argparse tree (beltmdsm/cli/tree.py): derive/ imports no argparse,
    and reaches the runtime only as a program (``python -m derive``)."""
    imported = set()
    for module, path in modules().items():
        if _package(module) != "beltmdsm.derive" or layer(module) != 0:
            continue  # the templates of generated/ (layer 1) are copied, not run by derive/
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                imported |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and not node.level:
                imported.add((node.module or "").split(".")[0])
    assert "argparse" not in imported and "beltmdsm" not in imported


@pytest.mark.parametrize(
    "old, new", [("generated", "beltmdsm.generated"), ("derive", "beltmdsm.derive")]
)
def test_an_old_top_level_name_refuses_in_one_line(old, new):
    """From the checkout's root (first on ``sys.path``) the folder would import under
    its old name too, a second copy of every module (and of the law registry): it
    refuses, naming the one name."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run(
        [sys.executable, "-c", f"import {old}"], cwd=ROOT, env=env, capture_output=True, text=True
    )
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith(f"ImportError: {old}/ is the package {new}: import it by that name")
    both = f"import {new}, sys; print(sorted(m for m in sys.modules if m.startswith('{old}')))"
    done = subprocess.run(
        [sys.executable, "-c", both], cwd=ROOT, env=env, capture_output=True, text=True
    )
    assert done.returncode == 0 and done.stdout.strip() == "[]", done.stderr
