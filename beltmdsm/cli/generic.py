"""The commands that run a model other than the paper's (``--model NAME``) on the generic
runtime `beltmdsm.oscillator`: ``simulate``, ``floquet`` (forced and autonomous) and
``branch`` (steady sliding's Hopf points, the self-excited cycle and its stick onset).

Each reads `beltmdsm.cli.models.system_from`'s `System`, refuses in one line every flag
that applies to the paper's model only, and names the model's states as the model does;
its JSON names the model (``"model": NAME``).
"""

from __future__ import annotations

import argparse
import json

import numpy as np

from .models import model_of, refuse_flags, system_from

__all__ = ["simulate", "floquet", "branch"]


def _jsonable(x):
    """``x`` for JSON: numpy as Python, a complex number as ``[re, im]``, NaN as None."""
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, (np.ndarray, np.generic)):
        return _jsonable(x.tolist())
    if isinstance(x, complex):  # as the paper's floquet writes its multipliers
        return [_jsonable(x.real), _jsonable(x.imag)]
    if isinstance(x, float) and not np.isfinite(x):
        return None
    return x


def _print(args, out: dict, lines: list[str]) -> None:
    print(json.dumps(_jsonable(out)) if args.json else "\n".join(lines))


def _pairs(values) -> list[list[float]]:
    """Multipliers or eigenvalues as ``[re, im]`` pairs (the paper's floquet's JSON)."""
    return [[float(z.real), float(z.imag)] for z in np.asarray(values, dtype=complex)]


def _named(states, values) -> dict[str, float]:
    return {name: float(v) for name, v in zip(states, values)}


def _switches(switches) -> list[dict]:
    return [{"t": float(t), "before": int(b), "after": int(a)} for t, b, a in switches]


def _head(system) -> str:
    given = ", ".join(f"{k}={v:g}" for k, v in system.params.items())
    return f"model {system.name} ({system.friction} friction): {given}"


def simulate(args: argparse.Namespace) -> int:
    """``simulate --model NAME``: one run of the model's hybrid system from its default
    start (steady sliding left along its least stable direction)."""
    from ..oscillator import simulate as run

    refuse_flags(
        args,
        ("start", "perturbation", "modulation", "png", "solver", "t_discard")
        + ("on_contact_loss",),
    )
    system = system_from(args)
    sim = run(system, args.t_end, dt=args.dt, rtol=args.rtol, atol=args.atol)
    attractor = _classified(args, system, sim.y[:, 0]) if args.classify else None
    out = {
        **system.as_dict(),
        "t_end": float(sim.t[-1]),
        "status": sim.status,
        "message": sim.message,
        "final": _named(system.states, sim.y[:, -1]),
        "ranges": {n: [float(row.min()), float(row.max())] for n, row in zip(system.states, sim.y)},
        "switches": len(sim.switches),
        "sticks": sum(1 for _, _, after in sim.switches if after == 0),
    }
    if args.save:
        np.savez(args.save, t=sim.t, modes=sim.modes, **dict(zip(system.states, sim.y)))
        out["saved"] = args.save
    lines = [
        _head(system),
        repr(sim),
        "final: " + ", ".join(f"{n} = {v:.10g}" for n, v in out["final"].items()),
        "ranges: "
        + ", ".join(
            f"{n} in [{a:.6g}, {b:.6g}] {u}"
            for (n, (a, b)), u in zip(out["ranges"].items(), system.units)
        ),
    ]
    if args.save:
        lines.append(f"samples written to {args.save}")
    if attractor is not None:
        out["attractor"] = attractor.as_dict()
        lines += [f"settles on: {attractor!r}", f"  {attractor.evidence}"]
    _print(args, out, lines)
    return 0 if sim.status == "done" else 2


def _classified(args: argparse.Namespace, system, y0):
    """``--classify``: `beltmdsm.classify` of the model from the run's start, over at
    least 2000 s (as the paper's ``simulate --classify``)."""
    from ..attractors.classification import classify

    return classify(model_of(system), y0=y0, t_end=max(2000.0, args.t_end))


def _cycle(c) -> dict:
    return {
        "kind": c.kind,
        "period": c.period,
        "state": _named(c.system.states, c.state),
        "multipliers": _pairs(c.multipliers),
        "trivial_multiplier": _pairs([c.trivial_multiplier])[0],
        "stable": c.stable,
        "sticks": c.sticks,
        "switches": _switches(c.switches),
        "residual": c.residual,
    }


def _state_line(label, system, state) -> str:
    return f"{label}: " + ", ".join(f"{n} = {v:.10g}" for n, v in zip(system.states, state))


def floquet(args: argparse.Namespace) -> int:
    """``floquet --model NAME``: the forced periodic response of ``--periods`` excitation
    periods, or without excitation the self-excited cycle; their Floquet multipliers."""
    from ..oscillator import forced_response, self_excited_cycle

    system = system_from(args)
    if system.excitation_period() is None:
        if args.periods != 1:
            args.parser.error(
                "argument --periods: the model is unforced (every excitation amplitude is 0): "
                "its self-excited cycle has no excitation period"
            )
        c = self_excited_cycle(system)
        out = {**system.as_dict(), "autonomous": True, **_cycle(c)}
        lines = [
            _head(system),
            repr(c),
            _state_line("state", system, c.state),
            "multipliers: " + ", ".join(f"{abs(m):.6g}" for m in c.multipliers),
            f"trivial multiplier: {abs(c.trivial_multiplier):.12g}",
        ]
    else:
        r = forced_response(system, periods=args.periods)
        out = {
            **system.as_dict(),
            "autonomous": False,
            "period": r.period,
            "periods": r.periods,
            "state": _named(system.states, r.state),
            "multipliers": _pairs(r.multipliers),
            "stable": r.stable,
            "sticks": r.sticks,
            "switches": _switches(r.switches),
            "residual": r.residual,
        }
        lines = [
            _head(system),
            repr(r),
            _state_line("state at phase 0", system, r.state),
            "multipliers: " + ", ".join(f"{abs(m):.6g}" for m in r.multipliers),
        ]
    _print(args, out, lines)
    return 0


def branch(args: argparse.Namespace) -> int:
    """``branch --model NAME``: steady sliding over ``--param`` in ``[--from, --to]``, its
    Hopf points by the derived Hurwitz determinants and its stability on each side; the
    pure-slip cycles born at each Hopf point, followed to their stick onset
    (`beltmdsm.oscillator.hopf_branch`)."""
    from ..oscillator import hopf_points, steady_sliding
    from ..oscillator.equilibria import no_hopf_reason
    from ..oscillator.hopf_branch import hopf_branch

    lo, hi = args.start, args.stop
    if not hi > lo:
        args.parser.error(f"argument --to: must be > --from ({lo:g}); got {hi:g}")
    system = system_from(args)
    if system.excitation_period() is not None:  # its forced response, continued
        from .generic_forced import branch as forced

        return forced(args)
    refuse_flags(args, ("png",))
    if args.param not in system.params:
        args.parser.error(
            f"argument --param: not a parameter of model {system.name!r} "
            f"({', '.join(system.params)}); got {args.param}"
        )
    points = hopf_points(system, args.param, lo, hi)
    rows = []
    for value in (lo, *points, hi):
        eq = steady_sliding(system.replace(**{args.param: float(value)}))
        rows.append(
            {
                args.param: float(value),
                "state": _named(system.states, eq.state),
                "stable": eq.stable,
                "growth_rate": eq.growth_rate,
                "eigenvalues": _pairs(eq.eigenvalues),
            }
        )
    branches = [hopf_branch(system, args.param, float(h), hi - lo, (lo, hi)) for h in points]
    none = "" if len(points) else no_hopf_reason(system, args.param, lo, hi)
    out = {
        **system.as_dict(),
        "param": args.param,
        "range": [lo, hi],
        "hopf_points": [float(v) for v in points],
        **({"no_hopf_point": none} if none else {}),
        "steady_sliding": rows,
        "cycle_branches": [_branch(b) for b in branches],
    }
    lines = [
        _head(system),
        f"steady sliding over {args.param} in [{lo:g}, {hi:g}]: Hopf points "
        + (", ".join(f"{v:.10g}" for v in points) or f"none: {none}"),
        *(
            f"  {args.param} = {r[args.param]:.10g}: "
            + ("Hopf point" if i and i < len(rows) - 1 else "stable" if r["stable"] else "unstable")
            + f", growth rate {r['growth_rate']:.6g}"
            for i, r in enumerate(rows)
        ),
        *(f"  cycles born at {args.param} = {b.hopf:.10g}: {b!r}" for b in branches),
    ]
    _print(args, out, lines)
    return 0


def _branch(b) -> dict:
    """A `beltmdsm.oscillator.hopf_branch.HopfBranch` for JSON."""
    return {
        "hopf": b.hopf,
        "side": b.side,
        "criticality": b.criticality,
        "cycles": [
            {
                b.param: c.system.params[b.param],
                "period": c.period,
                "stable": c.stable,
                "multipliers": _pairs(c.multipliers),
                "state": _named(c.system.states, c.state),
            }
            for c in b.cycles
        ],  # fmt: skip
        "stick_onset": None if b.onset is None else b.onset.system.params[b.param],
        "special_points": [s.as_dict() for s in b.special],
        "failure": b.failure,
        **({"degenerate": True, "note": b.note} if b.degenerate else {}),
    }
