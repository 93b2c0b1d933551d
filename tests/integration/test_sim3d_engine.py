"""The multi-body 3D engine (issue 8): columns at rest, Method A momentum, exact scaling,
specimens simulated at their own size with the scale-consistent defaults, time-step
independence, results (xarray, NetCDF) and bad input. Runs are shortened to keep the suite fast;
the full-length figures are in docs/sim3d.md (benchmarks/bench_sim3d.py --acceptance)."""

import json
import math
import warnings

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.block3d_similarity import block_dataset, block_summary
from blastscale.blast import Friedlander
from blastscale.blast.parameters import blast_parameters
from blastscale.sim3d import ContactSettings, MethodA, block_scene, make_load
from blastscale.sim3d.contact import default_contact
from blastscale.sim3d.results import VARIABLES
from blastscale.sim3d.simulate import simulate_structure
from blastscale.similitude import scaling_factors
from blastscale.structures import MonitoringPoint, MultiDrumColumn, RectangularBlock

SQUARE = MultiDrumColumn("square")  # the paper's: 10 x 1 m drums, 1.65 -> 1.28 m, 2700 kg/m^3
CIRCULAR = MultiDrumColumn("circular")


def _top_x(resp, lam=1.0):
    return resp.dataset["point_displacement"].sel(point="P-10", component="x").values / lam


@pytest.mark.parametrize("col", [SQUARE, CIRCULAR], ids=["square", "circular"])
def test_column_stands_still_under_gravity(col):
    # issue: top drift <= 0.1 mm over 10 s (measured over 10 s: docs/sim3d.md); 2 s here
    r = simulate_structure(col, None, 2.0, record_every=100)
    drift = np.abs(r.dataset["point_displacement"].sel(point="P-10").values).max()
    assert drift <= 1e-4
    assert not r.summary()["collapsed"]
    assert r.dataset["n_contacts"].values[-1] >= 4 * 10  # multiccd: >= 4 points per flat joint


@pytest.mark.parametrize("col", [SQUARE, CIRCULAR], ids=["square", "circular"])
def test_method_a_delivers_reflected_impulse_times_projected_front_area(col):
    load = make_load("A", col, blast_parameters(250.0, 10.0))
    r = simulate_structure(col, load, 0.03, record_every=10)
    ix, iy, iz = r.summary()["delivered_impulse_Ns"]
    # i_r x front area: the projected trapezoids, (s0 + s1)/2 x H per drum, summed
    z = col.joint_heights
    s = col.width_at(z)
    area = float(np.sum((s[:-1] + s[1:]) / 2 * np.diff(z)))
    # 1% (issue); the exact-impulse steps give ~1e-6 (the front faces turn during the pulse)
    assert ix == pytest.approx(load.pulse.impulse * area, rel=1e-2)
    # no sideways component: the load is symmetric about y = 0; the polygon drums' mesh contacts
    # let them turn by ~1e-7 rad while settling (measured |iy| / ix = 3e-7), boxes not at all
    assert abs(iy) <= 1e-6 * ix
    # the tapered faces lean back: a small downward component, (s0 - s1) / (2 H) of the thrust
    assert iz < 0 and abs(iz) < 0.03 * ix
    assert r.dataset.attrs["first_arrival_time_s"] == pytest.approx(load.first_arrival, rel=1e-15)


def test_exact_scaling_model_upscaled_equals_prototype():
    """REGRESSION TEST OF THE REFERENCE-UNIT NORMALISATION, not a test of similarity: the engine
    integrates a structure and its exactly scaled model as the same reference-unit MuJoCo model
    (blastscale.sim3d.reference), so their up-scaled histories agree by construction; this test fails
    when that normalisation breaks (a setting not scaled, a rounding that differs)."""
    # the exactly similar pulse (gamma = varsigma = 1): pressure x lambda, times x sqrt(lambda),
    # impulse x lambda^1.5; contact=None scales the contact with the structure's height
    # issue: 1e-4 of the peak over 8 s; measured 5e-11 over 8 s (docs/sim3d.md), 3e-15 over the
    # first peak here: the engine runs both in the same reference units (reference_factors), so
    # the scaled inputs are rounded to the same 12 digits there: 1e-12 leaves room for round-off
    lam, T = 0.01, 0.8
    lt = math.sqrt(lam)
    pulse = blast_parameters(250.0, 10.0).pulse("friedlander")
    proto = simulate_structure(SQUARE, MethodA(SQUARE, pulse, 0.0069), T, record_every=20)
    f = scaling_factors(lam)
    model = simulate_structure(
        SQUARE.scaled(f), MethodA(SQUARE.scaled(f), pulse.scaled(f), 0.0069 * lt), T * lt, record_every=20
    )
    p, m = _top_x(proto), _top_x(model, lam)
    assert np.allclose(model.time / lt, proto.time, rtol=1e-12)
    assert np.max(np.abs(m - p)) <= 1e-12 * np.max(np.abs(p))
    tilt_p, tilt_m = proto.dataset["tilt"].values, model.dataset["tilt"].values
    assert np.max(np.abs(tilt_m - tilt_p)) <= 1e-12 * np.max(tilt_p)


def test_block_specimen_at_its_own_size_reproduces_the_prototype():
    # issue: the 1/200 specimen of the paper's block (2h = 5 cm, alpha = 15 deg, 5 mm deep,
    # 2000 kg/m^3, masi2021, mu = 0.7, 2.3318e-7 kg at 0.01 m, 0.2121 s) gave 0.0355 rad with the
    # absolute full-scale contact, against the prototype's 0.0611 (50 kg at 2 m, 3 s)
    proto_blk = RectangularBlock.from_slenderness(10.0, math.radians(15.0), depth=1.0, density=2000.0)
    spec_blk = proto_blk.scaled(scaling_factors(1 / 200))
    proto_pulse = blast_parameters(50.0, 2.0, blast_model="masi2021").pulse()
    spec_pulse = blast_parameters(2.3318e-7, 0.01, blast_model="masi2021").pulse()
    proto = block_summary(
        simulate_structure(
            proto_blk,
            MethodA(proto_blk, proto_pulse),
            3.0,
            contact=default_contact(proto_blk, friction=0.7),
            record_every=10,
        )
    )
    spec = block_summary(
        simulate_structure(spec_blk, MethodA(spec_blk, spec_pulse), 0.2121, record_every=10)
    )  # contact=None: scale-consistent defaults
    # 2% (issue); measured 0.003% on the angle, 0.5% on the sliding (the general law matches
    # the impulse, not the pulse shape)
    assert spec["max_rotation_rad"] == pytest.approx(proto["max_rotation_rad"], rel=0.02)
    assert spec["max_sliding_m"] * 200 == pytest.approx(proto["max_sliding_m"], rel=0.02)
    assert proto["max_rotation_rad"] == pytest.approx(0.0611, abs=5e-4)
    # the old absolute setting is now flagged as soft relative to this specimen's blast
    with pytest.warns(RuntimeWarning, match="soft relative to the blast"):
        simulate_structure(spec_blk, MethodA(spec_blk, spec_pulse), 1e-3, contact=ContactSettings(friction=0.7))


def test_column_specimen_at_its_own_size_reproduces_the_prototype():
    from blastscale.similitude import design_model

    lam, T = 0.01, 0.8  # to past the first peak (0.5 s); 8 s in docs/sim3d.md
    d = design_model(250.0, 10.0, lam)  # general law, gamma = 1
    proto = simulate_structure(SQUARE, make_load("A", SQUARE, blast_parameters(250.0, 10.0)), T, record_every=20)
    spec_col = SQUARE.scaled(scaling_factors(lam))
    spec = simulate_structure(spec_col, make_load("A", spec_col, d.specimen), T * math.sqrt(lam), record_every=20)
    p, m = _top_x(proto), _top_x(spec, lam)
    # 2% (issue) on the first peak (measured 0.4%) and on the largest tilt (measured 0.2%)
    assert np.max(m) == pytest.approx(np.max(p), rel=0.02)
    assert spec.summary()["max_rotation_rad"] == pytest.approx(proto.summary()["max_rotation_rad"], rel=0.02)


def test_halving_the_time_step_moves_the_first_peak_by_less_than_1_percent():
    load = make_load("A", SQUARE, blast_parameters(250.0, 10.0))
    c = default_contact(SQUARE)
    half = ContactSettings(
        friction=c.friction, time_constant=c.time_constant, friction_time_constant=None, timestep=c.timestep / 2
    )
    peaks = [np.max(_top_x(simulate_structure(SQUARE, load, 0.7, contact=cs, record_every=8))) for cs in (c, half)]
    assert peaks[1] == pytest.approx(peaks[0], rel=0.01)  # issue: 1%; measured in docs/sim3d.md


def test_the_block_is_the_one_body_case_of_the_same_path():
    """A block and a one-drum prismatic square column of the same box (2.68 m square, 10 m high)
    are the same structure to the engine: the same body (mass, inertia, loaded face, point), the
    same one-body contact defaults and blast mode, the same scene: bitwise the same response (the
    column's quadrature inertia differs from the block's closed form by round-off, which the
    reference units' 12-digit rounding removes)."""
    from blastscale.sim3d.model import structure_scene

    blk = RectangularBlock(10.0, 2.68, depth=2.68, density=2000.0)
    col = MultiDrumColumn(section="square", drums=1, height=10.0, base_width=2.68, top_width=2.68, density=2000.0)
    pulse = blast_parameters(200.0, 2.0, blast_model="masi2021").pulse()
    one = simulate_structure(blk, MethodA(blk, pulse), 0.3, contact=ContactSettings(friction=2.0))
    gen = simulate_structure(col, MethodA(col, pulse), 0.3, contact=ContactSettings(friction=2.0))
    assert one.dataset.attrs["setting_blast_mode"] == gen.dataset.attrs["setting_blast_mode"] == "auto"
    for name in ("rotation_y", "tilt", "com_displacement", "point_displacement", "uplift", "n_contacts"):
        np.testing.assert_array_equal(one.dataset[name].values, gen.dataset[name].values)
    assert one.summary()["delivered_impulse_Ns"] == gen.summary()["delivered_impulse_Ns"]
    # and the block's own scene builder is the structure's (tilted or not)
    assert block_scene(blk, rotation=0.1).xml == structure_scene(blk, ContactSettings(), rotation=0.1).xml


def test_response_dataset_units_dimensions_netcdf_and_summary(tmp_path):
    import xarray as xr

    from blastscale.io.histories import write_netcdf

    r = simulate_structure(CIRCULAR, make_load("A", CIRCULAR, blast_parameters(200.0, 10.0)), 0.02, record_every=10)
    ds = r.dataset
    # the stored motion's dims (issue 26): a 32-gon drum has 64 vertices and 2 x 30 + 64 = 124 hull triangles
    assert dict(ds.sizes) == {
        "time": ds.sizes["time"],
        "body": 10,
        "point": 10,
        "component": 3,
        "quaternion": 4,
        "vertex": 64,
        "face": 124,
        "corner": 3,
    }
    for name, (dims, units, dim, _) in VARIABLES.items():
        assert ds[name].dims == dims and ds[name].attrs["units"] == units and ds[name].attrs["dimension"] == dim
    assert ds["time"].attrs["units"] == "s" and "version_mujoco" in ds.attrs
    path = write_netcdf(r.dataset, tmp_path / "col.nc")
    back = xr.load_dataset(path)
    assert np.array_equal(back["tilt"].values, ds["tilt"].values)
    assert json.loads(back.attrs["structure"])["section"] == "circular"
    assert [p.name for p in tmp_path.iterdir()] == ["col.nc"]  # no temporary file left
    s = r.summary()
    json.dumps(s, allow_nan=False)
    assert set(s["points"]) == {f"P-{i}" for i in range(1, 11)} and s["collapsed"] is False


def test_collapse_is_flagged_when_the_column_falls():
    # an initial shove far beyond any rocking capacity: the stack passes over its base edge
    bp = blast_parameters(250.0, 10.0)
    shove = Friedlander(30.0 * bp.reflected_pressure, bp.positive_duration, bp.friedlander_decay)  # 30x the pressure
    r = simulate_structure(SQUARE, MethodA(SQUARE, shove), 2.5, record_every=50)
    s = r.summary()
    assert s["collapsed"] and 0.0 < s["collapse_time_s"] <= 2.5


SLENDER = MultiDrumColumn(drums=3, height=3.0, base_width=0.5, top_width=0.45)  # topples under 100 kg at 5 m


def _lowest_base_point(col, resp):
    """Height of each body's lowest base point above the ground, (time, body) [m]."""
    from blastscale.sim3d.shapes import engine_shape

    rest = np.array([b.com[2] + engine_shape(b.shape, 1.0).base_points()[:, 2].min() for b in col.bodies])
    return resp.dataset["uplift"].values + rest


def test_collapsed_drums_stay_on_the_ground():
    """Every body is paired with the ground and with every other body, so a toppled column's
    drums land on the ground instead of falling through it. With the ground-base and adjacent
    pairs only, drums 2 and 3 of this column ended 4.3 m and 5.0 m below the ground after 1.2 s.
    Measured with all pairs: lowest base point -0.58 mm during the impacts (1.9 solimp widths of
    0.3 mm: the soft contact's transient penetration), -8e-8 m at the end (the static
    penetration); asserted: -5 widths over the run, -1 width at the end, every centre of mass
    above the ground."""
    load = make_load("A", SLENDER, blast_parameters(100.0, 5.0))
    r = simulate_structure(SLENDER, load, 1.2, record_every=8)
    assert r.summary()["collapsed"] and r.summary()["collapse_time_s"] < 0.2
    width = r.dataset.attrs["setting_impedance_width_m"]  # 0.3 mm: 1 mm scaled to the 3 m column
    low = _lowest_base_point(SLENDER, r)
    assert low.min() >= -5 * width and low[-1].min() >= -width
    com_z = r.dataset["com_displacement"].sel(component="z").values[-1] + np.array([b.com[2] for b in SLENDER.bodies])
    assert np.all(com_z > 0.2)  # lying drums: the COM ~ half a width (0.23-0.25 m) above the ground


def test_surfaces_apart_at_rest_leave_the_motion_before_they_touch_bitwise_unchanged(monkeypatch):
    """Every two surfaces that are not an interface collide through MuJoCo's broad phase (for falling
    drums): while their bodies are apart they make no contact, so up to the collapse (0.162 s) the
    slender column moves bitwise as with its interfaces alone (broad phase switched off)."""
    from blastscale.sim3d import model

    load = make_load("A", SLENDER, blast_parameters(100.0, 5.0))
    full = simulate_structure(SLENDER, load, 0.15, record_every=8).dataset
    scene = model.structure_scene(SLENDER, default_contact(SLENDER))
    assert scene.mj_model.npair == 3 and scene.mj_model.nexclude == 3  # the interfaces, kept out of the broad phase
    monkeypatch.setattr(model, "BROAD_PHASE", 'contype="0" conaffinity="0"')
    rest = simulate_structure(SLENDER, load, 0.15, record_every=8).dataset
    for name in ("com_displacement", "angular_velocity", "n_contacts"):
        np.testing.assert_array_equal(full[name].values, rest[name].values)


@pytest.mark.parametrize(
    "make, word",
    [
        (
            lambda: simulate_structure(SQUARE, None, 0.01, contact=ContactSettings(timestep=0.1, time_constant=0.4)),
            "timestep",
        ),
        (
            lambda: simulate_structure(
                RectangularBlock(10.0, 2.0), None, 0.01, contact=ContactSettings(timestep=1.0, time_constant=4.0)
            ),
            "timestep",
        ),
        (lambda: simulate_structure(RectangularBlock(10.0, 2.68).scaled(scaling_factors(1e-4)), None, 0.01), "mass"),
        (lambda: simulate_structure(RectangularBlock(1e-6, 2.68e-7), None, 0.01), "height"),
        (lambda: simulate_structure(RectangularBlock(10.0, 2.68, 1e-9), None, 0.01), "depth"),
        (lambda: simulate_structure(SQUARE, "friedlander", 0.01), "load"),
        (lambda: simulate_structure(SQUARE, None, -1.0), "duration"),
        (lambda: make_load("D", SQUARE, blast_parameters(1.0, 1.0)), "load method"),
        (lambda: MethodA(SQUARE, None), "pulse"),
    ],
    ids=[
        "timestep-column",
        "timestep-block",
        "tiny-mass",
        "tiny-height",
        "tiny-depth",
        "load",
        "duration",
        "method",
        "pulse",
    ],
)
def test_engine_rejects_bad_input_with_one_line_naming_it(make, word):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        with pytest.raises(BlastscaleInputError) as e:
            make()
    assert word in str(e.value) and len(str(e.value).splitlines()) == 1


def test_milligram_specimen_runs_in_reference_units_and_user_points_are_recorded():
    # a 1 cm block (54 mg) and a 1/1000 column run as the 10 m structures in reference units
    # (MuJoCo's absolute thresholds never see their size): at rest they stay put
    tiny = RectangularBlock(10.0, 2.68).scaled(scaling_factors(1e-3))
    r = block_dataset(simulate_structure(tiny, None, 0.05))
    assert tiny.mass < 1e-4 and np.max(np.abs(r["rotation_y"].values)) < 1e-9
    assert np.max(np.abs(r["sliding"].values)) < 1e-11
    col = MultiDrumColumn(
        drums=3, height=3.0, top_width=1.54, extra_points=(MonitoringPoint("cap", 2, (0.0, 0.0, 0.5)),)
    ).scaled(scaling_factors(1e-3))
    resp = simulate_structure(col, None, 0.02, record_every=10)
    assert list(resp.dataset["point"].values) == ["P-1", "P-2", "P-3", "cap"]
    assert np.abs(resp.dataset["point_displacement"].values).max() < 1e-9 * 3e-3


def test_sparse_jacobian_default_gives_the_dense_history():
    # A stack's default Jacobian is sparse (2.5-3.4x on the 10-drum columns, issue #19); the dense
    # path is the reference it must reproduce: on the square column (not chaotic) the two differ by
    # round-off (measured 2e-12 of the peak over 4 s, 3e-10 over 8 s); asserted 1e-9 over 0.5 s.
    from dataclasses import replace

    from blastscale.sim3d.contact import default_contact

    col = MultiDrumColumn("square")
    load = make_load("A", col, blast_parameters(250.0, 10.0))
    assert default_contact(col).jacobian == "sparse"
    sparse = simulate_structure(col, load, 0.5, record_every=10)
    dense = simulate_structure(col, load, 0.5, record_every=10, contact=replace(default_contact(col), jacobian="dense"))
    assert dense.dataset.attrs["setting_jacobian"] == "dense"
    assert sparse.dataset.attrs["setting_jacobian"] == "sparse"
    xd = dense.dataset["point_displacement"].sel(component="x").values
    xs = sparse.dataset["point_displacement"].sel(component="x").values
    assert np.max(np.abs(xs - xd)) <= 1e-9 * np.max(np.abs(xd))
    with pytest.raises(
        BlastscaleInputError, match=r"jacobian = 'csr' is not known: valid values are dense, sparse, auto"
    ):
        replace(default_contact(col), jacobian="csr")


def test_initial_tilt_and_rocking_velocity_are_rigid_about_the_base_edge():
    """initial_rotation turns the whole structure rigidly about its lowest body's +x base edge
    (every distance kept, the edge where it stood, each body's rotation_y = theta_0);
    initial_angular_velocity gives every body the rigid velocity w x (x - P) about that edge and
    the angular velocity w (round-off: 1e-12)."""
    from blastscale.sim3d.model import structure_scene
    from blastscale.sim3d.rotations import quaternion_to_matrix, tilt_angle

    col = MultiDrumColumn(drums=3, height=3.0, top_width=1.54)
    th0, w0 = 0.05, 0.3
    up = structure_scene(col, default_contact(col)).bodies
    tilted = structure_scene(col, default_contact(col), rotation=th0).bodies
    p0 = np.array([b.position for b in up])
    p1 = np.array([b.position for b in tilted])
    assert np.allclose(
        np.linalg.norm(p0[:, None] - p0[None], axis=2),
        np.linalg.norm(p1[:, None] - p1[None], axis=2),
        rtol=0,
        atol=1e-12,
    )
    edge = np.array([0.5 * col.base_width, 0.0, 0.0])  # the +x base edge of the lowest drum, on the ground
    assert np.allclose(np.linalg.norm(p0 - edge, axis=1), np.linalg.norm(p1 - edge, axis=1), rtol=0, atol=1e-12)
    assert np.allclose(tilt_angle(quaternion_to_matrix([b.quaternion for b in tilted])), th0, rtol=0, atol=1e-15)
    r = simulate_structure(col, None, 1e-3, initial_angular_velocity=w0, record_every=1).dataset
    x = np.array([b.com for b in col.bodies])  # rest positions; the settled ones sink by the static penetration
    v_rigid = np.cross([0.0, w0, 0.0], x - edge)  # so 1e-6 x w0 [m/s] (1 um lever arm) on the velocities
    assert np.allclose(r["com_velocity"].values[0], v_rigid, rtol=0, atol=1e-6 * w0)
    assert np.allclose(r["angular_velocity"].values[0], [0.0, w0, 0.0], rtol=0, atol=1e-12)
