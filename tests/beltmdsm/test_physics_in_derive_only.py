"""The runtime types no physics: every formula of the model comes from ``beltmdsm.generated``.

A module of beltmdsm/ must not define a right-hand side, a force law or a transfer
function of its own. The test reads every ``beltmdsm/**/*.py`` as a syntax tree and
flags each line with arithmetic (``+ - * / **``) on a coefficient of the equations of
motion: read from a mapping (``p["omega1"]``, ``model["mu_s"]``,
``self.model.params["g"]``), or through a name bound to one, by an assignment
(``w1 = p["omega1"]``, ``self.mu = p["mu_s"]``, tuple unpacking) or a ``for`` loop
over values that hold one. The lines that still do are listed in `ALLOWED` by their
text, each with the reason; a new or changed line fails here, naming the file, the
function and the line.
"""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "beltmdsm"
#: The coefficients of Eq. (4): damping, stiffness, excitation amplitudes, friction,
#: gravity. The belt speed, the excitation frequencies and phases are kinematics
#: (relative velocity, periods, spectral lines) and may be computed with.
COEFFICIENTS = {"beta1", "omega1", "beta2", "omega2", "alpha", "alpha_t", "alpha_n", "mu_s", "g"}

#: (file, function, line text) -> why it may compute with a coefficient.
ALLOWED = {
    (
        "run/summary.py",
        "omega1_band",
        "half = 0.25 * w1",
    ): "the frequency band where the omega1 peak is read: a spectral window, not dynamics",
    (
        "run/summary.py",
        "omega1_band",
        "half = min(half, 0.5 * abs(w1 - line))",
    ): "the same window, kept clear of the excitation lines",
    (
        "run/summary.py",
        "omega1_band",
        "return (w1 - half, w1 + half) if half > 0 else None",
    ): "the same window",
    (
        "run/modulation.py",
        "friction_loop",
        'period = 2 * np.pi / sim.params["omega1"] if period is None else float(period)',
    ): "the window of Fig. 3b, one period 2 pi / omega1",
    (
        "run/modulation.py",
        "modulation_scatter",
        'mu = cycle_averages(sim, 2 * np.pi / omega)["mu_eff"]',
    ): "the averaging periods of Figs. 10-12, 2 pi / Omega_t and 2 pi / omega1",
}


def _reads_coefficient(node, bound):
    """Whether ``node`` reads a coefficient: a subscript by its name, or a bound name
    or attribute (``w1``, ``self.mu``)."""
    if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Constant):
        return node.slice.value in COEFFICIENTS
    if isinstance(node, ast.Name):
        return node.id in bound
    if isinstance(node, ast.Attribute):
        return ast.unparse(node) in bound
    return False


def _holds_coefficient(node, bound):
    return any(_reads_coefficient(n, bound) for n in ast.walk(node))


def _targets(target):
    """The names (and attributes, as text) an assignment or a ``for`` binds."""
    if isinstance(target, ast.Tuple | ast.List):
        return [name for elt in target.elts for name in _targets(elt)]
    if isinstance(target, ast.Name):
        return [target.id]
    if isinstance(target, ast.Attribute):
        return [ast.unparse(target)]
    return []


def _bound_names(tree):
    """Names bound to a coefficient, to a fixed point: ``x = p["mu_s"]``, ``a, b = p["g"],
    p["mu_s"]`` (element by element), ``self.mu = p["mu_s"]``, ``mu = self.mu``, ``for x
    in (p["g"], ...)`` (every name the loop binds, when its iterable holds one)."""
    bound = set()
    while True:
        before = len(bound)
        for node in ast.walk(tree):
            if isinstance(node, ast.Assign):
                for target in node.targets:
                    if isinstance(target, ast.Tuple) and isinstance(node.value, ast.Tuple):
                        for t, v in zip(target.elts, node.value.elts):
                            if _holds_coefficient(v, bound):
                                bound.update(_targets(t))
                    elif _reads_coefficient(node.value, bound):
                        bound.update(_targets(target))
            elif isinstance(node, ast.For | ast.comprehension):
                if _holds_coefficient(node.iter, bound):
                    bound.update(_targets(node.target))
        if len(bound) == before:
            return bound


def _functions(tree):
    """``(function, node)`` for every node inside a function, innermost function named."""
    out = []

    def visit(node, name):
        for child in ast.iter_child_nodes(node):
            inner = (
                child.name if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef) else name
            )
            out.append((inner, child))
            visit(child, inner)

    visit(tree, "<module>")
    return out


def physics_sites(root=PACKAGE):
    """``{(file, function, line text): line number}`` of every line with arithmetic on a
    coefficient of Eq. (4) under ``root``."""
    sites = {}
    for path in sorted(root.rglob("*.py")):
        source = path.read_text()
        lines = source.splitlines()
        tree = ast.parse(source)
        bound = _bound_names(tree)
        for function, node in _functions(tree):
            if isinstance(node, ast.BinOp) and (
                _reads_coefficient(node.left, bound) or _reads_coefficient(node.right, bound)
            ):
                text = lines[node.lineno - 1].strip()
                sites[(path.relative_to(root).as_posix(), function, text)] = node.lineno
    return sites


def test_the_scan_finds_a_right_hand_side_typed_by_hand(tmp_path):
    (tmp_path / "rhs.py").write_text(
        """
class Field:
    def __init__(self, model):
        self.mu = model["mu_s"]

    def rhs(self, t, y, p):
        c1, k1 = 2 * p["beta1"] * p["omega1"], p["omega1"] ** 2
        mu = self.mu
        out = -c1 * y[1] - k1 * y[0] - mu * y[2]
        for gravity in (p["g"],):
            out += gravity * 0.5
        return out
"""
    )
    found = {(f, text): line for (_, f, text), line in physics_sites(tmp_path).items()}
    assert found[("rhs", 'c1, k1 = 2 * p["beta1"] * p["omega1"], p["omega1"] ** 2')] == 7
    assert found[("rhs", "out = -c1 * y[1] - k1 * y[0] - mu * y[2]")] == 9  # via self.mu
    assert found[("rhs", "out += gravity * 0.5")] == 11  # via the for loop
    assert len(found) == 3


def test_the_runtime_types_no_physics_beyond_the_listed_lines():
    new = [
        f"beltmdsm/{path}:{line} in {function}(): {text}"
        for (path, function, text), line in physics_sites().items()
        if (path, function, text) not in ALLOWED
    ]
    assert not new, (
        "arithmetic on a coefficient of Eq. (4) in the runtime (use generated/):\n" + "\n".join(new)
    )


def test_every_allowed_line_still_exists():
    # a line replaced by generated code is removed from the list
    gone = set(ALLOWED) - set(physics_sites())
    assert not gone, sorted(gone)
