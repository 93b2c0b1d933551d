"""What a range safety officer asks beyond the blast: how far fragments fly, what the charge stands on,
and where the detonator goes (the test card's ``fragments``, ``pad`` and ``detonator`` keys).

**Fragment hazard distance.** The farthest a fragment lands, whatever its energy at the end (eyes and skin
are hurt well below the 79 J that DDESB TP-12 counts as hazardous to a person): the keep-out radius for
fragments. Each source throws one fragment, the heaviest credible one (heavier fragments of one velocity
fly further, their drag length growing as ``m^(1/3)``), at its Gurney velocity (Gurney 1943; Cooper 1996
ch. 27), along the trajectory of a point mass under gravity and quadratic air drag,

.. math:: \\dot{\\mathbf v} = -\\frac{\\rho_a C_D A}{2 m} |\\mathbf v| \\mathbf v - g \\hat z,
          \\qquad A = (m / \\rho_f)^{2/3}

(a compact fragment, a cube's face presented; Baker et al. 1983 ch. 6: tumbling compact fragments have
C_D 0.6-1.3, the lowest taken here, :data:`FRAGMENT_DRAG_COEFFICIENT`, so the throw errs long) from the
floor at the launch angle that throws it furthest. Sources:

* **the initiator's shell** (its metal cup, :class:`~blastscale.blast.initiation.Initiator`): the whole
  shell as one fragment (an upper bound), driven as a cylinder, ``V = sqrt(2E) / sqrt(M/C + 1/2)``
  (C the initiator's explosive, M the shell);
* **the charge**: a bare charge throws no casing, only what touches it; the minimum distance for a bare
  charge is the throw of a 1 g stone (:data:`STRAY_FRAGMENT_KG`, 2650 kg/m^3) left in contact, driven as
  an open-faced sandwich, ``V = sqrt(2E) [((1 + 2M/C)^3 + 1) / (6 (1 + M/C)) + M/C]^(-1/2)``: sweep the
  pad, and this is the distance anything left on it reaches;
* **the pad**: none when the plate is not cut (:func:`pad_spec`), else the plate's piece under the
  charge thrown as a sandwich flyer.

``sqrt(2E)``, the Gurney constant, from Cooper 1996 Table 27.1 (:data:`GURNEY_M_S`); an explosive not in
it takes the table's largest (HMX's), which errs fast.

**The pad.** The blast fits are for a charge on a rigid reflecting plane (Kingery & Bulmash 1984's
surface burst: the hemisphere's energy reflected whole, twice a free-air charge's). Soil cratering under
the charge takes part of that (about 1.8 W instead of 2 W, UFC 3-340-02 section 2-13), and a contact
charge damages concrete: the charge stands on a mild-steel plate laid on a concrete slab. Its thickness
is 4 times what the charge would cut, by the US Army's steel-cutting rule ``P = 3/8 A`` (FM 5-250
(1992), P [lb TNT] cutting a section of A [in^2] of structural steel, the cut taken along the contact
diameter of the charge), and at least 10 mm (:data:`PAD_MIN_THICKNESS_M`); the plate reaches half the
stand-off behind and beside the charge and 0.1 m past the specimen's back, so the shock runs over one
rigid plane from the charge to and past the specimen.

**The detonator.** The fits assume the charge initiated at its centre: the detonator goes in along the
axis, its output end at the centre (a hemisphere: from the top, vertical, down to the centre of its flat
face on the plate; a sphere on a stand: horizontally from the side away from the specimen), its leads led
away from the specimen and the gauges. Its own output is counted in the charge: the explosive to weigh is
``(W - W_init) / f_I`` (:mod:`blastscale.blast.explosives`).

References
----------
.. [1] Gurney, R. W. (1943). The initial velocities of fragments from bombs, shells and grenades. BRL
       Report 405.
.. [2] Cooper, P. W. (1996). *Explosives Engineering*. Wiley-VCH, ch. 27 (Gurney equations and Table
       27.1 of Gurney constants).
.. [3] Baker, W. E., Cox, P. A., Westine, P. S., Kulesz, J. J., Strehlow, R. A. (1983). *Explosion
       Hazards and Evaluation*. Elsevier, ch. 6 (fragment trajectories and drag).
.. [4] DDESB Technical Paper 12 (2009 rev.). *Fragment and debris hazards* (hazardous fragment: 79 J).
.. [5] US Army FM 5-250 (1992). *Explosives and Demolitions*, steel-cutting charges ``P = 3/8 A``.
.. [6] UFC 3-340-02 (2008). Section 2-13, surface bursts (reflection factor 1.8 on ordinary ground).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from ..blast.initiation import INITIATORS

__all__ = [
    "GURNEY_M_S",
    "FRAGMENT_DRAG_COEFFICIENT",
    "STRAY_FRAGMENT_KG",
    "PAD_MIN_THICKNESS_M",
    "gurney_constant",
    "gurney_cylinder",
    "gurney_sandwich",
    "throw_distance",
    "Fragment",
    "fragment_hazard",
    "pad_spec",
    "detonator_placement",
]

#: Gurney constants sqrt(2E) [m/s] (Cooper 1996 Table 27.1).
GURNEY_M_S = {"tnt": 2440.0, "rdx": 2830.0, "hmx": 2970.0, "petn": 2930.0, "composition-b": 2700.0, "tetryl": 2500.0}
#: Drag coefficient of a tumbling compact fragment: the low end of 0.6-1.3 (Baker et al. 1983 ch. 6) [-].
FRAGMENT_DRAG_COEFFICIENT = 0.6
#: The stray fragment a bare charge may throw: a 1 g stone [kg] (module docstring).
STRAY_FRAGMENT_KG = 1e-3
_STONE = 2650.0  # kg/m^3
_STEEL = 7850.0  # kg/m^3
_AIR = 1.225  # kg/m^3, sea level
_G = 9.81
#: The thinnest pad plate [m] (module docstring).
PAD_MIN_THICKNESS_M = 0.01
_PAD_MARGIN = 4.0  # plate thickness over the thickness the charge cuts
_IN2 = 0.0254**2  # m^2 per in^2
_LB = 0.45359237  # kg per lb


def gurney_constant(explosive: str) -> float:
    """sqrt(2E) [m/s] of ``explosive`` (:data:`GURNEY_M_S`; the table's largest for any other)."""
    return GURNEY_M_S.get(explosive, max(GURNEY_M_S.values()))


def gurney_cylinder(sqrt2e: float, metal_kg: float, explosive_kg: float) -> float:
    """Velocity [m/s] of a cylindrical case of mass M around a charge C: ``sqrt(2E) / sqrt(M/C + 1/2)``."""
    return float(sqrt2e) / math.sqrt(float(metal_kg) / float(explosive_kg) + 0.5)


def gurney_sandwich(sqrt2e: float, metal_kg: float, explosive_kg: float) -> float:
    """Velocity [m/s] of a flyer of mass M on one face of a charge C (open-faced sandwich):
    ``sqrt(2E) [((1 + 2 M/C)^3 + 1) / (6 (1 + M/C)) + M/C]^(-1/2)``.

    >>> round(gurney_sandwich(2440.0, 1.0, 1.0), 1)  # M = C: sqrt(2E) / sqrt(28/12 + 1)
    1336.4
    """
    r = float(metal_kg) / float(explosive_kg)
    return float(sqrt2e) / math.sqrt(((1.0 + 2.0 * r) ** 3 + 1.0) / (6.0 * (1.0 + r)) + r)


def _ranges(mass: float, density: float, v0: float, angles: np.ndarray, cd: float) -> np.ndarray:
    """Landing distances [m] for each launch angle [rad]: classical RK4 on all angles at once, the step a
    tenth of the fastest drag or gravity time scale (at most 50 ms), the landing interpolated linearly."""
    k = _AIR * cd * (mass / density) ** (2.0 / 3.0) / (2.0 * mass)
    y = np.zeros((4, angles.size))
    y[2], y[3] = v0 * np.cos(angles), v0 * np.sin(angles)
    out = np.full(angles.size, np.nan)

    def f(y):
        s = np.hypot(y[2], y[3])
        return np.array([y[2], y[3], -k * s * y[2], -k * s * y[3] - _G])

    live = np.ones(angles.size, bool)
    for _ in range(200000):
        s = float(np.max(np.hypot(y[2, live], y[3, live])))
        dt = min(0.05, 0.1 / (k * s + _G / max(s, 1e-9)))
        k1 = f(y)
        k2 = f(y + 0.5 * dt * k1)
        k3 = f(y + 0.5 * dt * k2)
        k4 = f(y + dt * k3)
        y1 = y + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        down = live & (y1[1] < 0.0)
        frac = y[1, down] / (y[1, down] - y1[1, down])
        out[down] = y[0, down] + frac * (y1[0, down] - y[0, down])
        live &= ~down
        y = y1
        if not live.any():
            break
    return out


def throw_distance(
    mass_kg: float, density_kg_m3: float, velocity_m_s: float, drag: float = FRAGMENT_DRAG_COEFFICIENT
) -> tuple:
    """Farthest landing distance [m] of a compact fragment of ``mass_kg`` and ``density_kg_m3`` launched from the
    floor at ``velocity_m_s`` under gravity and quadratic drag (module docstring), over launch angles (every
    degree from 1 to 45 deg), and that angle [rad]. Without drag the answer is ``v^2 / g`` at 45 deg;
    drag shortens it and lowers the angle."""
    angles = np.radians(np.arange(1.0, 45.01, 1.0))
    r = _ranges(float(mass_kg), float(density_kg_m3), float(velocity_m_s), angles, float(drag))
    i = int(np.nanargmax(r))
    return float(r[i]), float(angles[i])


@dataclass(frozen=True)
class Fragment:
    """One source's fragment (SI): what (``source``, short, and ``note``), its mass, density, launch velocity, the
    distance it lands at most and at what launch angle, and how the velocity was found."""

    source: str
    note: str
    mass_kg: float
    density_kg_m3: float
    velocity_m_s: float
    distance_m: float
    angle_deg: float
    method: str

    def to_dict(self) -> dict:
        return asdict(self)


def _thrown(source, note, mass, density, v0, method) -> Fragment:
    d, a = throw_distance(mass, density, v0)
    return Fragment(source, note, mass, density, v0, d, math.degrees(a), method)


def pad_spec(
    tnt_kg: float, charge_radius_m: float, standoff_m: float, specimen_width_m: float, specimen_depth_m: float
) -> dict:
    """The pad under the charge [SI] (module docstring): a mild-steel plate on a concrete slab, 4 x the thickness
    the charge ``tnt_kg`` [kg TNT] would cut (FM 5-250, ``P = 3/8 A``, along its contact diameter
    ``2 charge_radius_m``) and at least :data:`PAD_MIN_THICKNESS_M`; its plan from half the stand-off behind the
    charge to 0.1 m past the specimen's back, and as wide as the specimen plus the stand-off."""
    area_m2 = 8.0 / 3.0 * (float(tnt_kg) / _LB) * _IN2
    cut = area_m2 / (2.0 * max(float(charge_radius_m), 1e-4))
    t = max(PAD_MIN_THICKNESS_M, _PAD_MARGIN * cut)
    return {
        "material": "mild steel plate on a concrete slab",
        "thickness_m": t,
        "cut_thickness_m": cut,
        "length_m": 1.5 * float(standoff_m) + float(specimen_width_m) + 0.1,
        "width_m": float(specimen_depth_m) + float(standoff_m),
        "why": "the blast fits assume a rigid reflecting floor (a surface burst's hemisphere reflected whole); "
        "soil gives about 1.8 W instead of 2 W (UFC 3-340-02 section 2-13) and a contact charge breaks concrete: "
        "a steel plate 4 x thicker than the charge cuts (FM 5-250, P = 3/8 A) and at least 10 mm",
    }


def fragment_hazard(ch, initiator: str, explosive: str, pad: dict) -> dict:
    """The card's ``fragments`` (module docstring): each source's :class:`Fragment` and ``distance_m``, the largest.

    ``ch``: the charge (:class:`~blastscale.blast.explosives.ChargeEquivalence`); ``initiator``: its name in
    :data:`~blastscale.blast.initiation.INITIATORS` (an initiator stated only by its TNT equivalent has no shell
    here: its row says so); ``explosive``: the library name of the charge's explosive; ``pad``: :func:`pad_spec`'s.
    """
    out = []
    ini = INITIATORS.get(initiator)
    if ini is not None and ini.contents and ini.shell_mass_kg > 0:
        c = ini.explosive_mass_kg
        v = gurney_cylinder(max(gurney_constant(n) for n, _ in ini.contents), ini.shell_mass_kg, c)
        out.append(
            _thrown(
                f"{initiator} shell",
                f"{ini.shell_material}, whole: {ini.shell_source}",
                ini.shell_mass_kg,
                ini.shell_density_kg_m3,
                v,
                "Gurney cylinder (Cooper 1996 ch. 27), the initiator's explosive",
            )
        )
    c = ch.explosive_mass_kg + (ini.explosive_mass_kg if ini is not None else 0.0)
    if c > 0:
        v = gurney_sandwich(gurney_constant(explosive), STRAY_FRAGMENT_KG, c)
        out.append(
            _thrown(
                "bare charge",
                "a 1 g stone left in contact: the minimum distance of a bare charge (sweep the pad)",
                STRAY_FRAGMENT_KG,
                _STONE,
                v,
                "Gurney open-faced sandwich (Cooper 1996 ch. 27)",
            )
        )
    if pad["thickness_m"] < pad["cut_thickness_m"]:  # a plate the charge cuts: its piece under the charge flies
        r = 0.5 * pad["cut_thickness_m"]
        m = _STEEL * math.pi * r * r * pad["thickness_m"]
        v = gurney_sandwich(gurney_constant(explosive), m, c)
        out.append(_thrown("pad plate", "the piece under the charge, cut out", m, _STEEL, v, "Gurney sandwich"))
    far = max((f.distance_m for f in out), default=0.0)
    return {
        "distance_m": far,
        "sources": [f.to_dict() for f in out],
        "pad_fragments": "none: the plate is not cut"
        if pad["thickness_m"] >= pad["cut_thickness_m"]
        else "the plate is cut: its piece under the charge flies",
        "drag_coefficient": FRAGMENT_DRAG_COEFFICIENT,
        "method": "the farthest landing of each source's heaviest credible fragment at its Gurney velocity, under "
        "gravity and air drag (C_D 0.6, Baker et al. 1983 ch. 6), any energy at the end (DDESB TP-12 counts 79 J "
        "as hazardous to a person; eyes are hurt far below)",
    }


def detonator_placement(initiator: str, used: str, burst: str, charge_radius_m: float, ch) -> dict:
    """The card's ``detonator``: where and how the initiator goes in (module docstring), and its own output counted."""
    if burst == "surface":
        where = (
            "vertical, pushed in from the top of the hemisphere down its axis, the output end at the centre of "
            "the flat face on the plate (where the fits start the detonation); leads led up and away from the "
            "specimen and the gauges"
        )
    else:
        where = (
            "horizontal, pushed in from the side facing away from the specimen along the charge-specimen axis, "
            "the output end at the centre of the sphere; leads led back along the stand"
        )
    return {
        "initiator": initiator,
        "used": used,
        "insertion_depth_m": float(charge_radius_m),
        "placement": where,
        "tnt_impulse_kg": ch.initiator_tnt_kg,
        "tnt_pressure_kg": ch.initiator_tnt_pressure_kg
        if ch.initiator_tnt_pressure_kg is not None
        else ch.initiator_tnt_kg,
        "counted": "its own output is part of the charge: the explosive to weigh is (W - W_init) / f_I, and the "
        "safety distances and the licence limit count it on the stricter basis",
    }
