"""Issue 28 section 1: a run or a grid that cannot tell says so, end to end.

Each command-line report is reproduced through ``python -m beltmdsm`` (run in the
test's process, tests/inprocess.py); the verdicts are checked against independent
references (a long run, an independent transform of the window's halves, independent
`floquet` calls).
"""

import json

import numpy as np
import pytest
from inprocess import cli as _run

from beltmdsm.model import Model
from beltmdsm.simulation import simulate


def _band_amplitude(v, dt, band):
    """The largest Hann-windowed amplitude of ``v`` in ``band`` on a fine frequency grid:
    a transform written here, apart from beltmdsm.run.spectra."""
    n = v.size
    w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(n) / (n - 1))
    x = (v - v.mean()) * w
    t = np.arange(n) * dt
    omegas = np.linspace(band[0], band[1], 2001)
    return max(2 * abs(np.sum(x * np.exp(-1j * om * t))) / w.sum() for om in omegas)


# ------------------------------------------------- false vibration on short runs


def test_simulate_vb8_t60_calls_the_decaying_transient_unresolved_not_present():
    r = _run("simulate", "--Vb", "8", "--t-end", "60", "--json", "--no-progress")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["resolved"] is False and out["omega1_peak_present"] is None
    # the reason gives the halves of the window; an independent transform reads them
    sim = simulate(Model(Vb=8.0), t_end=60.0)
    v = sim.y[1, sim.t >= 18.0]
    dt = sim.t[1] - sim.t[0]
    half = v.size // 2
    first, second = (_band_amplitude(p, dt, (0.75, 1.25)) for p in (v[:half], v[half:]))
    assert f"holds {first:.3g} m/s in the first half" in out["unresolved_reason"]
    assert f"and {second:.3g} m/s in the second" in out["unresolved_reason"]
    assert second < 0.9 * first  # 4.24 against 3.24: still decaying
    text = _run("simulate", "--Vb", "8", "--t-end", "60", "--no-progress").stdout
    assert "omega1 peak unresolved (" in text and "PRESENT" not in text


@pytest.mark.parametrize("Vb", [3.0, 8.0])
def test_short_runs_never_call_the_transient_present_and_a_long_run_says_absent(Vb):
    # the reference: by 1000 s the transient has died out, the peak is absent
    long = simulate(Model(Vb=Vb), t_end=1000.0).summary
    assert long.resolved and long.omega1_peak_present is False
    assert long.peak_omega1 < 1e-3 * long.peak_Omega
    for t_end in (40.0, 60.0, 80.0):
        s = simulate(Model(Vb=Vb), t_end=t_end).summary
        assert s.omega1_peak_present is not True, (Vb, t_end, s.peak_omega1)
        assert s.peak_omega1 > 10 * long.peak_omega1  # the transient is in the window


def test_a_settled_self_excited_oscillation_stays_present():
    # Vb = 4 from rest: the oscillation of constant amplitude (Fig. 2b); its halves
    # agree to 1e-3 by an independent transform
    sim = simulate(Model(Vb=4.0), t_end=300.0)
    s = sim.summary
    assert s.resolved and s.omega1_peak_present is True
    v = sim.y[1, sim.t >= s.t_discard]
    half = v.size // 2
    dt = sim.t[1] - sim.t[0]
    a, b = (_band_amplitude(p, dt, s.omega1_band) for p in (v[:half], v[half:]))
    assert abs(a - b) < 1e-3 * max(a, b)
    assert a > 0.5 * s.peak_Omega


def test_sweep_t50_finds_the_peak_nowhere_it_cannot_tell():
    r = _run(
        "sweep", "--param", "Vb", "--values", "3", "8", "--t-end", "50",
        "--no-cache", "--jobs", "1", "--no-progress", "--json",
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["omega1_peak_ranges"] == []
    assert out["unresolved"] == [3.0, 8.0]


# ------------------------------------------- floquet-band at the default grid


def _end_accuracy(band_edges, value, lo, hi):
    """The stated accuracy of a range's end: 0 at the range's bounds, else its edge's."""
    if value in (lo, hi):
        return 0.0
    (edge,) = [e for e in band_edges if e["value"] == value]
    return edge["accuracy"]


def test_floquet_band_default_grid_agrees_with_a_fine_grid_and_with_floquet():
    from beltmdsm.continuation.band import floquet_band
    from beltmdsm.continuation.edges import KINDS
    from beltmdsm.errors import NoPeriodicResponse
    from beltmdsm.periodic.floquet import floquet

    argv = ["floquet-band", "--param", "Vb", "--from", "0", "--to", "40", "--omega1", "12"]
    r = _run(*argv, "--no-progress", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    # every edge a documented kind, located (no zero-width bracket), no empty range
    for e in out["edges"]:
        assert e["kind"] in (*KINDS, "unclassified"), e
        assert e["accuracy"] > 0 and e["bracket"][0] < e["value"] < e["bracket"][1], e
    assert all(b > a for a, b in out["unstable"]), out["unstable"]
    # the same ranges as a grid of 160 points, to the accuracies the two state
    fine = floquet_band(Model(omega1=12.0), "Vb", 0.0, 40.0, points=160)
    fine_edges = [e.as_dict() for e in fine.edges]
    assert len(out["unstable"]) == len(fine.unstable) == 1
    for got, ref in zip(out["unstable"], fine.unstable):
        for x, y in zip(got, ref):
            bound = _end_accuracy(out["edges"], x, 0, 40) + _end_accuracy(fine_edges, y, 0, 40)
            assert abs(x - y) <= bound, (got, ref)
    # independent floquet() calls: none or unstable inside the range, stable outside
    ((lo, hi),) = out["unstable"]
    for v in (0.05, 0.1, 0.2):
        assert lo <= v <= hi
        try:
            assert floquet(Model(Vb=v, omega1=12.0)).stable is False
        except NoPeriodicResponse:
            pass
    for v in (0.3, 0.5, 0.7, 2.0, 10.0, 30.0):
        assert v > hi and floquet(Model(Vb=v, omega1=12.0)).stable is True


# ------------------------------------------------ a large --tol erases bands


@pytest.mark.parametrize(
    "argv",
    [
        ["--from", "1", "--to", "9", "--tol", "3"],
        ["--omega1", "3", "--from", "10", "--to", "15", "--tol", "1"],
    ],
)
def test_a_tol_above_the_grid_step_is_refused_by_name(argv):
    r = _run("floquet-band", "--param", "Vb", *argv, "--no-progress")
    assert r.returncode == 2 and r.stdout == ""
    (line,) = r.stderr.strip().splitlines()
    assert "--tol" in line and "grid's step" in line and "Traceback" not in r.stderr


def test_merging_that_removes_a_range_says_so():
    import re

    from beltmdsm.continuation.band import floquet_band

    argv = ["floquet-band", "--param", "Vb", "--omega1", "3", "--from", "10", "--to", "15"]
    r = _run(*argv, "--tol", "0.3", "--no-progress")
    assert r.returncode == 0, r.stderr
    text = r.stdout
    (bracket,) = re.findall(r"merged away: edges in \[([0-9.]+), ([0-9.]+)\]", text)
    a, b = map(float, bracket)
    assert "no periodic response found at 12.8125 (inside a merged-away bracket)" in text
    assert "no periodic response in" not in text
    # at the default tol the range without a response, which the merging removed, lies
    # inside the merged bracket (to the 4 decimals printed)
    fine = floquet_band(Model(omega1=3.0), "Vb", 10.0, 15.0)
    ((c, d),) = fine.no_periodic_response
    assert a - 1e-4 <= c < d <= b + 1e-4


# ------------------------------------------------- coarse grids without a word


def test_coexistence_refuses_a_step_that_leaves_no_seed_inside():
    argv = ["coexistence", "--param", "Vb", "--from", "0.5", "--to", "12", "--step", "20"]
    r = _run(*argv)
    assert r.returncode == 2 and r.stdout == ""
    (line,) = r.stderr.strip().splitlines()
    assert "--step" in line and "no seed inside" in line and "5.75" in line


def test_predict_with_a_coarse_vb_max_keeps_the_band_and_says_what_it_cannot_resolve():
    from beltmdsm.prediction.scan import unstable_intervals

    r = _run("predict", "--vb-max", "3000", "--no-progress", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    # the default grid's band (checked against the linear amplitude elsewhere)
    ((lo, hi),) = unstable_intervals()[0]
    ((a, b),) = out["consistent_mdsm"]
    assert abs(a - lo) < 1e-9 and abs(b - hi) < 1e-9
    assert "above it the step is 7.5 m/s" in out["reasons"]["consistent_mdsm"]
