"""Critical charge and critical stand-off of a rocking body (first-swing energy criterion).

The critical charge W_c(R) [kg TNT] is the largest charge at the stand-off R [m] that the
body survives without overturning, the critical stand-off the smallest R at which it survives
W; the outcome of each trial is the first-swing margin mu of
:mod:`blastscale.rocking.swing` (> 0 overturns) under the reflected pulse of the blast
model (paper Method A, Eq. eom).

Search
------
The root is found in ``u = ln x`` (x the charge, the stand-off or the impulse), for all the
cases of a call at once: a starting point from the structure's own scale (the impulsive closed
form ``J_o theta_dot_c = i S l`` gives the critical impulse; the blast model is inverted for
the charge or stand-off that delivers it), a geometric bracket search within the blast model's
valid range of Z, then the Illinois variant of regula falsi with a bisection safeguard to a
relative tolerance ``xtol_rel`` (default 1e-9). A case whose outcome does not change within the
range gives NaN in the curves and a one-line error in the scalar functions.

The root finder is :func:`blastscale.roots.vector_root`, the blast model's inversion (starting
point, range of Z) :mod:`blastscale.blast.inverse`;
:func:`critical_charge_by_bisection` (:mod:`blastscale.rocking.critical_reference`) is the slow
independent reference (full simulations).

References: paper Sec. "Equations of motion" (W_pc = 79.8 kg for the 10 m block at 2 m);
Masi et al. (2019), Int. J. Mech. Sci. 157 (critical impulse); Hopkinson-Cranz scaling (Baker
et al. 1983); Illinois method: Dowell & Jarratt (1971), BIT 11, 168-174.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from .._validate import BlastscaleInputError, check_positive, check_range
from ..blast.base import ExtrapolationWarning
from ..blast.inverse import model_name, scaled_distance_for, scaled_distance_range, warn_if_extrapolated
from ..blast.load_model import load_model_record
from ..blast.negative_phase import NEGATIVE_PHASE_MODELS
from ..blast.parameters import DEFAULT_BLAST_MODEL, burst_of
from ..blast.pulses import check_pulse_shape
from ..roots import vector_root
from .solver import DEFAULT_SOLVER, RockingSolver
from .swing import first_swing_checked
from .system import as_rocking_system

__all__ = ["critical_charge", "critical_standoff", "negative_phase_uncertainty", "CriticalResult", "critical_arrays"]


def critical_arrays(
    system, searched, fixed, pulse_shape, blast_model, extrapolate, solver, xtol_rel, guess=None, load_model=None
):
    """Vectorised critical charge (``searched="charge"``, ``fixed`` stand-offs [m]) or stand-off
    (``"standoff"``, ``fixed`` charges [kg]). Returns (x_critical, bracket_lo, bracket_hi,
    evaluations, status) arrays; x is the survive side of the final bracket."""
    check_pulse_shape(pulse_shape)
    check_range("xtol_rel", xtol_rel, 1e-14, 0.1)
    by_charge = searched == "charge"
    fixed = np.atleast_1d(np.asarray(fixed, dtype=float))
    zlo, zhi = scaled_distance_range(blast_model, extrapolate)
    if by_charge:  # W = (R / Z)^3: large Z, small charge
        ulo, uhi = 3.0 * np.log(fixed / zhi), 3.0 * np.log(fixed / zlo)
    else:  # R = Z W^(1/3): the margin decreases with R, so search in -ln R
        ulo, uhi = -np.log(zhi * np.cbrt(fixed)), -np.log(zlo * np.cbrt(fixed))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if guess is None:  # the load that delivers the impulsive critical impulse, within the range
            z0 = scaled_distance_for(
                np.full(fixed.size, system.critical_impulse),
                "reflected_impulse",
                blast_model,
                **{"standoff" if by_charge else "charge": fixed},
                extrapolate=extrapolate,
                z_range=(zlo, zhi),
                outside="clip",
            )
            u0 = 3.0 * np.log(fixed / z0) if by_charge else -np.log(z0 * np.cbrt(fixed))  # the bounds' own formulas
        else:
            u0 = np.full(fixed.size, math.log(guess) if by_charge else -math.log(guess))

        def evaluate(idx, u):
            x = np.exp(u if by_charge else -u)
            W, R = (x, fixed[idx]) if by_charge else (fixed[idx], x)
            W, R = np.broadcast_arrays(W, R)  # checked once, by the search's caller
            return first_swing_checked(system, W, R, pulse_shape, blast_model, extrapolate, solver, load_model).margin

        lo, hi, nev, status = vector_root(evaluate, u0, ulo, uhi, xtol_rel)
    # the search visits many points: pass on one warning of each other kind (extrapolation is
    # reported once for the results, by warn_if_extrapolated)
    seen = set()
    for w in caught:
        if w.category is not ExtrapolationWarning and w.category not in seen:
            seen.add(w.category)
            warnings.warn(w.message, w.category, stacklevel=4)
    if not by_charge:
        lo, hi = -lo, -hi
    x = np.where(status == 0, np.exp(lo), np.nan)
    return x, np.exp(np.minimum(lo, hi)), np.exp(np.maximum(lo, hi)), nev, status


@dataclass(frozen=True)
class CriticalResult:
    """Result of a critical charge / stand-off search (SI).

    ``charge_kg`` [kg] and ``standoff_m`` [m] define the critical scenario (the one searched
    for and the one held fixed); ``pulse`` the pulse shape; ``blast_model`` the blast fit; ``relative_tolerance`` the
    relative accuracy of the searched quantity; ``evaluations`` the number of pulse-phase
    integrations (first-swing criterion); ``bracket`` the final bracket of the searched quantity;
    ``load_model`` the record of the load that produced it (burst, clearing, negative phase).
    """

    charge_kg: float
    standoff_m: float
    searched: str
    pulse_shape: str
    blast_model: str
    relative_tolerance: float
    evaluations: int
    bracket: tuple[float, float]
    load_model: dict | None = None

    def to_dict(self) -> dict:
        """Plain dict with unit-suffixed keys (``critical_charge_kg`` or ``critical_standoff_m``)."""
        return {
            "critical_charge_kg" if self.searched == "charge" else "critical_standoff_m": (
                self.charge_kg if self.searched == "charge" else self.standoff_m
            ),
            "charge_kg": self.charge_kg,
            "standoff_m": self.standoff_m,
            "pulse_shape": self.pulse_shape,
            "blast_model": self.blast_model,
            "relative_tolerance": self.relative_tolerance,
            "evaluations": self.evaluations,
            "load_model": self.load_model,
        }


def critical_charge(
    body,
    standoff: float,
    *,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    guess: float | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
    load_model=None,
) -> CriticalResult:
    """Largest TNT charge [kg] at ``standoff`` [m] that the body survives without overturning.

    The reflected pulse of shape ``pulse`` from ``blast_parameters(W, standoff, blast_model)`` loads
    the front face uniformly (paper Method A, Eq. eom); the first-swing energy criterion
    (:mod:`blastscale.rocking.swing`) decides the outcome, and the search starts from the charge that
    delivers the impulsive critical impulse (the structure's own scale).

    Parameters
    ----------
    body : RockingSystem or RectangularBlock
        The body (a block is converted with ``gravity`` [m/s^2] and ``restitution`` [-]).
    standoff : float
        Stand-off R [m], > 0.
    pulse_shape : {"friedlander", "triangular", "impulsive"}
        Reflected pulse shape (paper Eqs. 1, 3, impulsive limit).
    blast_model : str
        Blast model, ``"kingery-bulmash"`` (Swisdak 1994) or ``"masi2021"`` (paper App. A);
        searched over its valid range of scaled distance Z (widened 5x each way with
        ``extrapolate``).
    solver : RockingSolver, optional
        Solver of the pulse phase (default rtol 1e-10, atol 1e-12).
    guess : float, optional
        Starting charge [kg], > 0 (default: from the impulsive closed form).
    xtol_rel : float
        Relative tolerance on the charge [-], in [1e-14, 0.1].
    extrapolate : bool
        Allow the blast fits outside their ranges.
    load_model : LoadModel, optional
        Clearing of the loaded face and the negative phase (:mod:`blastscale.blast.load_model`);
        None: the paper's load. A free-air burst is a blast model: ``blast_model=model_for_burst(...)``
        or its name ``"kingery-bulmash-free-air"``.

    Returns
    -------
    CriticalResult
        ``charge_kg`` [kg] (the critical charge), ``standoff_m`` [m], evaluations, bracket.

    Raises
    ------
    BlastscaleInputError
        If no change of outcome is found within the blast model's valid range of Z.

    Examples
    --------
    The paper's 10 m block (alpha = 15 deg) at 2 m: 79.8 kg (paper Sec. "Equations of motion").

    >>> import math
    >>> from blastscale.structures import RectangularBlock
    >>> blk = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    >>> round(critical_charge(blk, 2.0, blast_model="masi2021").charge_kg, 2)
    79.87
    """
    R = float(check_positive("standoff", standoff, "m"))
    if guess is not None:
        check_positive("guess", guess, "kg")
    return _critical(
        body,
        "charge",
        R,
        pulse_shape,
        blast_model,
        gravity,
        restitution,
        solver,
        guess,
        xtol_rel,
        extrapolate,
        load_model,
    )


def critical_standoff(
    body,
    charge: float,
    *,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    guess: float | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
    load_model=None,
) -> CriticalResult:
    """Smallest stand-off [m] at which the body survives ``charge`` [kg TNT] without
    overturning (same method and parameters as :func:`critical_charge`, with ``charge`` W
    [kg] > 0 fixed and ``guess`` an optional starting stand-off [m]; the margin decreases with
    distance). Returns a :class:`CriticalResult` whose ``standoff_m`` [m] is the critical
    (safe) stand-off. References: paper Sec. "Equations of motion"; Masi et al. (2019)."""
    W = float(check_positive("charge", charge, "kg"))
    if guess is not None:
        check_positive("guess", guess, "m")
    return _critical(
        body,
        "standoff",
        W,
        pulse_shape,
        blast_model,
        gravity,
        restitution,
        solver,
        guess,
        xtol_rel,
        extrapolate,
        load_model,
    )


def _critical(
    body,
    searched,
    fixed,
    pulse_shape,
    blast_model,
    gravity,
    restitution,
    solver,
    guess,
    xtol_rel,
    extrapolate,
    load_model=None,
):
    system = as_rocking_system(body, gravity, restitution)
    by_charge = searched == "charge"
    x, blo, bhi, nev, status = critical_arrays(
        system,
        searched,
        fixed,
        pulse_shape,
        blast_model,
        extrapolate,
        solver or DEFAULT_SOLVER,
        xtol_rel,
        guess,
        load_model,
    )
    if status[0] != 0:
        zlo, zhi = scaled_distance_range(blast_model, extrapolate)
        what = ("survives up to" if status[0] == 1 else "overturns down to") + (
            f" Z = {zlo if status[0] == 1 else zhi:.6g} m/kg^(1/3)"
        )
        raise BlastscaleInputError(
            f"no critical {searched} within the blast model's valid range of Z [{zlo:.6g}, {zhi:.6g}] m/kg^(1/3) "
            f"({'stand-off' if by_charge else 'charge'} = {fixed:.6g} {'m' if by_charge else 'kg'}): the body {what}"
            + ("" if extrapolate else "; --extrapolate (extrapolate=True) widens the range")
        )
    W, R = (float(x[0]), fixed) if by_charge else (fixed, float(x[0]))
    warn_if_extrapolated(blast_model, [R / np.cbrt(W)], extrapolate)
    return CriticalResult(
        W,
        R,
        searched,
        pulse_shape,
        model_name(blast_model),
        xtol_rel,
        int(nev[0]),
        (float(blo[0]), float(bhi[0])),
        _record(blast_model, load_model),
    )


def _record(blast_model, load_model) -> dict:
    """The load-model record of a capacity result (:func:`blastscale.blast.load_model.load_model_record`)."""

    return load_model_record(model_name(blast_model), burst_of(blast_model), load_model)


def negative_phase_uncertainty(system, standoff: float, load_model, **kw) -> dict:
    """The critical charge [kg] at ``standoff`` [m] under each negative-phase model
    (:data:`~blastscale.blast.negative_phase.NEGATIVE_PHASE_MODELS`) and without the negative phase:
    the spread between the models is the model uncertainty of the suction (docs/blast_physics.md;
    the paper's block at 2 m, Kingery-Bulmash: x1.29 with the chart's cubic, x1.03 with the
    continued Friedlander). ``load_model`` keeps its clearing; ``kw`` go to :func:`critical_charge`."""

    base = critical_charge(system, standoff, load_model=replace(load_model, negative_phase=False), **kw).charge_kg
    out = {"positive_phase_only_kg": float(base)}
    for m in NEGATIVE_PHASE_MODELS:
        c = critical_charge(system, standoff, load_model=replace(load_model, negative_phase_model=m), **kw).charge_kg
        out[m] = {"critical_charge_kg": float(c), "over_positive_phase_only": float(c / base)}
    return out
