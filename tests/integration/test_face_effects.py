"""Clearing and the negative phase on the faces of Methods A, B and C: exact impulse per step, the
unbounded face, where each effect acts (no simulation: the loads at rest)."""

import math

import numpy as np
import pytest

from blastscale.blast import blast_parameters
from blastscale.blast.load_model import LoadModel, PhasedPulse, front_face_pulse
from blastscale.sim3d import make_load
from blastscale.similitude.effects import front_face
from blastscale.structures import MultiDrumColumn, RectangularBlock

COL = MultiDrumColumn(section="square")
BP = blast_parameters(250.0, 10.0)


def _rest(structure):
    pos = np.array([b.com for b in structure.bodies], dtype=float)
    rot = np.broadcast_to(np.eye(3), (len(structure.bodies), 3, 3))
    return pos, rot


def _impulse(load, structure, dt):
    pos, rot = _rest(structure)
    t = np.arange(load.first_arrival - dt, load.end_time + 2 * dt, dt)
    return sum(load.step_wrenches(t0, t1, pos, rot)[:, :3] * (t1 - t0) for t0, t1 in zip(t[:-1], t[1:]))


@pytest.mark.parametrize("method", ["B", "C"])
def test_negative_phase_impulse_is_exact_per_step(method):
    load = make_load(method, COL, BP, load_model=LoadModel(negative_phase=True))
    a = _impulse(load, COL, 2.5e-4)
    b = _impulse(load, COL, 1.7e-3)
    np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9 * np.abs(a).max())
    np.testing.assert_allclose(a, load.delivered_impulse(), rtol=1e-9, atol=1e-9 * np.abs(a).max())
    paper = make_load(method, COL, BP)
    # the suction pulls back: less horizontal impulse than the positive phase alone, and it lasts longer
    assert a[:, 0].sum() < paper.delivered_impulse()[:, 0].sum()
    assert load.end_time > paper.end_time + 0.02


def test_an_unbounded_face_leaves_method_b_unchanged():
    paper = make_load("B", COL, BP)
    far = make_load("B", COL, BP, load_model=LoadModel(clearing=True, face_width_m=math.inf, face_height_m=math.inf))
    pos, rot = _rest(COL)
    for t0 in np.linspace(paper.first_arrival, paper.end_time, 7):
        np.testing.assert_array_equal(
            far.step_wrenches(t0, t0 + 1e-4, pos, rot), paper.step_wrenches(t0, t0 + 1e-4, pos, rot)
        )


def test_clearing_on_the_columns_front_faces_only():
    """Method C with clearing, 250 kg at 30 m (Z = 4.8; at 10 m the column's faces relieve after the
    incident wave's fictitious duration and UFC keeps the uncleared pulse): the front faces lose
    18-20 % of their impulse (the column is 1.3-1.65 m wide), the sides, top and rear keep their
    side-on load; Method B's fronts the same as C's."""
    lm = LoadModel(clearing=True)
    far = blast_parameters(250.0, 30.0)
    c = make_load("C", COL, far, load_model=lm)
    c0 = make_load("C", COL, far)
    fi, fi0 = c.face_impulses(), c0.face_impulses()
    front = np.array([lab == "front" for lab in c.labels])
    assert np.all(np.linalg.norm(fi[front], axis=1) < np.linalg.norm(fi0[front], axis=1))
    np.testing.assert_allclose(fi[~front], fi0[~front], rtol=1e-12)
    assert np.all(np.linalg.norm(fi[front], axis=1) < 0.9 * np.linalg.norm(fi0[front], axis=1))
    b = make_load("B", COL, far, load_model=lm)
    np.testing.assert_allclose(b.face_impulses(), fi[front], rtol=1e-12)


def test_method_a_pulse_is_the_front_face_pulse_of_the_structures_front():
    blk = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    bp = blast_parameters(84.0, 2.0)
    lm = LoadModel(clearing=True, negative_phase=True)
    a = make_load("A", blk, bp, load_model=lm)
    w, h = front_face(blk)
    want = front_face_pulse(bp, "friedlander", LoadModel(True, w, h, True))
    assert isinstance(a.pulse, PhasedPulse) and a.pulse.impulse == want.impulse
    assert a.describe()["load_model"]["face_width_m"] == w
    assert make_load("A", blk, bp).pulse == bp.pulse("friedlander")


def test_free_air_charge_stands_at_the_fronts_mid_height():
    fa = make_load("B", COL, blast_parameters(250.0, 10.0, burst="free-air"))
    assert fa.charge_position[2] == pytest.approx(5.0)
    assert make_load("B", COL, BP).charge_position[2] == 0.0
