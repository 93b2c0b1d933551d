"""Load Methods B and C (sim3d.face_loads): momentum bookkeeping, symmetry, ordering, far field, pose.

Independent checks: the faces' impulses from blast.faces (sum of i S n) against the wrenches the
strategy hands the engine step by step; mirror symmetry of the columns; Method A as the far-field
limit of Method B.
"""

import warnings

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.structure3d import arrival_spread_similarity
from blastscale.blast import blast_parameters
from blastscale.blast.faces import MixedModelWarning
from blastscale.blast.incidence import INCIDENCE_MODELS
from blastscale.sim3d.face_loads import FaceLoadStrategy, load_arrival_spread
from blastscale.sim3d.load_methods import LOAD_METHODS, make_load
from blastscale.sim3d.loads import LoadStrategy
from blastscale.similitude import design_model
from blastscale.structures import MultiDrumColumn, RectangularBlock

SQUARE = MultiDrumColumn(section="square")
CIRCULAR = MultiDrumColumn(section="circular", sides=16)


def _rest(structure):
    nb = len(structure.bodies)
    return np.array([b.com for b in structure.bodies]), np.broadcast_to(np.eye(3), (nb, 3, 3))


def _integrate(load, structure, dt=2.5e-4):
    """Sum of the step wrenches x dt from before the first arrival to past the end, at rest: (nbody, 6)."""
    pos, rot = _rest(structure)
    t = np.arange(load.first_arrival - 3 * dt, load.end_time + 3 * dt, dt)
    return sum(load.step_wrenches(a, b, pos, rot) * (b - a) for a, b in zip(t[:-1], t[1:]))


def test_b_and_c_are_registered_load_strategies():
    assert {"A", "B", "C"} <= set(LOAD_METHODS)
    load = make_load("C", SQUARE, blast_parameters(250.0, 10.0))
    assert isinstance(load, LoadStrategy) and isinstance(load, FaceLoadStrategy)


@pytest.mark.parametrize("method", ["B", "C"])
@pytest.mark.parametrize("structure", [SQUARE, CIRCULAR], ids=["square", "circular"])
def test_momentum_bookkeeping_step_wrenches_carry_every_face_impulse(method, structure):
    # delivered impulse = sum over faces of i S (-n), per body, for any step (exact step impulses);
    # the moment impulse = sum of (R c) x (i S (-n)). Round-off only: 1e-9 relative.
    load = make_load(method, structure, blast_parameters(250.0, 10.0))
    got = _integrate(load, structure)
    fi = load.face_impulses()
    per_body = np.zeros((len(structure.bodies), 3))
    np.add.at(per_body, load.body, fi)
    np.testing.assert_allclose(got[:, :3], per_body, rtol=1e-9, atol=1e-9 * np.abs(per_body).max())
    np.testing.assert_allclose(load.delivered_impulse(), per_body, rtol=1e-12, atol=1e-12 * np.abs(per_body).max())
    mom = np.zeros((len(structure.bodies), 3))
    np.add.at(mom, load.body, np.cross(load.centres, fi))
    np.testing.assert_allclose(got[:, 3:], mom, rtol=1e-9, atol=1e-9 * np.abs(mom).max())
    # the step size does not matter
    np.testing.assert_allclose(
        _integrate(load, structure, dt=1.7e-3)[:, :3], per_body, rtol=1e-9, atol=1e-9 * np.abs(per_body).max()
    )


@pytest.mark.parametrize("method", ["B", "C"])
@pytest.mark.parametrize("structure", [SQUARE, CIRCULAR], ids=["square", "circular"])
def test_no_net_sideways_impulse_on_a_symmetric_column(method, structure):
    imp = make_load(method, structure, blast_parameters(250.0, 10.0)).delivered_impulse().sum(axis=0)
    assert abs(imp[1]) < 1e-10 * abs(imp[0])


@pytest.mark.parametrize("incidence", INCIDENCE_MODELS)
@pytest.mark.parametrize("structure", [SQUARE, CIRCULAR], ids=["square", "circular"])
def test_rear_faces_reduce_the_push_c_below_b_below_a(incidence, structure):
    push = {
        m: make_load(m, structure, blast_parameters(250.0, 10.0), incidence=incidence).delivered_impulse()[:, 0].sum()
        for m in "ABC"
    }
    assert push["C"] < push["B"] < push["A"]


def test_b_and_c_read_the_current_pose():
    # moving the top drum 1 m towards the charge: nearer (earlier arrival) and more oblique
    load = make_load("B", SQUARE, blast_parameters(250.0, 10.0))
    pos, rot = _rest(SQUARE)
    moved = pos.copy()
    moved[-1, 0] -= 1.0
    a, b = load.face_loads_at(pos, rot), load.face_loads_at(moved, rot)
    assert b.distance[-1] < a.distance[-1] and b.arrival_time[-1] < a.arrival_time[-1]
    assert b.angle_of_incidence[-1] > a.angle_of_incidence[-1]
    np.testing.assert_allclose(b.arrival_time[:-1], a.arrival_time[:-1], rtol=1e-15)
    # a quarter turn about z puts the top drum's front sideways: the step wrench pushes along -y, not +x
    rq = np.array(rot)
    rq[-1] = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    w = load.step_wrenches(load.first_arrival, load.end_time, pos, rq)  # one step over the whole blast
    assert abs(w[-1, 0]) < 1e-9 * abs(w[-1, 1]) and w[-1, 1] > 0  # the front now faces -y: pushed to +y


def test_in_contact_faces_carry_nothing_and_polygon_faces_one_by_one():
    load = make_load("C", CIRCULAR, blast_parameters(250.0, 10.0))
    n_exposed = sum(not f.in_contact for b in CIRCULAR.bodies for f in b.faces)
    assert load.body.size == n_exposed == 10 * 16 + 1  # 16 sides per drum and the top of the top drum
    assert "bottom" not in load.labels and load.labels.count("top") == 1
    # turned-away faces get the side-on pulse at their own (later) arrival
    fl = load.rest_loads
    away = fl.cos_incidence < 0
    np.testing.assert_allclose(fl.pressure[away], fl.incident_pressure[away], rtol=1e-12)
    assert fl.arrival_time[away].min() > fl.arrival_time[~away].min()


def test_far_field_b_equals_a_within_one_percent_of_the_peak_response():
    # a 1 m block 40 m from 300 kg: its front centre is 0.08 % farther than the stand-off and at
    # 0.7 deg incidence, so B must reproduce A's rocking (0.041 rad, no overturning) within 1 % of
    # the peak (measured 0.44 %).
    from blastscale.sim3d.simulate import simulate_structure

    blk = RectangularBlock(height=1.0, width=0.5, depth=1.0)
    peaks = {}
    for m in "AB":
        load = make_load(m, blk, blast_parameters(300.0, 40.0))
        r = simulate_structure(blk, load, 0.6, record_every=4)
        peaks[m] = r.dataset["rotation_y"].values[:, 0]
    ref = np.abs(peaks["A"]).max()
    assert 0.02 < ref < 0.2  # it rocks and does not overturn
    n = min(peaks["A"].size, peaks["B"].size)
    assert np.abs(peaks["B"][:n] - peaks["A"][:n]).max() < 0.01 * ref


def test_masi2021_works_for_b_and_c_with_one_warning():
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        load = make_load("C", SQUARE, blast_parameters(250.0, 10.0, "masi2021"))
    assert sum(issubclass(w.category, MixedModelWarning) for w in rec) == 1
    assert load.describe()["incident_values_from"] == "kingery-bulmash"
    assert _integrate(load, SQUARE)[:, 0].sum() > 0


def test_arrival_spread_and_its_similarity_block():
    a = make_load("A", SQUARE, blast_parameters(250.0, 10.0))
    b = make_load("B", SQUARE, blast_parameters(250.0, 10.0))
    assert load_arrival_spread(a) == 0.0
    ta = b.rest_loads.arrival_time
    assert (
        load_arrival_spread(b) == pytest.approx(ta.max() - ta.min(), rel=1e-15) and 4e-3 < load_arrival_spread(b) < 8e-3
    )
    # independent check: the spread is the shock's travel time from the nearest to the farthest loaded
    # face, integral of dR / U(R / W^(1/3)) with the Kingery-Bulmash shock-front velocity fit (a fit
    # separate from the arrival-time one; they agree within ~4 %, docs/blast_models.md)
    from blastscale.blast.kingery_bulmash import KingeryBulmash

    R = b.rest_loads.distance
    r = np.linspace(R.min(), R.max(), 2001)
    u = KingeryBulmash().shock_front_velocity(r / 250.0 ** (1 / 3))
    travel = np.sum(0.5 * (1 / u[1:] + 1 / u[:-1]) * np.diff(r))
    assert load_arrival_spread(b) == pytest.approx(travel, rel=0.05)


def _spreads(structure, design, method):
    """The arrival spreads of a design's two loads (prototype, specimen at its size)."""
    return arrival_spread_similarity(
        make_load(method, structure, design.prototype),
        make_load(method, structure.scaled(design.factors), design.specimen),
        design.factors,
    )


def test_arrival_spread_scaling_hopkinson_cranz_and_general_law():
    # Hopkinson-Cranz: same Z at every face, so every blast time (arrivals, spread) scales with lambda
    # exactly; the comparison up-scales by the rigid-body time factor sqrt(lambda), hence the ratio
    # sqrt(lambda) (docs/face_loads.md)
    lam = 0.25
    hc = design_model(250.0, 10.0, lam, None, law="hopkinson-cranz")
    s = _spreads(SQUARE, hc, "B")
    assert s["arrival_spread_model_upscaled_s"] * hc.factors.time / lam == pytest.approx(
        s["arrival_spread_prototype_s"], rel=1e-9
    )
    # general law (gamma = 1): the model is farther out in Z, its shock slower, its spread
    # sqrt(lambda) U(Z_p) / U(Z_m) of the prototype's: 0.17 at lambda = 1/100 (U ratio ~1.7)
    g = _spreads(SQUARE, design_model(250.0, 10.0, 0.01), "B")
    ratio = g["arrival_spread_model_upscaled_s"] / g["arrival_spread_prototype_s"]
    assert 0.12 < ratio < 0.25


def test_bad_input_is_one_line():
    with pytest.raises(BlastscaleInputError, match="load method = 'D' is not known: valid values are A, B, C"):
        make_load("D", SQUARE, blast_parameters(250.0, 10.0))
    with pytest.raises(BlastscaleInputError, match="incidence model = 'x' is not known"):
        make_load("B", SQUARE, blast_parameters(250.0, 10.0), incidence="x")
    with pytest.raises(BlastscaleInputError, match="pulse = 'box' is not known"):
        make_load("C", SQUARE, blast_parameters(250.0, 10.0), pulse_shape="box")
    with pytest.raises(BlastscaleInputError, match="blast = float is not blast parameters"):
        make_load("B", SQUARE, 250.0)


def test_load_time_correction_moves_arrivals_and_scales_impulses():
    # the corrections of docs/face_loads.md: stretch the spread about the first arrival, weight the faces
    load = make_load("B", SQUARE, blast_parameters(250.0, 10.0))
    w = np.linspace(0.5, 1.5, 10)
    c = load.corrected(2.0, w)
    np.testing.assert_allclose(
        _integrate(c, SQUARE)[:, :3],
        load.face_impulses() * w[:, None],
        rtol=1e-9,
        atol=1e-9 * np.abs(load.face_impulses()).max(),
    )
    assert c.end_time == pytest.approx(load.end_time + load_arrival_spread(load), rel=1e-12)
    pos, rot = _rest(SQUARE)
    ta = load.rest_loads.arrival_time
    t_top = ta.min() + 2.0 * (ta[-1] - ta.min())  # the top drum's corrected arrival
    assert not np.any(c.step_wrenches(t_top - 1e-4, t_top - 1e-6, pos, rot)[-1])
    assert np.any(c.step_wrenches(t_top, t_top + 1e-4, pos, rot)[-1])
    assert load.weights.tolist() == [1.0] * 10  # the original is untouched


def test_comparison_similarity_reports_the_arrival_spreads():
    # compare_structure3d's similarity block carries the spreads (prototype, model / time factor)
    from blastscale.analysis.structure3d import compare_structure3d
    from blastscale.analysis.systems import Settings3D, Systems3D

    col = MultiDrumColumn(section="square", drums=3, height=3.0)
    design = design_model(50.0, 5.0, 0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = compare_structure3d(Systems3D.of_design(design, col, duration=0.05), Settings3D(load="B")).similarity()
    ref = _spreads(col, design, "B")
    assert s["arrival_spread_prototype_s"] == ref["arrival_spread_prototype_s"] > 0
    assert s["arrival_spread_model_upscaled_s"] == ref["arrival_spread_model_upscaled_s"] > 0
