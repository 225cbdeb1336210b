"""Issue 28: the Python API checks its arguments at the boundary, as the command line
does: one ValueError naming the argument, before anything is computed."""

import math

import numpy as np
import pytest

import beltmdsm
from beltmdsm import arguments
from beltmdsm.errors import Refused, ShorterPeriod
from beltmdsm.model import Model
from beltmdsm.periodic.shooting import MAX_SEED_PERIODS, SEED_PERIODS
from beltmdsm.settings import SolverSettings


@pytest.mark.parametrize(
    "call, name",
    [
        # each was accepted, or failed with another exception, deep inside
        (lambda: beltmdsm.sweep(None, "Vb", [True, 3.0], cache_dir=None), "values"),
        (lambda: beltmdsm.sweep(None, "Vb", np.array([True, False]), cache_dir=None), "values"),
        (lambda: beltmdsm.sweep(None, "Vb", [3.0], settings={"t_end": 10}), "settings"),
        (lambda: beltmdsm.sweep(None, "Vb", [3.0], modulation=1, cache_dir=None), "modulation"),
        (lambda: beltmdsm.floquet(periods=True), "periods"),
        (lambda: beltmdsm.floquet(forward=-1), "forward"),
        (lambda: beltmdsm.floquet(forward=2.5), "forward"),
        (lambda: beltmdsm.periodic_response(max_iter=-1), "max_iter"),
        (lambda: beltmdsm.periodic_response(max_iter=False), "max_iter"),
        (lambda: beltmdsm.floquet(guess=[math.nan] * 4), "guess"),
        (lambda: beltmdsm.floquet(guess=[1.0, 2.0, 3.0]), "guess"),
        (lambda: beltmdsm.floquet(guess=["1", 0, 0, 0]), "guess"),
        (lambda: beltmdsm.simulate(y0=[1j, 0, 0, 0], t_end=1.0), "y0"),
        (lambda: beltmdsm.simulate(y0=[True, 0, 0, 0], t_end=1.0), "y0"),
        (lambda: beltmdsm.simulate(settings={"t_end": 10}), "settings"),
        (lambda: beltmdsm.simulate(t_end=1.0, progress="yes"), "progress"),
        (lambda: beltmdsm.responses(limit=True), "limit"),
        (lambda: beltmdsm.coexistence(None, "Vb", 3.0, 4.0, limit=2.5), "limit"),
        (lambda: beltmdsm.coexistence(None, "Vb", 3.0, 4.0, points=True), "points"),
    ],
)
def test_a_bad_argument_is_one_value_error_naming_it(call, name):
    with pytest.raises(ValueError) as caught:
        call()
    assert type(caught.value) in (ValueError, Refused)
    assert str(caught.value).startswith(f"{name} must be "), str(caught.value)


def test_good_arguments_pass_as_they_are():
    assert arguments.count("k", np.int64(3), 1) == 3
    assert arguments.flag("f", np.bool_(True)) is True
    assert arguments.state("y", (1, 2.5), (2, 4), "x").tolist() == [1.0, 2.5]
    assert arguments.reals("v", np.arange(3)).dtype == float
    s = SolverSettings(t_end=5.0)
    assert arguments.settings_of(s) is s and arguments.settings_of(None) == SolverSettings()


def test_periods_beyond_the_seed_are_refused_with_the_bound():
    # the seed has SEED_PERIODS[1] samples; a lock at k needs more than 2 k of them
    assert 2 * MAX_SEED_PERIODS < SEED_PERIODS[1] <= 2 * (MAX_SEED_PERIODS + 1)
    with pytest.raises(Refused, match=f"periods must be <= {MAX_SEED_PERIODS} without a guess"):
        beltmdsm.floquet(periods=MAX_SEED_PERIODS + 1)


def test_a_lock_at_a_divisor_is_named_with_its_period():
    # issue 28: "no response of 8 periods" where the 4T orbit is 8T-periodic, and
    # "locks at 1 periods"
    with pytest.raises(ShorterPeriod) as caught:
        beltmdsm.periodic_response(Model(Vb=5.0), periods=8)
    assert (caught.value.asked, caught.value.periods) == (8, 4)
    assert "locks at 4 periods, whose orbit repeats after 8 too" in str(caught.value)
    with pytest.raises(ShorterPeriod, match="locks at 1 period, whose orbit repeats after 2"):
        beltmdsm.periodic_response(Model(Vb=10.0), periods=2)


def test_the_limit_bound_counts_the_samples_a_run_has():
    from beltmdsm.excitation import excitation_period
    from beltmdsm.model import Model
    from beltmdsm.starts.forced import check_limit, run_samples, run_stroboscope

    m = Model()
    T = excitation_period(m)
    # the run of 10 s: 3 samples, as the stroboscope itself says (the message of issue 28)
    assert run_samples(m, 10.0) == 3
    with pytest.raises(ValueError, match=r"got \(3, 2\)"):
        run_stroboscope(m, t_end=10.0)
    with pytest.raises(Refused, match="give t_end >= 98.9602 s or limit <= 1"):
        check_limit(12, [m], 10.0, ladder=False)
    # the t_end it suggests is enough: the run has more than 2 * 12 samples
    need = math.ceil(25 / 0.4) * T
    check_limit(12, [m], need, ladder=False)
    strobe = run_stroboscope(m, t_end=need)
    assert strobe.samples.shape[0] == run_samples(m, need) > 24
