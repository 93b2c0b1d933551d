"""Physical constants and the physical defaults of the method, each with its source (SI).

The paper's numbers are reproduced with g = 9.81 m/s^2 (Masi, Stefanou & Maffi-Berthier, Sec. 5:
every table of the paper is recomputed here with it, see docs/paper_slips.md), so that is the
standard gravity of the library, not the CGPM's 9.80665 m/s^2.

Settings of a study (duration, recording interval, blast model, ...) are not constants: their one
default lives in the scenario schema (:mod:`blastscale.scenario`).
"""

from __future__ import annotations

import math

__all__ = ["STANDARD_GRAVITY", "FRICTION_ANGLE_DEG", "DEFAULT_FRICTION"]

#: Standard gravity g [m/s^2] (the paper's value, which reproduces its tables).
STANDARD_GRAVITY = 9.81

#: Friction angle of stone and concrete interfaces [deg] (paper, Sec. "Validation", FE model:
#: "an angle of friction equal to 35 deg, which is common for many geomaterials").
FRICTION_ANGLE_DEG = 35.0

#: Coulomb friction coefficient mu = tan(35 deg) = 0.7002, rounded to 0.7 [-], the value of
#: every run of blastscale since its first release.
DEFAULT_FRICTION = 0.7

assert abs(math.tan(math.radians(FRICTION_ANGLE_DEG)) - DEFAULT_FRICTION) < 5e-4
