"""Laws that coincide give the same answers (issue 19, item 7).

Stribeck friction with ``mu_k = mu_s`` is Coulomb friction, and Hunt-Crossley contact
with ``n_h = 3/2`` is Hertz-Damp (derive/laws.py): the same equations, computed through
other generated functions and, for Stribeck, through the other Floquet engine
(beltmdsm/periodic/general_map.py). Every parameter set is built from the registry's base
values (`beltmdsm.Model`, ``beltmdsm.generated.parameters.BASE``), so a new law cannot break
these tests through a missing name.
"""

import numpy as np
import pytest

from beltmdsm.continuation.band import floquet_band
from beltmdsm.generated.parameters import BASE
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet
from beltmdsm.prediction.prediction import predict
from beltmdsm.simulation import simulate

#: The law that coincides with the default one, and what it is compared with.
VARIANTS = {
    "stribeck_mu_k_eq_mu_s": dict(friction="stribeck", mu_k=BASE["mu_s"]),
    "hunt_crossley_3_2": dict(contact="hunt_crossley", n_h=1.5),
}
#: Points of each switch structure: reversals, sliding throughout, a stick phase,
#: separation under the clipped law.
POINTS = {
    "reversals_low": dict(Vb=0.5),
    "reversals": dict(Vb=5.0),
    "sliding": dict(Vb=12.0),
    "stick": dict(Vb=0.1, alpha=0.05),
    "clipped": dict(Vb=4.0, tension="clipped"),
}
#: Duration of the compared runs [s].
T_END = 200.0
#: The Floquet multipliers of the same equations: both found to Newton's tolerance (1e-11
#: of the state) by integrators at 1e-12, the monodromies to about 1e-11, simple
#: eigenvalues of condition O(1-10) (tests/beltmdsm/periodic/test_general.py, AGREE).
AGREE = 1e-9


def _match(a, b):
    return max(float(np.min(np.abs(b - z))) / max(1.0, abs(z)) for z in a)


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("point", POINTS)
def test_simulate(variant, point):
    """The runs differ by less than ten times a run's global error.

    The equations are the same; their generated forms round differently (a product in
    another order, ``x**n_h`` for ``x**(3/2)``), and the adaptive step control turns a
    rounding into another step (a step accepted in one run and rejected in the other),
    so the runs differ by up to the sum of their global errors. The Coulomb run's
    global error is estimated by the same run at a tolerance 100 times tighter; the
    factor 10 covers the other run's error and the estimate's spread (measured: the
    Stribeck runs differ by 1e-11, the Hunt-Crossley runs by up to 3e-8, the global
    error is 1e-8 to 5e-8).
    """
    ref = simulate(Model(**POINTS[point]), t_end=T_END)
    tight = simulate(Model(**POINTS[point]), t_end=T_END, rtol=1e-12, atol=1e-12)
    other = simulate(Model(**POINTS[point], **VARIANTS[variant]), t_end=T_END)
    assert other.status == ref.status == "done"
    error = np.max(np.abs(ref.y - tight.y), axis=1)
    assert np.all(np.max(np.abs(other.y - ref.y), axis=1) <= 10 * error)
    assert [kind for _, kind, _ in other.events] == [kind for _, kind, _ in ref.events]
    assert other.summary.regime == ref.summary.regime


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("point", POINTS)
def test_floquet(variant, point):
    """Stribeck's on the general path against Coulomb's on the closed-form one;
    Hunt-Crossley's and Hertz-Damp's both on the closed-form one."""
    ref = floquet(Model(**POINTS[point]))
    other = floquet(Model(**POINTS[point], **VARIANTS[variant]))
    expected = "general" if "friction" in VARIANTS[variant] else "closed_form"
    assert (ref.engine, other.engine) == ("closed_form", expected)
    assert (other.n_reversals, other.n_sticks) == (ref.n_reversals, ref.n_sticks)
    assert _match(ref.multipliers, other.multipliers) <= AGREE
    assert _match(other.multipliers, ref.multipliers) <= AGREE
    scale = 1.0 + np.max(np.abs(ref.response.state0))
    assert np.max(np.abs(other.response.state0 - ref.response.state0)) <= AGREE * scale


def test_floquet_band_stribeck():
    """The same edges: each within the sum of the two edges' stated accuracies.

    Coulomb's sliding grazing point is the closed-form one (accuracy 1e-12), Stribeck's is
    located by continuation on the general path; the others are located alike.
    """
    kw = dict(points=9, tol=1e-3)
    ref = floquet_band(Model(), "Vb", 3.0, 8.0, **kw)
    other = floquet_band(Model(**VARIANTS["stribeck_mu_k_eq_mu_s"]), "Vb", 3.0, 8.0, **kw)
    assert other.as_dict()["engine"] == "general" and ref.as_dict()["engine"] == "closed_form"
    assert other.as_dict()["friction"] == "stribeck"
    assert [e.kind for e in other.edges] == [e.kind for e in ref.edges]
    assert len(ref.edges) == 3
    for a, b in zip(ref.edges, other.edges):
        assert abs(a.value - b.value) <= a.accuracy + b.accuracy
        assert (a.unstable_below, a.unstable_above) == (b.unstable_below, b.unstable_above)


def test_predict_stribeck():
    """The consistent MDSM: the same intervals to rounding (Stribeck's general path, the
    harmonic balance solved without reversal too and the onset of reversal solved for,
    against Coulomb's closed-form path). The paper's analysis has no closed form under
    Stribeck's law whatever mu_k (closed_form_average is a fact of the law: its fast
    average is a quadrature): it is solved numerically from the pointwise growth rate
    (its reason says so), and gives Coulomb's closed-form intervals to brentq's 1e-12."""
    ref = predict(Model()).as_dict()
    other = predict(Model(**VARIANTS["stribeck_mu_k_eq_mu_s"])).as_dict()
    assert other["friction"] == "stribeck"
    for key in ("paper_tangential_vhat", "paper_coupled_vhat"):
        assert other["reasons"].pop(key).startswith("numeric (friction='stribeck'")
    assert other["reasons"] == ref["reasons"]
    for key, intervals in ref.items():
        if key in ("reasons", "friction") or not isinstance(intervals, list):
            continue
        assert len(other[key]) == len(intervals)
        for (a, b), (c, d) in zip(intervals, other[key]):
            assert abs(a - c) <= 1e-9 * max(1.0, abs(a)) and abs(b - d) <= 1e-9 * max(1.0, abs(b))
