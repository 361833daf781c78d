"""The paper report's computations, one module per part that several of the report's sections share or that costs
enough to run as a task of its own (:mod:`softimpact.studies.tasks`); :mod:`softimpact.app.paper` composes their
results into sections.

- :mod:`~softimpact.studies.paper.series`: the built-in rubber-ball series reduced and fitted (Table I).
- :mod:`~softimpact.studies.paper.thresholds`: the identified contact law, the threshold and onset maps per
  structure, the plate's maps on both kinematics and the beams' large-deflection check.
- :mod:`~softimpact.studies.paper.hail`: the hail map on Rhymer's panels, panel by panel, linear and von Kármán.
"""
