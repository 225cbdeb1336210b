"""The normal motion's compiled integrator is one per contact law, not per friction law.

The normal motion (beltmdsm/integrate/normal.py) watches the normal surfaces alone, so it
binds the surface kernels of one friction law (`NORMAL_FRICTION`): numba then compiles
its integrator once per contact law (about 12 s each with a cold cache) where it compiled
it once per friction and contact law. These tests check the fact that makes this exact
(the normal rows of every friction law's kernels are the same numbers, bit for bit), that
the motion is the same bit for bit under every friction law, and that the laws share one
compiled integrator, under a name of its own.
"""

import itertools

import numpy as np
import pytest

from beltmdsm import Model, Unsupported
from beltmdsm.excitation import initial_state
from beltmdsm.generated import hybrid
from beltmdsm.generated.capabilities import CAPABILITIES
from beltmdsm.integrate import _compiled
from beltmdsm.integrate.normal import NORMAL_FRICTION, NormalMotion
from beltmdsm.integrate.switching import SURFACE_INDEX

FRICTIONS = sorted({f for f, _, _ in CAPABILITIES})
CONTACTS = sorted({c for _, c, _ in CAPABILITIES})
NORMAL_ROWS = [SURFACE_INDEX["penetration"], SURFACE_INDEX["contact_force"]]


@pytest.mark.parametrize("contact", CONTACTS)
def test_the_normal_rows_are_the_same_numbers_under_every_friction_law(contact):
    rng = np.random.default_rng(7)
    # states around the contact (penetration of either sign), every mode of the field
    states = rng.normal(0.0, [1.0, 3.0, 0.05, 1.0], size=(200, 4))
    times = rng.uniform(0.0, 20.0, 200)
    for friction in FRICTIONS:
        model = Model(friction=friction, contact=contact)
        ours, ref = (
            [
                bind(backend="python", **{**model.arguments(bind), "friction": law})
                for bind in (hybrid.bind_surfaces, hybrid.bind_surface_rates)
            ]
            for law in (friction, NORMAL_FRICTION)
        )
        for t, y in zip(times, states):
            assert np.array(ours[0](t, *y))[NORMAL_ROWS].tobytes() == (
                np.array(ref[0](t, *y))[NORMAL_ROWS].tobytes()
            )
            for mode in (-1.0, 0.0, 1.0, 2.0, 3.0):
                assert np.array(ours[1](t, *y, mode))[NORMAL_ROWS].tobytes() == (
                    np.array(ref[1](t, *y, mode))[NORMAL_ROWS].tobytes()
                ), (friction, contact, mode)


@pytest.mark.parametrize("contact", CONTACTS)
def test_the_normal_motion_is_the_same_under_every_friction_law(contact):
    motions = []
    for friction in FRICTIONS:
        # alpha_n = 8: contact and flight alternate; clipped tension adds separation
        model = Model(Vb=1.5, alpha_n=8.0, friction=friction, contact=contact, tension="clipped")
        motion = NormalMotion(model, 3.0, 1e-10, 1e-10, initial_state(model)[2:], "python")
        motions.append(motion)
    first = motions[0]
    assert len(first.switch_kind) >= 2  # it switches: the surfaces were watched
    for other in motions[1:]:
        assert other.switch_kind == first.switch_kind
        for name in ("switch_t", "t_steps", "h_steps", "y_steps", "F_steps", "on_grid"):
            assert getattr(other, name).tobytes() == getattr(first, name).tobytes(), name


def test_one_compiled_normal_integrator_per_contact_law_each_under_its_own_name():
    pytest.importorskip("numba")
    lazies = {}
    for friction, contact, tension in itertools.product(FRICTIONS, CONTACTS, ("allowed",)):
        model = Model(friction=friction, contact=contact, tension=tension)
        lazy = _compiled.advance("response_field", model, None, friction=NORMAL_FRICTION)
        lazies.setdefault(contact, set()).add(lazy)
    assert sorted(lazies) == CONTACTS and all(len(v) == 1 for v in lazies.values())
    stems = {next(iter(v)).stem for v in lazies.values()}
    # and the integrators of the whole field (one per friction and contact law): a name
    # for each kernel set, since the module so named holds its kernels
    # (and the scans of the laws with a closed-form tangential state: the static-kinetic
    # law's took the Coulomb scan's name)
    expected = len(stems)
    for friction, contact in itertools.product(FRICTIONS, CONTACTS):
        model = Model(friction=friction, contact=contact)
        stems.add(_compiled.advance("vector_field", model, None).stem)
        expected += 1
        try:
            stems.add(_compiled.scan(model, None).stem)
        except Unsupported:
            continue
        expected += 1
    assert expected > len(CONTACTS) * (len(FRICTIONS) + 1) and len(stems) == expected
