"""Any derived friction oscillator: the runtime of a model module (issue 39).

A model is a generated module ``beltmdsm.generated.models.<name>`` (or a module typed
to the same contract); `System` binds it to a friction law and parameter values, and
every analysis here reads the model through its kernels alone:

* `simulate` (`Trajectory`): the event-driven run with exact stick, slip reversal,
  flight where the contact is unilateral, and a Zeno guard;
* `steady_sliding` (`Equilibrium`) and `hopf_points`: the equilibrium, its eigenvalues
  and derived Hurwitz determinants, the Hopf points along a parameter;
* `cycle_seed` (`Seed`): where a settled run off steady sliding is on its cycle;
  `self_excited_cycle` (`Cycle`): a cycle of the unforced model by shooting, at its
  least period, with its Floquet multipliers (saltation matrices at every switch);
  `stick_onset`: a pure-slip cycle followed in a parameter to where it first touches
  ``v_r = 0``;
* `forced_response` (`Response`): the periodic response of the excitation's period,
  with its multipliers.

A run is compiled by numba with the model's kernels where they compile
(`beltmdsm.oscillator._compiled`, cached on disk like the paper's integrators); the
shooting's variational runs are plain numpy. See docs/howto/oscillator.md.
"""

from .cycle_seed import Seed, cycle_seed
from .cycles import Cycle, self_excited_cycle, stick_onset
from .equilibria import Equilibrium, hopf_points, steady_sliding
from .forced import Response, forced_response
from .hybrid import Trajectory, simulate
from .system import System, load_model

__all__ = [
    "System",
    "load_model",
    "simulate",
    "Trajectory",
    "steady_sliding",
    "Equilibrium",
    "hopf_points",
    "cycle_seed",
    "Seed",
    "self_excited_cycle",
    "Cycle",
    "stick_onset",
    "forced_response",
    "Response",
]
