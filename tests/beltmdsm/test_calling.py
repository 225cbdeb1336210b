"""One calling convention (issue 37, item 2) and one check per kind of argument (issue 36,
item 10).

* every public function takes the model first and names its keywords: no ``**kw``;
  ``inspect.signature`` shows the model first;
* the spellings of before (the model last, model parameters as keywords, ``rows=``,
  ``step=``, ``x_from=``, ``x_range=``, ``vb_max=``) still work, each with one
  `DeprecationWarning` line naming the new one;
* a misspelt keyword is a `TypeError` with "did you mean" over the function's keywords
  and the model's parameters, at run time and in mypy;
* the same name means the same thing everywhere (``executor``, ``cache_dir``, ranges,
  resolution), and the same bad value gets the same answer from every function.

Each call here fails at the boundary (a bad value after the one under test), so that
the test shows where the arguments went without computing anything.
"""

import inspect
import math
import os
import subprocess
import sys
import warnings
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import beltmdsm
from beltmdsm import Model

ROOT = Path(__file__).resolve().parents[2]
FUNCTIONS = [
    n for n in beltmdsm.__all__ if inspect.isfunction(getattr(beltmdsm, n)) and n != "validate"
]
M = Model(Vb=5.0)


def one_deprecation(record, *words):
    """The one DeprecationWarning of a call, one line, naming ``words``."""
    deprecations = [w for w in record if issubclass(w.category, DeprecationWarning)]
    assert len(deprecations) == 1, [str(w.message) for w in deprecations]
    text = str(deprecations[0].message)
    assert "\n" not in text and all(w in text for w in words), text
    # it points at the caller's line, not at the wrapper
    assert deprecations[0].filename == __file__
    return text


@pytest.mark.parametrize("name", FUNCTIONS)
def test_the_model_comes_first_and_every_keyword_is_named(name):
    function = getattr(beltmdsm, name)
    params = list(inspect.signature(function).parameters.values())
    assert params[0].name == "model", name
    assert not any(p.kind is p.VAR_KEYWORD for p in params), name
    # through beltmdsm/_calling.py: an unknown keyword gets "did you mean"
    with pytest.raises(TypeError, match=f"{name}\\(\\) got an unexpected keyword argument 'modle'"):
        function(M, modle=M)


@pytest.mark.parametrize(
    "name, old, new, error",
    [
        # the range reversed: a ValueError naming lo < hi shows the values reached them
        ("floquet_band", ("Vb", 5.0, 1.0, M), "floquet_band(model, param, lo, hi)", "lo < hi"),
        ("coexistence", ("Vb", 5.0, 1.0, M), "coexistence(model, param, lo, hi)", "lo < hi"),
        (
            "floquet_map",
            ("Vb", 5.0, 1.0, "beta1", 0.1, 0.2, M),
            "floquet_map(model, x, x_lo, x_hi, y, y_lo, y_hi)",
            "x_hi must",
        ),
        ("sweep", ("Vb", [True], M), "sweep(model, param, values)", "values must"),
    ],
)
def test_the_old_order_still_works_with_one_warning(name, old, new, error):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        with pytest.raises(ValueError, match=error):
            getattr(beltmdsm, name)(*old)
    one_deprecation(record, new, "deprecated")


def test_the_old_order_reaches_the_same_computation():
    with pytest.warns(DeprecationWarning):
        old = beltmdsm.floquet_band("Vb", 5.2, 5.8, Model(beta1=0.3), points=3)
    new = beltmdsm.floquet_band(Model(beta1=0.3), "Vb", 5.2, 5.8, points=3)
    assert old.unstable == new.unstable and len(old.unstable) == 1


def test_model_parameters_as_keywords_go_to_the_model_with_one_warning():
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        old = beltmdsm.periodic_response(Vb=5.0)
    one_deprecation(record, "Model(Vb=5.0)", "model.replace(Vb=5.0)")
    new = beltmdsm.periodic_response(Model(Vb=5.0))
    np.testing.assert_array_equal(old.state0, new.state0)
    # a Model given too: replaced; the parameter's check is the model's
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match="parameter 'Vb'"):
        beltmdsm.simulate(M, Vb=-1.0)


@pytest.mark.parametrize(
    "call, hint",
    [
        (lambda: beltmdsm.simulate(M, t_edn=10), "did you mean 't_end'?"),
        (lambda: beltmdsm.floquet_band(M, "Vb", 1, 2, pionts=3), "did you mean 'points'?"),
        (lambda: beltmdsm.lyapunov(M, t_transeint=1), "did you mean 't_transient'?"),
        (lambda: beltmdsm.basins(M, executr="serial"), "did you mean 'executor'?"),
        (lambda: beltmdsm.simulate(M, Vbb=3), "did you mean the model parameter 'Vb'"),
        (lambda: beltmdsm.floquet(M, mu_ss=3), "did you mean the model parameter 'mu_s'"),
        (lambda: beltmdsm.simulate(M, start="periodic"), "periodic_start"),
    ],
)
def test_a_misspelt_keyword_fails_with_did_you_mean(call, hint):
    with pytest.raises(TypeError, match="unexpected keyword argument|start state") as caught:
        call()
    assert hint in str(caught.value), str(caught.value)


@pytest.mark.parametrize(
    "call, new, error",
    [
        (
            lambda: beltmdsm.floquet_map(M, "Vb", 1, 2, "beta1", 0.1, 0.2, rows=1),
            "points=",
            "points",
        ),
        (lambda: beltmdsm.floquet_map(M, "Vb", 2, 1, "beta1", 0.1, 0.2), None, "x_hi"),
        (
            lambda: beltmdsm.floquet_map(
                M, x="Vb", x_from=2, x_to=1, y="beta1", y_from=0.1, y_to=0.2
            ),
            "x_lo=",
            "x_hi",
        ),
        (lambda: beltmdsm.coexistence(M, "Vb", 1.0, 2.0, step=1.0), "points=", "step = 1"),
        (lambda: beltmdsm.basins(M, x_range=(2.0, 1.0)), "x_lo/x_hi=", "x_range"),
        (lambda: beltmdsm.predict(M, vb_max=-1.0), "hi=", "hi must"),
    ],
)
def test_renamed_keywords_still_work_naming_the_new_one(call, new, error):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        with pytest.raises(ValueError, match=error):
            call()
    if new is None:
        assert not record, [str(w.message) for w in record]
    else:
        one_deprecation(record, f"use {new}", "deprecated")


@pytest.mark.parametrize(
    "old, new, word",
    [
        (
            lambda: beltmdsm.predict(M, vb_max=8.0, points=10),
            lambda: beltmdsm.predict(M, hi=8.0, points=10),
            "use hi=",
        ),
        (
            lambda: beltmdsm.basins(
                M, x_range=(3.0, 7.0), y_range=(-8.5, -4.5), points=2, cache_dir=None
            ),
            lambda: beltmdsm.basins(
                M, x_lo=3.0, x_hi=7.0, y_lo=-8.5, y_hi=-4.5, points=2, cache_dir=None
            ),
            "use x_lo/x_hi=, y_lo/y_hi=",
        ),
    ],
    ids=["vb_max", "x_range"],
)
def test_a_renamed_keyword_computes_what_the_new_one_does(old, new, word):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        before = old()
    one_deprecation(record, word, "deprecated")
    assert before.as_dict() == new().as_dict()


def test_the_same_names_mean_the_same_everywhere():
    signatures = {n: inspect.signature(getattr(beltmdsm, n)).parameters for n in FUNCTIONS}
    signatures["validate"] = inspect.signature(beltmdsm.validate).parameters
    # one default of cache_dir, one of executor's meanings documented alike
    caches = {n: p["cache_dir"].default for n, p in signatures.items() if "cache_dir" in p}
    expected = {"sweep", "basins", "basin_stability", "validate"}  # basin_stability: issue 39
    assert set(caches) == expected and set(caches.values()) == {"default"}
    # ranges lo/hi, resolution points: none of the old spellings is a parameter
    old = {"x_from", "x_to", "y_from", "y_to", "x_range", "y_range", "vb_max", "rows", "step"}
    assert not any(old & set(p) for p in signatures.values())
    for name in ("floquet_band", "floquet_map", "coexistence", "basins", "predict"):
        assert "points" in signatures[name], name
    for name in ("floquet_band", "coexistence", "branch"):
        assert {"lo", "hi"} <= set(signatures[name]), name


@pytest.mark.parametrize("bad", ["proces", "threads", 2])
@pytest.mark.parametrize("name", ["sweep", "basins", "validate"])
def test_a_bad_executor_is_one_line_naming_the_choices(name, bad):
    call = {
        "sweep": lambda: beltmdsm.sweep(M, "Vb", [3.0], executor=bad, cache_dir=None),
        "basins": lambda: beltmdsm.basins(M, executor=bad, cache_dir=None),
        "validate": lambda: beltmdsm.validate(True, executor=bad, cache_dir=None, cases=[]),
    }[name]
    with pytest.raises(ValueError) as caught:
        call()
    text = str(caught.value)
    assert text.startswith("executor must be None (a process pool") and "\n" not in text
    assert "'serial' (in this process)" in text and repr(bad) in text


def test_executor_none_is_a_process_pool_in_basins_as_in_sweep(monkeypatch):
    from beltmdsm.basin import basins as basins_module

    class Started(Exception):
        pass

    def pool(workers):
        raise Started(workers)

    monkeypatch.setattr(basins_module, "process_pool", pool)
    with pytest.raises(Started) as caught:
        beltmdsm.basins(Model(Vb=3.88), executor=None, points=2, cache_dir=None)
    assert caught.value.args == (os.cpu_count(),)


# issue 36, item 10: each was computed, ignored, or failed with a raw TypeError /
# AttributeError deep inside; now one ValueError naming the argument, before anything runs
STRIBECK = Model(friction="stribeck", alpha=0.0, Vb=1.5)


@pytest.mark.parametrize(
    "call, name",
    [
        *[
            (lambda v=v: beltmdsm.cycle(STRIBECK, max_iter=v), "max_iter")
            for v in (-1, True, 0, 2.5)
        ],
        *[(lambda v=v: beltmdsm.cycle(STRIBECK, period=v), "period") for v in ("6", -1, math.nan)],
        *[
            (lambda v=v: beltmdsm.lyapunov(M, t_transient=v), "t_transient")
            for v in ("abc", True, [1])
        ],
        (lambda: beltmdsm.basins(M, attractors=[1]), "attractors"),
        (lambda: beltmdsm.basins(M, cache_dir=123), "cache_dir"),
        (lambda: beltmdsm.sweep(M, "Vb", [3.0], cache_dir=123), "cache_dir"),
        (lambda: beltmdsm.basins(M, t_end="x"), "t_end"),
        (lambda: beltmdsm.classify(M, t_end="x"), "t_end"),
        (lambda: beltmdsm.lyapunov(M, t_end=Fraction(-1)), "t_end"),
    ],
)
def test_a_bad_argument_is_one_value_error_naming_it(call, name):
    with pytest.raises(ValueError) as caught:
        call()
    assert str(caught.value).startswith(f"{name} must be "), str(caught.value)


@pytest.mark.parametrize(
    "value, answer",
    [
        (np.int64(1), "points must be an integer >= 2; got 1"),  # numpy integers: counted
        (3.0, "points must be an integer >= 2; got 3.0"),  # 3.0 is no count, anywhere
        (Fraction(3), "points must be an integer >= 2; got Fraction(3, 1)"),
    ],
)
def test_the_same_value_gets_the_same_answer_everywhere(value, answer):
    calls = [
        lambda: beltmdsm.floquet_band(M, "Vb", 1.0, 2.0, points=value),
        lambda: beltmdsm.basins(M, points=value, cache_dir=None),
        lambda: beltmdsm.floquet_map(M, "Vb", 1.0, 2.0, "beta1", 0.1, 0.2, points=value),
        lambda: beltmdsm.predict(M, points=value),
    ]
    for call in calls:
        with pytest.raises(ValueError) as caught:
            call()
        assert str(caught.value) == answer


def test_a_fraction_is_a_number_wherever_a_number_is_taken():
    # simulate took it, lyapunov refused it, periodic_attractor crashed (issue 36)
    from beltmdsm.attractors.classification import periodic_attractor

    with pytest.raises(ValueError, match=r"t_transient must be .* < t_end \(100\); got Fraction"):
        beltmdsm.lyapunov(M, t_end=Fraction(100), t_transient=Fraction(500))
    with pytest.raises(ValueError, match="t_end must be at least 22 excitation periods"):
        periodic_attractor(M, t_end=Fraction(10))
    assert beltmdsm.cycle(STRIBECK, max_iter=np.int32(30)).period == pytest.approx(6.654, abs=1e-3)


def test_dir_shows_the_public_names_only():
    shown = dir(beltmdsm)
    assert set(shown) == {*beltmdsm.__all__, "__version__"}
    for private in ("TYPE_CHECKING", "import_module", "map_siblings", "annotations"):
        assert private not in shown


def _beltmdsm(*args, timeout=120):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "beltmdsm", *args],
        capture_output=True, text=True, timeout=timeout, cwd=ROOT, env=env,
    )  # fmt: skip


def test_a_bare_beltmdsm_prints_help_and_derives_nothing():
    before = {p: p.stat().st_mtime_ns for p in (ROOT / "generated").glob("*.py")}
    done = _beltmdsm(timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("usage: python -m beltmdsm") and "--regenerate" in done.stdout
    assert "derived" not in done.stdout + done.stderr
    assert {p: p.stat().st_mtime_ns for p in (ROOT / "generated").glob("*.py")} == before


def test_a_typo_fails_in_mypy(tmp_path):
    pytest.importorskip("mypy", reason="mypy is in the test extra (pyproject.toml)")
    from test_public_types import _as_installed  # tests/beltmdsm/ is on the path

    site = tmp_path / "site"
    site.mkdir()
    script = tmp_path / "typos.py"
    script.write_text(
        "from beltmdsm import Model, floquet_band, simulate\n"
        "m = Model()\n"
        "simulate(m, t_edn=10.0)\n"
        'floquet_band(m, "Vb", 1.0, 2.0, pionts=3)\n'
        "simulate(m, t_end=10.0)\n"
    )
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--follow-imports=silent", "--no-incremental",
         "--cache-dir=/dev/null", str(script)],
        capture_output=True, text=True, cwd=_as_installed(site), timeout=300,
        env={k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MYPYPATH")},
    )  # fmt: skip
    errors = [line for line in done.stdout.splitlines() if ": error:" in line]
    assert len(errors) == 2, done.stdout
    assert 'typos.py:3: error: Unexpected keyword argument "t_edn"' in errors[0]
    assert "typos.py:4: error:" in errors[1]  # "no overload variant" of the model-first call
