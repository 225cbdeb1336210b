"""Direct simulation of Eq. (4): event-driven integration, spectra, sweeps, stability.

Imports ``generated`` (the code-generated model), numpy and scipy; never SymPy.
`simulate` runs Eq. (4) as a hybrid system with one of two solvers: ``"events"``
(the default: a compiled DOP853 with dense output, runtime/_dop853.py, driven mode by
mode through located switches by `runtime.events`) or ``"superposition"`` (the
normal motion once, the tangential motion in closed form between switches; it falls
back to ``"events"`` where it does not apply).

* `runtime.parameters`: `resolve_parameters` (the base set completed and checked),
  `initial_state` (the unforced equilibrium, Eq. 9), `excitation_period`, limits.
* `runtime.model`: the tension laws (`TENSIONS`), the modes and their names; re-exports
  `resolve_parameters` and `initial_state`.
* `runtime.switching`: the guard table and Filippov's rules: which mode follows a switch.
* `runtime.events`: the event-driven integrator, one smooth mode at a time, with
  Zeno detection.
* `runtime.normal`: the normal motion, integrated once and cached across a sweep.
* `runtime.superposition`: the fast integrator using the one-way coupling.
* `runtime.trajectory`: `Trajectory`, smooth segments between switches: state,
  forces, quadrature, energy balance (Sect. 3).
* `runtime.simulate`: `simulate`, `SolverSettings`, `Simulation`, and `summarize`
  (regime, peaks, energy balance, whether the window resolves the omega1 peak).
* `runtime.spectra`: amplitude spectrum, peak amplitudes, spectrogram (Fig. 2).
* `runtime.modulation`: friction loop (Fig. 3b), cycle averages (Figs. 10-12).
* `runtime.sweep`: sweeps on executors with a disk cache, continued up or down.
* `runtime.floquet`: the periodic response and its Floquet multipliers, with
  saltation matrices; the bands of a parameter where it is unstable.
* `runtime.predict`: predicted unstable belt speeds, the paper's analysis and a
  consistent MDSM.
* `runtime.validation`: the validation table (``VALIDATION.md``): predicted unstable
  belt speeds against simulated sweeps and the Floquet bands.
* `runtime.intervals`: runs on a grid, set algebra of intervals, their text.
* `runtime.cli`: the runtime commands of ``python -m derive`` (simulate, sweep,
  predict, validate, floquet, floquet-band).
"""

from .simulate import REGIMES, Simulation, SolverSettings, simulate

__all__ = ["simulate", "Simulation", "SolverSettings", "REGIMES"]
