"""Multi-drum stone columns: drums of square or circular section stacked without mortar.

The paper's columns (Masi et al., Sec. "Application to multi-drum masonry columns"): 10 m high,
ten 1 m drums, section side / diameter tapering linearly from 1.65 m at the base to 1.28 m at
the top (after the Parthenon's Doric columns), marble. Each drum is a frustum: of a square
pyramid for the square section, of a regular ``sides``-gon (default 32, vertices on the circle
of the nominal diameter) for the circular one. Mass properties are exact for these solids
(:func:`~.base.frustum_mass_properties`).

Each drum's solid (``RigidBody.vertices``: the frustum's two rings) is what its mass, volume, centre of
mass and inertia are, and what ``show`` and the report draw and print. Contact geometry for the
engine (docs/design.md, "Multi-drum columns on MuJoCo") is not the solid: each drum collides as the
right prism of its *base* section (box / polygon prism, ``RigidBody.shape``) carrying the frustum's
exact mass and inertia; drum k+1's base then rests fully on drum k's (wider) top, which is the exact
contact patch, while frustum meshes whose faces coincide at the joints are ill-conditioned.

A monument's column (issue #38) adds three things to the shaft of drums:

* **drums of given heights** (``drum_heights``, summing to ``height``, the shaft's height);
* **entasis**, the swelling of the shaft's profile, as a *width profile*: the side / diameter at relative
  heights z/H, piecewise linear between the points (``width_profile``, pairs (z/H, width [m]) from z/H = 0 to
  1). A survey gives exactly this: the diameters measured at a few heights (the Parthenon's columns:
  Penrose 1888, Pl. 7; Coulton 1977, Ch. 5). The profile is sampled at the joints and each drum stays the
  frustum between its two end sections (a stone drum's face is straight to within a fraction of a
  millimetre over its height: the chord of the entasis curve over one drum deviates from it by about
  e (h/H)^2 for a bulge e). Without a profile the width tapers linearly from ``base_width`` to
  ``top_width``. The width may not grow with height: each drum's base section then carries the drum
  above it entirely, which keeps the contact prisms' patches exact (a Greek entasis bulges out of the
  straight taper line, never above the base diameter);
* **a capital** (:class:`Capital`): the *echinus*, a frustum of the shaft's section from the top drum's
  top section (its side / diameter) to the abacus's width (for a circular column a polygon frustum whose
  top circumscribed diameter is the abacus width: the circle inscribed in the abacus), and the *abacus*,
  a square slab ``abacus_width`` x ``abacus_width`` x ``abacus_height`` for either section. Both are
  bodies ("echinus", "abacus") on top of the drums, with exact mass properties. The echinus collides as
  its own convex frustum (:class:`~.convex_block.ConvexGeometry`): it widens upward, so the base-section
  prism of a drum would leave the abacus a patch narrower than its true bed; the abacus as its box.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_positive, check_positive_scalar, check_range
from .base import (
    BoxGeometry,
    Face,
    MonitoringPoint,
    PrismGeometry,
    RigidBody,
    as_vertex_tuple,
    frustum_vertices,
    polygon_ring,
    rectangle_ring,
    tapered_face,
)
from .convex_block import ConvexGeometry
from .frustum import frustum_mass_properties, polygon_section_constants

__all__ = ["MultiDrumColumn", "Capital", "SECTIONS", "MIN_SIDES", "MAX_SIDES", "TOP_WIDTH_RATIO_RANGE", "MAX_DRUMS"]

#: Section shapes.
SECTIONS = ("square", "circular")
#: Fewest / most polygon sides of a circular drum (8 keeps the section within 8 % of the circle's
#: area; more than 256 only costs collision time).
MIN_SIDES, MAX_SIDES = 8, 256
#: Allowed top/base width ratio: tapered (entasis-free) to prismatic; a top wider than the base
#: would overhang the base-section contact prisms the engine builds.
TOP_WIDTH_RATIO_RANGE = (0.25, 1.0)
#: Most drums in one column.
MAX_DRUMS = 200
#: Allowed abacus width over the shaft's top width: at least the echinus's base (a capital never narrows
#: the shaft), at most 3x (a generous bound on a capital's spread; a wider slab is a lintel, not a capital).
ABACUS_WIDTH_RATIO_RANGE = (1.0, 3.0)


@dataclass(frozen=True)
class Capital:
    """The capital on a column's shaft: echinus and abacus (module docstring).

    Parameters
    ----------
    abacus_width : float
        Side of the square abacus [m], 1-3 x the shaft's top width (:data:`ABACUS_WIDTH_RATIO_RANGE`);
        also the echinus's top width (square section) or circumscribed diameter (circular).
    abacus_height : float
        Height of the abacus slab [m].
    echinus_height : float
        Height of the echinus [m].
    """

    abacus_width: float
    abacus_height: float
    echinus_height: float

    def __post_init__(self):
        for name, v in (
            ("abacus width", self.abacus_width),
            ("abacus height", self.abacus_height),
            ("echinus height", self.echinus_height),
        ):
            check_positive_scalar(name, v, "m")

    @property
    def height(self) -> float:
        """Echinus and abacus together [m]."""
        return self.echinus_height + self.abacus_height


@dataclass(frozen=True)
class MultiDrumColumn:
    """A column of rigid drums stacked on a rigid ground, optionally with a capital.

    Parameters
    ----------
    section : {"square", "circular"}
        Cross-section shape.
    drums : int
        Number of drums N, 1 <= N <= 200.
    height : float
        Height of the shaft (the drums) [m].
    base_width : float
        Side (square) or diameter (circular) at the base [m].
    top_width : float
        Side or diameter at the shaft's top [m], 0.25-1.0 x ``base_width``; without ``width_profile`` the
        width tapers linearly with height.
    sides : int
        Polygon sides of a circular drum, 8-256 (ignored for a square section).
    density : float
        rho [kg/m^3] (marble 2700).
    drum_heights : sequence of float, optional
        Height of each drum from the base up [m], summing to ``height``; default equal drums.
    extra_points : sequence of MonitoringPoint
        User monitoring points added after the default ones (one per body).
    width_profile : sequence of (float, float), optional
        Entasis: (z/H [-], width [m]) pairs, z/H from 0 to 1 strictly increasing, the width never growing
        with height; piecewise linear between the points, its ends ``base_width`` and ``top_width``
        (module docstring). None: the linear taper.
    capital : Capital, optional
        Echinus and abacus on the top drum (module docstring). None: the bare shaft.
    """

    section: str = "square"
    drums: int = 10
    height: float = 10.0
    base_width: float = 1.65
    top_width: float = 1.28
    sides: int = 32
    density: float = 2700.0
    drum_heights: tuple | None = None
    extra_points: tuple = ()
    width_profile: tuple | None = None
    capital: Capital | None = None

    def __post_init__(self):
        check_choice("section", self.section, SECTIONS)
        for name, v, lo, hi in (("drums", self.drums, 1, MAX_DRUMS), ("sides", self.sides, MIN_SIDES, MAX_SIDES)):
            if (
                isinstance(v, bool)
                or not isinstance(v, (int, float, np.integer, np.floating))
                or not (math.isfinite(v) and float(v).is_integer() and lo <= v <= hi)
            ):
                raise BlastscaleInputError(f"{name} = {v!r} is out of range: valid range is whole numbers {lo}-{hi}")
        object.__setattr__(self, "drums", int(self.drums))
        object.__setattr__(self, "sides", int(self.sides))
        check_positive_scalar("height", self.height, "m")
        check_positive_scalar("base width", self.base_width, "m")
        check_positive_scalar("top width", self.top_width, "m")
        lo, hi = TOP_WIDTH_RATIO_RANGE
        check_range("top width", self.top_width, lo * self.base_width, hi * self.base_width, "m")
        check_positive_scalar("density", self.density, "kg/m^3")
        if self.drum_heights is not None:
            hs = tuple(float(x) for x in np.atleast_1d(check_positive("drum heights", self.drum_heights, "m")))
            if len(hs) != self.drums:
                raise BlastscaleInputError(f"drum heights has {len(hs)} values: must have one per drum ({self.drums})")
            if abs(sum(hs) - self.height) > 1e-9 * self.height:
                raise BlastscaleInputError(
                    f"drum heights sum = {sum(hs):.9g} m is out of range: must equal height = {self.height:.9g} m"
                )
            object.__setattr__(self, "drum_heights", hs)
        if self.width_profile is not None:
            object.__setattr__(
                self, "width_profile", _checked_profile(self.width_profile, self.base_width, self.top_width)
            )
        if self.capital is not None:
            if not isinstance(self.capital, Capital):
                raise BlastscaleInputError(f"capital = {self.capital!r} is not a Capital")
            lo, hi = ABACUS_WIDTH_RATIO_RANGE
            check_range("abacus width", self.capital.abacus_width, lo * self.top_width, hi * self.top_width, "m")
        n = self.n_bodies
        for p in self.extra_points:
            if not isinstance(p, MonitoringPoint) or not 0 <= p.body < n:
                raise BlastscaleInputError(
                    f"extra point = {p!r} is out of range: must be a MonitoringPoint on a body 0-{n - 1}"
                )

    # geometry ------------------------------------------------------------------------
    @property
    def n_bodies(self) -> int:
        """Bodies: the drums, plus echinus and abacus with a capital."""
        return self.drums + (0 if self.capital is None else 2)

    @property
    def drum_heights_m(self) -> tuple:
        """Drum heights from the base up [m] (equal drums unless ``drum_heights`` is given)."""
        return self.drum_heights if self.drum_heights is not None else (self.height / self.drums,) * self.drums

    @property
    def heights(self) -> tuple:
        """Each body's height from the base up [m]: the drums, then echinus and abacus with a capital."""
        cap = () if self.capital is None else (self.capital.echinus_height, self.capital.abacus_height)
        return self.drum_heights_m + cap

    @property
    def joint_heights(self) -> np.ndarray:
        """Heights of the bodies' bases, then the top, shape (bodies + 1,) [m]."""
        return np.concatenate([[0.0], np.cumsum(self.heights)])

    @property
    def total_height(self) -> float:
        """Shaft and capital [m]."""
        return self.height + (0.0 if self.capital is None else self.capital.height)

    def width_at(self, z) -> np.ndarray:
        """Side / diameter of the shaft at height z [m] (0 <= z <= ``height``): the width profile, piecewise
        linear, or the linear taper without one."""
        z = np.asarray(z, dtype=float)
        if self.width_profile is None:
            return self.base_width + (self.top_width - self.base_width) * z / self.height
        zr, w = np.array(self.width_profile, dtype=float).T
        return np.interp(z / self.height, zr, w)

    @property
    def mass(self) -> float:
        """Total mass [kg]."""
        return float(sum(b.mass for b in self.bodies))

    @property
    def front_x(self) -> float:
        """x of the base drum's front face at the ground [m]: -side/2 (square), minus the base
        polygon's inradius (circular, a flat faces the charge)."""
        if self.section == "square":
            return -0.5 * self.base_width
        return -0.5 * self.base_width * math.cos(math.pi / self.sides)

    @property
    def bodies(self) -> tuple:
        """The drums "D-1" (base) .. "D-N" (top) as :class:`~.base.RigidBody`, then "echinus" and "abacus"
        with a capital."""
        return _bodies(self)

    @property
    def interfaces(self) -> tuple:
        """(-1, 0), (0, 1), ...: ground-base and every adjacent pair of bodies."""
        return tuple((i - 1, i) for i in range(self.n_bodies))

    @property
    def monitoring_points(self) -> tuple:
        """ "P-1".."P-n" at each body's front-face centre (drums, then echinus and abacus), then
        ``extra_points``."""
        pts = tuple(
            MonitoringPoint(f"P-{i + 1}", i, next(f.centre for f in b.faces if f.label == "front"))
            for i, b in enumerate(self.bodies)
        )
        return pts + tuple(self.extra_points)

    def describe(self) -> dict:
        """Geometry and material, SI scalar keys and the drum heights (``height_m`` the shaft's; the capital's keys
        with one). The width profile is not among them (its ends are ``base_width_m`` and ``top_width_m``): a sweep
        store names every key's place in a fixed layout, and the scenario file keeps the profile."""
        cap = self.capital
        out = {
            "kind": "multi-drum column",
            "section": self.section,
            "drums": self.drums,
            "height_m": self.height,
            "base_width_m": self.base_width,
            "top_width_m": self.top_width,
            "sides": self.sides if self.section == "circular" else None,
            "density_kg_m3": self.density,
            "drum_heights_m": list(self.drum_heights_m),
            "mass_kg": self.mass,
        }
        if cap is not None:
            out.update(
                abacus_width_m=cap.abacus_width,
                abacus_height_m=cap.abacus_height,
                echinus_height_m=cap.echinus_height,
                total_height_m=self.total_height,
            )
        return out

    def scaled(self, factors) -> "MultiDrumColumn":
        """The geometrically similar column: lengths x ``factors.length`` (lambda), density x
        ``factors.density`` (gamma) (``factors``: a :class:`~blastscale.similitude.ScalingFactors`)."""
        L = check_positive_scalar("scale", factors.length)
        g = check_positive_scalar("density ratio", factors.density)
        return replace(
            self,
            height=self.height * L,
            base_width=self.base_width * L,
            top_width=self.top_width * L,
            density=self.density * g,
            drum_heights=None if self.drum_heights is None else tuple(h * L for h in self.drum_heights),
            extra_points=tuple(replace(p, position=tuple(x * L for x in p.position)) for p in self.extra_points),
            width_profile=None if self.width_profile is None else tuple((z, w * L) for z, w in self.width_profile),
            capital=None
            if self.capital is None
            else Capital(
                self.capital.abacus_width * L, self.capital.abacus_height * L, self.capital.echinus_height * L
            ),
        )


def _checked_profile(profile, base_width: float, top_width: float) -> tuple:
    """The width profile as a tuple of (z/H, width [m]) pairs, checked (class docstring)."""
    try:
        a = np.asarray(profile, dtype=float)
    except (TypeError, ValueError):
        a = np.empty((0, 0))
    if a.ndim != 2 or a.shape[1] != 2 or a.shape[0] < 2 or not np.all(np.isfinite(a)):
        raise BlastscaleInputError(
            f"width profile = {profile!r} is not a list of at least two finite [z/H, width] pairs"
        )
    z, w = a[:, 0], a[:, 1]
    if z[0] != 0.0 or z[-1] != 1.0 or np.any(np.diff(z) <= 0.0):
        raise BlastscaleInputError(
            f"width profile heights z/H = {z.tolist()} are out of range: must rise strictly from 0 to 1"
        )
    if np.any(w <= 0.0) or np.any(np.diff(w) > 0.0):
        raise BlastscaleInputError(
            f"width profile widths = {w.tolist()} m are out of range: must be > 0 and never grow with height "
            "(each drum's base carries the drum above, docs/columns.md)"
        )
    for name, given, end in (("base width", base_width, w[0]), ("top width", top_width, w[-1])):
        if abs(given - end) > 1e-12 * max(abs(given), abs(end)):
            raise BlastscaleInputError(
                f"{name} = {given:.12g} m is out of range: must equal the width profile's end, {end:.12g} m"
            )
    return tuple((float(zi), float(wi)) for zi, wi in zip(z, w))


def _frustum_body(
    col: MultiDrumColumn, name: str, z0: float, H: float, s0: float, s1: float, section: str, top_contact
):
    """One body: the frustum of the ``section`` ("square", or "circular": the ``col.sides``-gon) between
    widths ``s0`` (base, at height ``z0`` [m]) and ``s1`` (top) [m], ``H`` [m] high. A drum collides as the
    prism of its base section (module docstring); a body that widens upward (the echinus) as its own frustum."""
    rho = col.density
    widens = s1 > s0
    if section == "square":
        mp = frustum_mass_properties(s0, s1, H, rho)
        zc = mp.z_com
        faces = (
            tapered_face("front", s0 / 2, s1 / 2, s0, s1, H, zc, math.pi),
            tapered_face("rear", s0 / 2, s1 / 2, s0, s1, H, zc, 0.0),
            tapered_face("side", s0 / 2, s1 / 2, s0, s1, H, zc, -math.pi / 2),
            tapered_face("side", s0 / 2, s1 / 2, s0, s1, H, zc, math.pi / 2),
        )
        load = faces[0]
        shape = BoxGeometry(s0 / 2, s0 / 2, H / 2, H / 2 - zc)
        solid = frustum_vertices(rectangle_ring(s0 / 2, s0 / 2), rectangle_ring(s1 / 2, s1 / 2), -zc, H - zc)
        top_area, base_area, support = s1 * s1, s0 * s0, s0 / 2
    else:
        a, k = polygon_section_constants(col.sides)
        R0, R1 = s0 / 2, s1 / 2
        mp = frustum_mass_properties(R0, R1, H, rho, a, k)
        zc = mp.z_com
        ci, si = math.cos(math.pi / col.sides), math.sin(math.pi / col.sides)
        faces = []
        for j in range(col.sides):
            ang = math.pi + 2.0 * math.pi * j / col.sides
            label = "front" if j == 0 else "rear" if 2 * j == col.sides else "side"
            faces.append(tapered_face(label, R0 * ci, R1 * ci, 2 * R0 * si, 2 * R1 * si, H, zc, ang))
        faces = tuple(faces)
        # Method A: the projected silhouette, diameter x height (tapered)
        load = tapered_face("front", R0, R1, s0, s1, H, zc, math.pi)
        shape = PrismGeometry(R0, col.sides, H / 2, H / 2 - zc)
        solid = frustum_vertices(polygon_ring(R0, col.sides), polygon_ring(R1, col.sides), -zc, H - zc)
        top_area, base_area, support = a * R1 * R1, a * R0 * R0, R0 * ci
    if widens:
        shape = ConvexGeometry(as_vertex_tuple(solid))
    faces = faces + (
        Face("top", (0.0, 0.0, H - zc), (0.0, 0.0, 1.0), top_area, top_contact),
        Face("bottom", (0.0, 0.0, -zc), (0.0, 0.0, -1.0), base_area, True),
    )
    return RigidBody(
        name,
        mp.mass,
        (0.0, 0.0, float(z0) + zc),
        mp.inertia,
        shape,
        faces,
        load,
        -zc,
        math.atan2(support, zc),
        mp.volume,
        as_vertex_tuple(solid),
    )


@functools.lru_cache(maxsize=256)  # a frozen column's bodies never change: built once (they cost ~1 ms)
def _bodies(col: MultiDrumColumn) -> tuple:
    z = col.joint_heights
    n = col.drums
    s = col.width_at(z[: n + 1])
    hs = col.heights
    cap = col.capital
    out = [
        _frustum_body(col, f"D-{i + 1}", z[i], hs[i], float(s[i]), float(s[i + 1]), col.section, i < col.n_bodies - 1)
        for i in range(n)
    ]
    if cap is not None:
        A = cap.abacus_width
        out.append(_frustum_body(col, "echinus", z[n], cap.echinus_height, float(s[n]), A, col.section, True))
        out.append(_frustum_body(col, "abacus", z[n + 1], cap.abacus_height, A, A, "square", False))
    return tuple(out)
