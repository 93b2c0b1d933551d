"""Capacity curves of a rocking body: critical charge against stand-off, W_c(R), and its
reduced-scale model's curve up-scaled to the prototype.

Each point is a critical charge of :mod:`blastscale.rocking.critical` (first-swing energy
criterion, :mod:`blastscale.rocking.swing`), all stand-offs searched together. The
model's curve is up-scaled with the paper's general law: equal impulse up to the factor
``gamma sqrt(varsigma lambda^3)`` (paper Eq. 8, Table 1).

References: paper Sec. "Equations of motion" and Sec. "Similitude" (Eq. 8, Table 1);
Hopkinson-Cranz scaling (Baker et al. 1983).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_positive
from ..blast.parameters import DEFAULT_BLAST_MODEL, blast_parameters
from .blast_inverse import _check_extrapolated, _model_name, charge_for_impulse
from .critical import _critical_arrays
from .solver import DEFAULT_SOLVER, RockingSolver
from .system import as_rocking_system
from ..similitude.factors import scaling_factors
from ..similitude.specimen import specimen_system

__all__ = ["capacity_curve", "CapacityCurve", "model_capacity_curve", "ModelCapacity"]


def _finite_or_none(values) -> list:
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
            "critical_charge_kg": _finite_or_none(self.critical_charge_kg),
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
    W, _, _, nev, _ = _critical_arrays(
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
    _check_extrapolated(blast_model, R / np.cbrt(W), extrapolate)
    return CapacityCurve(R, W, nev, dt, pulse_shape, _model_name(blast_model))


@dataclass(frozen=True)
class ModelCapacity:
    """Capacity curve of a reduced-scale model and its up-scaling to the prototype (SI).

    ``curve`` is the model's own W_c at the model stand-offs ``lambda R`` [m] (model charges
    [kg]); ``upscaled_charge_kg`` (n,) [kg] the prototype charges they correspond to under the
    paper's general law (equal impulse up to the factor ``gamma sqrt(varsigma lambda^3)``, Eq. 8),
    to be read against the prototype's W_c(R); ``scale``, ``density_ratio``, ``gravity_ratio``
    are lambda, gamma, varsigma [-].
    """

    curve: CapacityCurve
    upscaled_charge_kg: np.ndarray
    scale: float
    density_ratio: float
    gravity_ratio: float

    def to_dict(self) -> dict:
        """Plain dict (lists; None for NaN)."""
        d = self.curve.to_dict()
        return {
            "scale": self.scale,
            "density_ratio": self.density_ratio,
            "gravity_ratio": self.gravity_ratio,
            "standoff_m": d["standoff_m"],
            "critical_charge_kg": d["critical_charge_kg"],
            "upscaled_critical_charge_kg": _finite_or_none(self.upscaled_charge_kg),
            "seconds_per_case": d["seconds_per_case"],
        }


def model_capacity_curve(
    body,
    standoffs,
    scale: float,
    density_ratio: float = 1.0,
    gravity_ratio: float = 1.0,
    *,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
    load_model=None,
) -> ModelCapacity:
    """Capacity curve of the reduced-scale model of ``body`` and its up-scaling to the prototype.

    The model is the prototype with lengths x ``scale`` (lambda), density x ``density_ratio``
    (gamma) and gravity x ``gravity_ratio`` (varsigma), same restitution, and the load model's face
    x lambda: the specimen system of :func:`blastscale.similitude.specimen.specimen_system` (the one place
    a specimen is scaled, as for a design: :meth:`RockingSystem.scaled`, :meth:`LoadModel.scaled`); its critical charges
    are searched at the stand-offs ``scale * standoffs`` [m] (as :func:`capacity_curve`) and each
    is up-scaled to the prototype charge that delivers, at the prototype stand-off, the model's
    reflected impulse divided by ``gamma sqrt(varsigma lambda^3)`` (paper Eq. 8, Table 1).
    In the impulsive limit the up-scaled curve equals the prototype's exactly; finite pulses
    depart from it by the effect of the pulse duration, which the law does not match.
    """

    lam = float(check_positive("scale", scale))
    gam = float(check_positive("density ratio", density_ratio))
    sig = float(check_positive("gravity ratio", gravity_ratio))
    R = np.atleast_1d(check_positive("standoffs", standoffs, "m")).astype(float)
    f = scaling_factors(lam, gam, sig)  # no charge, no lambda_Z: the specimen system needs lambda, gamma, varsigma
    spec = specimen_system(f, as_rocking_system(body, gravity, restitution), load_model)  # scaled once, there
    curve = capacity_curve(
        spec.structure,
        lam * R,
        pulse_shape=pulse_shape,
        blast_model=blast_model,
        solver=solver,
        xtol_rel=xtol_rel,
        extrapolate=extrapolate,
        load_model=spec.load_model,
    )
    ok = np.isfinite(curve.critical_charge_kg)
    up = np.full(R.size, np.nan)
    if np.any(ok):
        im = blast_parameters(
            curve.critical_charge_kg[ok], lam * R[ok], blast_model, extrapolate=extrapolate
        ).reflected_impulse
        up[ok] = charge_for_impulse(im / f.impulse, R[ok], blast_model, extrapolate=extrapolate)
    return ModelCapacity(curve, up, lam, gam, sig)
