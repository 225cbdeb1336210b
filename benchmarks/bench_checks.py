"""What checking a model once saves per point of a Floquet band (issue 30, item 5).

A band evaluates `beltmdsm.floquet` at every value of its parameter: a `Model.replace`
of that value, then the generated functions the analysis binds or calls
(``beltmdsm.generated.hybrid.bind_*``, ``beltmdsm.generated.oscillator.bind_*``,
``beltmdsm.generated.unforced.equilibrium``, ...). Each part is timed both ways, in the same run:

* **ours**: `Model.replace` checks only the changed parameter; the generated functions
  take `Model.arguments`, whose parameters are marked as checked
  (``beltmdsm.generated._support.CHECKED``), and do not check them again;
* **baseline (checked again)**: the model built and checked whole from what it was
  built from (what `Model.replace` did before), and the generated functions given the
  same keywords without the mark, so that they check every parameter.

The argument checks a Floquet point makes are recorded from a real `floquet` call
and replayed. A whole point (a warm `floquet` continued from its neighbour) is timed
for scale. Run from the repository root: ``python -m benchmarks.bench_checks``.
"""

from __future__ import annotations

import time

from beltmdsm import Model, floquet
from beltmdsm.generated import _support

REPEAT = 2000


def _per_call(fn, repeat=REPEAT):
    """Best of 5 mean times of ``fn()`` over ``repeat`` calls [s]."""
    best = float("inf")
    for _ in range(5):
        t0 = time.perf_counter()
        for _ in range(repeat):
            fn()
        best = min(best, (time.perf_counter() - t0) / repeat)
    return best


def _recorded_checks(model):
    """The ``(checker, function, names, params)`` calls one `floquet` point makes."""
    calls, real = [], {}
    for name in ("arguments", "_scalar_arguments"):
        real[name] = getattr(_support, name)

        def record(function, names, params, _name=name):
            calls.append((real[_name], function, names, dict(params)))
            return real[_name](function, names, params)

        setattr(_support, name, record)
    try:
        floquet(model)
    finally:
        for name, fn in real.items():
            setattr(_support, name, fn)
    return calls


def main() -> None:
    model = Model(Vb=5)
    response = floquet(model)  # compiled and warm
    calls = _recorded_checks(model.replace(Vb=5.01))
    marked = [c for c in calls if _support.CHECKED in c[3]]
    stripped = [
        (fn, f, names, {k: v for k, v in p.items() if k != _support.CHECKED})
        for fn, f, names, p in calls
    ]

    def replay(rows):
        for fn, f, names, params in rows:
            fn(f, names, params)

    given = {**model._given, **model.options}
    ours_replace = _per_call(lambda: model.replace(Vb=5.01))
    base_replace = _per_call(lambda: Model(**{**given, "Vb": 5.01}))
    ours_calls = _per_call(lambda: replay(calls), REPEAT // 10)
    base_calls = _per_call(lambda: replay(stripped), REPEAT // 10)
    point = _per_call(lambda: floquet(model.replace(Vb=5.01), guess=response.response), 5)

    ours, base = ours_replace + ours_calls, base_replace + base_calls
    print(f"argument checks of one Floquet point: {len(calls)} calls, {len(marked)} marked checked")
    rows = [
        ("Model.replace", ours_replace, base_replace),
        ("generated argument checks", ours_calls, base_calls),
        ("per point", ours, base),
    ]
    for what, a, b in rows:
        print(f"{what:26s} ours {a * 1e6:7.1f} us  baseline (checked again) {b * 1e6:7.1f} us")
    print(f"saving per point: {(base - ours) * 1e6:.1f} us ({base / ours:.1f}x less checking)")
    print(f"a warm Floquet point: {point * 1e3:.2f} ms; the saving: {(base - ours) / point:.2%}")


if __name__ == "__main__":
    main()
