"""The check at rest before the blast in the run's size (issue #39, honest time): every 3D run under a charge
first runs its structure under gravity alone for 3 sqrt(H / g) (sim3d.rest), which on a 3000-block wall costs
far more than a 0.01 s blast. The estimate counts its steps (the rest time at the step after the load, the
settling included: a closed form checked here to 1e-12), once for a prototype and a specimen that is its exact
model (the check is shared), twice for a specimen of another friction, never under gravity alone or for the
planar engine; the size line says the rest time."""

from __future__ import annotations

import math

import pytest

from blastscale.scenario import load_scenario
from blastscale.sim3d.integrate import SETTLE_TIME_CONSTANTS
from blastscale.sim3d.rest import REST_NATURAL_TIMES
from blastscale.study import Study, memory


@pytest.fixture(scope="module")
def column():
    sc = load_scenario("paper_column_square_250kg")  # specimen of marble: the prototype's friction (0.7)
    plan = Study(sc).check()
    return sc, plan.structure, plan.contact


def test_the_rest_time_and_its_steps_in_closed_form(column):
    sc, st, c = column
    checks, steps, T = memory.rest_check_size(sc, st, c)
    h, g = st.describe()["height_m"], sc.simulation.gravity_m_s2
    assert checks == 1  # the marble specimen is the prototype's exact model: one check, shared
    assert T == pytest.approx(REST_NATURAL_TIMES * math.sqrt(h / g), rel=1e-12)
    dt = 2.0 * c.timestep  # a stack's step after the load: twice the run's (half the 1 ms contact time constant)
    assert steps == pytest.approx(T / dt + SETTLE_TIME_CONSTANTS * c.time_constant / dt, rel=1e-12)


def test_a_specimen_of_another_friction_is_checked_again(column):
    sc, st, c = column
    steel = sc.with_values({"scale.specimen_material": "steel"})  # joint friction 0.74 against 0.7
    assert memory.rest_check_size(steel, st, c)[0] == 2
    assert memory.rest_check_size(sc.model_copy(update={"scale": None}), st, c)[0] == 1  # the prototype alone


def test_no_check_under_gravity_alone_or_in_the_plane(column):
    sc, st, c = column
    assert memory.rest_check_size(sc.with_values({"blast.charge_kg": 0.0}), st, c) == (0, 0.0, 0.0)
    assert memory.rest_check_size(sc.with_values({"simulation.engine": "planar"}), st, c) == (0, 0.0, 0.0)
    assert memory.rest_check_size(sc, None, c) == (0, 0.0, 0.0)


def test_the_estimate_adds_the_check_and_the_line_says_it(column):
    sc, st, c = column
    nc = 10
    checks, steps, T = memory.rest_check_size(sc, st, c)
    u = len(st.bodies) + nc
    per_step = memory.STEP_BASE_SECONDS + memory.CONTACT_STEP_SECONDS * u  # u = 20 <= CONTACT_STEP_UNITS: linear
    alone = sc.with_values({"blast.charge_kg": 0.0})
    added = memory.estimate_seconds(sc, st, c, nc) - memory.estimate_seconds(alone, st, c, nc)
    assert added == pytest.approx(checks * (steps * per_step + memory.REST_CHECK_SECONDS), rel=1e-9)
    line = memory.estimate_run(sc, st, c, True, nc).line()
    assert f"8 s simulated (and {T:.2g} s at rest before the blast), " in line
    assert "at rest" not in memory.estimate_run(alone, st, c, True, nc).line()
