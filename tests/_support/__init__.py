"""Support for the tests: shared problems with their exact solutions, oracles and reference codes.

Importable as ``_support`` because pyproject's pytest options put ``tests/`` on the path
(``pythonpath = ["tests"]``); no test module imports another test module.

- :mod:`_support.constants`  inch-pound conversion factors, written here independently of the package.
- :mod:`_support.problems`   the paper's 8 × 8 in plate problem (laminate, pulses) shared by the plate tests.
- :mod:`_support.plate_navier`  the FSDT Navier series of that plate (its exact solution).
- :mod:`_support.plain_plate`   a plain scikit-fem assembly of the same plate (a second, independent FE code).
- :mod:`_support.coupled`    the paper's long beam model and an independent explicit coupled integration.
- :mod:`_support.contract`   the output contract (golden master): commands, fingerprints, comparison.
- :mod:`_support.paper`      the paper report, computed once per test run and read back from disk.
- :mod:`_support.plastic_reference`  independent elastic–plastic strip and axisymmetric plate (the dent's references).
- :mod:`_support.small_cases`  a small beam case and a small plate case (TOML text) for the field-output and API tests.
"""
