"""Capacity curve of a rocking body: critical charge against stand-off, W_c(R), on plain arrays.

Each point is a critical charge of :mod:`blastscale.rocking.critical` (first-swing energy
criterion, :mod:`blastscale.rocking.swing`), all stand-offs searched together. A reduced-scale
model's curve, up-scaled to the prototype, is the specimen's side and lives above the engine
(:func:`blastscale.analysis.capacity.model_capacity_curve`).

References: paper Sec. "Equations of motion"; Hopkinson-Cranz scaling (Baker et al. 1983).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_positive
from ..blast.inverse import model_name, warn_if_extrapolated
from ..blast.parameters import DEFAULT_BLAST_MODEL
from .critical import critical_arrays
from .solver import DEFAULT_SOLVER, RockingSolver
from .system import as_rocking_system

__all__ = ["capacity_curve", "CapacityCurve", "finite_or_none"]


def finite_or_none(values) -> list:
    """Plain list of floats, None for NaN (JSON)."""
    return [None if not math.isfinite(w) else float(w) for w in values]


@dataclass(frozen=True)
class CapacityCurve:
    """Critical charge against stand-off, W_c(R), of one body (SI).

    ``standoff_m`` (n,) [m], ``critical_charge_kg`` (n,) [kg] (NaN where the outcome does not
    change within the blast model's range), ``evaluations`` (n,) pulse-phase integrations per
    case, ``seconds`` [s] the wall time of the search, ``pulse``, ``blast_model``.
    """

    standoff_m: np.ndarray
    critical_charge_kg: np.ndarray
    evaluations: np.ndarray
    seconds: float
    pulse_shape: str
    blast_model: str

    @property
    def seconds_per_case(self) -> float:
        """Wall time per stand-off [s]."""
        return self.seconds / max(1, self.standoff_m.size)

    def safe_standoff(self, charge: float) -> float:
        """Stand-off [m] beyond which ``charge`` [kg] no longer overturns the body, interpolated
        on the curve (log-log linear; NaN outside it). For an exact value use
        :func:`critical_standoff`."""
        ok = np.isfinite(self.critical_charge_kg)
        R, W = self.standoff_m[ok], self.critical_charge_kg[ok]
        if R.size < 2:
            return float("nan")
        order = np.argsort(W)
        lw, lr = np.log(W[order]), np.log(R[order])
        x = math.log(float(check_positive("charge", charge, "kg")))
        return float(np.exp(np.interp(x, lw, lr))) if lw[0] <= x <= lw[-1] else float("nan")

    def to_dict(self) -> dict:
        """Plain dict (lists; None for NaN)."""
        return {
            "standoff_m": self.standoff_m.tolist(),
            "critical_charge_kg": finite_or_none(self.critical_charge_kg),
            "seconds_per_case": self.seconds_per_case,
            "pulse_shape": self.pulse_shape,
            "blast_model": self.blast_model,
        }


def capacity_curve(
    body,
    standoffs,
    *,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
    load_model=None,
) -> CapacityCurve:
    """Critical charge W_c(R) [kg] at every stand-off R [m] of ``standoffs``, vectorised.

    Same method and parameters as :func:`critical_charge` (first-swing energy criterion, the
    cases searched together; ``load_model`` adds clearing and the negative phase); ``standoffs`` a non-empty 1-D array of stand-offs [m] > 0. A
    stand-off whose outcome does not change within the blast model's range of Z gives NaN.
    """
    R = np.atleast_1d(check_positive("standoffs", standoffs, "m")).astype(float)
    if R.ndim != 1 or R.size == 0:
        raise BlastscaleInputError(f"standoffs must be a non-empty 1-D list of stand-offs [m], got shape {R.shape}")
    system = as_rocking_system(body, gravity, restitution)
    t0 = time.perf_counter()
    W, _, _, nev, _ = critical_arrays(
        system,
        "charge",
        R,
        pulse_shape,
        blast_model,
        extrapolate,
        solver or DEFAULT_SOLVER,
        xtol_rel,
        load_model=load_model,
    )
    dt = time.perf_counter() - t0
    warn_if_extrapolated(blast_model, R / np.cbrt(W), extrapolate)
    return CapacityCurve(R, W, nev, dt, pulse_shape, model_name(blast_model))
