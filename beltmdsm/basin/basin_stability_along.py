"""Basin stability along a parameter: each attractor's share, matched by continuation.

`basin_stability_along` estimates basin stability (`beltmdsm.basin.basin_stability`)
at ``points`` values of a parameter with the same starts at every value (one seed:
common random numbers, so the curves are smooth where the basins change smoothly).
An attractor at one value is the same as at another where continuation says so, not
where its features look alike (bSTAB clusters features; Attractors.jl's
``global_continuation`` matches by distance):

* **steady sliding** is one branch (Eq. 9 at every value), an attractor where its
  eigenvalues lie in the left half-plane: it is born or dies at a Hopf point
  (`beltmdsm.cycles.hopf.hopf_points`);
* a **cycle** belongs to a stable part of the branch of cycles through the Hopf point
  (`beltmdsm.cycles.branch.cycle_branch`, computed once over the whole range), the part
  whose points bracket the value nearest to it; the part's ends name where it is born
  or dies: ``stick_onset`` (grazing-sliding), ``fold``, ``hopf``, ``period_doubling``...
  A stable cycle on no part of the branch (the seed's, off it) is listed as such.
"""

from __future__ import annotations

import concurrent.futures as cf
import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..model import MODEL_PARAMETERS, Model, as_model
from .basin_stability import BasinStability, basin_stability, branch_range, landscape_of

__all__ = ["BasinStabilityAlong", "Edge", "basin_stability_along", "MAX_POINTS"]

#: Most parameter values of one study.
MAX_POINTS = 200


@dataclass(frozen=True)
class Edge:
    """Where an attractor of the study is born or dies.

    Attributes
    ----------
    attractor : str
    value : float
    kind : str
        The bifurcation: ``hopf``, ``stick_onset``, ``fold``...
    event : {"born", "dies"}
        Along increasing values of the parameter.

    See Also
    --------
    basin_stability_along : lists them.

    Examples
    --------
    >>> Edge("steady sliding", 1.151293, "hopf", "born").as_dict()["kind"]
    'hopf'
    """

    attractor: str
    value: float
    kind: str
    event: str

    def as_dict(self) -> dict:
        return {"attractor": self.attractor, "value": self.value, "kind": self.kind,
                "event": self.event}  # fmt: skip


@dataclass
class BasinStabilityAlong:
    """Basin stability at each value of a parameter (module docstring).

    Attributes
    ----------
    param : str
    values : ndarray (K,)
    names : list of str
        The attractors, matched by continuation (columns of ``fractions``).
    fractions, errors : ndarray (K, len(names))
        Each attractor's share and standard error at each value (0 where absent).
    unidentified : ndarray (K,) of int
    edges : list of Edge
    results : list of BasinStability
    branch : CycleBranch or None

    See Also
    --------
    basin_stability_along : computes it.
    """

    param: str
    values: NDArray[np.float64] = field(repr=False)
    names: list[str]
    fractions: NDArray[np.float64] = field(repr=False)
    errors: NDArray[np.float64] = field(repr=False)
    unidentified: NDArray[np.int_] = field(repr=False)
    edges: list[Edge]
    results: list[BasinStability] = field(repr=False)
    branch: Any = field(repr=False, default=None)

    def __repr__(self) -> str:
        lo, hi = self.values[0], self.values[-1]
        edges = ", ".join(f"{e.attractor} {e.event} at {e.kind} {e.value:.6g}" for e in self.edges)
        return (
            f"BasinStabilityAlong({self.param} in [{lo:.6g}, {hi:.6g}], {len(self.values)} "
            f"values, {self.results[0].samples} starts each: {', '.join(self.names)}"
            + (f"; {edges}" if edges else "")
            + ")"
        )

    def to_pandas(self):
        """A `pandas.DataFrame`, one row per value and attractor: ``param``'s value,
        ``attractor``, ``fraction``, ``standard_error``, ``samples``."""
        from .._tables import frame

        rows = [
            {self.param: float(v), "attractor": name, "fraction": float(self.fractions[k, j]),
             "standard_error": float(self.errors[k, j]), "samples": self.results[k].samples}
            for k, v in enumerate(self.values)
            for j, name in enumerate(self.names)
        ]  # fmt: skip
        return frame(rows, [self.param, "attractor", "fraction", "standard_error", "samples"])

    def as_dict(self) -> dict:
        """JSON-ready: ``param``, ``values``, ``attractors`` (name, fraction and
        standard_error per value), ``unidentified``, ``edges``, ``samples``, ``seed``."""
        return {
            "param": self.param,
            "values": [float(v) for v in self.values],
            "attractors": [
                {
                    "name": name,
                    "fraction": self.fractions[:, j].tolist(),
                    "standard_error": self.errors[:, j].tolist(),
                }
                for j, name in enumerate(self.names)
            ],  # fmt: skip
            "unidentified": self.unidentified.tolist(),
            "edges": [e.as_dict() for e in self.edges],
            "samples": self.results[0].samples,
            "seed": self.results[0].seed,
        }

    def plot(self, ax: Any = None) -> Any:
        """The fractions stacked against the parameter, the edges marked (vertical lines
        named by their bifurcation), on matplotlib axes ``ax`` (new ones if None)."""
        import matplotlib.pyplot as plt

        if ax is None:
            ax = plt.figure(figsize=(7, 4)).add_subplot()
        ax.stackplot(self.values, self.fractions.T, labels=self.names, alpha=0.7)
        for e in self.edges:
            ax.axvline(e.value, color="k", ls="--", lw=0.8)
            ax.text(e.value, 1.01, f"{e.kind} {e.value:.4g}", rotation=90, va="bottom",
                    ha="center", fontsize="x-small")  # fmt: skip
        ax.set_xlabel(self.param)
        ax.set_ylabel("basin stability")
        ax.set_ylim(0, 1)
        ax.legend(loc="lower left", fontsize="small")
        return ax


def _point_parts(branch):
    """The index of the part of ``branch`` each of its points lies on: the part of the
    same stability whose range holds its value (the first, where several do)."""
    parts = branch.parts()
    out = []
    for p in branch.points:
        on = [j for j, q in enumerate(parts)
              if q.stable == p.stable and q.range[0] <= p.value <= q.range[1]]  # fmt: skip
        out.append(on[0] if on else None)
    return out


def _identify(s, branch, parts, value):
    """The name of the stable set ``s`` at ``value`` and the part it lies on (None)."""
    if s.kind == "equilibrium":
        return "steady sliding", None
    if branch is not None:
        best = None
        for i, (a, b) in enumerate(zip(branch.points, branch.points[1:])):
            if (a.value - value) * (b.value - value) <= 0:
                gap = float(np.max(np.abs(a.state[:2] - s.state[:2])))
                if abs(a.period - s.period) < 0.05 * s.period and (best is None or gap < best[0]):
                    best = (gap, parts[i])
        if best is not None and best[1] is not None:
            part = branch.parts()[best[1]]
            return f"{s.name} ({part.lower} to {part.upper})", best[1]
    return f"{s.name} (not on the branch)", None


def basin_stability_along(
    model: Model | None = None,
    region: dict | None = None,
    *,
    param: str = "Vb",
    lo: float,
    hi: float,
    points: int = 5,
    samples: int = 1000,
    seed: int = 0,
    executor: cf.Executor | str | None = "serial",
    cache_dir: os.PathLike | str | None = "default",
    progress: bool = False,
) -> BasinStabilityAlong:
    """Basin stability at ``points`` values of ``param`` in ``[lo, hi]`` (module
    docstring).

    Parameters
    ----------
    model : Model, optional
        Without excitation (`beltmdsm.Model`; a dict of its keywords is taken too).
    region : dict of str to (float, float)
        The box of starts (`beltmdsm.basin.basin_stability.basin_stability`).
    param : str
        A model parameter.
    lo, hi : float
    points : int
        Values, evenly spaced, ends included.
    samples, seed, executor, cache_dir, progress
        As `beltmdsm.basin.basin_stability.basin_stability`'s, at each value.

    Returns
    -------
    BasinStabilityAlong

    Raises
    ------
    ValueError
        For an unknown parameter, a bad range or ``points``, a forced model, and as
        `beltmdsm.basin.basin_stability.basin_stability`.

    See Also
    --------
    beltmdsm.basin.basin_stability.basin_stability : at one value.
    beltmdsm.cycles.branch.cycle_branch : the branch the cycles are matched on.

    Examples
    --------
    The friction oscillator of bSTAB and pyBasin: steady sliding becomes stable at the
    Hopf point (``0.5 ln 10``), the stick-slip cycle ends at the stick onset:

    >>> from beltmdsm import Model
    >>> m = Model(alpha=0.0, omega1=1.0, beta1=0.05, g=1.0, friction="stribeck",
    ...           mu_s=1.0, mu_k=0.5, v_s=0.5)
    >>> r = basin_stability_along(m, {"X1": (-2.0, 2.0), "Y1": (0.0, 2.0)}, lo=1.0, hi=2.0,
    ...                           points=3, samples=50)
    >>> [(e.kind, round(e.value, 6), e.event) for e in r.edges]
    [('hopf', 1.151293, 'born'), ('stick_onset', 1.836601, 'dies')]
    >>> r.fractions[:, r.names.index("steady sliding")].tolist()
    [0.0, 0.32, 1.0]
    """
    from ..cycles.branch import cycle_branch
    from ..cycles.hopf import hopf_points
    from ..starts.cycle_seed import require_autonomous

    model = as_model(model)
    require_autonomous(model, "basin stability along a parameter")
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo}, {hi}]")
    if isinstance(points, bool) or not isinstance(points, int) or not 2 <= points <= MAX_POINTS:
        raise ValueError(f"points must be an integer in [2, {MAX_POINTS}]; got {points!r}")
    values = np.linspace(lo, hi, points)
    span = branch_range(model, param, [lo, hi])
    branch = None if span is None else cycle_branch(model, param=param, lo=span[0], hi=span[1])
    parts = [] if branch is None else _point_parts(branch)
    results, keys, present = [], [], []
    for v in values:
        at = model.replace(**{param: float(v)})
        ls = landscape_of(at, branch)
        r = basin_stability(
            at, region, samples=samples, seed=seed, executor=executor,
            cache_dir=cache_dir, progress=progress, landscape=ls,
        )  # fmt: skip
        results.append(r)
        named = [_identify(s, branch, parts, float(v)) for s in r.attractors]
        present.append(named)
        keys += [n for n, _ in named if n not in keys]
    fractions = np.zeros((points, len(keys)))
    errors = np.zeros((points, len(keys)))
    for k, (r, named) in enumerate(zip(results, present)):
        for label, (name, _) in enumerate(named):
            fractions[k, keys.index(name)], errors[k, keys.index(name)] = r.fraction(label)
    edges = _edges(model, param, lo, hi, branch, present, keys, hopf_points)
    unidentified = np.array([r.unidentified for r in results])
    return BasinStabilityAlong(
        param, values, keys, fractions, errors, unidentified, edges, results, branch
    )


def _edges(model, param, lo, hi, branch, present, keys, hopf_points):
    """Where each attractor is born or dies inside ``[lo, hi]``: steady sliding at the
    Hopf points, a cycle at the ends of its stable part."""
    edges = []
    if "steady sliding" in keys:
        for h in hopf_points(model, param, lo, hi):
            grows = h.transversality > 0  # the pair's real part grows with the parameter
            edges.append(Edge("steady sliding", h.value, "hopf", "dies" if grows else "born"))
    if branch is not None:
        parts = branch.parts()
        for named in present:
            for name, j in named:
                if j is None or any(e.attractor == name for e in edges):
                    continue
                part = parts[j]
                for value, kind, event in ((part.range[0], part.lower, "born"),
                                           (part.range[1], part.upper, "dies")):  # fmt: skip
                    if kind != "range" and lo < value < hi:
                        edges.append(Edge(name, value, kind, event))
    return sorted(edges, key=lambda e: e.value)
