"""Models as registry entries: any friction oscillator, derived whole (issue 39).

A model is one ``register("model", Oscillator(...))`` beside the laws
(docs/howto/own_model.md). Modules, one per concept:

* `beltmdsm.derive.models.entry`: what an entry gives (`Oscillator`, `Contact`,
  `Excitation`);
* `beltmdsm.derive.models.registry`: `register` (models and laws), its checks;
* `beltmdsm.derive.models.dimensions`: the units of the coordinates and their rates, the
  slip form's dimension check;
* `beltmdsm.derive.models.system`: the equations of motion of each mode, the derived
  holding force;
* `beltmdsm.derive.models.hybrid`: switching surfaces, saltation matrices, mode
  Jacobians;
* `beltmdsm.derive.models.steady`: steady sliding, its Jacobian, characteristic
  polynomial and Hurwitz determinants;
* `beltmdsm.derive.models.linearity`: whether the slip field is affine in the state
  (a degenerate Hopf point);
* `beltmdsm.derive.models.render`: generated/models/<name>.py;
* `beltmdsm.derive.models.entries`: the shipped models, ``paper`` (the default),
  ``belt_1dof``, ``hoffmann``.
"""

from . import entries  # noqa: E402, F401  (registers the shipped models)
from .entry import Contact, Excitation, Oscillator
from .registry import MODELS, UnsupportedModel, choices, default, get, register

__all__ = [
    "Oscillator",
    "Contact",
    "Excitation",
    "MODELS",
    "register",
    "UnsupportedModel",
    "choices",
    "default",
    "get",
]
