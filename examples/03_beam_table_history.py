"""
A beam under a Table II force history
=====================================

The long laminated cantilever of the paper (``paper-long-beam``, Figs 18–22) loaded by the
second row of Table II: the eq-(15) history of peak F0 = 90 lbf and duration T = 250 µs
(``softimpact beam paper-long-beam --history 2``).

Checked against a closed form: eq (15) is a half-sine in a skewed time, so its impulse is
2·F0·T/π whatever the time of peak; the applied force integrates to it.
"""

# %%
# ``si.load`` reads any case file or built-in case (``history=2``: row 2 of its
# ``[[load.table]]``); ``si.run`` runs it as its command would. ``figures=False`` keeps no
# displacement history (no deformed-shape figures, no ``write_fields``).
import numpy as np

import softimpact as si

case = si.load("paper-long-beam", history=2)
res = si.run(case, figures=False)
print(case.kind, res.problem.title)

# %%
# The gauge strains (tension +); ``res.to_frame()`` holds the same histories as a pandas
# DataFrame indexed by time, the columns of ``history.csv``.
ax = res.plot()
print(res.to_frame().describe().T[["min", "max"]])

# %%
# One number: the impulse of the applied force against 2·F0·T/π (eq 15, Table II row 2,
# written out from the paper).
F0, T = 90 * 4.4482216152605, 250e-6  # lbf → N, µs → s
expected = 2 * F0 * T / np.pi
impulse = np.trapezoid(res.force, res.time)
assert abs(impulse / expected - 1) < 0.01, (impulse, expected)
