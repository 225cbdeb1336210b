"""Direct simulation of Eq. (4): event-driven integration, spectra, friction modulation, sweeps.

Imports ``generated`` (the code-generated model), numpy and scipy; never SymPy.

* `runtime.simulate`: `simulate` (solve_ivp with located events, stick and flight
  modes, regime, energy balance), `SolverSettings`.
* `runtime.superposition`: the fast integrator using the one-way coupling.
* `runtime.spectra`: amplitude spectrum, peak amplitudes, spectrogram (Fig. 2).
* `runtime.modulation`: friction loop (Fig. 3b), cycle averages (Figs. 10-12).
* `runtime.sweep`: sweeps on executors with a disk cache.
"""
from .simulate import REGIMES, Simulation, SolverSettings, simulate

__all__ = ["simulate", "Simulation", "SolverSettings", "REGIMES"]
