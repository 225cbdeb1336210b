"""beltmdsm.generated._support: blockwise evaluation and the numba backend switch."""

import numpy as np
import pytest

from beltmdsm.generated import _support


def kernel(a, b, c):
    """A chain of array operations with a branch, like a generated numpy kernel."""
    return np.where(a < b, np.sqrt(np.abs(a - b)) * c, a * b - c)


@pytest.mark.parametrize(
    "shapes",
    [
        [(700, 1), (1, 300), ()],
        [(5000 * 40,), (1,), (5000 * 40,)],
        [(3, 1, 40000), (20, 1), (1, 40000)],
    ],
)
def test_blockwise_equals_one_call_for_broadcast_inputs(shapes):
    rng = np.random.default_rng(1)
    args = [rng.uniform(0, 2, s) for s in shapes]
    expected = kernel(*args)
    assert np.prod(expected.shape) > 2 * 1000  # several blocks
    got = _support.blockwise(kernel, *args, block=1000)
    assert got.shape == expected.shape and got.dtype == expected.dtype
    np.testing.assert_array_equal(got, expected)


def test_blockwise_keeps_bool_and_promotes_an_integer_first_block_to_float():
    a = np.arange(10_000.0)
    stable = _support.blockwise(lambda x: x > 5000, a, block=1000)
    assert stable.dtype == bool and stable.sum() == 4999
    # a kernel whose first block comes back as integers must not truncate later blocks
    values = _support.blockwise(lambda x: np.where(x < 1000, 0, x / 3), a, block=1000)
    assert values.dtype == float and values[-1] == pytest.approx(9999 / 3)


def test_blockwise_small_grids_are_one_call():
    calls = []

    def counting(x):
        calls.append(len(x))
        return x * 2

    np.testing.assert_array_equal(_support.blockwise(counting, np.ones(50), block=1000), 2.0)
    assert calls == [50]
    _support.blockwise(counting, np.ones(4500), block=1000)
    assert calls[1:] == [1000] * 4 + [500]


def test_compiled_numpy_backend_is_none_and_unknown_backend_raises():
    def k(x):
        return x + 1.0

    assert _support.compiled(k, "float64", "numpy") is None
    with pytest.raises(ValueError, match="backend"):
        _support.compiled(k, "float64", "gpu")


def test_compiled_numba_ufunc_broadcasts_and_is_cached():
    pytest.importorskip("numba")

    def k(x, y):
        return x * y + 1.0

    ufunc = _support.compiled(k, "float64", "numba")
    assert _support.compiled(k, "float64", None) is ufunc  # compiled once per session
    out = ufunc(np.arange(3.0)[:, None], np.arange(4.0)[None, :])
    np.testing.assert_array_equal(out, np.arange(3.0)[:, None] * np.arange(4.0) + 1.0)


# ---------------------------------------------------------------- argument checks


@pytest.mark.parametrize("value", [np.inf, -np.inf, [1.0, np.inf]])
def test_infinite_parameters_are_refused_by_name(value):
    """Parameters are finite physical numbers; infinity was once passed straight through."""
    from beltmdsm.generated import friction, stability, unforced
    from beltmdsm.generated.parameters import BASE

    with pytest.raises(ValueError, match=r"equilibrium\(\): parameter 'mu_s' must be finite"):
        unforced.equilibrium(**{**BASE, "mu_s": value})
    with pytest.raises(ValueError, match="'Vb' must be finite"):
        stability.is_stable(**{**BASE, "Vb": value}, backend="numpy")
    with pytest.raises(ValueError, match="'phase_t' must be finite"):  # domain "real"
        stability.is_stable(**{**BASE, "phase_t": value}, backend="numpy")
    with pytest.raises(ValueError, match="'Vr' must be finite"):  # a state input
        friction.mu_bar(value, 8.0, 0.4)


def test_infinite_parameters_are_refused_by_the_mpmath_variants():
    import mpmath

    from beltmdsm.generated.mp import stability, unforced
    from beltmdsm.generated.parameters import BASE

    with pytest.raises(ValueError, match="'mu_s' must be finite"):
        unforced.equilibrium(**{**BASE, "mu_s": mpmath.inf})
    with pytest.raises(ValueError, match="'Vb' must be finite"):
        stability.is_stable(**{**BASE, "Vb": -mpmath.inf})


def test_nan_and_domain_messages_are_unchanged_and_an_empty_array_passes():
    from beltmdsm.generated import unforced
    from beltmdsm.generated.parameters import BASE

    with pytest.raises(ValueError, match="'omega1' must be a number, not NaN"):
        unforced.equilibrium(**{**BASE, "omega1": [1.0, np.nan, np.inf]})
    with pytest.raises(ValueError, match=r"'omega1' must be > 0"):
        unforced.equilibrium(**{**BASE, "omega1": [1.0, 0.0]})
    assert _support.param("f", "omega1", np.empty(0)).shape == (0,)


def test_infinite_outputs_are_still_allowed():
    from beltmdsm.generated import friction

    assert friction.mu_bar_slope(8.5, 8.5, 0.4) == np.inf


def test_an_infinite_computed_vhat_is_reported_as_such():
    from beltmdsm.generated import stability
    from beltmdsm.generated.parameters import BASE

    resonant = {**BASE, "beta1": 0.0, "Omega": BASE["omega1"]}
    with pytest.raises(
        ValueError,
        match=r"is_stable\(\): Vhat of vhat_model='tangential' "
        "is not finite",
    ):
        with np.errstate(divide="ignore"):
            stability.is_stable(**resonant, backend="numpy")
    assert not stability.is_stable(**resonant, Vhat=8.0, backend="numpy")
