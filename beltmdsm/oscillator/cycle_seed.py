"""Where a self-excited cycle's seed run starts: steady sliding moved along its least
stable direction, and the stick state over steady sliding.
"""

from __future__ import annotations

import numpy as np

from .equilibria import steady_sliding
from .hybrid import _to_stick


def _starts(system):
    """Steady sliding moved along its least stable direction, where it grows; and the
    stick state over steady sliding (its position, the slip velocity 0), from which a
    stick-slip cycle coexisting with stable sliding is reached."""
    eq = steady_sliding(system)
    out = []
    if eq.growth_rate > 1e-9 * np.abs(eq.eigenvalues).max():
        J = np.asarray(system.kernels.jacobian(0.0, eq.state, system.p, eq.mode))
        w, V = np.linalg.eig(J)
        v = np.real(V[:, np.argmax(w.real)])
        out.append(eq.state + 1e-3 * (1.0 + np.abs(eq.state).max()) * v / np.abs(v).max())
    out.append(_to_stick(system, 0.0, eq.state))
    return out


def _moving(system, seed):
    """Whether a run ends away from steady sliding (not decayed onto it)."""
    eq = steady_sliding(system)
    return np.abs(seed.y - eq.state).max() > 1e-6 * (1.0 + np.abs(eq.state).max())
