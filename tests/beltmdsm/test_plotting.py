"""The figures of the results (issue 30, item 4), read back from the axes they draw on.

A figure is tested by its data, not its pixels: the lines drawn must be the result's
own arrays (stable parts solid, unstable dashed), every axis must carry a unit, the
special points their labels. The observables a bifurcation diagram draws (ranges of
X1 and X1') are checked against an independent reference: a simulation started on
the orbit and sampled finely over its period.
"""

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import beltmdsm  # noqa: E402
from beltmdsm.cli import main  # noqa: E402
from beltmdsm.plotting import unit  # noqa: E402


@pytest.fixture
def ax():
    fig, ax = plt.subplots()
    yield ax
    plt.close(fig)


def _units(ax):
    return ax.get_xlabel().endswith("]") and ax.get_ylabel().endswith("]")


def test_a_run_draws_its_samples_and_its_friction_loop(small_results, ax):
    sim = small_results["simulation"]
    (line,) = sim.plot(ax).get_lines()
    np.testing.assert_array_equal(line.get_xdata(), sim.t)
    np.testing.assert_array_equal(line.get_ydata(), sim.y[1])
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("t [s]", "X1' [m/s]")
    ax.clear()
    (loop,) = sim.plot(ax, kind="friction").get_lines()
    w = sim.window
    np.testing.assert_array_equal(loop.get_xdata(), sim.y[1][w] - sim.params["Vb"])
    np.testing.assert_array_equal(loop.get_ydata(), sim.friction[w])
    assert ax.get_xlabel() == "Vr = X1' - Vb [m/s]" and _units(ax)
    with pytest.raises(ValueError, match="variable"):
        sim.plot(ax, variable="Vb")


def test_a_band_draws_its_grid_breaks_where_no_response_is_and_labels_its_edges(small_results, ax):
    band = small_results["band"]
    line = band.plot(ax).get_lines()[0]
    x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
    drawn = ~np.isnan(x)
    np.testing.assert_array_equal(x[drawn], [g.value for g in band.grid])
    np.testing.assert_array_equal(y[drawn], [g.max_abs_multiplier for g in band.grid])
    values = [g.value for g in band.grid]
    gaps = sum(
        any(a0 <= a and b <= b0 for a, b in band.no_periodic_response)
        for a0, b0 in zip(values, values[1:])
    )
    assert band.no_periodic_response and (~drawn).sum() == gaps >= 1
    labels = {"neimark_sacker": "NS", "grazing": "GR", "tangency": "TG", "fold": "LP"}
    assert [t.get_text() for t in ax.texts] == [labels[e.kind] for e in band.edges]
    assert ax.get_xlabel() == "Vb [m/s]" and _units(ax)


def test_a_bifurcation_diagram_is_the_branch_observables_by_stability(small_results, ax):
    branch = small_results["branch"]
    table = branch.observables()
    branch.plot(ax)
    stable = {p.value: p.stable for p in branch.points}
    assert set(stable.values()) == {True, False}  # both parts are drawn
    drawn = set()
    for tag, style, want in (("stable", "-", True), ("unstable", "--", False)):
        lines = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith(f"branch:{tag}")]
        assert lines and all(ln.get_linestyle() == style for ln in lines)
        for ln in lines:
            x, y = ln.get_xdata(), ln.get_ydata()
            # each run's points are of its stability; the last is the next run's first
            assert all(stable[v] == want for v in x[:-1])
            drawn |= set(zip(x, y))
    assert drawn == set(zip(table["Vb"], table["X1'_amplitude"]))
    assert [t.get_text() for t in ax.texts] == ["NS"]
    (ns,) = [s for s in branch.special if s.kind == "neimark_sacker"]
    (marker,) = [ln for ln in ax.get_lines() if ln.get_marker() == "o"]
    assert marker.get_xdata()[0] == ns.value
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("Vb [m/s]", "X1' amplitude [m/s]")


def test_the_observables_are_those_of_a_run_on_the_orbit(small_results):
    branch = small_results["branch"]
    table = branch.observables(record=lambda p: {"X1_0": p.state[0], "twice": 2 * p.value})
    np.testing.assert_array_equal(table["X1_0"], [p.state[0] for p in branch.points])
    np.testing.assert_array_equal(table["twice"], 2 * table["Vb"])
    for i in (0, len(branch.points) // 2, len(branch.points) - 1):
        p = branch.points[i]
        f = beltmdsm.floquet(branch.model.replace(Vb=p.value), guess=p.state)
        run = beltmdsm.simulate(
            branch.model.replace(Vb=p.value), y0=f.response.state0, t_end=f.period, dt=2e-4
        )
        x1, v1 = run.y[0], run.y[1]
        scale = v1.max() - v1.min()
        # the run samples at 2e-4 s, the observables at T/1000: extremes low by at
        # most (h w)^2 / 8 of the amplitude, w <= 14 rad/s here (the spikes of X1')
        tol = 5e-4 * scale
        assert abs(table["X1'_max"][i] - v1.max()) < tol
        assert abs(table["X1'_min"][i] - v1.min()) < tol
        assert abs(table["X1_amplitude"][i] - 0.5 * (x1.max() - x1.min())) < tol
        assert abs(table["max_abs_Vr"][i] - np.abs(v1 - p.value).max()) < tol
        # the means: the trapezoidal rule over the run's samples (the friction jumps at
        # the switches: an error of dt x jump / T, below 2e-3 of the mean here)
        dt = np.diff(run.t)
        Ff = 0.5 * np.sum((run.friction[1:] + run.friction[:-1]) * dt)
        Fn = 0.5 * np.sum((run.normal_force[1:] + run.normal_force[:-1]) * dt)
        assert table["mean_friction"][i] == pytest.approx(Ff / run.t[-1], rel=2e-3)
        assert table["mu_eff"][i] == pytest.approx(Ff / Fn, rel=2e-3)


def test_coexistence_draws_each_response_and_shades_the_ranges(small_results, ax):
    found = small_results["coexistence"]
    found.plot(ax)
    labels = {ln.get_label() for ln in ax.get_lines()}
    for r in found.responses:
        assert any(label.startswith(f"{r.name} ") for label in labels)
    shaded = [p for p in ax.patches if p.get_label() == "stable responses coexist"]
    assert len(shaded) == min(1, len(found.ranges))
    assert ax.get_xlim() == (found.lo, found.hi) and _units(ax)


def test_a_map_draws_its_curves(small_results, ax):
    fmap = small_results["map"]
    fmap.plot(ax)
    curves = [ln for ln in ax.get_lines() if ln.get_marker() == "."]
    assert len(curves) == len(fmap.curves)
    for ln, c in zip(curves, fmap.curves):
        np.testing.assert_array_equal(ln.get_xdata(), c.x)
        np.testing.assert_array_equal(ln.get_ydata(), c.y)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("Vb [m/s]", "beta1 [-]")


def test_units_follow_the_contact_law():
    assert unit("omega2", beltmdsm.Model()) == "rad/(m^(1/4) s)"
    assert unit("omega2", beltmdsm.Model(contact="kelvin_voigt")) == "rad/s"
    assert unit("Vb") == "m/s"


@pytest.mark.parametrize(
    "argv",
    [
        ["simulate", "--t-end", "20"],
        ["branch", "--param", "Vb", "--from", "3.9", "--to", "4.2", "--Vb", "4"],
    ],
    ids=["simulate", "branch"],
)
def test_the_command_line_draws_a_png(argv, tmp_path, capsys):
    path = tmp_path / "figure.png"
    assert main([*argv, "--png", str(path)]) == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"drawn to {path}" in capsys.readouterr().out


def _title_and_legend(ax):
    legend = ax.get_legend()
    return ax.get_title(), [t.get_text() for t in legend.get_texts()] if legend else None


def test_every_figure_has_a_legend_and_a_title_naming_what_it_draws(small_results, ax):
    """Issue 37 item 3: a figure is read alone, so it says which response (or run) it
    draws and at which point of the model, and each line is in its legend."""
    fig = ax.figure
    wants = {
        "simulation": ("a run to t = 50 s", "X1'"),
        "band": ("the T response", "max |mu|"),
        "branch": ("the T response", "stable"),
        "coexistence": ("stable responses along Vb", None),
        "map": ("where no stable periodic response is", "no stable periodic response"),
    }
    for name, (title, entry) in wants.items():
        ax.clear()
        small_results[name].plot(ax)
        got, entries = _title_and_legend(ax)
        assert got.startswith(title) and "Model(" in got, (name, got)
        assert entries, name
        assert entry is None or entry in entries, (name, entries)
    fig.clear()


def test_a_multipliers_modulus_is_drawn_on_a_log_scale(small_results, ax):
    small_results["band"].plot(ax)
    assert ax.get_yscale() == "log"


def test_a_stick_onset_is_marked_sl_in_its_own_colour(small_results, ax):
    """Every kind of special point the package reports has a label and a colour: a
    stick onset (grazing-sliding, `beltmdsm.cycles.stick`) was drawn unmarked."""
    from dataclasses import replace

    from beltmdsm._display import LABELS
    from beltmdsm.continuation.branch_result import SpecialPoint
    from beltmdsm.plotting import KIND_COLOURS

    assert set(LABELS) == set(KIND_COLOURS)
    branch = small_results["branch"]
    mid = branch.points[len(branch.points) // 2].value
    onset = SpecialPoint("stick_onset", mid, 1e-6, None, np.zeros(3), False, True)
    replace(branch, special=[*branch.special, onset]).plot(ax)
    assert "SL" in [t.get_text() for t in ax.texts]
    (marker,) = [ln for ln in ax.get_lines() if ln.get_marker() == "o" and ln.get_xdata()[0] == mid]
    assert marker.get_color() == KIND_COLOURS["stick_onset"]


def test_a_basin_map_is_clipped_to_its_starts_and_names_its_point(ax):
    b = beltmdsm.basins(beltmdsm.Model(Vb=3.88), points=3, x_lo=3.0, x_hi=7.0, y_lo=-8.5, y_hi=-4.5)
    b.plot(ax)
    assert ax.get_xlim() == (3.0, 7.0) and ax.get_ylim() == (-8.5, -4.5)
    assert ax.get_title() == f"basins at {b.model!r}" and "Vb=3.88" in ax.get_title()


def test_the_tables_are_the_results_own_numbers(small_results):
    """Issue 37 item 3: ``to_pandas()`` of Floquet, Cycle, Lyapunov, Basins, Simulation
    and Coexistence, read against the results' attributes."""
    pytest.importorskip("pandas")
    sim = small_results["simulation"]
    table = sim.to_pandas()
    np.testing.assert_array_equal(table["t"], sim.t)
    np.testing.assert_array_equal(table["X2'"], sim.y[3])
    np.testing.assert_array_equal(table["friction"], sim.friction)
    f = small_results["floquet"]
    table = f.to_pandas()
    np.testing.assert_array_equal(table["multiplier"], f.multipliers)
    assert table["abs"].max() == pytest.approx(f.max_abs_multiplier, rel=1e-15)
    assert table["rate"].max() == pytest.approx(f.growth_rate, rel=1e-12)
    found = small_results["coexistence"]
    table = found.to_pandas()
    assert len(table) == sum(len(r.stable) for r in found.responses)
    assert len(found.to_pandas("ranges")) == len(found.ranges)
    with pytest.raises(ValueError, match="table must be"):
        found.to_pandas("points")
