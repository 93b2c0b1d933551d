"""What clearing, the negative phase and the burst type do to a designed experiment, for both systems.

The scaling laws match the reflected positive impulse of an unbounded face (paper Eq. 8). Three
effects the paper leaves out change the load of the prototype and of the specimen differently:

* **clearing** (:mod:`blastscale.blast.clearing`): the relief time ``t_c = 4 S / ((1 + R) C_r)``
  scales with the face (lambda) and with the sound speed behind the reflected shock, the positive
  duration with ``W^(1/3) t_o_hat(Z)``; under the general law their ratio is not preserved, and
  neither is the cleared fraction of the impulse;
* **the negative phase** (:mod:`blastscale.blast.negative_phase`): its impulse relative to the
  positive one depends on Z, which the general law changes (lambda_Z != 1);
* **the burst type** (:mod:`blastscale.blast.bursts`): a specimen shot on a stand (free-air) for a
  monument threatened by a ground burst, and a lab charge that is neither.

:func:`blast_effects` gives, for prototype and specimen, ``t_c / t_o``, the cleared and uncleared
impulse, the negative impulse over the positive one, and a note wherever the two systems differ by
more than :data:`SIMILARITY_TOLERANCE` (a violation of similarity the scaling law does not see).
:func:`clearing_corrected_charge` solves for the specimen charge whose *cleared* impulse scales as
the law requires (the correction asked in docs/blast_physics.md).
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import BlastscaleInputError, check_positive_scalar
from ..blast.bursts import lab_burst
from ..blast.load_model import PAPER_LOAD, front_face_clearing, front_face_negative, load_model_record
from ..blast.parameters import blast_parameters, get_blast_model, valid_scaled_distance_range
from ..roots import scalar_root
from ..structures.assembly import Assembly
from .factors import to_specimen

__all__ = [
    "FRAME",
    "SIMILARITY_TOLERANCE",
    "CONTINUOUS_FRONT",
    "front_geometry",
    "structure_top",
    "charge_height",
    "charge_position",
    "front_face",
    "blast_effects",
    "clearing_corrected_charge",
    "BlastSimilarityWarning",
]

#: The one frame of blastscale's positions, in words (:func:`charge_position`; the test card states it).
FRAME = (
    "x along the blast, from the charge to the structure; y across; z up; origin at the centre of the "
    "structure's footprint on the floor at rest"
)

#: Relative difference between prototype and specimen above which a design notes a violation [-].
SIMILARITY_TOLERANCE = 0.05


class BlastSimilarityWarning(UserWarning):
    """A blast effect the scaling law does not match differs between prototype and specimen."""


#: Fraction of an assembly's front outline its blocks' fronts must fill for clearing to treat it as one face.
CONTINUOUS_FRONT = 0.99


def front_geometry(structure) -> tuple:
    """The loaded front of a structure for clearing: each body's front width [m] and the height of
    the structure's top above the ground [m] (the front is continuous from the ground to the top:
    relief from the two vertical edges and the top, UFC 3-340-02 Sec. 2-15.3.2).

    A block or a column: each body's ``load_face`` projected on the y-z plane over the body's height
    (a block's depth, a drum's side or diameter). An assembly (wall, arch, portal, block file): its
    front outline as one face for every body, the blocks' y extent by the top's height, provided the
    fronts of its blocks (their exposed faces towards the charge, projected) fill at least
    :data:`CONTINUOUS_FRONT` of it; a front with openings (an arch, a portal) has no UFC clearing
    procedure here and is refused in one line.
    """

    if isinstance(structure, Assembly):
        return _assembly_front(structure)
    widths, top = [], 0.0
    for b in structure.bodies:
        h, body_top = _height_and_top(b)
        f = b.load_face
        widths.append(float(f.area) * abs(float(f.normal[0])) / h)
        top = max(top, body_top)
    return np.array(widths), top


def _height_and_top(body) -> tuple:
    """A body's height [m] and its top above the ground [m]: from its contact box or prism, or (a convex mesh:
    a column's echinus) from its solid's vertices."""
    sh = body.shape
    if hasattr(sh, "half_height"):
        return 2.0 * float(sh.half_height), float(body.com[2]) + float(getattr(sh, "centre_z", 0.0)) + float(
            sh.half_height
        )
    z = np.asarray(body.vertices, dtype=float)[:, 2]
    return float(z.max() - z.min()), float(body.com[2]) + float(z.max())


def structure_top(structure) -> float:
    """Height of a structure's top above the ground [m] (a free-air charge stands at half of it)."""

    if isinstance(structure, Assembly):
        return float(max(b.points[:, 2].max() for b in structure.blocks))
    return float(front_geometry(structure)[1])


def charge_height(structure, burst: str = "surface", height_m: float | None = None) -> float:
    """Height of the charge's centre above the floor [m]: ``height_m`` where the scenario sets it (the lab's
    stand, ``scale.specimen_charge_height_m``), else half the structure's top (:func:`structure_top`) for a
    ``"free-air"`` burst (a stand at the front's mid-height, as the 3D engine places it), else 0 (a surface
    burst: on the floor)."""
    if height_m is not None:
        return float(height_m)
    return 0.5 * structure_top(structure) if burst == "free-air" else 0.0


def charge_position(front_x_m: float, standoff_m: float, height_m: float = 0.0) -> np.ndarray:
    """The charge's centre [x, y, z] [m] in the one frame of blastscale: the 3D engine's loads, the test
    card's layout, the plan and the ``[fired]`` records share it. x horizontal along the blast, from the
    charge to the structure; y across; z up; the origin at the centre of the structure's footprint on the
    floor at rest (a block's front face at x = -width/2). The charge stands ``standoff_m`` in front of the
    structure's front ``front_x_m`` (its smallest x: ``structure.front_x``), on the blast axis (y = 0), at
    ``height_m`` (:func:`charge_height`): ``(front_x - standoff, 0, height)``.

    Raises
    ------
    BlastscaleInputError
        A stand-off that is not > 0, or a height below 0.
    """
    R = check_positive_scalar("standoff_m", standoff_m, "m")
    if not height_m >= 0.0:
        raise BlastscaleInputError(f"charge height = {height_m!r} m is out of range: must be >= 0 m")
    return np.array([float(front_x_m) - R, 0.0, float(height_m)])


def _assembly_front(structure) -> tuple:
    pts = np.vstack([b.points for b in structure.blocks])
    width, top = float(np.ptp(pts[:, 1])), float(pts[:, 2].max())
    filled = sum(
        float(f.area) * -float(f.normal[0])
        for b in structure.bodies
        for f in b.faces
        if not f.in_contact and float(f.normal[0]) < 0.0
    )
    frac = filled / (width * top)
    if frac < CONTINUOUS_FRONT:
        raise BlastscaleInputError(
            f"blast.clearing = true on structure.kind = {structure.kind!r}: its blocks' fronts fill {100 * frac:.3g} % "
            f"of its {width:.4g} m x {top:.4g} m front (openings); clearing needs a continuous front (valid: block, "
            f"column, wall, or a block file whose front is full, >= {100 * CONTINUOUS_FRONT:g} %)"
        )
    return np.full(len(structure.bodies), width), top


def front_face(structure) -> tuple:
    """(width, height) [m] of the structure's front as one face for a design's summary: the lowest
    body's front width and the top's height (:func:`front_geometry`)."""
    w, top = front_geometry(structure)
    return float(w[0]), float(top)


def _rel(a, b) -> float:
    """|a / b - 1| (inf where b is 0)."""
    return abs(a / b - 1.0) if b else math.inf


def blast_effects(
    prototype,
    specimen,
    load_model=None,
    *,
    specimen_load_model,
    factors,
    face=None,
    specimen_charge_height=None,
    extrapolate: bool = False,
) -> tuple:
    """Clearing, negative phase and burst type of a designed experiment, for both systems.

    Parameters
    ----------
    prototype, specimen : BlastParameters
        The design's blast parameters of each system (one charge and stand-off each).
    load_model : LoadModel, optional
        The prototype's load model (its face for clearing; the specimen's face is lambda times it).
    factors : ScalingFactors
        The design's specimen / prototype factors (``length``: lambda, for the specimen's face).
    face : (float, float), optional
        The prototype's loaded face (width, height) [m] (:func:`front_face`), for the lab burst's check
        when the load model has no clearing face.
    specimen_charge_height : float, optional
        Height [m] of the lab charge's centre above the floor: classified as a surface, free-air or
        neither burst at the specimen's face (:func:`blastscale.blast.bursts.lab_burst`).
    extrapolate : bool
        Let the negative-phase calibration run outside its range.
    specimen_load_model : LoadModel
        The specimen's load model: the design's (``ModelDesign.specimen_load_model``, scaled once by
        :func:`~.specimen.specimen_system`); this function scales nothing.

    Returns
    -------
    (dict, tuple of str)
        ``blast_effects`` record (SI keys; ``prototype`` / ``model`` sub-dicts) and the notes (each a
        one-line warning of a difference above :data:`SIMILARITY_TOLERANCE` or a lab burst that is
        neither surface nor free-air).
    """

    lm_p = load_model or PAPER_LOAD
    lm_s = PAPER_LOAD if specimen_load_model is None else specimen_load_model  # the design's
    out: dict = {
        "load_model": {
            "prototype": load_model_record(prototype.blast_model, prototype.burst, lm_p),
            "model": load_model_record(specimen.blast_model, specimen.burst, lm_s),
        }
    }
    notes: list = []
    if prototype.burst != specimen.burst:
        notes.append(
            f"burst: the prototype's is a {prototype.burst} burst, the model's a {specimen.burst} burst "
            f"(the general law matches their reflected impulses, {prototype.blast_model} against "
            f"{specimen.blast_model})"
        )
    if lm_p.clearing:
        out["clearing"] = _clearing(((prototype, lm_p), (specimen, lm_s)), notes)
    if lm_p.negative_phase:
        out["negative_phase"] = _negative_phase(((prototype, lm_p), (specimen, lm_s)), notes, extrapolate)
    if specimen_charge_height is not None:
        height = (
            lm_s.face_height_m
            if lm_s.clearing
            else (None if face is None else to_specimen(float(face[1]), factors, "length"))
        )
        out["lab_burst"] = _lab_burst(specimen, specimen_charge_height, height, notes)
    return out, tuple(notes)


def _clearing(systems, notes: list) -> dict:
    """The clearing of each system's front face (``systems``: (blast parameters, load model) of the prototype,
    then of the model): t_c / t_o, the cleared / uncleared impulse and their relative differences; a note
    appended to ``notes`` where they differ above :data:`SIMILARITY_TOLERANCE`."""
    c = {}
    for name, (bp, lm) in zip(("prototype", "model"), systems):
        cl = front_face_clearing(bp, lm)
        c[name] = {
            **cl.to_dict(),
            "positive_duration_s": float(bp.positive_duration),
            "clearing_time_over_positive_duration": float(cl.clearing_time / bp.positive_duration),
            "cleared_over_uncleared_impulse": float(cl.impulse / cl.uncleared_impulse),
        }
    r_t = _rel(
        c["model"]["clearing_time_over_positive_duration"], c["prototype"]["clearing_time_over_positive_duration"]
    )
    r_i = _rel(c["model"]["cleared_over_uncleared_impulse"], c["prototype"]["cleared_over_uncleared_impulse"])
    c["relative_difference_clearing_time_over_duration"] = r_t
    c["relative_difference_cleared_fraction"] = r_i
    if r_i > SIMILARITY_TOLERANCE:
        notes.append(
            f"clearing: the cleared / uncleared impulse is {c['prototype']['cleared_over_uncleared_impulse']:.3g} "
            f"(prototype) vs {c['model']['cleared_over_uncleared_impulse']:.3g} (model), t_c / t_o "
            f"{c['prototype']['clearing_time_over_positive_duration']:.3g} vs "
            f"{c['model']['clearing_time_over_positive_duration']:.3g}: a {100 * r_i:.3g} % difference the "
            "scaling law does not see"
        )
    elif r_t > SIMILARITY_TOLERANCE:
        fp, fm = c["prototype"]["cleared_over_uncleared_impulse"], c["model"]["cleared_over_uncleared_impulse"]
        what = (
            "no clearing in either system (UFC keeps the uncleared pulse)"
            if fp == 1.0 and fm == 1.0
            else f"the cleared / uncleared impulse still agrees ({fp:.3g} vs {fm:.3g})"
        )
        notes.append(
            f"clearing: t_c / t_o is {c['prototype']['clearing_time_over_positive_duration']:.3g} (prototype) vs "
            f"{c['model']['clearing_time_over_positive_duration']:.3g} (model), the relief is not similar; {what}"
        )
    return c


def _negative_phase(systems, notes: list, extrapolate: bool) -> dict:
    """The negative phase on each system's front face (``systems`` as :func:`_clearing`'s): its impulse over the
    positive one and their relative difference; a note appended to ``notes`` above
    :data:`SIMILARITY_TOLERANCE`."""
    n = {}
    for name, (bp, lm) in zip(("prototype", "model"), systems):
        neg = front_face_negative(bp, lm, extrapolate=extrapolate)
        n[name] = {**neg.to_dict(), "negative_over_positive_impulse": float(neg.impulse / bp.reflected_impulse)}
    r_n = _rel(n["model"]["negative_over_positive_impulse"], n["prototype"]["negative_over_positive_impulse"])
    n["relative_difference_negative_fraction"] = r_n
    if r_n > SIMILARITY_TOLERANCE:
        notes.append(
            f"negative phase: its impulse is {n['prototype']['negative_over_positive_impulse']:.3g} of the positive "
            f"one in the prototype, {n['model']['negative_over_positive_impulse']:.3g} in the model (a "
            f"{100 * r_n:.3g} % difference the scaling law does not see)"
        )
    return n


def _lab_burst(specimen, charge_height: float, face_height, notes: list) -> dict:
    """The lab charge at ``charge_height`` [m] classified at the specimen's face of height ``face_height`` [m]
    (None: unknown, an error); a note appended to ``notes`` when it is not the burst the design assumed."""
    if face_height is None:
        raise BlastscaleInputError(
            "specimen charge height needs the specimen's face height: give the structure (or clearing's face)"
        )
    lb = lab_burst(specimen.charge_kg, specimen.standoff_m, charge_height, face_height, extrapolate=True)
    if lb.kind != specimen.burst:
        notes.append(
            f"lab charge at {charge_height:.4g} m is {'neither a surface nor a free-air burst' if lb.kind == 'neither' else 'a ' + lb.kind + ' burst'}: "
            f"the floor's reflection reaches the face {lb.reflection_delay_s:.3g} s after the shock, "
            f"{lb.delay_ratio:.2g} of the positive duration (the design assumed a {specimen.burst} burst)"
        )
    return lb.to_dict()


def clearing_corrected_charge(design, load_model=None, *, extrapolate: bool = False) -> dict:
    """The specimen charge (at the design's stand-off lambda R) whose *cleared* impulse is the
    prototype's cleared impulse times the required impulse factor gamma sqrt(varsigma lambda^3).

    The general law matches the reflected impulse of an unbounded face; on finite faces the two
    systems clear differently (:func:`blast_effects`). Bisection in ln W over the specimen fit's
    range of Z (the cleared impulse grows with the charge). ``load_model``: the prototype's, with
    clearing and its face: the design's (``ModelDesign.load_model``; default), whose specimen load model
    is used as the design carries it (another one raises: design with ``design_model(..., load_model=...)``).

    Returns
    -------
    dict
        ``charge_kg`` (corrected) and ``design_charge_kg`` [kg], their ratio, the corrected
        specimen's scaled distance, peak pressure and positive duration against the design's
        (the cost: what moves away from similarity to restore the impulse).
    """

    if load_model is not None and load_model != design.load_model:
        raise BlastscaleInputError(
            f"load model = {load_model!r} is not the design's ({design.load_model!r}): the specimen's load model "
            "comes from the design; design with design_model(..., load_model=...)"
        )
    load_model, lm_s = design.load_model, design.specimen_load_model  # the design's, scaled once by it
    if load_model is None or not load_model.clearing:
        raise BlastscaleInputError("clearing corrected charge needs a load model with clearing (and its face)")
    target = to_specimen(float(front_face_clearing(design.prototype, load_model).impulse), design.factors, "impulse")
    ms = get_blast_model(design.specimen.blast_model)
    R = float(design.specimen_standoff_m)
    zlo, zhi = valid_scaled_distance_range(ms)
    lo, hi = 3.0 * math.log(R / zhi * (1 + 1e-12)), 3.0 * math.log(R / zlo * (1 - 1e-12))

    def cleared(u):
        bp = blast_parameters(math.exp(u), R, ms, extrapolate=extrapolate)
        return float(front_face_clearing(bp, lm_s).impulse), bp

    if not (cleared(lo)[0] <= target <= cleared(hi)[0]):
        raise BlastscaleInputError(
            "clearing corrected charge: no specimen charge within the fits' range of Z "
            "delivers the required cleared impulse"
        )
    u = scalar_root(lambda x: cleared(x)[0] - target, lo, hi)  # the cleared impulse grows with the charge
    W = math.exp(u)
    bp = cleared(u)[1]
    d = design.specimen
    return {
        "charge_kg": W,
        "design_charge_kg": float(d.charge_kg),
        "charge_ratio": W / float(d.charge_kg),
        "scaled_distance": float(bp.scaled_distance),
        "design_scaled_distance": float(d.scaled_distance),
        "reflected_pressure_ratio": float(bp.reflected_pressure / d.reflected_pressure),
        "positive_duration_ratio": float(bp.positive_duration / d.positive_duration),
        "uncleared_impulse_ratio": float(bp.reflected_impulse / d.reflected_impulse),
        "target_cleared_impulse_Pa_s": target,
    }
