"""The runtime types no physics: every formula of the model comes from ``generated``.

Issue 12: a runtime module must not define a right-hand side, a force law or a
transfer function of its own. The test reads every ``runtime/*.py`` as a syntax tree
and flags arithmetic (``+ - * / **``) on a coefficient of the equations of motion,
read from a parameter mapping (``p["omega1"]``) or through a local name bound to one
(``w1 = p["omega1"]``). The few places that still do are listed in `ALLOWED` with the
reason; a new one fails here, naming the module, the function and the line.
"""

import ast
from pathlib import Path

RUNTIME = Path(__file__).resolve().parents[1] / "runtime"
#: The coefficients of Eq. (4): damping, stiffness, excitation amplitudes, friction,
#: gravity. The belt speed, the excitation frequencies and phases are kinematics
#: (relative velocity, periods, spectral lines) and may be computed with.
COEFFICIENTS = {"beta1", "omega1", "beta2", "omega2", "alpha", "alpha_t", "alpha_n", "mu_s", "g"}
#: (module, function) -> why it may compute with a coefficient.
ALLOWED = {
    ("predict", "_balance"): "the harmonic balance of the consistent MDSM: the tangential "
    "transfer function, not yet generated (issue 12 closing note)",
    ("predict", "fast_motion"): "the same harmonic balance",
    ("predict", "consistent_mdsm_damping"): "the slow damping 2 beta1 omega1 + mu_s dF/du "
    "of the consistent MDSM, not yet generated (issue 12 closing note)",
    ("simulate", "omega1_band"): "the frequency band where the omega1 peak is read: a "
    "spectral window, not dynamics",
    ("simulate", "_resolution"): "the a-priori decay of the free transient, "
    "exp(-beta1 omega1 t), to decide whether a window can tell the peak",
    ("floquet", "_sliding_guess"): "superposition of generated responses: x = Phi x0 + zf "
    "+ mu_s z (the tangential equation is linear with the friction as a forcing)",
    ("floquet", "_largest_sliding_velocity"): "the same superposition",
    ("superposition", "run"): "the same superposition (mu_s sgn scales the response z)",
    ("modulation", "friction_loop"): "the window of Fig. 3b, one period 2 pi / omega1",
}


def _is_coefficient(node, bound):
    if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Constant):
        return node.slice.value in COEFFICIENTS
    return isinstance(node, ast.Name) and node.id in bound


def _bound_names(function):
    """Local names bound to a coefficient: ``x = p["mu_s"]``, ``a, b = p["g"], p["mu_s"]``."""
    bound = set()
    for node in ast.walk(function):
        if not isinstance(node, ast.Assign):
            continue
        for target in node.targets:
            pairs = [(target, node.value)]
            if isinstance(target, ast.Tuple) and isinstance(node.value, ast.Tuple):
                pairs = list(zip(target.elts, node.value.elts))
            for name, value in pairs:
                if isinstance(name, ast.Name) and _is_coefficient(value, set()):
                    bound.add(name.id)
    return bound


def physics_sites():
    """``(module, function, line)`` of every arithmetic on a coefficient in runtime/."""
    sites = []
    for path in sorted(RUNTIME.glob("*.py")):
        tree = ast.parse(path.read_text())
        for function in ast.walk(tree):
            if not isinstance(function, ast.FunctionDef | ast.AsyncFunctionDef):
                continue
            bound = _bound_names(function)
            for node in ast.walk(function):
                if isinstance(node, ast.BinOp) and (
                    _is_coefficient(node.left, bound) or _is_coefficient(node.right, bound)
                ):
                    sites.append((path.stem, function.name, node.lineno))
    return sites


def test_the_scan_finds_a_right_hand_side_typed_by_hand():
    code = """
def rhs(t, y, p):
    c1, k1 = 2 * p["beta1"] * p["omega1"], p["omega1"] ** 2
    mu = p["mu_s"]
    return -c1 * y[1] - k1 * y[0] - mu * y[2]
"""
    tree = ast.parse(code)
    function = tree.body[0]
    bound = _bound_names(function)
    assert bound == {"mu"}
    flagged = [
        n.lineno
        for n in ast.walk(function)
        if isinstance(n, ast.BinOp)
        and (_is_coefficient(n.left, bound) or _is_coefficient(n.right, bound))
    ]
    assert 3 in flagged and 5 in flagged


def test_runtime_types_no_physics_beyond_the_listed_places():
    new = [
        f"runtime/{m}.py:{line} in {f}()" for m, f, line in physics_sites() if (m, f) not in ALLOWED
    ]
    assert not new, (
        "arithmetic on a coefficient of Eq. (4) in the runtime (use generated/):\n" + "\n".join(new)
    )


def test_every_allowed_place_still_exists():
    # an entry whose code was replaced by generated code is removed from the list
    found = {(m, f) for m, f, _ in physics_sites()}
    assert set(ALLOWED) <= found, sorted(set(ALLOWED) - found)
