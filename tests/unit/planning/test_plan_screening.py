"""The screening of every structure kind (no 3D run): every feasible design within every limit of a
random lab (a property), the impulsive check and the stand of a free-air charge for every kind, and
a lab nothing can satisfy answered in one line naming the binding constraint, for every kind."""

import json
import math

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from blastscale.blast.bursts import lab_burst
from blastscale.planning import PlanInfeasible, plan
from blastscale.planning.planner import screen
from blastscale.scenario import Scenario
from blastscale.scenario.lab import LabSpec
from blastscale.similitude.effects import structure_top

COLUMN = {
    "structure": {
        "kind": "column",
        "section": "square",
        "drums": 10,
        "height_m": 10.0,
        "base_width_m": 1.65,
        "top_width_m": 1.28,
        "density_kg_m3": 2700.0,
        "friction": 0.7,
    },
    "blast": {"charge_kg": 250.0, "standoff_m": 10.0, "blast_model": "masi2021"},
    "simulation": {"engine": "3d", "duration_s": 0.5},
}
WALL = {
    "structure": {
        "kind": "wall",
        "length_m": 4.0,
        "height_m": 2.5,
        "thickness_m": 0.5,
        "courses": 5,
        "units_per_course": 4,
        "bond": "running",
        "density_kg_m3": 2400.0,
    },
    "blast": {"charge_kg": 10.0, "standoff_m": 5.0},
    "simulation": {"engine": "3d", "duration_s": 0.5},
}
ARCH = {
    "structure": {
        "kind": "arch",
        "radius_m": 2.5,
        "thickness_m": 0.5,
        "depth_m": 1.0,
        "voussoirs": 9,
        "density_kg_m3": 2400.0,
    },
    "blast": {"charge_kg": 20.0, "standoff_m": 6.0},
    "simulation": {"engine": "3d", "duration_s": 0.5},
}
HEIGHT = {"column": 10.0, "wall": 2.5}  # prototype heights [m]


def _scenario(data, tmp_path=None):
    return Scenario.from_dict(json.loads(json.dumps(data)), source="test")


def _stack(tmp_path):
    """A two-block stack from a block-model file (0.6 m along the blast, 1 m wide, 2.4 m high)."""
    box = lambda n, z0, z1: {"name": n, "vertices": [[x, y, z] for x in (0, 0.6) for y in (0, 1) for z in (z0, z1)]}
    f = tmp_path / "stack.json"
    f.write_text(json.dumps({"blocks": [box("A", 0.0, 1.2), box("B", 1.2, 2.4)]}))
    return {
        "structure": {"kind": "assembly", "file": str(f), "density_kg_m3": 2400.0},
        "blast": {"charge_kg": 5.0, "standoff_m": 4.0},
        "simulation": {"engine": "3d", "duration_s": 0.5},
    }


@st.composite
def labs(draw):
    lo, hi = sorted((draw(st.sampled_from([0.0, 1e-4, 1e-2])), draw(st.floats(1e-3, 10.0))))
    return LabSpec(
        explosive=draw(st.sampled_from(["tnt", "c-4", "petn"])),
        initiator=draw(st.sampled_from(["rp-80", "rp-83", "no-8", "none"])),
        standoff_min_m=draw(st.sampled_from([None, 0.05, 0.5])),
        standoff_max_m=draw(st.sampled_from([None, 1.0, 10.0])),
        gauge_rate_max_hz=draw(st.sampled_from([None, 1e5, 1e6])),
        tnt_max_kg=draw(st.sampled_from([None, 0.01, 1.5])),
        initiator_max_fraction=draw(st.sampled_from([0.05, 0.5, 1.0])),
        charge_min_kg=lo,
        charge_max_kg=max(hi, 1e-3),
        specimen_max_height_m=draw(st.floats(0.05, 6.0)),
        specimen_max_mass_kg=draw(st.floats(0.01, 5000.0)),
        materials=draw(
            st.lists(st.sampled_from(["same", "balsa", "marble", "steel"]), min_size=1, max_size=2, unique=True)
        ),
        camera_max_fps=draw(st.floats(20.0, 1e5)),
        space_radius_m=draw(st.floats(0.2, 60.0)),
        bursts=draw(st.sampled_from([["surface"], ["surface", "free-air"]])),
    )


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(lab=labs(), kind=st.sampled_from(["column", "wall"]))
def test_every_screened_design_is_within_every_limit(lab, kind):
    """Every limit checked on the design's own numbers and, for the specimen's size, on lambda x the
    prototype's height and lambda^3 gamma x its mass (independent of the specimen built by the design)."""
    sc = _scenario({"column": COLUMN, "wall": WALL}[kind])
    _, evs, proto = screen(sc, lab)
    ok = [e for e in evs if not e.violations]
    for e in ok:
        c, d, ch = e.candidate, e.design, e.charge
        assert c.scale * HEIGHT[kind] <= lab.specimen_max_height_m * (1 + 1e-12)
        assert c.scale**3 * d.density_ratio * proto["mass_kg"] <= lab.specimen_max_mass_kg * (1 + 1e-9)
        assert lab.charge_min_kg * (1 - 1e-12) <= ch.explosive_mass_kg <= lab.charge_max_kg * (1 + 1e-12)
        assert (
            ch.explosive_mass_kg >= ch.explosive.min_charge_kg and ch.initiator_fraction <= lab.initiator_max_fraction
        )
        assert e.safety.radius_m <= lab.space_radius_m and e.instruments.camera_fps_required <= lab.camera_max_fps
        assert max(e.impulsive.prototype_ratio, e.impulsive.model_ratio) < 0.4
        assert c.burst in lab.bursts
        # issue #37's limits: the stand-off window, the gauges, the licence (stricter basis, initiator included)
        assert (lab.standoff_min_m or 0.0) <= d.specimen_standoff_m <= (lab.standoff_max_m or math.inf)
        assert e.instruments.pressure_sampling_needed_hz <= (lab.gauge_rate_max_hz or math.inf)
        assert (
            ch.tnt_equivalent_safety_kg <= (lab.tnt_max_kg or math.inf)
            and e.safety.tnt_kg == ch.tnt_equivalent_safety_kg
        )
        if c.burst == "free-air":  # a stand the planner chose: the floor's reflection after the positive phase
            s = d.specimen
            top = structure_top(d.specimen_structure)
            assert lab_burst(s.charge_kg, s.standoff_m, e.charge_height_m, top, extrapolate=True).kind == "free-air"
        else:
            assert e.charge_height_m == 0.0
    if not ok:
        with pytest.raises(PlanInfeasible) as exc:
            plan(sc, lab=lab)
        assert "\n" not in str(exc.value) and str(exc.value).startswith("no design fits the lab")


def test_impulsive_check_for_every_kind_is_the_envelope_blocks():
    """t_o p of the column's envelope (10 m x 1.65 m): p = sqrt(3 g / (4 r)), r the half-diagonal (Housner)."""
    import math

    sc = _scenario(COLUMN)
    _, evs, _ = screen(sc, LabSpec(materials=["same"]))
    e = next(e for e in evs if e.design is not None and e.candidate.scale == 1.0)
    r = 0.5 * math.hypot(10.0, 1.65)
    assert e.impulsive.prototype_ratio == pytest.approx(
        e.design.prototype.positive_duration * math.sqrt(3 * 9.81 / (4 * r)), rel=1e-3
    )


PORTAL = {
    "structure": {"kind": "portal"},
    "blast": {"charge_kg": 20.0, "standoff_m": 6.0},
    "simulation": {"engine": "3d", "duration_s": 0.5},
}
CIRCULAR = {**COLUMN, "structure": {**COLUMN["structure"], "section": "circular"}}


@pytest.mark.parametrize("kind", ["column", "circular", "wall", "arch", "portal", "assembly"])
def test_a_lab_nothing_satisfies_names_the_binding_constraint(kind, tmp_path):
    data = {"column": COLUMN, "circular": CIRCULAR, "wall": WALL, "arch": ARCH, "portal": PORTAL}.get(kind) or _stack(
        tmp_path
    )
    with pytest.raises(PlanInfeasible) as exc:  # screening only: nothing simulated in 3D
        plan(_scenario(data), lab=LabSpec(space_radius_m=0.05, materials=["same"]))
    msg = str(exc.value)
    assert "\n" not in msg and "space_radius_m = 0.05 cannot be met" in msg and "space_radius_m at least" in msg


def test_arrival_spread_of_a_hopkinson_cranz_specimen_is_the_cube_root_scaled_one():
    """Hopkinson-Cranz: every blast time scales as lambda (the charge's cube root), the rocking's as
    sqrt(lambda): the specimen's spread up-scaled by lambda_t is sqrt(lambda) x the prototype's, 1e-9."""
    from blastscale.planning.plan3d import front_arrival_spread
    from blastscale.similitude import design_model
    from blastscale.structures import from_spec

    s = from_spec(_scenario(WALL).structure)
    d = design_model(10.0, 5.0, 1 / 16, None, 1.0, "hopkinson-cranz", "kingery-bulmash", s)
    dt_p = front_arrival_spread(d.prototype, s)
    dt_s = front_arrival_spread(d.specimen, s, d.factors)
    assert 1e-4 < dt_p < 1e-2  # ms over a 2.5 m front at 5 m
    assert dt_s / (d.factors.time * dt_p) == pytest.approx(0.25, rel=1e-9)


def test_the_ensemble_members_the_plan_runs():
    """``lab.ensemble_3d`` unset: 0 for a block on the paper's load (the planar path), 32 for a column or a block
    under clearing (the 3D path); set: as given. `plan --workers/--scheduler` warns only when this is 0."""
    from blastscale.planning.plan3d import ENSEMBLE_3D_DEFAULT, ensemble_members
    from blastscale.scenario import load_scenario
    from blastscale.structures import from_spec

    block = Scenario.default()
    column = load_scenario("paper_column_square_250kg")
    cleared = block.with_values({"blast.clearing": True})
    assert ENSEMBLE_3D_DEFAULT == 32
    for sc, auto in ((block, 0), (column, 32), (cleared, 32)):
        structure = from_spec(sc.structure)
        assert ensemble_members(sc, structure, LabSpec()) == auto
        assert ensemble_members(sc, structure, LabSpec(ensemble_3d=5)) == 5
