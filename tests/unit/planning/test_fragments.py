"""The test card's fragments, pad and detonator (planning.fragments): closed forms of the Gurney velocities and of
the steel-cutting rule, the throw against the vacuum range and an independent ODE solution."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from blastscale.blast.initiation import INITIATORS
from blastscale.planning.fragments import (
    FRAGMENT_DRAG_COEFFICIENT,
    PAD_MIN_THICKNESS_M,
    fragment_hazard,
    gurney_constant,
    gurney_cylinder,
    gurney_sandwich,
    pad_spec,
    throw_distance,
)
from blastscale.planning.shot import lab_charge
from blastscale.scenario.lab import LabSpec


def test_gurney_closed_forms():
    """Cylinder: M -> 0 gives sqrt(2) sqrt(2E), M = C gives sqrt(2E) / sqrt(1.5); sandwich: M = C gives
    sqrt(2E) / sqrt(28/12 + 1); an explosive outside the table takes its largest constant (HMX's 2.97 km/s)."""
    assert gurney_cylinder(2440.0, 1e-12, 1.0) == pytest.approx(2440.0 * math.sqrt(2.0), rel=1e-9)
    assert gurney_cylinder(2440.0, 1.0, 1.0) == pytest.approx(2440.0 / math.sqrt(1.5), rel=1e-15)
    assert gurney_sandwich(2440.0, 1.0, 1.0) == pytest.approx(2440.0 / math.sqrt(28.0 / 12.0 + 1.0), rel=1e-15)
    assert gurney_constant("tnt") == 2440.0 and gurney_constant("anfo") == gurney_constant("hmx") == 2970.0


def test_throw_without_drag_is_the_vacuum_range_and_with_drag_an_ode():
    """Without drag: v^2 / g at 45 deg (to 3e-4: RK4, the landing interpolated). With drag: the landing of an
    independent solve_ivp integration at the angle found (to 1e-3), shorter, the angle lower; the heavier fragment
    of one velocity and density flies further (its drag length grows as m^(1/3)); a zero velocity goes nowhere."""
    d, a = throw_distance(1.0, 2650.0, 30.0, drag=0.0)
    assert d == pytest.approx(900.0 / 9.81, rel=3e-4) and a == pytest.approx(math.pi / 4)
    m, rho, v0 = 1e-3, 2650.0, 1000.0
    d, a = throw_distance(m, rho, v0)
    k = 1.225 * FRAGMENT_DRAG_COEFFICIENT * (m / rho) ** (2 / 3) / (2 * m)

    def rhs(_t, y):
        s = math.hypot(y[2], y[3])
        return [y[2], y[3], -k * s * y[2], -k * s * y[3] - 9.81]

    def ground(_t, y):
        return y[1]

    ground.terminal, ground.direction = True, -1
    sol = solve_ivp(rhs, (0, 100), [0, 0, v0 * math.cos(a), v0 * math.sin(a)], events=ground, rtol=1e-9, atol=1e-12)
    assert d == pytest.approx(float(sol.y_events[0][0][0]), rel=1e-3)
    assert d < v0**2 / 9.81 / 100 and a < math.pi / 4
    assert throw_distance(8e-3, rho, v0)[0] > d
    assert throw_distance(m, rho, 1e-9)[0] == pytest.approx(0.0, abs=1e-9)


def test_pad_by_the_steel_cutting_rule():
    """FM 5-250: P = 3/8 A (lb TNT, in^2): 1 lb cuts 8/3 in^2 = 1.7204e-3 m^2, over a 0.1 m contact diameter
    17.2 mm; the plate is 4 x that. A tiny charge gets the 10 mm floor."""
    pad = pad_spec(0.45359237, 0.05, 1.0, 0.3, 0.3)
    assert pad["cut_thickness_m"] == pytest.approx(8 / 3 * 0.0254**2 / 0.1, rel=1e-12)
    assert pad["thickness_m"] == pytest.approx(4 * pad["cut_thickness_m"], rel=1e-12)
    assert pad_spec(1e-4, 0.003, 0.1, 0.05, 0.05)["thickness_m"] == PAD_MIN_THICKNESS_M
    assert pad["length_m"] == pytest.approx(1.5 + 0.3 + 0.1) and pad["width_m"] == pytest.approx(1.3)


def test_fragment_sources():
    """A named initiator throws its shell (the cylinder velocity of its explosive and shell); none throws no shell;
    a plate the charge cuts throws its piece (the answer "no" to "no pad fragments")."""
    lab = LabSpec(initiator="rp-80")
    ch = lab_charge(1e-2, lab)
    pad = pad_spec(ch.tnt_equivalent_safety_kg, 0.01, 0.5, 0.2, 0.2)
    f = fragment_hazard(ch, "rp-80", "tnt", pad)
    shell = f["sources"][0]
    ini = INITIATORS["rp-80"]
    assert shell["velocity_m_s"] == pytest.approx(gurney_cylinder(2930.0, ini.shell_mass_kg, 203e-6), rel=1e-12)
    assert f["distance_m"] == max(s["distance_m"] for s in f["sources"]) and "none" in f["pad_fragments"]
    none = fragment_hazard(lab_charge(1e-2, LabSpec(initiator="none")), "none", "tnt", pad)
    assert [s["source"].split(":")[0] for s in none["sources"]] == ["bare charge"]
    thin = {**pad, "thickness_m": 0.5 * pad["cut_thickness_m"]}
    cut = fragment_hazard(ch, "rp-80", "tnt", thin)
    assert cut["sources"][-1]["source"] == "pad plate" and "cut" in cut["pad_fragments"]
    assert np.isfinite([s["distance_m"] for s in cut["sources"]]).all()
