"""Kinetic settling (docs/performance.md, "What the settling leaves in a tall stack"): an assembly of more than 10
bodies settles with kinetic damping for 80 contact time constants and starts its blast at its static state; a
plain settling of 20 leaves a tall stack oscillating. The rule by size, one setting, the scenario key, and the
physics where it must say no."""

from __future__ import annotations

from dataclasses import replace

import mujoco
import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.scenario import Scenario
from blastscale.sim3d import integrate
from blastscale.sim3d.collision import level_stack
from blastscale.sim3d.contact import STACK_REFERENCE, ContactSettings, default_contact
from blastscale.sim3d.reference import clear_scene_cache, reference_scene
from blastscale.structures import MultiDrumColumn, arch, wall
from blastscale.structures.block import RectangularBlock
from blastscale.study.engines import contact_settings


def _stack(courses: int = 40):
    """One block per course (0.25 x 0.5 x 0.15 m blocks), ``courses`` high: the tall stack at its cheapest."""
    return wall(
        length_m=0.25, height_m=0.15 * courses, thickness_m=0.5, courses=courses, units_per_course=1, bond="stack"
    )


def _settled(structure, settling: str):
    clear_scene_cache()
    scene, _ = reference_scene(structure, replace(default_contact(structure), settling=settling), 9.81)
    return scene.mj_model, integrate._settled(scene)


def test_walls_above_ten_bodies_settle_kinetically_and_the_rest_as_before():
    """Columns (10 drums), a 10-block wall and a block keep the plain settling (their results and goldens bitwise
    unchanged); a stack on level beds above 10 bodies settles kinetically, an arch does not; explicit settings are
    plain; 80 and 20 time constants."""
    for s in (MultiDrumColumn("square"), MultiDrumColumn("circular"), RectangularBlock.from_slenderness(10.0, 0.26)):
        assert default_contact(s).settling == "plain"
    assert default_contact(wall(courses=2, units_per_course=5, bond="stack")).settling == "plain"  # 10 bodies
    assert default_contact(_stack(11)).settling == "kinetic"
    assert default_contact(wall(courses=6, units_per_course=4)).settling == "kinetic"  # running bond: side joints
    # an arch's joints are inclined: it keeps the plain settling (kinetically settled, its creep transient ran 2 s:
    # final speeds 5e-5 to 1.2e-4 sqrt(g H) at 0.8-1.5 s against 2.2-5.5e-5; docs/performance.md)
    voussoirs = arch(radius_m=5.0, thickness_m=0.7, voussoirs=20)
    assert len(voussoirs.bodies) > 10 and not level_stack(voussoirs.interface_details)
    assert default_contact(voussoirs).settling == "plain"
    assert level_stack(_stack(11).interface_details) and not level_stack(())
    assert ContactSettings().settling == "plain" and ContactSettings().to_dict()["settling"] == "plain"
    assert integrate.settle_time_constants(ContactSettings()) == integrate.SETTLE_TIME_CONSTANTS == 20.0
    kinetic = ContactSettings(settling="kinetic")
    assert integrate.settle_time_constants(kinetic) == integrate.KINETIC_SETTLE_TIME_CONSTANTS == 80.0


def test_an_unknown_settling_is_refused_and_the_scenario_key_reaches_the_engine():
    with pytest.raises(BlastscaleInputError, match="settling"):
        ContactSettings(settling="damped")
    base = Scenario.default()
    s = _stack(12)
    assert contact_settings(base, s).settling == "kinetic"
    plain = contact_settings(base.with_values({"simulation.contact.settling": "plain"}), s)
    assert plain == replace(contact_settings(base, s), settling="plain")


def test_a_kinetically_settled_tall_stack_is_at_its_static_state_and_a_plainly_settled_one_is_not(monkeypatch):
    """40 blocks stacked, 10 m reference. Measured: settled plainly for 20 time constants the stack still carries its
    axial oscillation: its positions 2.8e-4 m from the stack settled plainly for 1000 (its static state) and, freed,
    3.6e-2 m/s within the next 20; kinetically, 8.2e-10 m and 1.1e-7 m/s. Bounds: 1e-8 m and 1e-5 m/s (12x and 94x
    above the kinetic figures) against 1e-5 m and 1e-3 m/s (28x and 36x below the plain ones)."""
    st = _stack(40)
    with monkeypatch.context() as mp:  # the plain settling made 50x longer: the stack's static state
        mp.setattr(integrate, "SETTLE_TIME_CONSTANTS", 1000.0)
        static_m, static = _settled(st, "plain")
    static_q = static.qpos.copy()
    clear_scene_cache()
    for settling, must_be_static in (("kinetic", True), ("plain", False)):
        m, d = _settled(st, settling)
        off = float(np.abs(d.qpos - static_q).max())
        speeds = []
        for _ in range(int(round(20 * STACK_REFERENCE.time_constant / STACK_REFERENCE.timestep))):  # 20 of them
            mujoco.mj_step(m, d)
            speeds.append(float(np.abs(d.qvel.reshape(-1, 6)[:, :3]).max()))
        if must_be_static:
            assert off < 1e-8 and max(speeds) < 1e-5, (settling, off, max(speeds))
        else:
            assert off > 1e-5 and max(speeds) > 1e-3, (settling, off, max(speeds))
    assert static_m.nbody == 41
