"""Studies: steps of the chain that compose several workflows (one level above :mod:`softimpact.workflows`,
whose modules import no other workflow; beside :mod:`softimpact.input` and :mod:`softimpact.output`).

- :mod:`softimpact.studies.series`: a bar test series conditioned, reduced and fitted (α1–α4)
  (conditioning + reduction + scaling).
- :mod:`softimpact.studies.calibration`: the calibration of a beam's force history on a ladder
  of refined models (beam_impact + refinement + calibration + convergence + scaling).
- :mod:`softimpact.studies.references`: what the paper's references can tell: the beams' first zero
  crossing against the free length and clamp compliance, and bar series made with another α3.
- :mod:`softimpact.studies.tasks`: a multi-part study's parts run as tasks on the machine's cores, what they share
  computed once.
- :mod:`softimpact.studies.paper`: the paper report's computations (the identified law, threshold maps, hail map).
"""
