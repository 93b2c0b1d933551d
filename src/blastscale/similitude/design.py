"""Design a reduced-scale blast experiment from a prototype scenario (the top of the data flow).

``design_model`` takes the prototype (charge W at stand-off R), the geometric scale lambda,
the density ratio gamma and the gravity ratio varsigma, applies a scaling law and returns a
:class:`ModelDesign`: the model's charge and stand-off, lambda_Z, every factor, the blast
parameters of both systems, the ratios the blast actually delivers next to those the
rigid-body response requires, and (when the structure is given) the a-posteriori check that
the load is impulsive (:mod:`.experiment`).
"""

from __future__ import annotations


import numpy as np

from .._validate import BlastscaleInputError, OutOfRangeError, check_positive, check_positive_scalar
from ..blast.base import BlastModel
from ..blast.bursts import DEFAULT_BURST, model_for_burst
from ..blast.parameters import (
    DEFAULT_BLAST_MODEL,
    BlastParameters,
    blast_parameters,
    valid_scaled_distance_range,
)
from ..structures.block import STANDARD_GRAVITY, RectangularBlock
from .experiment import DEFAULT_IMPULSIVE_THRESHOLD, ImpulsiveCheck, ModelDesign, impulsive_check
from .factors import scaling_factors
from .laws import (
    LAWS,
    admissible_scales,
    hopkinson_cranz_density_ratio,
    solve_scaled_distance_factor,
    solve_scaled_distance_factors,
)

__all__ = ["design_model"]

def design_model(
    charge: float,
    standoff: float,
    scale: float,
    density_ratio: float | None = 1.0,
    gravity_ratio: float = 1.0,
    law: str = "general",
    blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    geometry: RectangularBlock | None = None,
    *,
    gravity: float = STANDARD_GRAVITY,
    impulsive_threshold: float = DEFAULT_IMPULSIVE_THRESHOLD,
    extrapolate: bool = False,
    burst: str = DEFAULT_BURST,
    specimen_burst: str | None = None,
    load_model=None,
    face=None,
    specimen_charge_height: float | None = None,
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
    blast_model : str or BlastModel
        Blast model (``"kingery-bulmash"`` default, ``"masi2021"`` the paper's fits).
    geometry : RectangularBlock, optional
        Prototype structure; enables the impulsive check and fills the specimen block.
    gravity : float
        Prototype gravity g [m/s^2].
    impulsive_threshold : float
        Bound on t_o p for the impulsive check (default 0.4).
    extrapolate : bool
        Allow the blast fits outside their ranges (warns).
    burst : {"surface", "free-air"}
        The prototype's burst type (:mod:`blastscale.blast.bursts`; the paper's: surface).
    specimen_burst : {"surface", "free-air"}, optional
        The specimen's (default the prototype's): a lab charge on a stand is a free-air burst. The
        law then matches the specimen's free-air reflected impulse to the prototype's
        (``i_hat_s(Z lambda_Z) / (lambda_Z i_hat_p(Z)) = gamma sqrt(varsigma lambda)``; Hopkinson-Cranz:
        ``= 1``, so that lambda_Z is no longer 1).
    load_model : LoadModel, optional
        Clearing (on the prototype's face; the specimen's is lambda times it) and the negative phase:
        reported for both systems in ``effects`` (:func:`~.effects.blast_effects`), warned where they
        differ by more than 5 %. The law itself matches the reflected impulse (paper Eq. 8).
    face : (float, float), optional
        The prototype's loaded face (width, height) [m] (from ``geometry`` when not given).
    specimen_charge_height : float, optional
        Height of the lab charge's centre above the floor [m]: warned when it is neither a surface
        nor a free-air burst at the specimen's face.

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

    Arrays of charges and stand-offs (broadcast; the scales are single numbers) are designed at
    once, with the same solution of the law: every numeric field of the design is then an array,
    NaN where a case cannot be designed (a scaled distance outside the blast fits; ``valid`` says
    which), and nothing is raised for such a case.

    Examples
    --------
    The paper's 10 m block, 50 kg at 2 m, lambda = 1/200, same material (model 2 of the
    paper's Table 4: 0.233 mg at Z = 1.62 m/kg^(1/3)):

    >>> d = design_model(50.0, 2.0, 1 / 200, blast_model="masi2021")
    >>> round(d.specimen_charge_kg * 1e6, 3), round(d.specimen.scaled_distance, 2)
    (0.233, 1.62)
    """
    if np.ndim(charge) or np.ndim(standoff):
        return _design_arrays(charge, standoff, scale, density_ratio, gravity_ratio, law, blast_model, geometry,
                              gravity, impulsive_threshold, extrapolate, burst, specimen_burst)
    W = check_positive_scalar("charge", charge, "kg")
    R = check_positive_scalar("standoff", standoff, "m")
    lam = check_positive_scalar("scale", scale)
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    check_positive_scalar("gravity", gravity, "m/s^2")
    check_positive_scalar("impulsive threshold", impulsive_threshold)
    if law not in LAWS:
        raise BlastscaleInputError(f"law = {law!r} is not known: valid values are {', '.join(LAWS)}")
    bm = model_for_burst(blast_model, burst)
    ms = bm if specimen_burst is None else model_for_burst(blast_model, specimen_burst)
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
        if ms is not bm:  # another burst type: the scaled distance whose impulse factor is lambda
            sol = solve_scaled_distance_factor(proto.scaled_distance, lam, gam, sig, bm, ms)
            lz, res_note = sol.factor, "Hopkinson-Cranz with another specimen burst: " + sol.note
    else:
        if density_ratio is None:
            raise BlastscaleInputError("density ratio = None is out of range: the general law needs gamma > 0")
        gam = check_positive_scalar("density ratio", density_ratio)
        if not extrapolate:  # the model's Z must lie where every fit holds, not only the impulse fit
            zr = valid_scaled_distance_range(ms)
            lo, hi = admissible_scales(proto.scaled_distance, gam, sig, bm, zr, specimen_blast_model=ms)
            if not lo <= lam <= hi:
                raise OutOfRangeError(
                    f"scale = {lam:.6g} is out of range for the general law: valid range of scale is "
                    f"[{lo:.6g}, {hi:.6g}] (it keeps the model's Z inside [{zr[0]:g}, {zr[1]:g}] m/kg^(1/3), where "
                    f"every {ms.name} fit holds, for density ratio = {gam:.6g}, gravity ratio = {sig:.6g} and "
                    f"prototype Z = {proto.scaled_distance:.6g} m/kg^(1/3))"
                )
        sol = solve_scaled_distance_factor(proto.scaled_distance, lam, gam, sig, bm, None if ms is bm else ms)
        lz, res_note = sol.factor, sol.note
    f = scaling_factors(lam, gam, sig, lz)
    model_params = blast_parameters(W * f.charge, R * lam, ms, extrapolate=extrapolate)
    imp = None
    mblock = None
    if geometry is not None:
        mblock = geometry.scaled(f)
        imp = ImpulsiveCheck(
            prototype_ratio=impulsive_check(proto.positive_duration, geometry, gravity),
            model_ratio=impulsive_check(model_params.positive_duration, mblock, gravity * sig),
            threshold=float(impulsive_threshold),
        )
    effects, notes = None, ()
    if face is None and geometry is not None:
        face = (geometry.depth, geometry.height)
    if ms is not bm or (load_model is not None and not load_model.is_paper) or specimen_charge_height is not None:
        import warnings

        from .effects import BlastSimilarityWarning, blast_effects

        effects, notes = blast_effects(proto, model_params, load_model, scale=lam, face=face,
                                       specimen_charge_height=specimen_charge_height, extrapolate=extrapolate)
        for note in notes:
            warnings.warn(note, BlastSimilarityWarning, stacklevel=2)
    return ModelDesign(
        law=law,
        scale=lam,
        density_ratio=gam,
        gravity_ratio=sig,
        scaled_distance_factor=lz,
        root_note=res_note,
        prototype=proto,
        specimen=model_params,
        factors=f,
        impulsive=imp,
        prototype_block=geometry,
        specimen_block=mblock,
        gravity=float(gravity),
        effects=effects,
        notes=notes,
    )


def _design_arrays(charge, standoff, scale, density_ratio, gravity_ratio, law, blast_model, geometry, gravity,
                   impulsive_threshold, extrapolate, burst=DEFAULT_BURST, specimen_burst=None) -> ModelDesign:
    """:func:`design_model` for arrays of charges and stand-offs (its docstring): the law solved for
    every case at once (:func:`~.laws.solve_scaled_distance_factors`), the invalid cases NaN."""
    import warnings
    from dataclasses import replace

    from ..blast.base import ExtrapolationWarning

    try:
        W, R = np.broadcast_arrays(check_positive("charge", charge, "kg"), check_positive("standoff", standoff, "m"))
    except ValueError:
        raise BlastscaleInputError(f"charge and standoff have shapes {np.shape(charge)} and {np.shape(standoff)}, "
                                   "which do not broadcast together") from None
    W, R = W.astype(float), R.astype(float)
    lam = check_positive_scalar("scale", scale)
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    check_positive_scalar("gravity", gravity, "m/s^2")
    if law not in LAWS:
        raise BlastscaleInputError(f"law = {law!r} is not known: valid values are {', '.join(LAWS)}")
    bm = model_for_burst(blast_model, burst)
    ms = bm if specimen_burst is None else model_for_burst(blast_model, specimen_burst)
    # where the design holds: every fit used, or (extrapolate) the impulse fit the law is solved on
    zr = bm.valid_range("scaled_reflected_impulse") if extrapolate else valid_scaled_distance_range(bm)
    zs = ms.valid_range("scaled_reflected_impulse") if extrapolate else valid_scaled_distance_range(ms)
    Z = R / np.cbrt(W)
    if law == "hopkinson-cranz":
        gam = hopkinson_cranz_density_ratio(lam, sig)
        given = None if density_ratio is None else check_positive_scalar("density ratio", density_ratio)
        if given is not None and abs(given - gam) > 1e-9 * gam:
            raise BlastscaleInputError(
                f"density ratio = {given:.6g} is out of range for the Hopkinson-Cranz law: it imposes gamma = "
                f"1/sqrt(gravity_ratio * scale) = {gam:.6g} (use law='general' for another gamma)")
        lz = np.ones_like(Z)
        note = "Hopkinson-Cranz: lambda_Z = 1 (same scaled distance and pressure)"
        if ms is not bm:
            lz = np.asarray(solve_scaled_distance_factors(Z, lam, gam, sig, bm, ms), dtype=float)
            note = "Hopkinson-Cranz with another specimen burst: roots of Eq. (8) with impulse factor lambda"
    else:
        if density_ratio is None:
            raise BlastscaleInputError("density ratio = None is out of range: the general law needs gamma > 0")
        gam = check_positive_scalar("density ratio", density_ratio)
        lz = np.asarray(solve_scaled_distance_factors(Z, lam, gam, sig, bm, None if ms is bm else ms), dtype=float)
        note = f"roots of Eq. (8) on the {ms.name} impulse range (bisection, every case at once)"
    ok = (Z >= zr[0]) & (Z <= zr[1]) & np.isfinite(lz) & (Z * lz >= zs[0]) & (Z * lz <= zs[1])
    f = scaling_factors(lam, gam, sig)
    f = replace(f, scaled_distance=np.where(ok, lz, np.nan), charge=np.where(ok, (lam / lz) ** 3, np.nan))
    with warnings.catch_warnings():
        if extrapolate:
            warnings.simplefilter("ignore", ExtrapolationWarning)
        proto = _scatter(blast_parameters(W[ok], R[ok], bm, extrapolate=extrapolate), ok)
        mod = _scatter(blast_parameters(W[ok] * f.charge[ok], R[ok] * lam, ms, extrapolate=extrapolate), ok)
    imp = mblock = None
    if geometry is not None:  # t_o p (impulsive_check) over arrays, NaN where invalid
        mblock = geometry.scaled(f)
        imp = ImpulsiveCheck(prototype_ratio=proto.positive_duration * geometry.frequency_parameter(gravity),
                             model_ratio=mod.positive_duration * mblock.frequency_parameter(gravity * sig),
                             threshold=float(impulsive_threshold))
    return ModelDesign(law=law, scale=lam, density_ratio=gam, gravity_ratio=sig, scaled_distance_factor=f.scaled_distance,
                       root_note=note, prototype=proto, specimen=mod, factors=f, impulsive=imp, prototype_block=geometry,
                       specimen_block=mblock, gravity=float(gravity), valid=ok)


def _scatter(bp: BlastParameters, ok: np.ndarray) -> BlastParameters:
    """Blast parameters of the valid cases spread over every case (NaN elsewhere)."""
    from dataclasses import fields

    out = {}
    for fld in fields(bp):
        v = getattr(bp, fld.name)
        if isinstance(v, str) or v is None:
            out[fld.name] = v
        else:
            full = np.full(ok.shape, np.nan)
            full[ok] = v
            out[fld.name] = full
    return BlastParameters(**out)
