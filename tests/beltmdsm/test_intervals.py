"""beltmdsm.intervals: runs over a grid, crossings, set algebra, formatting."""

import numpy as np
import pytest

from beltmdsm import intervals as iv


def test_runs_of_true_flags_over_a_grid_in_any_order():
    assert iv.true_runs([False, True, True, False, True]) == [(1, 2), (4, 4)]
    assert iv.true_runs([]) == [] and iv.true_runs([False, False]) == []
    assert iv.runs([1, 2, 3, 4, 5], [False, True, True, False, True]) == [(2.0, 3.0), (5.0, 5.0)]
    # the grid is sorted first, the flags travel with their points
    assert iv.runs([5, 1, 3, 2, 4], [True, False, True, True, False]) == [(2.0, 3.0), (5.0, 5.0)]
    assert iv.runs([1.0, 2.0], [True, True]) == [(1.0, 2.0)]
    with pytest.raises(ValueError, match="one length"):
        iv.runs([1.0, 2.0], [True])


def test_true_runs_agree_with_a_loop_over_the_flags():
    # the vectorised runs against the plain loop of label_runs, on every length to 12
    # and all densities, runs touching either end included
    rng = np.random.default_rng(20)
    for n in range(13):
        for density in (0.0, 0.3, 0.7, 1.0):
            flags = rng.random(n) < density
            loop = [(i, j) for label, i, j in iv.label_runs(flags.tolist()) if label]
            assert iv.true_runs(flags) == loop
    assert iv.true_runs([True] * 3) == [(0, 2)]


def test_label_runs_keep_sequence_order():
    labels = ["a", "a", "b", "a", "a", "a"]
    assert iv.label_runs(labels) == [("a", 0, 1), ("b", 2, 2), ("a", 3, 5)]
    assert iv.label_runs([]) == []


def test_sign_changes_and_crossings_bound_the_negative_set():
    x = np.array([0.0, 1.0, 2.0, 3.0, 4.0, 5.0])
    values = np.array([-1.0, -0.5, 0.5, 1.0, -2.0, -1.0])
    edges = iv.sign_changes(values)
    np.testing.assert_array_equal(edges, [1, 3])
    # crossings refined inside the brackets [x[i], x[i+1]]
    got = iv.from_crossings(x, values < 0, [1.5, 3.25])
    assert got == [(0.0, 1.5), (3.25, 5.0)]
    assert iv.from_crossings(x, np.zeros(6, bool), []) == []
    with pytest.raises(ValueError, match="one point per change"):
        iv.from_crossings(x, values < 0, [1.5])
    # zero is not negative: touching zero is no change
    assert iv.sign_changes([1.0, 0.0, 2.0]).size == 0


def test_union_merges_overlapping_and_touching_intervals():
    assert iv.union([(3.0, 4.0), (0.0, 1.0), (0.5, 2.0), (2.0, 2.5)]) == [(0.0, 2.5), (3.0, 4.0)]
    assert iv.union([]) == []
    with pytest.raises(ValueError, match="lo > hi"):
        iv.union([(2.0, 1.0)])


def test_intersection_difference_and_symmetric_difference():
    a = [(0.0, 4.0), (6.0, 8.0)]
    b = [(3.0, 7.0)]
    assert iv.intersection(a, b) == [(3.0, 4.0), (6.0, 7.0)]
    assert iv.difference(a, b) == [(0.0, 3.0), (7.0, 8.0)]
    assert iv.difference(b, a) == [(4.0, 6.0)]
    assert iv.symmetric_difference(a, b) == [(0.0, 3.0), (4.0, 6.0), (7.0, 8.0)]
    assert iv.difference(a, [(-1.0, 10.0)]) == []
    assert iv.difference(a, []) == a
    # a shared end point is a point of the intersection, of no length
    assert iv.intersection([(0.0, 1.0)], [(1.0, 2.0)]) == [(1.0, 1.0)]
    assert iv.length(iv.intersection([(0.0, 1.0)], [(1.0, 2.0)])) == 0.0


def test_clip_hull_and_length():
    assert iv.clip([(-2.0, 1.0), (9.0, 30.0), (40.0, 50.0)], 0.0, 10.0) == [(0.0, 1.0), (9.0, 10.0)]
    assert iv.hull([(3.0, 4.0), (0.5, 1.0)]) == (0.5, 4.0)
    with pytest.raises(ValueError, match="empty"):
        iv.hull([])
    assert iv.length([(0.0, 2.0), (1.0, 3.0), (5.0, 5.5)]) == pytest.approx(3.5)


def test_jaccard_overlap():
    assert iv.jaccard([(0.0, 2.0)], [(1.0, 3.0)]) == pytest.approx(1 / 3)
    assert iv.jaccard([(0.0, 1.0)], [(0.0, 1.0)]) == 1.0
    assert iv.jaccard([(0.0, 1.0)], []) == 0.0
    assert iv.jaccard([], []) == 1.0
    # points count only through a grid's resolution
    assert iv.jaccard([(2.0, 2.0)], [(3.0, 3.0)]) == 1.0


def test_format_intervals():
    assert iv.format_intervals([(0.0, 8.5214)], ".3f") == "[0.000, 8.521]"
    assert iv.format_intervals([(3.5, 7.5), (9.0, 9.0)], "g") == "[3.5, 7.5], [9, 9]"
    assert iv.format_intervals([]) == "none"
    assert iv.format_intervals([], "g", "nowhere") == "nowhere"


def test_the_notebook_helpers_are_the_interval_functions():
    """notebooks/_nbutil.py keeps its names; they must agree with beltmdsm.intervals."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "notebooks" / "_nbutil.py"
    spec = importlib.util.spec_from_file_location("_nbutil", path)
    nb = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(nb)
    a, b = [(0.0, 2.0), (4.0, 5.0)], [(1.0, 4.5)]
    assert nb.overlap(a, b) == iv.jaccard(a, b) == pytest.approx(1.5 / 5.0)
    assert nb.fmt_ranges(a, 1) == "[0.0, 2.0], [4.0, 5.0]" and nb.fmt_ranges([]) == "none"
    scan = {
        "param": "Vb",
        "Vb": np.array([1.0, 2.0, 3.0]),
        "omega1_peak_present": np.array([True, False, True]),
    }
    assert nb.peak_ranges(scan) == [(1.0, 1.0), (3.0, 3.0)]
