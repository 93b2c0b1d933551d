"""Design a reduced-scale blast experiment from a prototype scenario (the top of the data flow).

``design_model`` takes the prototype (charge W at stand-off R), the geometric scale lambda,
the density ratio gamma and the gravity ratio varsigma, applies a scaling law and returns a
:class:`ModelDesign`: the model's charge and stand-off, lambda_Z, every factor, the blast
parameters of both systems, the ratios the blast actually delivers next to those the
rigid-body response requires, and (when the structure is given) the a-posteriori check that
the load is impulsive (:mod:`.experiment`).
"""

from __future__ import annotations

import warnings
from dataclasses import asdict, fields, replace

import numpy as np

from .._validate import BlastscaleInputError, OutOfRangeError, check_choice, check_positive, check_positive_scalar
from ..blast.base import BlastModel, ExtrapolationWarning
from ..blast.load_model import PAPER_LOAD
from ..blast.parameters import (
    DEFAULT_BLAST_MODEL,
    DEFAULT_BURST,
    BlastParameters,
    blast_parameters,
    model_for_burst,
    valid_scaled_distance_range,
)
from ..constants import STANDARD_GRAVITY
from ..structures.from_spec import is_block
from .effects import BlastSimilarityWarning, blast_effects, structure_top
from .experiment import DEFAULT_IMPULSIVE_THRESHOLD, ImpulsiveCheck, ModelDesign
from .factors import scaling_factors
from .laws import (
    LAWS,
    admissible_scales,
    hopkinson_cranz_density_ratio,
    solve_scaled_distance_factor,
    solve_scaled_distance_factors,
)
from .specimen import specimen_system

__all__ = ["design_model"]


def design_model(
    charge: float,
    standoff: float,
    scale: float,
    density_ratio: float | None = 1.0,
    gravity_ratio: float = 1.0,
    law: str = "general",
    blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    geometry=None,
    *,
    gravity: float = STANDARD_GRAVITY,
    impulsive_threshold: float = DEFAULT_IMPULSIVE_THRESHOLD,
    extrapolate: bool = False,
    burst: str = DEFAULT_BURST,
    specimen_burst: str | None = None,
    load_model=None,
    face=None,
    specimen_charge_height: float | None = None,
    contact=None,
    duration: float | None = None,
    effects: bool = True,
    friction_ratio: float = 1.0,
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
    geometry : structure, optional
        The prototype structure, of any kind (block, column, wall, arch, portal, assembly): the design
        carries it and its specimen (``structure.scaled(factors)``, built here once, by
        :func:`~.specimen.specimen_system` as every part of the specimen system); a rectangular
        block also enables the impulsive check.
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
    contact : ContactSettings, optional
        The prototype's 3D contact settings (:mod:`blastscale.sim3d.contact`): the design carries them
        and the specimen's, ``contact.scaled(factors)`` (times x lambda_t, lengths x lambda), scaled once.
    duration : float, optional
        The prototype's simulated time [s]: the design carries it and the specimen's, x lambda_t.
    effects : bool
        Evaluate the blast effects and their notes (default); False for a caller that needs the
        systems only (a sweep's outcome mode: ~3 ms per case with clearing): ``effects`` is then None
        and ``notes`` empty, the load models are carried all the same.
    friction_ratio : float
        lambda_mu = mu_specimen / mu_prototype [-] (default 1): the specimen's contact settings carry the
        prototype's friction times it (a specimen of another material, :mod:`blastscale.structures.materials`).

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
    once, by the same body, with the same solution of the law: every numeric field of the design is
    then an array, NaN where a case cannot be designed (a scaled distance outside the blast fits;
    ``valid`` says which), and nothing is raised for such a case. The load model, the face and the
    lab charge's height count for arrays as for one case: ``effects`` holds arrays over the cases
    (NaN where invalid) and ``notes`` each note of any case once.

    Examples
    --------
    The paper's 10 m block, 50 kg at 2 m, lambda = 1/200, same material (model 2 of the
    paper's Table 4: 0.233 mg at Z = 1.62 m/kg^(1/3)):

    >>> d = design_model(50.0, 2.0, 1 / 200, blast_model="masi2021")
    >>> round(d.specimen_charge_kg * 1e6, 3), round(d.specimen.scaled_distance, 2)
    (0.233, 1.62)
    """
    scalar = np.ndim(charge) == 0 and np.ndim(standoff) == 0
    W, R = _charges_and_standoffs(charge, standoff, scalar)
    lam = check_positive_scalar("scale", scale)
    if lam > 1.0:  # allowed (the laws hold both ways), but rarely meant: said once
        warnings.warn(
            f"scale = {lam:g} > 1: the specimen is {lam:g} times larger than the prototype (the laws hold "
            f"both ways; for a reduced model give 1/{lam:g})",
            BlastSimilarityWarning,
            stacklevel=2,
        )
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    check_positive_scalar("gravity", gravity, "m/s^2")
    check_positive_scalar("impulsive threshold", impulsive_threshold)
    check_choice("law", law, LAWS)
    bm = model_for_burst(blast_model, burst)
    ms = bm if specimen_burst is None else model_for_burst(blast_model, specimen_burst)
    gam = _density_ratio(law, density_ratio, lam, sig)
    if scalar:  # one case: an invalid one raises, the law's closed-form root
        proto = blast_parameters(W, R, bm, extrapolate=extrapolate)
        lz, note = _solve_one(proto.scaled_distance, lam, gam, sig, law, bm, ms, extrapolate)
        f = scaling_factors(lam, gam, sig, lz, friction_ratio)
        spec = blast_parameters(W * f.charge, R * lam, ms, extrapolate=extrapolate)
        ok = True
    else:  # every case at once, NaN where a case cannot be designed
        f, note, ok, proto, spec = _design_cases(W, R, lam, gam, sig, law, bm, ms, extrapolate)
        f = replace(f, friction=check_positive_scalar("friction ratio", friction_ratio))
    structure = geometry
    lm = PAPER_LOAD if load_model is None else load_model
    spec_sys = specimen_system(f, structure, lm, contact, duration, gravity)  # the specimen system, once, here
    specimen_structure = spec_sys.structure
    imp = None
    if structure is not None and is_block(structure):  # t_o p (:func:`~.experiment.impulsive_check`)
        rp = proto.positive_duration * structure.frequency_parameter(gravity)
        rm = spec.positive_duration * specimen_structure.frequency_parameter(spec_sys.gravity)
        imp = ImpulsiveCheck(
            prototype_ratio=float(rp) if scalar else rp,
            model_ratio=float(rm) if scalar else rm,
            threshold=float(impulsive_threshold),
        )
    lm_s = spec_sys.load_model  # the specimen's load model: its face lambda times the prototype's
    if face is None and structure is not None:
        face = (structure.depth, structure.height) if is_block(structure) else (None, structure_top(structure))
    effects_, notes = None, ()
    if effects and (ms is not bm or not lm.is_paper or specimen_charge_height is not None):
        effects_, notes = _effects(proto, spec, ok, scalar, lm, lm_s, f, face, specimen_charge_height, extrapolate)
        for n in notes:
            warnings.warn(n, BlastSimilarityWarning, stacklevel=2)
    return ModelDesign(
        law=law,
        scale=lam,
        density_ratio=gam,
        gravity_ratio=sig,
        scaled_distance_factor=f.scaled_distance,
        root_note=note,
        prototype=proto,
        specimen=spec,
        factors=f,
        impulsive=imp,
        prototype_structure=structure,
        specimen_structure=specimen_structure,
        gravity=float(gravity),
        valid=ok,
        effects=effects_,
        notes=notes,
        load_model=lm,
        specimen_load_model=lm_s,
        contact=contact,
        specimen_contact=spec_sys.contact,
        duration=None if duration is None else float(duration),
        specimen_duration=spec_sys.duration,
    )


def _charges_and_standoffs(charge, standoff, scalar: bool):
    """W [kg] and R [m], checked: floats for one case, float arrays broadcast together for many."""
    if scalar:
        return check_positive_scalar("charge", charge, "kg"), check_positive_scalar("standoff", standoff, "m")
    try:
        W, R = np.broadcast_arrays(check_positive("charge", charge, "kg"), check_positive("standoff", standoff, "m"))
    except ValueError:
        raise BlastscaleInputError(
            f"charge and standoff have shapes {np.shape(charge)} and {np.shape(standoff)}, "
            "which do not broadcast together"
        ) from None
    return W.astype(float), R.astype(float)


def _density_ratio(law: str, density_ratio, lam: float, sig: float) -> float:
    """gamma [-]: the given one (general law), or the one Hopkinson-Cranz imposes (1/sqrt(varsigma lambda))."""
    if law == "hopkinson-cranz":
        gam = hopkinson_cranz_density_ratio(lam, sig)
        given = None if density_ratio is None else check_positive_scalar("density ratio", density_ratio)
        if given is not None and abs(given - gam) > 1e-9 * gam:
            raise BlastscaleInputError(
                f"density ratio = {given:.6g} is out of range for the Hopkinson-Cranz law: it "
                f"imposes gamma = 1/sqrt(gravity_ratio * scale) = {gam:.6g} (use law='general' for another gamma)"
            )
        return gam
    if density_ratio is None:
        raise BlastscaleInputError("density ratio = None is out of range: the general law needs gamma > 0")
    return check_positive_scalar("density ratio", density_ratio)


def _solve_one(Z: float, lam, gam, sig, law, bm, ms, extrapolate) -> tuple:
    """(lambda_Z, note) of one case: the closed-form root of the law (:func:`~.laws.solve_scaled_distance_factor`);
    a scale that puts the specimen's Z outside the fits raises with the admissible range of the scale."""
    if law == "hopkinson-cranz":
        if ms is bm:
            return 1.0, "Hopkinson-Cranz: lambda_Z = 1 (same scaled distance and pressure)"
        sol = solve_scaled_distance_factor(Z, lam, gam, sig, bm, ms)  # the Z whose impulse factor is lambda
        return sol.factor, "Hopkinson-Cranz with another specimen burst: " + sol.note
    if not extrapolate:  # the model's Z must lie where every fit holds, not only the impulse fit
        zr = valid_scaled_distance_range(ms)
        lo, hi = admissible_scales(Z, gam, sig, bm, zr, specimen_blast_model=ms)
        if not lo <= lam <= hi:
            raise OutOfRangeError(
                f"scale = {lam:.6g} is out of range for the general law: valid range of scale is "
                f"[{lo:.6g}, {hi:.6g}] (it keeps the model's Z inside [{zr[0]:g}, {zr[1]:g}] m/kg^(1/3), where "
                f"every {ms.name} fit holds, for density ratio = {gam:.6g}, gravity ratio = {sig:.6g} and "
                f"prototype Z = {Z:.6g} m/kg^(1/3))"
            )
    sol = solve_scaled_distance_factor(Z, lam, gam, sig, bm, None if ms is bm else ms)
    return sol.factor, sol.note


def _design_cases(W, R, lam, gam, sig, law, bm, ms, extrapolate) -> tuple:
    """(factors, note, valid, prototype, specimen) of arrays of cases: the law solved for every case at once
    (:func:`~.laws.solve_scaled_distance_factors`), NaN where a case cannot be designed."""
    # where the design holds: every fit used, or (extrapolate) the impulse fit the law is solved on
    zr = bm.valid_range("scaled_reflected_impulse") if extrapolate else valid_scaled_distance_range(bm)
    zs = ms.valid_range("scaled_reflected_impulse") if extrapolate else valid_scaled_distance_range(ms)
    Z = R / np.cbrt(W)
    if law == "hopkinson-cranz" and ms is bm:
        lz = np.ones_like(Z)
        note = "Hopkinson-Cranz: lambda_Z = 1 (same scaled distance and pressure)"
    elif law == "hopkinson-cranz":
        lz = np.asarray(solve_scaled_distance_factors(Z, lam, gam, sig, bm, ms), dtype=float)
        note = "Hopkinson-Cranz with another specimen burst: roots of Eq. (8) with impulse factor lambda"
    else:
        lz = np.asarray(solve_scaled_distance_factors(Z, lam, gam, sig, bm, None if ms is bm else ms), dtype=float)
        note = f"roots of Eq. (8) on the {ms.name} impulse range (Illinois, every case at once)"
    ok = (Z >= zr[0]) & (Z <= zr[1]) & np.isfinite(lz) & (Z * lz >= zs[0]) & (Z * lz <= zs[1])
    f = scaling_factors(lam, gam, sig)
    f = replace(f, scaled_distance=np.where(ok, lz, np.nan), charge=np.where(ok, (lam / lz) ** 3, np.nan))
    with warnings.catch_warnings():
        if extrapolate:
            warnings.simplefilter("ignore", ExtrapolationWarning)
        proto = _scatter(blast_parameters(W[ok], R[ok], bm, extrapolate=extrapolate), ok)
        spec = _scatter(blast_parameters(W[ok] * f.charge[ok], R[ok] * lam, ms, extrapolate=extrapolate), ok)
    return f, note, ok, proto, spec


def _effects(proto, spec, ok, scalar, lm, lm_s, factors, face, specimen_charge_height, extrapolate) -> tuple:
    """(effects, notes) of :func:`~.effects.blast_effects`: of the one case, or of every valid case (the
    numbers then arrays over the cases, NaN where invalid; each note once). None when no case is valid."""
    kw = dict(
        specimen_load_model=lm_s,
        factors=factors,
        face=face,
        specimen_charge_height=specimen_charge_height,
        extrapolate=extrapolate,
    )
    if scalar:
        return blast_effects(proto, spec, lm, **kw)
    records, notes = [], []
    cases = np.flatnonzero(np.ravel(ok))
    for i in cases:
        rec, case_notes = blast_effects(_case(proto, i), _case(spec, i), lm, **kw)
        records.append(rec)
        notes += [n for n in case_notes if n not in notes]
    return (_stack(records, cases, np.shape(ok)) if records else None), tuple(notes)


def _case(bp: BlastParameters, i: int) -> BlastParameters:
    """The blast parameters of case ``i`` (flat index) of arrays of them, as numbers."""
    return BlastParameters(
        **{k: (v if isinstance(v, str) or v is None else float(np.ravel(v)[i])) for k, v in asdict(bp).items()}
    )


def _stack(records: list, cases: np.ndarray, shape: tuple):
    """Records of the valid cases (same keys) as one record: numbers become arrays over every case (NaN
    where invalid), values equal in every case are kept, other values become object arrays."""
    first = records[0]
    if isinstance(first, dict):
        return {k: _stack([r.get(k) for r in records], cases, shape) for k in first}
    if all(isinstance(v, (int, float, np.number)) and not isinstance(v, (bool, np.bool_)) for v in records):
        out = np.full(shape, np.nan)
        out.flat[cases] = records
        return out
    if all(v == first for v in records):
        return first
    out = np.full(shape, None, dtype=object)
    out.flat[cases] = records
    return out


def _scatter(bp: BlastParameters, ok: np.ndarray) -> BlastParameters:
    """Blast parameters of the valid cases spread over every case (NaN elsewhere)."""
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
