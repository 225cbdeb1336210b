"""Every response at one point (beltmdsm.multistability.responses, seeded by
beltmdsm.starts) against the simulated runs.

References: the runs of `beltmdsm.simulation.simulate` from rest (their stroboscopic
samples end on the computed orbit), and the response the analysis seeds from the
attractor of the period map (`periodic_response(..., periods=k)`: another start, the
same orbit).
"""

import pytest

from beltmdsm.model import Model
from beltmdsm.multistability import responses as R
from beltmdsm.periodic.locked import same_phases
from beltmdsm.periodic.shooting import periodic_response
from beltmdsm.starts.forced import ladder_stroboscope, run_stroboscope


@pytest.mark.parametrize(("case", "k"), [(dict(Vb=5.0), 4), (dict(Vb=6.3), 4), (dict(Vb=7.0), 4)])
def test_the_run_from_rest_locks_and_its_samples_are_the_computed_orbit(case, k):
    model = Model(**case)
    assert run_stroboscope(model).candidate == k
    found = R.responses(model, ladder=0.0)
    (locked,) = [r for r in found.responses if r.periods == k]
    assert locked.floquet.stable
    # the run from rest ends on the computed orbit (its samples to ~1e-10)
    assert locked.run_distance < 1e-8
    # the analysis' own seed (the period map iterated from rest) finds the same orbit
    seeded = periodic_response(model, periods=k)
    assert same_phases(locked.phases, seeded.state0[:2])


def test_the_run_from_rest_locks_at_6T_at_omega_6():
    assert run_stroboscope(Model(Vb=12.0, Omega=6.0)).candidate == 6


def test_responses_at_the_base_point_list_both_and_say_what_is_not_locked():
    found = R.responses(Model(Vb=5.0))
    by_k = {r.periods: r for r in found.responses}
    assert set(by_k) == {1, 4}
    assert by_k[1].floquet.stable is False and by_k[4].floquet.stable is True
    assert 4 * by_k[1].floquet.n_reversals == 2 * by_k[4].floquet.n_reversals
    assert by_k[4].amplitude > by_k[1].amplitude
    # every seed of the 4T orbit: both runs and both ladders
    assert len(by_k[4].sources) == 4
    keys = {"periods", "stable", "max_abs_multiplier", "multipliers", "n_reversals", "n_sticks"}
    assert keys | {"amplitude"} <= set(by_k[4].as_dict())
    assert set(found.as_dict()) == {
        "params",
        "friction",
        "contact",
        "tension",
        "limit",
        "responses",
        "unlocked",
        "failed",
    }
    # just below the lower band edge the run from rest does not lock within 12 periods
    # (its samples on a closed curve, rotation -0.254); classified, it is a 59T lock
    # (issue 31), shot and listed as a response with its Floquet rate as its exponent
    below = R.responses(Model(Vb=3.5), ladder=0.0)
    assert [r.periods for r in below.responses] == [1, 59] and not below.unlocked
    lock = below.responses[1]
    assert lock.sources == ["run from rest (classified)"] and lock.floquet.stable
    d = lock.as_dict()
    assert d["kind"] == "periodic" and d["lyapunov"] == lock.floquet.growth_rate < 0


def test_bad_arguments_are_refused():
    for kw in (dict(limit=0), dict(ladder=-1.0), dict(t_end=0.0)):
        with pytest.raises(ValueError):
            R.responses(Model(Vb=5.0), **kw)
    with pytest.raises(ValueError, match="direction"):
        ladder_stroboscope(Model(), "sideways")
