"""Issue 36, items 5 and 7, at the API: what a Lyapunov run keeps, and the error floor
of Floquet multipliers."""

import tracemalloc

import numpy as np

from beltmdsm import Model
from beltmdsm.attractors.lyapunov import lyapunov
from beltmdsm.integrate.events import integrate_events
from beltmdsm.settings import SolverSettings


def _peak(f):
    tracemalloc.start()
    try:
        f()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_the_transient_of_a_lyapunov_run_keeps_only_its_state():
    """Item 5: memory grew by about 21 kB per simulated second of transient (the dense
    output of one run over it) until MemoryError. Run in pieces, the peak does not grow
    with the transient; the plain run over it, the reference, grows in proportion."""
    m = Model(Vb=4.0)
    lyapunov(m, t_end=60.0)  # compiled kernels and caches, out of the measurement
    short = _peak(lambda: lyapunov(m, t_end=500.0, t_transient=450.0))
    long = _peak(lambda: lyapunov(m, t_end=2000.0, t_transient=1950.0))
    plain_short = _peak(lambda: integrate_events(m, SolverSettings(t_end=450.0)))
    plain_long = _peak(lambda: integrate_events(m, SolverSettings(t_end=1950.0)))
    assert plain_long > 3 * plain_short  # the reference grows with the run
    assert long < 1.3 * short, (short, long)
    assert long < plain_long / 4


def test_periodic_attractor_reports_exponents_below_the_floor_as_bounds():
    """Item 7: at Omega = 0.5, Vb = 2 `periodic_attractor` gave -3.365 1/s for the
    contact's direction, whose exponent a Lyapunov run (Benettin, the independent
    reference) measures at -5.661. That multiplier lies below the error floor of the
    Floquet computation: its exponent is NaN, with the floor's bound, which the
    reference satisfies; the resolved exponents agree with the reference."""
    from beltmdsm.attractors.classification import periodic_attractor

    m = Model(Omega=0.5, Vb=2.0)
    a = periodic_attractor(m, t_end=600.0)
    ref = lyapunov(m, t_end=600.0)
    resolved = np.isfinite(a.exponents)
    assert not resolved.all() and a.exponent_floor is not None
    assert np.all(ref.exponents[~resolved] < a.exponent_floor)
    # the tangential pair (complex: each of its two exponents converges slowly in a
    # Benettin run, their mean fast), then the normal direction
    assert resolved[:3].all()
    pair, ref_pair = a.exponents[:2].mean(), ref.exponents[:2].mean()
    assert abs(pair - ref_pair) <= 3 * ref.error[:2].max()
    T = 2 * np.pi / 0.5
    floor = np.exp(a.exponent_floor * T)  # the multipliers' absolute error
    own = floor / (np.exp(a.exponents[2] * T) * T)  # d ln|mu| / T
    assert abs(a.exponents[2] - ref.exponents[2]) <= 3 * (ref.error[2] + own)
    assert "below the computation's error floor" in a.evidence
