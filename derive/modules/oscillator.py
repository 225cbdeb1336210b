"""The tangential oscillator in closed form: the spec of generated/oscillator.py."""

from __future__ import annotations

from .. import capabilities as cap
from .. import laws
from .. import oscillator as osc
from ..codegen import FunctionSpec, ModuleSpec
from ..model import t
from ._shared import (
    FRICTION,
    STATE_DOCS,
    _or_refuse,
)

__all__ = ["build"]


#: The arguments of `beltmdsm.generated.oscillator.tangential_state` after ``tau``.
SUPERPOSITION_DOCS = {
    "X1_0": "tangential displacement at the switch t0 [m]",
    "Y1_0": "tangential velocity X1' at the switch t0 [m/s]",
    "zf_0": "excitation response at t0 (`excitation_response`) [m]",
    "vf_0": "its rate at t0 [m/s]",
    "z_0": "response to the contact force at t0 (per unit friction coefficient) [m]",
    "v_0": "its rate at t0 [m/s]",
    "zf": "excitation response at t0 + tau [m]",
    "vf": "its rate at t0 + tau [m/s]",
    "z": "response to the contact force at t0 + tau [m]",
    "v": "its rate at t0 + tau [m/s]",
    "sgn": "friction direction of the mode: -1 (mass slower than the belt), +1, "
    "or 0 (flight or separation: no friction)",
}


def build() -> ModuleSpec:
    """The tangential oscillator in closed form: state-transition matrix, forced response,
    their superposition."""
    docs = {"tau": "time since the switch [s], >= 0", **STATE_DOCS}
    fns = (
        FunctionSpec(
            "state_transition",
            "State-transition matrix expm(A tau) of the tangential oscillator.",
            "Eq. (4), first row",
            "matrix",
            "Phi : ndarray, shape (..., 2, 2)\n    (X1, X1')(t0 + tau) = Phi (X1, "
            "X1')(t0) without forcing.",
            {(): osc.state_transition()},
            (),
            (osc.tau,),
            docs,
            notes="Under-, over- and critically damped closed forms; exact at "
            "beta1 = 1, no overflow for long tau (derive/oscillator.py).",
            bind=True,
            examples=(
                "Its determinant is exp(-2 beta1 omega1 tau) (Liouville); critically damped\n"
                "(beta1 = 1) Phi[0, 0] = (1 + tau) exp(-tau):\n"
                "\n"
                ">>> from beltmdsm.generated import oscillator\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> import math, numpy as np\n"
                ">>> Phi = oscillator.state_transition(2.0, **BASE)\n"
                ">>> round(float(np.linalg.det(Phi)), 4), round(math.exp(-2 * 0.1 * 2.0), 4)\n"
                "(0.6703, 0.6703)\n"
                '>>> Phi = oscillator.state_transition(1.0, **{**BASE, "beta1": 1.0})\n'
                ">>> round(float(Phi[0, 0]), 4), round(2 * math.exp(-1.0), 4)\n"
                "(0.7358, 0.7358)"
            ),
            bind_examples=(
                "The kernel at one point gives `state_transition` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import oscillator\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.7,)\n"
                '>>> kernel = oscillator.bind_state_transition(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0).tolist()\n"
                "[0.7754, 0.6012, -0.6012, 0.6551]\n"
                ">>> ref = oscillator.state_transition(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
        ),
        FunctionSpec(
            "excitation_response",
            "Response (X1, X1') to the tangential excitation from rest at t = 0.",
            "Eq. (4), first row",
            "tuple",
            "X1, Y1 : ndarray",
            {(): list(osc.excitation_response())},
            (),
            (t,),
            docs,
            notes="The periodic response minus the free motion that cancels its "
            "initial value. Not finite at undamped resonance (beta1 = 0, "
            "Omega_t = omega1).",
            bind=True,
            examples=(
                "From rest at t = 0, and Y1 is the rate of X1 (a central difference):\n"
                "\n"
                ">>> from beltmdsm.generated import oscillator\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> [float(v) for v in oscillator.excitation_response(0.0, **BASE)]\n"
                "[0.0, 0.0]\n"
                ">>> X1, Y1 = oscillator.excitation_response(1.0, **BASE)\n"
                ">>> h = 1e-5\n"
                ">>> Xp, _ = oscillator.excitation_response(1.0 + h, **BASE)\n"
                ">>> Xm, _ = oscillator.excitation_response(1.0 - h, **BASE)\n"
                ">>> round(float(Y1), 4), round(float((Xp - Xm) / (2 * h)), 4)\n"
                "(8.6753, 8.6753)"
            ),
            bind_examples=(
                "The kernel at one point gives `excitation_response` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import oscillator\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.7,)\n"
                '>>> kernel = oscillator.bind_excitation_response(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0).tolist()\n"
                "[4.5977, 13.6758]\n"
                ">>> ref = oscillator.excitation_response(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
        ),
        FunctionSpec(
            "tangential_state",
            "(X1, X1') at t0 + tau of a mode entered at t0: the superposition.",
            "Eq. (4), first row",
            "tuple",
            "X1, Y1 : ndarray\n    The tangential state at t0 + tau.",
            {
                (f,): _or_refuse(
                    None if osc.tangential_state(f) is None else list(osc.tangential_state(f)),
                    cap.slip_friction_state_independent(f, laws.default("contact"))[1]
                    + ": the tangential motion of a slip mode is no superposition",
                )
                for f in laws.choices("friction")
            },
            FRICTION,
            (osc.tau, *osc.SUPERPOSITION_ARGS),
            {**docs, **SUPERPOSITION_DOCS},
            notes="Phi(tau) (x0 - f(t0)) + f(t) with f = zf - mu sgn z: the free motion "
            "from the state at the switch and the forced responses, zf to the "
            "excitation (`excitation_response`) and z to the contact force (integrated "
            "with the normal motion, beltmdsm.generated.hybrid.response_field), both from rest "
            "at t = 0 (derive/oscillator.py). Exact for a friction law whose slip-mode "
            "friction mu sgn F does not depend on the tangential state.",
            bind=True,
            examples=(
                "Without forcing (every response 0, sgn = 0) it is the free motion\n"
                "Phi(tau) (X1_0, Y1_0):\n"
                "\n"
                ">>> from beltmdsm.generated import oscillator\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> X1, Y1 = oscillator.tangential_state(2.0, 1.0, 0.0, *[0.0] * 8, 0, **BASE)\n"
                ">>> Phi = oscillator.state_transition(2.0, **BASE)\n"
                ">>> [round(float(v), 4) for v in (X1, Y1)], Phi[:, 0].round(4).tolist()\n"
                "([-0.2581, -0.7516], [-0.2581, -0.7516])"
            ),
            bind_examples=(
                "The kernel at one point gives `tangential_state` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import oscillator\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.7, 1.0, 0.5, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, -1)\n"
                '>>> kernel = oscillator.bind_tangential_state(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0).tolist()\n"
                "[1.4689, 0.5428]\n"
                ">>> ref = oscillator.tangential_state(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
        ),
    )
    return ModuleSpec(
        "oscillator",
        """The tangential oscillator of Eq. (4) in closed form.

Between two switches the tangential motion is linear: the state-transition matrix
carries the state at the switch, the excitation response and the response to the
contact force (integrated by the runtime) add to it (derive/oscillator.py);
`tangential_state` is that superposition.
""",
        fns,
    )
