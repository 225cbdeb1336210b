"""Pieces of the superposition integrator against independent references."""
import numpy as np
import pytest
from scipy.linalg import expm

from runtime import superposition
from runtime.simulate import simulate
from runtime.superposition import _Member, fundamental_matrix


@pytest.mark.parametrize("c1, k1", [(0.2, 1.0), (2.0, 1.0), (5.0, 1.0), (0.0, 4.0)])
def test_fundamental_matrix_is_the_matrix_exponential(c1, k1):
    A = np.array([[0.0, 1.0], [-k1, -c1]])
    taus = np.array([0.0, 1e-3, 0.7, 5.0, 40.0])
    Phi = fundamental_matrix(taus, c1, k1)
    for i, tau in enumerate(taus):
        np.testing.assert_allclose(Phi[:, :, i], expm(A * tau), rtol=1e-12, atol=1e-14)


def test_double_crossing_inside_one_grid_cell_is_bracketed():
    # g = (t - 0.5)^2 - 1e-4 on the grid {0, 1}: positive at both nodes, negative between
    t = np.array([0.0, 1.0])
    g = (t - 0.5) ** 2 - 1e-4
    dg = 2 * (t - 0.5)
    a, b = _Member._first_crossing(t, g, dg)
    assert 0 <= a < 0.5 - 0.01 < b <= 0.5
    assert (b - 0.5) ** 2 - 1e-4 <= 0


def test_sign_change_is_bracketed_and_no_crossing_is_none():
    t = np.linspace(0, 1, 11)
    assert _Member._first_crossing(t, 0.55 - t, -np.ones_like(t)) == (0.5, pytest.approx(0.6))
    assert _Member._first_crossing(t, 1 + t, np.ones_like(t)) is None


def test_clear_cache_forgets_the_shared_normal_motion_without_changing_results():
    first = simulate(Vb=4.0, solver="superposition", t_end=40.0)
    assert superposition._shared_cached.cache_info().currsize >= 1
    superposition.clear_cache()
    assert superposition._shared_cached.cache_info().currsize == 0
    again = simulate(Vb=4.0, solver="superposition", t_end=40.0)
    np.testing.assert_array_equal(again.y, first.y)
