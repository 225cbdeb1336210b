"""The ``paper`` model entry against today's generated modules (issue 39 item 3).

The generic derivation of derive/models/ applied to the paper's entry must give the
numbers of today's generated/hybrid.py (vector field per mode, mode Jacobian, surfaces,
saltation) and generated/unforced.py (equilibrium, characteristic coefficients), and
Hurwitz determinants equal to the quartic's, typed here, on random points.

Tolerance: 1e-14 relative to the sum of the absolute values of the compared entries'
scale (both sides evaluate the same expressions in a different order: a few ulps of the
largest term). Stick is compared on its manifold ``Y1 = Vb``: today's stick field holds
``X1' = Vb`` by hand, the derived one keeps ``X1' = Y1`` and ``v_r' = 0``; they agree
there, and their Jacobians agree on the constrained directions (every column but
``Y1``'s, the direction that the saltation into stick removes).
"""

import math

import numpy as np
import pytest

from beltmdsm.generated import hybrid, unforced
from beltmdsm.generated.models import MODELS, load

paper = load("paper")
LAWS = paper.FRICTION_LAWS
NAMES = {"slip_back": -1, "slip_forward": 1, "stick": 0, "flight": 2}
TOL = 1e-14


def _params(rng, law):
    draw = {
        "beta1": rng.uniform(0.01, 0.5),
        "omega1": rng.uniform(0.5, 2.0),
        "beta2": rng.uniform(0.05, 0.5),
        "omega2": rng.uniform(0.2, 1.0),
        "g": rng.uniform(5.0, 15.0),
        "Vb": rng.uniform(0.5, 5.0),
        "alpha_t": rng.uniform(0.0, 3.0),
        "Omega_t": rng.uniform(0.5, 5.0),
        "phase_t": rng.uniform(-math.pi, math.pi),
        "alpha_n": rng.uniform(0.0, 3.0),
        "Omega_n": rng.uniform(0.5, 5.0),
        "phase_n": rng.uniform(-math.pi, math.pi),
        "mu_s": rng.uniform(0.2, 0.6),
        "v_s": rng.uniform(0.5, 2.0),
    }
    draw["mu_k"] = draw["mu_s"] * rng.uniform(0.3, 1.0)
    names = paper.PARAMETERS[law]
    return {n: draw[n] for n in names}, np.array([draw[n] for n in names])


def _points(law, count=8, seed=0):
    rng = np.random.default_rng(seed + LAWS.index(law))
    for _ in range(count):
        kw, p = _params(rng, law)
        t = rng.uniform(0.0, 50.0)
        y = np.array(
            [rng.normal(0, 3), rng.normal(0, 3), rng.uniform(-2.0, 20.0), rng.normal(0, 3)]
        )
        yield t, y, kw, p


def _close(mine, ref, scale=None):
    mine, ref = np.asarray(mine, float), np.asarray(ref, float)
    scale = np.max(np.abs(ref)) if scale is None else scale
    assert np.max(np.abs(mine - ref)) <= TOL * max(scale, 1e-300), (mine, ref)


def test_models_list_paper_first():
    assert MODELS[0] == "paper" and paper.STATES == ("X1", "Y1", "X2", "Y2")
    assert paper.UNILATERAL and paper.ABSENT == {}


@pytest.mark.parametrize("law", LAWS)
def test_fields_and_jacobians_per_mode(law):
    k = paper.kernels(law)
    for t, y, kw, p in _points(law):
        for mode in NAMES.values():
            z = y.copy()
            if mode == 0:
                z[1] = kw["Vb"]  # stick: on its manifold
            ref = hybrid.vector_field(t, *z, mode, friction=law, contact="hertz_damp", **kw)
            _close(k.field(t, z, p, mode), ref)
            J = k.jacobian(t, z, p, mode)
            Jref = hybrid.mode_jacobian(t, *z, mode, friction=law, contact="hertz_damp", **kw)
            cols = [0, 2, 3] if mode == 0 else [0, 1, 2, 3]
            _close(J[:, cols], np.asarray(Jref)[:, cols])


@pytest.mark.parametrize("law", LAWS)
def test_surfaces(law):
    k = paper.kernels(law)
    assert paper.SURFACES == ("slip_velocity", "stick_forward", "stick_back", "gap")
    for t, y, kw, p in _points(law):
        ref = hybrid.surfaces(t, *y, friction=law, contact="hertz_damp", **kw)
        mine = k.surfaces(t, y, p)
        _close(mine[:3], np.array(ref[:3], float))
        assert mine[3] == -y[2] == -float(ref[3])
        assert k.slip_velocity(t, y, p) == mine[0]
        # stick_forward - stick_back = 2 lambda
        _close(2 * k.holding_force(t, y, p), mine[1] - mine[2], abs(mine[1]) + abs(mine[2]))


@pytest.mark.parametrize("law", LAWS)
def test_saltation_every_transition(law):
    k = paper.kernels(law)
    surfaces = {"relative_velocity", "stick_forward", "stick_back", "penetration"}
    transitions = [tr for tr in hybrid.TRANSITIONS if tr[2] in surfaces and "separated" not in tr]
    assert len(transitions) == len(paper.SWITCHES)
    for t, y, kw, p in _points(law, count=4):
        for before, after, surface in transitions:
            b, a = NAMES[before], NAMES[after]
            assert paper.SWITCHES[(b, a)] == {
                "relative_velocity": "slip_velocity",
                "penetration": "gap",
            }.get(surface, surface)
            z = y.copy()
            if 0 in (b, a):
                z[1] = kw["Vb"]
            ref = hybrid.saltation(
                t,
                *z,
                friction=law,
                contact="hertz_damp",
                before=before,
                after=after,
                surface=surface,
                **kw,
            )
            _close(k.saltation(t, z, p, b, a), ref)


@pytest.mark.parametrize("law", LAWS)
def test_equilibrium_characteristic_hurwitz(law):
    k = paper.kernels(law)
    assert paper.EQUILIBRIUM[law] == "closed form"
    for _, _, kw, p in _points(law):
        ref = np.array(unforced.equilibrium(friction=law, contact="hertz_damp", **kw))
        _close(k.equilibrium(p), ref)
        a = k.characteristic(p)
        aref = np.array(unforced.charpoly(friction=law, contact="hertz_damp", **kw))
        assert a[0] == 1.0
        for mine, theirs in zip(a[1:], aref):
            _close(mine, theirs)
        # the quartic's Hurwitz determinants, typed by hand
        a1, a2, a3, a4 = aref
        H2 = a1 * a2 - a3
        H3 = a3 * H2 - a1**2 * a4
        typed = [a1, H2, H3, a4 * H3]
        scales = [abs(a1), abs(a1 * a2) + abs(a3)]
        scales.append(abs(a3) * scales[1] + a1**2 * abs(a4))
        scales.append(abs(a4) * scales[2])
        for mine, theirs, scale in zip(k.hurwitz(p), typed, scales):
            _close(mine, theirs, 4 * scale)


@pytest.mark.parametrize("law", LAWS)
def test_surface_rates(law):
    k = paper.kernels(law)
    for t, y, kw, p in _points(law, count=4):
        for mode in NAMES.values():
            z = y.copy()
            if mode == 0:
                z[1] = kw["Vb"]
            ref = hybrid.surface_rates(t, *z, mode, friction=law, contact="hertz_damp", **kw)
            ref = np.array([*ref[:3], -ref[3]], float)
            mine = k.surface_rates(t, z, p, mode)
            for a, b in zip(mine, ref):
                _close(a, b, np.max(np.abs(ref)))
            assert mine[0] == pytest.approx(k.slip_acceleration(t, z, p, mode), rel=1e-14)


def test_guards_are_todays_under_a_contact_that_pulls():
    """Today's GUARDS of the tension law ``allowed`` (the paper's), in mode codes and with
    the gap (-X2) for the penetration (crossings reversed)."""
    surface = {"relative_velocity": "slip_velocity", "penetration": "gap"}
    target = {**NAMES, hybrid.DECIDE_SLIP: paper.DECIDE_SLIP}
    target[hybrid.DECIDE_CONTACT] = paper.DECIDE_CONTACT
    for before, guards in hybrid.GUARDS["allowed"].items():
        mine = {
            (surface.get(h, h), -sign if h == "penetration" else sign, target[to])
            for h, sign, to in guards
        }
        assert mine == set(paper.GUARDS[NAMES[before]]), before
