"""Every model module the runtime is given holds to the contract's relations, checked
generically by finite differences: the modules typed by hand here, and every module
``beltmdsm.generated.models`` registers (paper, belt_1dof, hoffmann, ...).

At random states near steady sliding: each mode's Jacobian against central differences
of its field; the slip acceleration is the slip gradient times the field; stick holds
the slip velocity (its field has ``v_r' = 0``) and its friction force is the holding
force; steady sliding is a zero of its slip mode's field; the characteristic polynomial
is numpy's of the Jacobian there and the Hurwitz determinants are those of its
coefficients; each saltation matrix, on its switching surface, is
``I + (f+ - f-) n^T / (n^T f- + dh/dt)`` with ``n`` and ``dh/dt`` by central differences
of the surface (v_r; ``|holding_force| - stick_limit``; the gap).
"""

import importlib

import numpy as np
import pytest
import reference_belt_1dof
import reference_paper_kv
import reference_two_dof

from beltmdsm.oscillator import System


def _generated():
    registry = importlib.import_module("beltmdsm.generated.models")
    return [(name, law) for name in registry.MODELS for law in registry.load(name).FRICTION_LAWS]


def test_every_registered_model_is_checked():
    names = {name for name, _ in _generated()}
    assert {"paper", "belt_1dof", "hoffmann"} <= names
    assert names == set(importlib.import_module("beltmdsm.generated.models").MODELS)


CASES = [
    (module, law)
    for module in (reference_belt_1dof, reference_two_dof, reference_paper_kv)
    for law in module.FRICTION_LAWS
] + _generated()


def _system(module, law):
    return System(module, friction=law, **({"Vb": 1.5} if "Vb" in _params(module, law) else {}))


def _params(module, law):
    if isinstance(module, str):
        module = importlib.import_module(f"beltmdsm.generated.models.{module}")
    return module.PARAMETERS[law]


def _fd(fn, x, h=1e-6):
    cols = []
    for e in np.eye(x.size):
        step = h * (1.0 + abs(x @ e))
        cols.append((np.asarray(fn(x + step * e)) - np.asarray(fn(x - step * e))) / (2 * step))
    return np.array(cols).T


def _hurwitz(a):
    """Hurwitz determinants H_1..H_n of 1, a_1..a_n (the Hurwitz matrix's leading minors)."""
    n = len(a) - 1
    M = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            k = 2 * (j + 1) - (i + 1)
            if 0 <= k <= n:
                M[i, j] = a[k]
    return np.array([np.linalg.det(M[:k, :k]) for k in range(1, n + 1)])


def _on_surface(h, y, iterations=30):
    """``y`` moved along the gradient of ``h`` onto ``h = 0`` (Newton)."""
    for _ in range(iterations):
        g = _fd(lambda z: np.array([h(z)]), y)[0]
        y = y - h(y) * g / (g @ g)
    return y


@pytest.mark.parametrize("module, law", CASES, ids=lambda v: getattr(v, "NAME", v))
def test_the_module_holds_to_the_contract(module, law):
    s = _system(module, law)
    k, p = s.kernels, s.p
    m = len(s.states)
    assert m == 2 * len(s.coordinates)
    eq = np.asarray(k.equilibrium(p), dtype=float)
    mode_eq = 1 if k.slip_velocity(0.0, eq, p) > 0 else -1
    assert np.allclose(k.field(0.0, eq, p, mode_eq), 0.0, atol=1e-12)
    J = np.asarray(k.jacobian(0.0, eq, p, mode_eq))
    a = np.asarray(k.characteristic(p))
    assert np.allclose(a, np.poly(J), rtol=1e-10, atol=1e-12)
    assert np.allclose(k.hurwitz(p), _hurwitz(a), rtol=1e-9, atol=1e-12)
    rng = np.random.default_rng(39)
    modes = (-1, 0, 1, 2) if s.unilateral else (-1, 0, 1)
    for _ in range(3):
        t = float(rng.uniform(0, 10))
        y = eq + 0.1 * rng.standard_normal(m) * (1.0 + np.abs(eq))
        w = np.asarray(k.slip_gradient(t, y, p))
        for mode in modes:
            field = lambda z, mode=mode: k.field(t, z, p, mode)  # noqa: E731
            assert np.allclose(k.jacobian(t, y, p, mode), _fd(field, y), rtol=1e-6, atol=1e-7)
            if mode in (-1, 0, 1):
                assert k.slip_acceleration(t, y, p, mode) == pytest.approx(w @ field(y), abs=1e-12)
        stick = y - w * k.slip_velocity(t, y, p) / (w @ w)
        assert w @ k.field(t, stick, p, 0) == pytest.approx(0.0, abs=1e-12)
        assert k.friction_force(t, stick, p, 0) == pytest.approx(k.holding_force(t, stick, p))
        _check_saltation(s, t, y)


def _check_saltation(s, t, y):
    k, p = s.kernels, s.p
    surfaces = {
        "slip": lambda tt, z: k.slip_velocity(tt, z, p),
        "cone": lambda tt, z: abs(k.holding_force(tt, z, p)) - k.stick_limit(tt, z, p),
    }
    pairs = [(-1, 0, "slip"), (1, 0, "slip"), (-1, 1, "slip"), (1, -1, "slip")]
    pairs += [(0, -1 if k.holding_force(t, y, p) > 0 else 1, "cone")]
    if s.unilateral:
        surfaces["gap"] = lambda tt, z: k.gap(tt, z, p)
        pairs += [(-1, 2, "gap"), (2, -1, "gap"), (0, 2, "gap")]
    for before, after, name in pairs:
        h = surfaces[name]
        z = _on_surface(lambda v: h(t, v), y.copy())
        if name == "cone":  # the stick state: on v_r = 0 too
            w = np.asarray(k.slip_gradient(t, z, p))
            z = _on_surface(lambda v: h(t, v), z - w * k.slip_velocity(t, z, p) / (w @ w))
        n = _fd(lambda v: np.array([h(t, v)]), z)[0]
        dt = 1e-6 * (1 + abs(t))
        h_t = (h(t + dt, z) - h(t - dt, z)) / (2 * dt)
        f0, f1 = np.asarray(k.field(t, z, p, before)), np.asarray(k.field(t, z, p, after))
        expected = np.eye(z.size) + np.outer(f1 - f0, n) / (n @ f0 + h_t)
        got = np.asarray(k.saltation(t, z, p, before, after))
        assert np.allclose(got, expected, rtol=1e-5, atol=1e-6), (before, after)


@pytest.mark.parametrize("module, law", CASES, ids=lambda v: getattr(v, "NAME", v))
def test_surface_rates_are_the_surfaces_rates_along_each_field(module, law):
    """``surfaces`` are the runtime's switching functions (``SURFACES``: v_r, the static
    limit plus and minus the holding force, the gap), and ``surface_rates`` their time
    derivatives along each mode's field, explicit time included (both excitations on):
    against the central difference along the field, ``(h(t + d, y + d f) - h(t - d,
    y - d f)) / 2d``, whose error is its truncation, ~|D(d) - D(2d)| / 3, plus the
    rounding of ``h``, ~64 eps of its terms over d."""
    s = _system(module, law)
    names = _params(module, law)
    excite = {n: 0.3 for n in ("alpha_t", "alpha_n") if n in names}
    s = s.replace(**excite, **{n: 1.7 for n in ("Omega_t", "Omega_n") if n in names})
    k, p, mod = s.kernels, s.p, s.module
    at = {name: i for i, name in enumerate(mod.SURFACES)}
    expected = ["slip_velocity", "stick_forward", "stick_back"] + (["gap"] if s.unilateral else [])
    assert list(mod.SURFACES) == expected
    eq = np.asarray(k.equilibrium(p), dtype=float)
    rng = np.random.default_rng(7)
    modes = (-1, 0, 1, 2) if s.unilateral else (-1, 0, 1)
    eps = np.finfo(float).eps
    for _ in range(4):
        t = float(rng.uniform(0, 10))
        y = eq + 0.1 * rng.standard_normal(eq.size) * (1.0 + np.abs(eq))
        h = np.asarray(k.surfaces(t, y, p), dtype=float)
        L, H = k.stick_limit(t, y, p), k.holding_force(t, y, p)
        terms = 1.0 + abs(L) + abs(H) + np.abs(y).max()
        assert h[at["slip_velocity"]] == pytest.approx(
            k.slip_velocity(t, y, p), abs=8 * eps * terms
        )
        assert h[at["stick_forward"]] == pytest.approx(L + H, abs=8 * eps * terms)
        assert h[at["stick_back"]] == pytest.approx(L - H, abs=8 * eps * terms)
        if s.unilateral:
            assert h[at["gap"]] == k.gap(t, y, p)
        for mode in modes:
            f = np.asarray(k.field(t, y, p, mode), dtype=float)
            d = 1e-5

            def quotient(d, f=f):
                up = np.asarray(k.surfaces(t + d, y + d * f, p), dtype=float)
                down = np.asarray(k.surfaces(t - d, y - d * f, p), dtype=float)
                return (up - down) / (2 * d)

            D1, D2 = quotient(d), quotient(2 * d)
            tol = np.abs(D1 - D2) + 64 * eps * terms * (1 + np.abs(f).max()) / d
            got = np.asarray(k.surface_rates(t, y, p, mode), dtype=float)
            assert np.all(np.abs(got - D1) <= tol), (mode, got, D1, tol)
            # the slip guard's rate is the contract's slip acceleration
            if mode != 2:
                a = k.slip_acceleration(t, y, p, mode)
                assert got[at["slip_velocity"]] == pytest.approx(a, rel=1e-12, abs=1e-12)
