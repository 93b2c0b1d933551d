"""Design a reduced-scale blast experiment from a prototype scenario (the top of the data flow).

``design_model`` takes the prototype (charge W at stand-off R), the geometric scale lambda,
the density ratio gamma and the gravity ratio varsigma, applies a scaling law and returns a
:class:`ModelDesign`: the model's charge and stand-off, lambda_Z, every factor, the blast
parameters of both systems, the ratios the blast actually delivers next to those the
rigid-body response requires, and (when the structure is given) the a-posteriori check that
the load is impulsive.

Impulsive check
---------------
The general law matches the impulse only; the pulse duration and peak do not scale as the
response requires (paper Sec. "Scaling laws"). This is harmless when the pulse is short
compared with the structure's characteristic time: for a rocking block, when
``t_o * p << 1`` with Housner's frequency parameter ``p = sqrt(3 g / (4 r))``. We flag the
load as impulsive when ``t_o p`` is below ``impulsive_threshold`` (default 0.4) in *both*
prototype and model; 0.4 is the bound of the impulsive regime of a linear oscillator,
``omega t_d < 0.4`` (Baker et al. 1983, *Explosion Hazards and Evaluation*, ch. 4), applied
with p in place of omega. The paper's wording "pi_23 << 1" is not literally true (the peak
force exceeds the weight by orders of magnitude); t_o p is the meaningful measure.
"""

from __future__ import annotations

from dataclasses import dataclass

from .._validate import BlastscaleInputError, OutOfRangeError, check_positive, check_positive_scalar
from ..blast.base import BlastModel
from ..blast.parameters import (
    DEFAULT_BLAST_MODEL,
    BlastParameters,
    blast_parameters,
    get_blast_model,
    valid_scaled_distance_range,
)
from ..structures.block import STANDARD_GRAVITY, RectangularBlock
from .factors import ScalingFactors, scaling_factors
from .laws import LAWS, admissible_scales, hopkinson_cranz_density_ratio, solve_scaled_distance_factor

__all__ = ["ImpulsiveCheck", "ModelDesign", "design_model", "impulsive_check", "DEFAULT_IMPULSIVE_THRESHOLD"]

DEFAULT_IMPULSIVE_THRESHOLD = 0.4


@dataclass(frozen=True)
class ImpulsiveCheck:
    """A-posteriori check of the impulsive hypothesis.

    Attributes
    ----------
    prototype_ratio, model_ratio : float
        t_o * p of prototype and model [-] (t_o the positive duration [s], p = sqrt(3 g / 4 r) [rad/s]).
    threshold : float
        Bound below which the load counts as impulsive [-].
    impulsive : bool
        Both ratios below the threshold.
    """

    prototype_ratio: float
    model_ratio: float
    threshold: float

    @property
    def impulsive(self) -> bool:
        return max(self.prototype_ratio, self.model_ratio) < self.threshold

    def to_dict(self) -> dict:
        return {
            "prototype_to_p": self.prototype_ratio,
            "model_to_p": self.model_ratio,
            "threshold": self.threshold,
            "impulsive": self.impulsive,
        }


def impulsive_check(
    duration: float, block: RectangularBlock, gravity: float = STANDARD_GRAVITY
) -> float:
    """The impulsiveness measure of a pulse on a rocking block [-].

    .. math:: t_o\\,p, \\qquad p = \\sqrt{3 g / (4 r)}

    with ``duration`` t_o [s] (> 0), ``block`` (r = half-diagonal [m]) and ``gravity`` g [m/s^2].
    The load acts as an impulse when t_o p << 1; :func:`design_model` flags it below 0.4 (the
    impulsive regime omega t_d < 0.4 of Baker et al. 1983, ch. 4). References: Housner (1963)
    for p; DESIGN.md on why this, not the paper's "pi_23 << 1", is the meaningful check.
    """
    check_positive("positive duration", duration, "s")
    return float(duration) * block.frequency_parameter(gravity)


@dataclass(frozen=True)
class ModelDesign:
    """A designed reduced-scale experiment (all SI; ratios are model / prototype).

    Attributes
    ----------
    law : str
        ``"general"`` (paper Eq. 8) or ``"hopkinson-cranz"``.
    scale, density_ratio, gravity_ratio : float
        lambda, gamma, varsigma [-].
    scaled_distance_factor : float
        lambda_Z = Z_model / Z_prototype [-].
    root_note : str
        Which root of the law was taken.
    prototype, model : BlastParameters
        Blast parameters at the prototype and model stand-offs.
    factors : ScalingFactors
        Every factor (charge and scaled distance included).
    impulsive : ImpulsiveCheck or None
        Present when the structure was given.
    prototype_block, model_block : RectangularBlock or None
        The structures, when given.
    gravity : float
        Prototype gravity [m/s^2].
    """

    law: str
    scale: float
    density_ratio: float
    gravity_ratio: float
    scaled_distance_factor: float
    root_note: str
    prototype: BlastParameters
    model: BlastParameters
    factors: ScalingFactors
    impulsive: ImpulsiveCheck | None = None
    prototype_block: RectangularBlock | None = None
    model_block: RectangularBlock | None = None
    gravity: float = STANDARD_GRAVITY

    # convenient views -------------------------------------------------------
    @property
    def model_charge_kg(self) -> float:
        """Model TNT-equivalent charge [kg]."""
        return self.model.charge_kg

    @property
    def model_standoff_m(self) -> float:
        """Model stand-off [m] (= lambda R)."""
        return self.model.standoff_m

    @property
    def pressure_ratio(self) -> float:
        """Delivered peak reflected pressure ratio P_model / P_prototype [-]."""
        return self.model.reflected_pressure / self.prototype.reflected_pressure

    @property
    def impulse_ratio(self) -> float:
        """Delivered reflected impulse ratio i_model / i_prototype [-] (= gamma sqrt(varsigma lambda^3))."""
        return self.model.reflected_impulse / self.prototype.reflected_impulse

    @property
    def duration_ratio(self) -> float:
        """Delivered positive-duration ratio t_o,model / t_o,prototype [-]."""
        return self.model.positive_duration / self.prototype.positive_duration

    def to_dict(self) -> dict:
        """Plain dict (the CLI's ``design --json`` object)."""
        out = {
            "law": self.law,
            "blast_model": self.prototype.model,
            "scale": self.scale,
            "density_ratio": self.density_ratio,
            "gravity_ratio": self.gravity_ratio,
            "prototype_charge_kg": self.prototype.charge_kg,
            "prototype_standoff_m": self.prototype.standoff_m,
            "prototype_scaled_distance": self.prototype.scaled_distance,
            "model_scaled_distance": self.model.scaled_distance,
            "scaled_distance_factor": self.scaled_distance_factor,
            "root": self.root_note,
            "model_charge_kg": self.model_charge_kg,
            "model_standoff_m": self.model_standoff_m,
            "pressure_ratio": self.pressure_ratio,
            "impulse_ratio": self.impulse_ratio,
            "duration_ratio": self.duration_ratio,
            "required_pressure_ratio": self.factors.pressure,
            "required_impulse_ratio": self.factors.impulse,
            "required_duration_ratio": self.factors.time,
            "factors": self.factors.to_dict(),
            "prototype": self.prototype.to_dict(),
            "model": self.model.to_dict(),
        }
        if self.impulsive is not None:
            out["impulsive"] = self.impulsive.to_dict()
        return out


def design_model(
    charge: float,
    standoff: float,
    scale: float,
    density_ratio: float | None = 1.0,
    gravity_ratio: float = 1.0,
    law: str = "general",
    model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    geometry: RectangularBlock | None = None,
    *,
    gravity: float = STANDARD_GRAVITY,
    impulsive_threshold: float = DEFAULT_IMPULSIVE_THRESHOLD,
    extrapolate: bool = False,
) -> ModelDesign:
    """Design the reduced-scale model of a blast scenario.

    Parameters
    ----------
    charge : float
        Prototype TNT-equivalent charge W [kg], > 0.
    standoff : float
        Prototype stand-off R [m], > 0.
    scale : float
        Geometric scale lambda = l_model / l_prototype [-], in (0, 1] for a reduced model
        (values > 1 are accepted: an up-scaled model).
    density_ratio : float or None
        gamma = rho_model / rho_prototype [-]. For ``law="hopkinson-cranz"`` leave None (or
        give exactly 1/sqrt(varsigma lambda)): that law imposes it.
    gravity_ratio : float
        varsigma = g_model / g_prototype [-].
    law : {"general", "hopkinson-cranz"}
        Scaling law: the paper's general law (Eq. 8, model Z solved so that the impulse
        factor equals gamma sqrt(varsigma lambda^3)) or Hopkinson-Cranz (lambda_Z = 1).
    model : str or BlastModel
        Blast model (``"kingery-bulmash"`` default, ``"masi2021"`` the paper's fits).
    geometry : RectangularBlock, optional
        Prototype structure; enables the impulsive check and fills the model block.
    gravity : float
        Prototype gravity g [m/s^2].
    impulsive_threshold : float
        Bound on t_o p for the impulsive check (default 0.4).
    extrapolate : bool
        Allow the blast fits outside their ranges (warns).

    Returns
    -------
    ModelDesign

    Raises
    ------
    BlastscaleInputError
        A parameter that is not a finite number in its range (message names it, its value and
        the range).
    OutOfRangeError
        Prototype or model Z outside a blast fit's range; for the general law the message gives
        the admissible range of ``scale``.

    Notes
    -----
    Validity: the prototype's and the model's scaled distances must lie inside every fit used
    (Kingery-Bulmash: Z in [0.2, 40] for all seven quantities; masi2021: [0.2, 20], duration
    [0.2, 6.5] m/kg^(1/3)). The general law matches only the impulse (impulsive hypothesis,
    checked a posteriori with ``geometry``). References: paper Sec. "Scaling laws", Eqs. (5)-(8),
    Tables 1-2.

    Examples
    --------
    The paper's 10 m block, 50 kg at 2 m, lambda = 1/200, same material (model 2 of the
    paper's Table 4: 0.233 mg at Z = 1.62 m/kg^(1/3)):

    >>> d = design_model(50.0, 2.0, 1 / 200, model="masi2021")
    >>> round(d.model_charge_kg * 1e6, 3), round(d.model.scaled_distance, 2)
    (0.233, 1.62)
    """
    W = check_positive_scalar("charge", charge, "kg")
    R = check_positive_scalar("standoff", standoff, "m")
    lam = check_positive_scalar("scale", scale)
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    check_positive_scalar("gravity", gravity, "m/s^2")
    check_positive_scalar("impulsive threshold", impulsive_threshold)
    if law not in LAWS:
        raise BlastscaleInputError(f"law = {law!r} is not known: valid values are {', '.join(LAWS)}")
    bm = get_blast_model(model)
    proto = blast_parameters(W, R, bm, extrapolate=extrapolate)
    if law == "hopkinson-cranz":
        gam_hc = hopkinson_cranz_density_ratio(lam, sig)
        given = None if density_ratio is None else check_positive_scalar("density ratio", density_ratio)
        if given is not None and abs(given - gam_hc) > 1e-9 * gam_hc:
            raise BlastscaleInputError(
                f"density ratio = {given:.6g} is out of range for the Hopkinson-Cranz law: it "
                f"imposes gamma = 1/sqrt(gravity_ratio * scale) = {gam_hc:.6g} (use law='general' for another gamma)"
            )
        gam, lz, res_note = gam_hc, 1.0, "Hopkinson-Cranz: lambda_Z = 1 (same scaled distance and pressure)"
    else:
        if density_ratio is None:
            raise BlastscaleInputError("density ratio = None is out of range: the general law needs gamma > 0")
        gam = check_positive_scalar("density ratio", density_ratio)
        if not extrapolate:  # the model's Z must lie where every fit holds, not only the impulse fit
            zr = valid_scaled_distance_range(bm)
            lo, hi = admissible_scales(proto.scaled_distance, gam, sig, bm, zr)
            if not lo <= lam <= hi:
                raise OutOfRangeError(
                    f"scale = {lam:.6g} is out of range for the general law: valid range of scale is "
                    f"[{lo:.6g}, {hi:.6g}] (it keeps the model's Z inside [{zr[0]:g}, {zr[1]:g}] m/kg^(1/3), where "
                    f"every {bm.name} fit holds, for density ratio = {gam:.6g}, gravity ratio = {sig:.6g} and "
                    f"prototype Z = {proto.scaled_distance:.6g} m/kg^(1/3))"
                )
        sol = solve_scaled_distance_factor(proto.scaled_distance, lam, gam, sig, bm)
        lz, res_note = sol.factor, sol.note
    f = scaling_factors(lam, gam, sig, lz)
    model_params = blast_parameters(W * f.charge, R * lam, bm, extrapolate=extrapolate)
    imp = None
    mblock = None
    if geometry is not None:
        mblock = geometry.scaled(lam, gam)
        imp = ImpulsiveCheck(
            prototype_ratio=impulsive_check(proto.positive_duration, geometry, gravity),
            model_ratio=impulsive_check(model_params.positive_duration, mblock, gravity * sig),
            threshold=float(impulsive_threshold),
        )
    return ModelDesign(
        law=law,
        scale=lam,
        density_ratio=gam,
        gravity_ratio=sig,
        scaled_distance_factor=lz,
        root_note=res_note,
        prototype=proto,
        model=model_params,
        factors=f,
        impulsive=imp,
        prototype_block=geometry,
        model_block=mblock,
        gravity=float(gravity),
    )


