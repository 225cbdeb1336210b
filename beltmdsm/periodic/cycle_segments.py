"""Multiple shooting of a self-excited cycle: ``m`` segments of ``T / m`` each.

Single shooting (`beltmdsm.periodic.cycle_flow`) solves ``phi_T(x) = x``: a cycle whose
largest multiplier is ``mu`` amplifies every error of the run (its rounding, the
tolerance ``RTOL``) by ``|mu|`` before it reaches the residual, so above about ``1e3``
the residual's noise passes Newton's tolerance and the corrector's steps shrink
towards nothing. Multiple shooting takes the states ``x_0 .. x_{m-1}`` at ``t = i T /
m`` as unknowns, with the continuity conditions

    G_i = phi_{T/m}(x_i; p) - x_{i+1}   (i = 0 .. m-1, x_m = x_0)

and the one phase condition ``h(x_0) = 0`` of `CycleFlow.section`; the period ``T``
and the parameter ``p`` are unknowns too. Each segment amplifies by its own
monodromy ``M_i`` only, about ``|mu|^(1/m)``. The Jacobian is block-cyclic:
``dG_i/dx_i = M_i``, ``dG_i/dx_{i+1} = -I``, ``dG_i/dT = f(phi_i) / m``, ``dG_i/dp``
by central differences; the Floquet multipliers are the eigenvalues of the product
``M_{m-1} ... M_0`` (the monodromy of the whole period, each factor well conditioned).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from .cycle_flow import P_STEP, CycleFlow, FlowImage

__all__ = [
    "SegmentImages",
    "segment_images",
    "continuity",
    "product_monodromy",
    "segment_jacobian",
    "p_column",
    "whole",
    "split_run",
]


@dataclass
class SegmentImages(FlowImage):
    """A cycle shot in segments: `FlowImage` of the whole period (``state`` the end of
    the last segment, ``monodromy`` the product of the segments', ``field`` at the
    end, ``run`` one run over the period from ``x_0`` for the observables), with the
    segments' starts and images.

    Attributes
    ----------
    states : numpy.ndarray, shape (m, 4)
        ``x_0 .. x_{m-1}``.
    segments : list of FlowImage
        ``phi_{T/m}(x_i)``, ``M_i`` and the field there, per segment.
    """

    states: NDArray[np.float64] = field(default=None, repr=False)
    segments: list = field(default_factory=list, repr=False)


def segment_images(flow: CycleFlow, states, T: float, p: float, monodromy=True) -> list:
    """``phi_{T/m}(x_i; p)`` (with ``M_i`` where ``monodromy``) for each row of ``states``."""
    m = len(states)
    return [flow.image(x, T / m, p, monodromy) for x in np.asarray(states, float)]


def continuity(states, images) -> NDArray[np.float64]:
    """``G_i = phi_{T/m}(x_i) - x_{i+1}`` (``x_m = x_0``), shape (m, 4).

    Examples
    --------
    Three segments whose images land on the next start close up, but for the last:

    >>> from types import SimpleNamespace
    >>> xs = np.arange(12.0).reshape(3, 4)
    >>> images = [SimpleNamespace(state=xs[1]), SimpleNamespace(state=xs[2]),
    ...           SimpleNamespace(state=xs[0] + 1e-3)]
    >>> np.round(continuity(xs, images), 12).tolist()[2]
    [0.001, 0.001, 0.001, 0.001]
    """
    states = np.asarray(states, float)
    ends = np.array([img.state for img in images])
    return ends - np.roll(states, -1, axis=0)


def product_monodromy(images) -> NDArray[np.float64]:
    """``M_{m-1} ... M_0``: the monodromy of the whole period.

    Examples
    --------
    Two segments that each double the first coordinate and halve the second:

    >>> from types import SimpleNamespace
    >>> half = SimpleNamespace(monodromy=np.diag([2.0, 0.5, 1.0, 1.0]))
    >>> np.diag(product_monodromy([half, half])).tolist()
    [4.0, 0.25, 1.0, 1.0]
    """
    M = np.eye(4)
    for img in images:
        M = img.monodromy @ M
    return M


def segment_jacobian(flow: CycleFlow, states, T: float, p: float, images, column=True):
    """The unscaled Jacobian of ``(G_0 .. G_{m-1}, h(x_0))`` in ``(x_0 .. x_{m-1}, T,
    p)``: shape ``(4m + 1, 4m + 2)``; the ``p`` column by central differences (zeros
    where ``column`` is False, for the caller to fill in).

    Examples
    --------
    Against central differences of the residual, on the stick-slip cycle at ``Vb =
    1.5`` in 3 segments: see tests/beltmdsm/cycles/test_multiple_shooting.py.
    """
    states = np.asarray(states, float)
    m = len(states)
    J = np.zeros((4 * m + 1, 4 * m + 2))
    for i, img in enumerate(images):
        r = slice(4 * i, 4 * i + 4)
        J[r, 4 * i : 4 * i + 4] = img.monodromy
        k = (i + 1) % m
        J[r, 4 * k : 4 * k + 4] -= np.eye(4)
        J[r, 4 * m] = img.field / m
    J[4 * m, :4] = flow.section_gradient(states[0], p)
    if column:
        J[:, 4 * m + 1] = p_column(flow, states, T, p)
    return J


def p_column(flow: CycleFlow, states, T: float, p: float) -> NDArray[np.float64]:
    """``dG_i/dp`` and ``dh(x_0)/dp`` by central differences (as `CycleFlow.p_column`)."""
    h = P_STEP * max(1.0, abs(p))
    up = segment_images(flow, states, T, p + h, monodromy=False)
    down = segment_images(flow, states, T, p - h, monodromy=False)
    dG = (np.array([u.state for u in up]) - np.array([d.state for d in down])) / (2 * h)
    dh = (flow.section(states[0], p + h) - flow.section(states[0], p - h)) / (2 * h)
    return np.append(dG.ravel(), dh)


def whole(flow: CycleFlow, states, T: float, p: float, images) -> SegmentImages:
    """The `SegmentImages` of a solved set of segments (one more run, over the whole
    period from ``x_0``, for the observables: its end is not used)."""
    states = np.asarray(states, float)
    last = images[-1]
    return SegmentImages(
        last.state,
        product_monodromy(images),
        last.field,
        flow.run(states[0], T, p),
        states,
        list(images),
    )


def split_run(flow: CycleFlow, x, T: float, p: float, m: int) -> NDArray[np.float64]:
    """The states at ``t = i T / m`` of one run from ``x`` (a start for the segments)."""
    tr = flow.run(x, T, p).trajectory
    return tr.state(np.arange(m) * (T / m)).T.copy()
