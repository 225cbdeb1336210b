"""generated/models/ is what derive/models/ writes, and its per-step kernels compile with
numba as they stand (issue 39 item 2)."""

import numpy as np
import pytest

from beltmdsm.derive.codegen import stale
from beltmdsm.derive.models import choices
from beltmdsm.derive.models.render import files
from beltmdsm.generated.models import MODELS, load


def test_generated_models_are_up_to_date():
    """The same comparison as ``python -m derive --check``, for generated/models/ alone."""
    differ = {rel: diff for rel, diff in stale(files()).items() if rel.startswith("models/")}
    assert differ == {}, "\n".join(differ.values())[:3000]
    assert MODELS == choices() and MODELS[0] == "paper"


@pytest.mark.parametrize("name", MODELS)
def test_step_kernels_compile_with_numba(name):
    numba = pytest.importorskip("numba")
    m = load(name)
    law = m.FRICTION_LAWS[1]
    k = m.kernels(law)
    p = np.array([m.DEFAULTS[x] for x in m.PARAMETERS[law]])
    y = k.equilibrium(p) + 0.1
    # one kernel of each output kind: a vector per mode, a matrix per switch, a float
    for args, kernels in (
        ((0.3, y, p, -1), ("field",)),
        ((0.3, y, p, -1, 0), ("saltation",)),
        ((0.3, y, p), ("holding_force",)),
    ):
        for kernel in kernels:
            f = getattr(k, kernel)
            np.testing.assert_allclose(numba.njit(f)(*args), f(*args), rtol=1e-13)


@pytest.mark.parametrize("name", MODELS)
def test_every_parameter_has_a_default_in_its_domain(name):
    from beltmdsm.generated.parameters import within

    m = load(name)
    names = {n for law in m.FRICTION_LAWS for n in m.PARAMETERS[law]}
    assert set(m.DEFAULTS) == names == set(m.DOMAINS) == set(m.UNITS)
    for n, value in m.DEFAULTS.items():
        assert within(m.DOMAINS[n], value), (n, value)
    if name == "paper":  # the per-direction excitation defaults to Eq. (4)'s alpha, Omega
        from beltmdsm.generated.parameters import BASE

        assert m.DEFAULT_FROM == {
            "alpha_t": "alpha",
            "Omega_t": "Omega",
            "alpha_n": "alpha",
            "Omega_n": "Omega",
        }
        assert all(m.DEFAULTS[n] == BASE[src] for n, src in m.DEFAULT_FROM.items())
