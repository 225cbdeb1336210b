"""Small helpers shared by the notebooks (plain module, no SymPy).

The notebooks run in two modes, chosen by the environment variable ``BELTMDSM_FULL``:

* quick (the default, ``BELTMDSM_FULL`` unset, empty or ``0``): coarse grids and short
  runs, so that ``python -m pytest`` (nbmake) executes every notebook within the CI
  budget;
* full (``BELTMDSM_FULL=1``): the paper's resolution.

Figures go to `FIGURES`: ``notebooks/figures/`` in full mode, a temporary folder in
quick mode, or ``BELTMDSM_FIGURES`` when it is set.

Importing this module also puts the repository root on ``sys.path``: nbmake runs a
notebook with its own folder as working directory, where ``beltmdsm`` (with
``beltmdsm.generated``) and ``benchmarks`` are importable only through an editable install (and
``benchmarks`` never is, since it is not a package of the distribution).
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from beltmdsm import SolverSettings, simulate  # noqa: E402
from beltmdsm.batch.table import omega1_peak_ranges  # noqa: E402
from beltmdsm.intervals import format_intervals, jaccard  # noqa: E402
from beltmdsm.run.spectra import amplitude_spectrum  # noqa: E402

__all__ = [
    "FULL",
    "MODE",
    "FIGURES",
    "pick",
    "settings",
    "save",
    "spectrum_scan",
    "plot_spectrum_map",
    "peak_ranges",
    "fmt_ranges",
    "overlap",
    "show",
]

FULL = os.environ.get("BELTMDSM_FULL", "").strip() not in ("", "0")
MODE = "full" if FULL else "quick"
# Full mode writes the committed PNGs (notebooks/figures/); quick mode (the test run)
# writes to a temporary folder so that `python -m pytest` leaves the repository as it
# was. BELTMDSM_FIGURES overrides both.
FIGURES = Path(
    os.environ.get("BELTMDSM_FIGURES")
    or (
        Path(__file__).resolve().parent / "figures"
        if FULL
        else Path(tempfile.gettempdir()) / "beltmdsm-figures-quick"
    )
)


def pick(quick, full):
    """The value for the current mode: ``full`` if ``BELTMDSM_FULL`` is set, else ``quick``."""
    return full if FULL else quick


def settings(t_end_quick=400.0, t_end_full=1000.0, **kw):
    """Solver settings of the notebooks' runs.

    The fast configuration of the simulation benchmark (superposition, DOP853,
    rtol = atol = 1e-7: peak_omega1 within about 3e-7 of the reference, README);
    the run length depends on the mode, the paper's figures use 1000 s. Quick mode
    runs 400 s: a run's summary calls the omega1 peak present only where the two halves
    of its steady window agree to 1 % (issue 28), and the slowest attractor the base
    set's runs reach, the 59T lock at Vb = 3.5 (contracting at 0.015 1/s), is that
    settled by 400 s, not by 300 s (unresolved there).

    Parameters
    ----------
    t_end_quick, t_end_full : float
        run length [s] in quick and full mode
    **kw
        further `beltmdsm.settings.SolverSettings` fields
    """
    base = dict(solver="events", method="DOP853", rtol=1e-7, atol=1e-7)
    return SolverSettings(t_end=pick(t_end_quick, t_end_full), **{**base, **kw})


def save(fig, name):
    """Save ``fig`` as ``<FIGURES>/<name>.png`` (returns nothing, so that a notebook
    cell ending with it shows only the figure)."""
    FIGURES.mkdir(parents=True, exist_ok=True)
    path = FIGURES / f"{name}.png"
    # committed PNGs are stripped of their notebook: the stamp says which mode made them
    fig.text(0.995, 0.005, f"{MODE} mode", ha="right", va="bottom", fontsize=6, color="0.5")
    fig.savefig(path, dpi=110, bbox_inches="tight")


def spectrum_scan(
    values, param="Vb", params=None, *, contact="hertz_damp", solver=None, omega_max=10.0
):
    """Amplitude spectra of X1' over the steady window for each value of one parameter.

    Runs `beltmdsm.simulate` serially (the machines that run the notebooks are shared;
    a scan in quick mode takes seconds).

    Parameters
    ----------
    values : array_like
        values of ``param``
    params : dict, optional
        the other parameters (default: the base set)
    solver : SolverSettings, optional
        default `settings()`
    omega_max : float
        highest frequency kept [rad/s]

    Returns
    -------
    dict with ``param``, ``values``, ``omega`` (n_omega,), ``amplitude``
    (n_values, n_omega; NaN for runs that stopped early), ``stopped`` (the values whose
    run did not reach t_end), ``summaries`` (list of the runs' summary dicts) and, as arrays,
    ``omega1_peak_present``, ``resolved``, ``peak_omega1``, ``regime``. ``resolved``
    (bool) is False where the run could not tell the omega1 peak
    (`beltmdsm.run.summary.summarize`); ``omega1_peak_present`` is False there too, as in a
    sweep table, so read it together with ``resolved`` (`peak_ranges` does).
    """
    values = np.asarray(values, dtype=float)
    solver = solver or settings()
    # the spectrum of a full steady window fixes the frequency grid; a run that stops
    # early (status "too_many_events", "contact_lost") gets a NaN row and keeps its status
    n_window = int(
        np.sum(
            solver.dt * np.arange(int(solver.t_end / solver.dt + 1e-9) + 1) >= solver.window_start
        )
    )
    omega = np.fft.rfftfreq(n_window, solver.dt) * 2 * np.pi
    keep = omega <= omega_max
    spectra, summaries = [], []
    for v in values:
        model = {**(params or {}), param: float(v), "contact": contact}
        sim = simulate(model, settings=solver)
        if sim.window.sum() == n_window:
            spectra.append(amplitude_spectrum(sim.y[1, sim.window], solver.dt, pad=1)[1][keep])
        else:
            spectra.append(np.full(keep.sum(), np.nan))
        summaries.append(sim.summary)
    return {
        "param": param,
        "values": values,
        "omega": omega[keep],
        "amplitude": np.array(spectra),
        "stopped": values[[s.status != "done" for s in summaries]],
        "summaries": summaries,
        param: values,
        # a summary's None (unresolved) would make an object array: False beside
        # resolved = False, as beltmdsm.batch.sweep stores it
        "omega1_peak_present": np.array(
            [bool(s.resolved and s.omega1_peak_present) for s in summaries]
        ),
        "resolved": np.array([bool(s.resolved) for s in summaries]),
        "peak_omega1": np.array([s.peak_omega1 for s in summaries]),
        "regime": np.array([s.regime for s in summaries]),
    }


def plot_spectrum_map(ax, scan, intervals=(), title=None):
    """Draw a scan as a map: belt speed (x), frequency (y), log10 amplitude (colour).

    Points where the omega1 peak is present are marked with white dots at the
    peak's frequency; each ``(label, [(lo, hi), ...], colour)`` of ``intervals`` is
    drawn as a bar under the map (a predicted unstable range).
    """
    x, w = scan["values"], scan["omega"]
    amp = np.log10(np.maximum(scan["amplitude"], 1e-6))  # NaN rows (stopped runs) stay blank
    mesh = ax.pcolormesh(
        x, w, amp.T, shading="nearest", cmap="viridis", vmin=-4, vmax=max(1.0, np.nanmax(amp))
    )
    present = scan["omega1_peak_present"]
    at = np.array([s.omega1_peak_at for s in scan["summaries"]])
    ax.plot(x[present], at[present], "o", mfc="w", mec="k", ms=4, label=r"$\omega_1$ peak")
    for k, (label, ranges, colour) in enumerate(intervals):
        y = -0.35 - 0.3 * k
        for n, (lo, hi) in enumerate(ranges):
            ax.plot(
                [lo, hi],
                [y, y],
                color=colour,
                lw=4,
                solid_capstyle="butt",
                label=label if n == 0 else None,
                clip_on=False,
            )
    ax.set_ylim(-0.35 - 0.3 * len(intervals), w[-1])
    ax.set_xlabel(f"{scan['param']} [m/s]" if scan["param"] == "Vb" else scan["param"])
    ax.set_ylabel(r"$\omega$ [rad/s]")
    if title:
        ax.set_title(title, fontsize=9)
    return mesh


def peak_ranges(scan):
    """Contiguous ranges of the scanned parameter where the omega1 peak is present."""
    return omega1_peak_ranges(scan, scan["param"])


def fmt_ranges(ranges, digits=2):
    """``[(a, b), ...]`` as text, ``"none"`` when empty (`beltmdsm.intervals.format_intervals`)."""
    return format_intervals(ranges, f".{digits}f")


def overlap(a, b):
    """Jaccard overlap |A and B| / |A or B| of two unions of intervals (1 = identical).

    `beltmdsm.intervals.jaccard`: both empty gives 1. Points (zero-length intervals)
    count through the grid resolution only, so callers pass ranges widened by half a
    grid step.
    """
    return jaccard(a, b)


def show(text):
    """Render computed markdown text in the notebook (plain print outside IPython)."""
    try:
        from IPython.display import Markdown, display
    except ImportError:
        print(text)
    else:
        display(Markdown(text))
