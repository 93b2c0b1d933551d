"""The layouts the compiled rocking kernel shares with the Python around it, kept free of numba.

* The summary vector of one case (float64, :data:`N_SUMMARY` entries), written by the kernel
  (:mod:`.kernel`, :mod:`._events`) and read by the solver, the first swing and the batch: the ``S_*``
  indices below.
* The encoded pulse (:mod:`._load`, :func:`blastscale.rocking.encoding.encode_pulse`): the pulse codes
  and the :data:`PAR_SIZE` entries of its ``par``.

Importing this module, or the modules that only read these layouts (:mod:`.solver`, :mod:`.swing`,
:mod:`.encoding`), loads no numba: the compiled kernels are imported on the first solve.
"""

from __future__ import annotations

__all__ = [
    "S_STATUS",
    "S_OVERTURNED",
    "S_OVERTURN_TAU",
    "S_FIRST_IMPACT_TAU",
    "S_MAX_ABS_THETA",
    "S_N_IMPACTS",
    "S_END_TAU",
    "S_NSTEPS",
    "S_W_AT_ALPHA",
    "S_N_PEAKS",
    "S_FINAL_THETA",
    "S_FINAL_W",
    "S_NREJECT",
    "S_FIRST_PEAK",
    "N_SUMMARY",
    "NO_PULSE",
    "FRIEDLANDER",
    "TRIANGULAR",
    "TABULATED",
    "PAR_SIZE",
]

# summary vector layout (float64), shared with solver.py and the capacity modules
S_STATUS = 0  # 0 ok, 1 step limit reached, 2 step size underflow
S_OVERTURNED = 1
S_OVERTURN_TAU = 2  # nan when none
S_FIRST_IMPACT_TAU = 3  # nan when none
S_MAX_ABS_THETA = 4
S_N_IMPACTS = 5
S_END_TAU = 6  # end of the simulated motion (t_end, lying-down time, or stop)
S_NSTEPS = 7
S_W_AT_ALPHA = 8  # |w| when |theta| crossed alpha (overturn), nan otherwise
S_N_PEAKS = 9
S_FINAL_THETA = 10
S_FINAL_W = 11
S_NREJECT = 12
S_FIRST_PEAK = 13  # |theta| at the first peak (nan if none)
N_SUMMARY = 14

# pulse codes (:mod:`._load` documents each one's parameters)
NO_PULSE = 0
FRIEDLANDER = 1
TRIANGULAR = 2
TABULATED = 3
#: Entries of an encoded pulse's ``par``: (f0, tau_o, d) of the positive pulse, then the negative
#: phase's (f_-, tau_-s, tau_-).
PAR_SIZE = 6
