"""Per-face blast loads (Methods B/C): geometry, incidence models, vectorised pulses, time origin.

Reference values are hand computations: the closed-form blend evaluated by hand at chosen angles on
the model's own P_r, P_so (which are tested against UFC Fig. 2-15 in test_kingery_bulmash.py); the
vectorised pulses are checked against the scalar pulse classes of blast.pulses (an independent path).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from blastscale._validate import BlastscaleInputError, OutOfRangeError
from blastscale.blast import Friedlander, Triangular
from blastscale.blast.faces import MixedModelWarning, face_loads
from blastscale.blast.incidence import INCIDENCE_MODELS, oblique_combination
from blastscale.blast.kingery_bulmash import KingeryBulmash
from blastscale.blast.masi_fits import Masi2021

KB = KingeryBulmash()
W = 8.0  # kg, W^(1/3) = 2 exactly
ORIGIN = np.zeros(3)


@pytest.mark.parametrize("incidence", INCIDENCE_MODELS)
def test_face_looking_at_charge_gets_normal_reflection(incidence):
    # a = 0: P = P_r, i = i_r, t_A = W^(1/3) t_A(Z) since detonation; R = 4 m -> Z = 2
    f = face_loads(W, ORIGIN, [4.0, 0.0, 0.0], [-1.0, 0.0, 0.0], incidence=incidence)
    assert f.distance == pytest.approx(4.0, rel=1e-15) and f.scaled_distance == pytest.approx(2.0, rel=1e-15)
    assert f.angle_of_incidence == pytest.approx(0.0, abs=1e-7)
    assert f.pressure == pytest.approx(KB.reflected_pressure(2.0), rel=1e-12)
    assert f.impulse == pytest.approx(2.0 * KB.scaled_reflected_impulse(2.0), rel=1e-12)
    assert f.arrival_time == pytest.approx(2.0 * KB.scaled_arrival_time(2.0), rel=1e-12)
    assert f.positive_duration == pytest.approx(2.0 * KB.scaled_positive_duration(2.0), rel=1e-12)


@pytest.mark.parametrize("incidence", INCIDENCE_MODELS)
def test_grazing_face_gets_incident_pressure(incidence):
    # a = 90 deg (a side face): P = P_so, i = i_s
    f = face_loads(W, ORIGIN, [4.0, 0.0, 0.0], [0.0, 1.0, 0.0], incidence=incidence)
    assert f.angle_of_incidence == pytest.approx(math.pi / 2, rel=1e-12)
    assert f.pressure == pytest.approx(KB.incident_pressure(2.0), rel=1e-12)
    assert f.impulse == pytest.approx(2.0 * KB.scaled_incident_impulse(2.0), rel=1e-12)


@pytest.mark.parametrize("incidence", INCIDENCE_MODELS)
def test_face_turned_away_gets_incident_only(incidence):
    # a = 180 deg (rear face) and a = 120 deg: incident values, not a negative blend
    for normal in ([1.0, 0.0, 0.0], [0.5, math.sqrt(3) / 2, 0.0]):
        f = face_loads(W, ORIGIN, [4.0, 0.0, 0.0], normal, incidence=incidence)
        assert f.cos_incidence < 0
        assert f.pressure == pytest.approx(KB.incident_pressure(2.0), rel=1e-12)
        assert f.impulse == pytest.approx(2.0 * KB.scaled_incident_impulse(2.0), rel=1e-12)


def test_45_and_60_degrees_by_hand():
    # cos 45 = 1/sqrt2: P = P_r/2 + P_so (1 + 1/sqrt2 - 1) = 0.5 P_r + 0.70711 P_so
    # cos 60 = 1/2:     P = P_r/4 + P_so (1 + 1/2 - 1/2)  = 0.25 P_r + P_so
    Pr, Pso = KB.reflected_pressure(2.0), KB.incident_pressure(2.0)
    s = math.sqrt(0.5)
    f45 = face_loads(W, ORIGIN, [4.0, 0.0, 0.0], [-s, s, 0.0], incidence="closed-form")
    assert math.degrees(f45.angle_of_incidence) == pytest.approx(45.0, rel=1e-9)
    assert f45.pressure == pytest.approx(0.5 * Pr + 0.7071067811865476 * Pso, rel=1e-12)
    f60 = face_loads(W, ORIGIN, [4.0, 0.0, 0.0], [-0.5, math.sqrt(3) / 2, 0.0], incidence="closed-form")
    assert f60.pressure == pytest.approx(0.25 * Pr + Pso, rel=1e-12)


def test_distance_3_4_5_and_incidence_from_geometry():
    # charge at (1, 1, 0); face centre at (4, 5, 0): R = 5; normal -x: cos a = 3/5
    f = face_loads(W, [1.0, 1.0, 0.0], [4.0, 5.0, 0.0], [-1.0, 0.0, 0.0], incidence="closed-form")
    assert f.distance == pytest.approx(5.0, rel=1e-15)
    assert f.cos_incidence == pytest.approx(0.6, rel=1e-14)
    Pr, Pso = KB.reflected_pressure(2.5), KB.incident_pressure(2.5)
    assert f.pressure == pytest.approx(0.36 * Pr + Pso * (1 + 0.6 - 0.72), rel=1e-12)


def _cube_faces(centre, half):
    """Front (-x, toward a charge on -x), rear, two sides and top of a cube: Method C's exposed faces."""
    c = np.asarray(centre, dtype=float)
    normals = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    return c + half * normals, normals, np.full(5, (2 * half) ** 2)


def test_cube_method_c_vectorised_equals_face_by_face():
    centres, normals, areas = _cube_faces([5.0, 0.0, 1.0], 0.5)
    f = face_loads(W, ORIGIN, centres, normals, areas)
    assert f.shape == (5,) and f.force_direction.shape == (5, 3)
    for k in range(5):
        g = face_loads(W, ORIGIN, centres[k], normals[k], areas[k])
        for name in ("distance", "cos_incidence", "arrival_time", "pressure", "impulse"):
            assert getattr(f, name)[k] == pytest.approx(float(getattr(g, name)), rel=1e-14)
    # physics ordering: the front face is hit first and hardest, the rear last and softest
    front, rear = 0, 1
    assert f.arrival_time[front] == f.arrival_time.min() and f.arrival_time[rear] == f.arrival_time.max()
    assert f.pressure[front] == f.pressure.max() and f.pressure[rear] == f.pressure.min()
    # forces push into the faces; magnitudes are P S and i S
    np.testing.assert_array_equal(f.force_direction, -normals)
    np.testing.assert_allclose(f.peak_force, f.pressure * areas, rtol=1e-15)
    np.testing.assert_allclose(f.force_impulse, f.impulse * areas, rtol=1e-15)


def test_batched_shape_is_preserved():
    centres = np.random.default_rng(1).uniform(2.0, 6.0, size=(4, 6, 3))
    normals = np.broadcast_to([-1.0, 0.0, 0.0], (4, 6, 3))
    f = face_loads(W, ORIGIN, centres, normals)
    assert f.pressure.shape == (4, 6) and f.area.shape == (4, 6)


@settings(max_examples=60, deadline=None)
@given(c1=st.floats(0.0, 1.0), c2=st.floats(0.0, 1.0), ratio=st.floats(1.5, 20.0))
def test_blend_is_monotone_in_cos_incidence_when_reflection_factor_at_least_1p5(c1, c2, ratio):
    # dY/dc = 2 c Y_r + Y_s (1 - 4 c) is linear in c, = Y_s > 0 at c = 0 and 2 Y_r - 3 Y_s >= 0
    # at c = 1 when Y_r >= 1.5 Y_s: no bump between the side-on and the normal value.
    # KB over Z = 0.2-40: P_r/P_so >= 2.01, i_r/i_s >= 1.75 (at Z = 34).
    lo, hi = sorted((c1, c2))
    assert oblique_combination(ratio, 1.0, lo) <= oblique_combination(ratio, 1.0, hi) + 1e-12


def test_blend_continuous_at_grazing_incidence():
    assert oblique_combination(10.0, 1.0, 1e-12) == pytest.approx(1.0, rel=1e-11)
    assert oblique_combination(10.0, 1.0, -1e-12) == 1.0


@pytest.mark.parametrize("shape, cls", [("friedlander", Friedlander), ("triangular", Triangular)])
def test_vectorised_pulses_equal_the_scalar_pulses_face_by_face(shape, cls):
    # independent slow path: one blast.pulses object per face, time shifted by the face's own arrival
    centres, normals, areas = _cube_faces([5.0, 0.0, 1.0], 0.5)
    f = face_loads(W, ORIGIN, centres, normals, areas)
    fp = f.pulses(shape)
    ts = np.linspace(0.0, fp.end_time * 1.1, 157)
    for k in range(5):
        if shape == "friedlander":
            ref = Friedlander.from_impulse(f.pressure[k], f.positive_duration[k], f.impulse[k])
        else:
            ref = Triangular(f.pressure[k], f.impulse[k])
        for t0, t1 in zip(ts[:-1], ts[1:]):
            ta = f.arrival_time[k]
            assert fp.pressure(t1)[k] == pytest.approx(ref.pressure(t1 - ta), rel=1e-9, abs=1e-9 * ref.peak)
            exact = ref.cumulative_impulse(t1 - ta) - ref.cumulative_impulse(t0 - ta)
            assert fp.impulse_between(t0, t1)[k] == pytest.approx(exact, rel=1e-9, abs=1e-12 * ref.impulse)
    # time origin is the detonation: nothing before each face's arrival, the full impulse after its end
    np.testing.assert_array_equal(fp.cumulative_impulse(0.999999 * f.arrival_time.min()), 0.0)
    np.testing.assert_allclose(fp.cumulative_impulse(fp.end_time), f.impulse, rtol=1e-10)


def test_step_impulses_telescope_to_the_face_impulse_for_any_step():
    # exact impulse per step: the sum over any partition equals i (no sampling of the peak)
    f = face_loads(W, ORIGIN, *_cube_faces([5.0, 0.0, 1.0], 0.5))
    for shape in ("friedlander", "triangular", "impulsive"):
        fp = f.pulses(shape)
        for n in (3, 17, 1000):
            t = np.linspace(0.0, max(fp.end_time, f.arrival_time.max()) * 1.01, n)
            total = sum(fp.impulse_between(a, b) for a, b in zip(t[:-1], t[1:]))
            np.testing.assert_allclose(total, f.impulse, rtol=1e-12)


def test_newton_refinement_from_a_nearby_geometry_equals_the_cold_solve():
    centres, normals, areas = _cube_faces([5.0, 0.0, 1.0], 0.5)
    cold = face_loads(W, ORIGIN, centres, normals, areas).pulses()
    moved = face_loads(W, ORIGIN, centres + [0.01, 0.003, 0.0], normals, areas)
    warm = moved.pulses(decay_guess=cold.decay)
    np.testing.assert_allclose(warm.decay, moved.pulses().decay, rtol=1e-10, atol=1e-12)
    with pytest.raises(BlastscaleInputError, match="pulse = 'square' is not known"):
        moved.pulses("square")


def test_masi2021_uses_its_reflected_values_and_kingery_bulmash_side_on_values():
    m = Masi2021()
    with pytest.warns(MixedModelWarning, match="Kingery-Bulmash side-on"):
        f = face_loads(
            W, ORIGIN, [[4.0, 0.0, 0.0], [4.0, 0.0, 0.0]], [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], blast_model="masi2021"
        )
    assert f.pressure[0] == pytest.approx(m.reflected_pressure(2.0), rel=1e-12)  # the paper's P_r at 0 deg
    assert f.arrival_time[0] == pytest.approx(2.0 * m.scaled_arrival_time(2.0), rel=1e-12)
    assert f.pressure[1] == pytest.approx(KB.incident_pressure(2.0), rel=1e-12)  # side-on from KB at 90 deg
    assert f.impulse[1] == pytest.approx(2.0 * KB.scaled_incident_impulse(2.0), rel=1e-12)


def test_bad_inputs_name_the_parameter():
    with pytest.raises(BlastscaleInputError, match="normal length"):
        face_loads(W, ORIGIN, [4.0, 0.0, 0.0], [-2.0, 0.0, 0.0])
    with pytest.raises(BlastscaleInputError, match="last axis of length 3"):
        face_loads(W, ORIGIN, [4.0, 0.0], [-1.0, 0.0])
    with pytest.raises(BlastscaleInputError, match="distance to the charge"):
        face_loads(W, ORIGIN, [0.0, 0.0, 0.0], [-1.0, 0.0, 0.0])
    with pytest.raises(BlastscaleInputError, match="face area"):
        face_loads(W, ORIGIN, [4.0, 0.0, 0.0], [-1.0, 0.0, 0.0], areas=0.0)
    with pytest.raises(BlastscaleInputError, match="incidence model = 'flat' is not known"):
        face_loads(W, ORIGIN, [4.0, 0.0, 0.0], [-1.0, 0.0, 0.0], incidence="flat")
    with pytest.raises(BlastscaleInputError, match="do not broadcast"):
        face_loads(W, ORIGIN, np.ones((3, 3)) * 4, np.tile([-1.0, 0, 0], (2, 1)))
    # Z = 100 m / 2 = 50 > 40: the reflected-pressure fit's range
    with pytest.raises(OutOfRangeError, match="reflected_pressure"):
        face_loads(W, ORIGIN, [100.0, 0.0, 0.0], [-1.0, 0.0, 0.0])
    with pytest.raises(BlastscaleInputError, match=r"charge has shape \(2,\)"):
        face_loads([W, W], ORIGIN, [4.0, 0.0, 0.0], [-1.0, 0.0, 0.0])
    with pytest.raises(BlastscaleInputError, match="face centres = nan"):
        face_loads(W, ORIGIN, [np.nan, 0.0, 0.0], [-1.0, 0.0, 0.0])


@pytest.mark.parametrize(
    "args, words",
    [
        ((2.0, 1.0, float("nan")), ["cosine of the angle of incidence = nan", "finite"]),
        ((2.0, 1.0, 1.5), ["cosine of the angle of incidence = 1.5", "[-1, 1]"]),
        ((-2.0, 1.0, 0.5), ["reflected value = -2", "[0, inf]"]),
        ((2.0, float("inf"), 0.5), ["incident value = inf", "finite"]),
    ],
)
def test_oblique_combination_rejects_nan_and_out_of_range(args, words):
    # Never a silent NaN or a silently clipped cosine: a named one-line error.
    with pytest.raises(BlastscaleInputError) as e:
        oblique_combination(*args)
    assert all(w in str(e.value) for w in words), str(e.value)
