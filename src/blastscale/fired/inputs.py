"""The shot's inputs, checked before any simulation and before the engines are imported: where the gauges and
markers of ``[fired]`` stand, and the records read (:mod:`.records`).

Geometry, in the record axes of :mod:`blastscale.scenario.fired` (x along the blast away from the charge,
z up, origin at the centre of the specimen's footprint at rest; the specimen's bodies at rest, ``com`` +
``vertices``):

* **The charge** stands at ``c = (front_x - standoff, 0, h_c)`` (the one frame's
  :func:`blastscale.similitude.effects.charge_position`, as the engine places it): ``front_x`` the
  specimen's front, ``standoff`` ``[fired] standoff_m`` (else the designed one), ``h_c``
  :func:`shot_charge_height`: ``[scale] specimen_charge_height_m``, else half the specimen's top for a
  free-air specimen burst, else 0 (on the floor).
* **A gauge behind the charge**: ``x_gauge < c_x``: on the far side of the charge from the specimen (the
  plane through the charge normal to the blast axis divides the two sides); a gauge there is a sign or
  an axis mistake (the records' x points away from the charge).
* **Distance from the specimen**: the distance from a point to the specimen's bounding box at rest
  (zero inside it). A gauge farther than :data:`GAUGE_REACH` times the larger of the stand-off and the
  specimen's height is refused (a unit or an axis mistake: the gauges of a shot stand between the charge
  and the specimen, beside it or on it).
* **A reflected gauge's surface**: its ``normal`` as given, else the outward normal of the specimen's face it
  is flush in (:func:`gauge_incidence`): among the faces of the bodies at rest, those whose plane passes within
  :data:`GAUGE_FACE_TOLERANCE` times the specimen's height of the gauge and whose body's solid (the planes of
  its faces and of its bounding box) holds the gauge within that tolerance; the nearest plane. A gauge in no
  face, or at an edge (two such faces of different normals), is refused: give its ``normal``. The angle of
  incidence ``a``, ``cos a = n . (c - g) / |c - g|`` (the charge c, the gauge g), must lie in what the UFC
  charts cover, [0, 90] deg (:data:`blastscale.blast.inverse.INCIDENCE_RANGE_DEG`).
* **A marker on a body**: a marker's rest point lies within :data:`MARKER_TOLERANCE` times the specimen's
  height of some body's solid, the distance to a body measured to the planes of its faces and of its
  bounding box (exact for a point off a face; never more than the true distance to the solid).

Each fault is one :class:`~blastscale._validate.BlastscaleInputError` line naming the table, the point and
why.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError
from ..blast.inverse import INCIDENCE_RANGE_DEG
from ..io.source_file import read_source
from ..similitude.effects import charge_height, charge_position
from ..study.study import Study
from .records import GaugeRecord, TrackRecord, read_gauges, read_tracks

__all__ = [
    "GAUGE_FACE_TOLERANCE",
    "GAUGE_REACH",
    "MARKER_TOLERANCE",
    "GaugeIncidence",
    "ShotInputs",
    "body_gaps",
    "check_geometry",
    "gauge_incidence",
    "shot_charge_height",
    "shot_inputs",
]

#: A gauge lies within this many times max(stand-off, specimen height) of the specimen's bounding box.
GAUGE_REACH = 2.0
#: A marker lies within this fraction of the specimen's height of one of its bodies.
MARKER_TOLERANCE = 0.05
#: A gauge is in a face when the face's plane passes within this fraction of the specimen's height of it (a
#: flush gauge's position is measured to a few mm: 5 mm on a 0.5 m specimen).
GAUGE_FACE_TOLERANCE = 0.01


@dataclass(frozen=True)
class ShotInputs:
    """The shot's checked inputs: the design, the stand-off as fired [m] and the records (None: not given)."""

    design: object
    standoff_m: float
    gauges: GaugeRecord | None
    tracks: TrackRecord | None
    source: object = None  #: the lab's calibrated source (``[lab] source``), None for a chemical charge


def shot_charge_height(scenario, design) -> float:
    """Height of the shot's charge above the floor [m] (:func:`blastscale.similitude.effects.charge_height`):
    ``[scale] specimen_charge_height_m`` where given, else the specimen burst's (half the specimen's top for
    a free-air burst, as the engine places it; 0 on the floor)."""
    given = scenario.scale.specimen_charge_height_m if scenario.scale is not None else None
    return charge_height(design.specimen_structure, getattr(design.specimen, "burst", "surface"), given)


def _body_boxes(structure) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Per body: its centre of mass, its vertices relative to it, and the unit normals and offsets of the
    planes bounding its solid (faces and bounding box) [m]."""
    axes = np.vstack([np.eye(3), -np.eye(3)])
    out = []
    for b in structure.bodies:
        v = np.asarray(b.vertices, dtype=float)
        n = np.vstack([axes] + [np.asarray(f.normal, dtype=float)[None, :] for f in b.faces])
        n = n / np.linalg.norm(n, axis=1)[:, None]
        out.append((np.asarray(b.com, dtype=float), v, n, (v @ n.T).max(axis=0)))
    return out


def body_gaps(structure, point_m) -> np.ndarray:
    """Per body of ``structure`` at rest, the distance [m] from ``point_m`` to its solid measured to the planes
    of its faces and of its bounding box, ``max_k (n_k . (p - c) - h_k)``: <= 0 inside or on the solid, exact
    for a point off a face, never more than the true distance (module docstring)."""
    p = np.asarray(point_m, dtype=float)
    return np.array([float(np.max(n @ (p - c) - h)) for c, _, n, h in _body_boxes(structure)])


def _box_distance(p: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> float:
    return float(np.linalg.norm(np.maximum(np.maximum(lo - p, p - hi), 0.0)))


def check_geometry(scenario, design, standoff_m: float) -> None:
    """Refuse a gauge behind the charge or far from the specimen, and a marker on no body (module docstring).

    Parameters
    ----------
    scenario : Scenario
        With its ``[fired]`` table.
    design : ModelDesign
        ``Study(scenario).check().design``: the specimen at rest.
    standoff_m : float
        The stand-off as fired [m].

    Raises
    ------
    BlastscaleInputError
        One line naming the gauge or marker, its point and why.
    """
    fs = scenario.fired
    structure = design.specimen_structure
    bodies = _body_boxes(structure)
    world = np.vstack([c + v for c, v, _, _ in bodies])
    lo, hi = world.min(axis=0), world.max(axis=0)
    height = float(hi[2] - lo[2])
    charge = charge_position(structure.front_x, standoff_m, shot_charge_height(scenario, design))
    reach = GAUGE_REACH * max(standoff_m, height)
    for name, g in fs.gauge.items():
        p = np.asarray(g.position_m, dtype=float)
        where = f"[fired.gauge.{name}] position_m = {g.position_m!r}"
        if p[0] < charge[0]:
            raise BlastscaleInputError(
                f"{where} is behind the charge (x {p[0]:g} m < the charge's x {charge[0]:g} m = front "
                f"{structure.front_x:g} m - stand-off {standoff_m:g} m): x points from the charge to the specimen"
            )
        off = _box_distance(p, lo, hi)
        if off > reach:
            raise BlastscaleInputError(
                f"{where} is {off:.3g} m from the specimen: a gauge stands within {reach:.3g} m of it "
                f"({GAUGE_REACH:g} x max(stand-off, specimen height)); check its units (m) and axes"
            )
        gauge_incidence(scenario, design, standoff_m, name)
    tol = MARKER_TOLERANCE * height
    for name, m in fs.marker.items():
        p = np.asarray(m.point_m, dtype=float)
        gaps = body_gaps(structure, p)
        k = int(np.argmin(gaps))
        if gaps[k] > tol:
            raise BlastscaleInputError(
                f"[fired.marker.{name}] point_m = {m.point_m!r} is not on any body: {gaps[k]:.3g} m from the "
                f"nearest ({structure.bodies[k].name!r}), {_box_distance(p, lo, hi):.3g} m from the specimen; "
                f"a marker is on a body within {tol:.3g} m ({MARKER_TOLERANCE:g} x the specimen's height), "
                "in the record axes (origin at the centre of the footprint, z up)"
            )


@dataclass(frozen=True)
class GaugeIncidence:
    """Where a reflected gauge looks: the outward unit normal of its surface [-], how it was found (``"given"``
    or the face and body it is in) and the angle of incidence from the charge [deg]."""

    normal: tuple
    found: str
    angle_deg: float


def gauge_incidence(scenario, design, standoff_m: float, name: str) -> GaugeIncidence | None:
    """The surface and angle of incidence of the reflected gauge ``name`` (module docstring); None for a
    side-on gauge.

    Raises
    ------
    BlastscaleInputError
        A gauge in no face of the specimen or at an edge, without a ``normal``; an angle of incidence outside
        what the UFC charts cover (one line naming the gauge, the angle and the range).
    """
    g = scenario.fired.gauge[name]
    if g.kind != "reflected":
        return None
    p = np.asarray(g.position_m, dtype=float)
    where = f"[fired.gauge.{name}] position_m = {g.position_m!r}"
    if g.normal is not None:
        n, found = np.asarray(g.normal, dtype=float), "given"
    else:
        n, found = _face_normal(design.specimen_structure, p, where)
    c = charge_position(design.specimen_structure.front_x, standoff_m, shot_charge_height(scenario, design))
    to_charge = c - p
    cos_a = float(np.clip(n @ to_charge / np.linalg.norm(to_charge), -1.0, 1.0))
    angle = float(np.degrees(np.arccos(cos_a)))
    lo, hi = INCIDENCE_RANGE_DEG
    if not lo <= angle <= hi:
        raise BlastscaleInputError(
            f"{where}: angle of incidence = {angle:.4g} deg (normal {_vec(n)} {found}, charge at {_vec(c)}) is out of "
            f"range: valid range is [{lo:g}, {hi:g}] deg, what UFC 3-340-02 Figs. 2-193 and 2-194 chart (the "
            "surface is turned away from the charge)"
        )
    return GaugeIncidence(tuple(float(x) for x in n), found, angle)


def _vec(v) -> str:
    return "[" + ", ".join(f"{float(x):.4g}" for x in v) + "]"


def _face_normal(structure, p: np.ndarray, where: str) -> tuple[np.ndarray, str]:
    """The outward normal of the face of ``structure`` (at rest) that the point ``p`` [m] is flush in, and
    ``"face LABEL of BODY"`` (module docstring)."""
    bodies = _body_boxes(structure)
    world = np.vstack([c + v for c, v, _, _ in bodies])
    tol = GAUGE_FACE_TOLERANCE * float(world[:, 2].max() - world[:, 2].min())
    near, nearest = [], (np.inf, "no face")
    for body, (com, _, planes, offsets) in zip(structure.bodies, bodies):
        outside = max(float(np.max(planes @ (p - com) - offsets)), 0.0)
        for f in body.faces:
            n = np.asarray(f.normal, dtype=float)
            gap = abs(float(n @ (p - com - np.asarray(f.centre, dtype=float))))
            label = f"face {f.label!r} of {body.name!r}"
            if outside <= tol and gap <= tol:
                near.append((gap, n, label))
            elif max(gap, outside) < nearest[0]:
                nearest = (max(gap, outside), label)
    if not near:
        raise BlastscaleInputError(
            f"{where} is in no face of the specimen ({nearest[0]:.3g} m from the nearest, {nearest[1]}; a gauge "
            f"is in a face within {tol:.3g} m, "
            f"{GAUGE_FACE_TOLERANCE:g} x its height): give normal = [x, y, z], the outward normal of the surface "
            "it is flush in"
        )
    near.sort(key=lambda x: x[0])
    gap, n, label = near[0]
    other = [lab for _, m, lab in near[1:] if float(m @ n) < 1.0 - 1e-9]
    if other:
        raise BlastscaleInputError(
            f"{where} is at an edge, within {tol:.3g} m of {label} and {other[0]}: give normal = [x, y, z], the "
            "outward normal of the surface it is flush in"
        )
    return n, label


def shot_inputs(scenario, *, gauges: GaugeRecord | None = None, tracks: TrackRecord | None = None) -> ShotInputs:
    """The shot's design made (``Study(scenario).check()``: no simulation), its geometry checked
    (:func:`check_geometry`) and its records read (:mod:`.records`; those not given as ``gauges`` /
    ``tracks``), in that order: a bad input is refused before any simulation, and before the engines are
    imported (this module imports none).

    Raises
    ------
    BlastscaleInputError
        No ``[fired]`` or ``[scale]`` table, or a bad point or record (one line).
    """
    fs = scenario.fired
    if fs is None:
        raise BlastscaleInputError("scenario has no [fired] table: give the records (docs/fired.md)")
    if scenario.scale is None or scenario.blast.gravity_only:
        raise BlastscaleInputError("fired needs a designed specimen: the scenario has no [scale] table or no charge")
    source = _shot_source(scenario)
    design = Study(scenario).check().design
    standoff = float(fs.standoff_m if fs.standoff_m is not None else design.specimen.standoff_m)
    check_geometry(scenario, design, standoff)
    if gauges is None and fs.gauges:
        gauges = read_gauges(fs.gauges, names=fs.gauge, max_mb=fs.max_record_mb)
    if tracks is None and fs.tracks:
        px = {n: m.px_per_mm for n, m in fs.marker.items()}
        tracks = read_tracks(fs.tracks, names=fs.marker, px_per_mm=px, max_mb=fs.max_record_mb)
    return ShotInputs(design, standoff, gauges, tracks, source)


def _shot_source(scenario):
    """The lab's calibrated source for a shot fired with it (``[lab] source``: its control value as set,
    ``[fired] control``), None for a chemical charge; a control without a source, or a weighed charge with one,
    refused (one line naming the keys)."""
    fs, lab = scenario.fired, scenario.lab
    path = getattr(lab, "source", None)
    if path is None:
        if fs.control is not None:
            raise BlastscaleInputError(
                f"fired.control = {fs.control:g} needs a calibrated source ([lab] source = SOURCE.toml): the control "
                "value is read through the source's law; a chemical charge is fired.charge_kg"
            )
        return None
    if fs.charge_kg is not None:
        raise BlastscaleInputError(
            f"fired.charge_kg = {fs.charge_kg:g} with [lab] source = {path!r}: a source's shot has no weighed charge; "
            "give the control value as set (fired.control, in the source's unit), or drop [lab] source for a "
            "chemical charge"
        )
    return read_source(path)
