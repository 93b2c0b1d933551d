"""Structures behind one interface (issue 8): exact mass properties of drums (closed forms, an
independent slicing integral and MuJoCo's own mesh inertia), faces, interfaces, monitoring
points, scaling and bad input. Paper's columns: 10 x 1 m drums, 1.65 -> 1.28 m, marble 2700."""

import math

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.similitude import scaling_factors
from blastscale.structures import MonitoringPoint, MultiDrumColumn, RectangularBlock
from blastscale.structures.frustum import frustum_mass_properties, polygon_section_constants


def _slices(s0, s1, H, rho, a, k, n=20000):
    """Independent slow path: midpoint rule over n slices (error ~ (H/n)^2, 1e-9 relative)."""
    z = (np.arange(n) + 0.5) * H / n
    s = s0 + (s1 - s0) * z / H
    A = a * s**2
    m = rho * A.sum() * H / n
    zc = (A * z).sum() / A.sum()
    ixx = rho * ((k * s**4 + A * (z - zc) ** 2).sum()) * H / n
    izz = rho * 2 * (k * s**4).sum() * H / n
    return m, zc, ixx, izz


@pytest.mark.parametrize("s0, s1", [(1.65, 1.613), (2.0, 1.0), (1.0, 1.0)])
def test_square_frustum_matches_closed_forms_and_slicing(s0, s1):
    H, rho = 1.0, 2700.0
    mp = frustum_mass_properties(s0, s1, H, rho)
    A0, A1 = s0 * s0, s1 * s1
    # frustum of a pyramid: V = H/3 (A0 + A1 + sqrt(A0 A1)), z_c = H (A0 + 2 sqrt(A0 A1) + 3 A1) / (4 (A0 + sqrt + A1))
    root = math.sqrt(A0 * A1)
    assert mp.volume == pytest.approx(H / 3 * (A0 + A1 + root), rel=1e-13)
    assert mp.z_com == pytest.approx(H * (A0 + 2 * root + 3 * A1) / (4 * (A0 + root + A1)), rel=1e-13)
    m, zc, ixx, izz = _slices(s0, s1, H, rho, 1.0, 1 / 12)
    # 1e-7: the midpoint rule's error at 20000 slices is ~1e-9
    assert mp.inertia[0] == pytest.approx(ixx, rel=1e-7) and mp.inertia[1] == mp.inertia[0]
    assert mp.inertia[2] == pytest.approx(izz, rel=1e-7)
    if s0 == s1:  # prism: I = m (s^2 + H^2) / 12, I_zz = m s^2 / 6
        assert mp.inertia[0] == pytest.approx(mp.mass * (s0**2 + H**2) / 12, rel=1e-13)
        assert mp.inertia[2] == pytest.approx(mp.mass * s0**2 / 6, rel=1e-13)


def test_polygon_section_tends_to_the_circle_and_is_a_square_for_four_sides():
    a, k = polygon_section_constants(4)  # square of circumradius R: side R sqrt 2
    assert a == pytest.approx(2.0, rel=1e-15) and k == pytest.approx(4 / 12, rel=1e-15)
    a, k = polygon_section_constants(100000)
    # the polygon approaches the circle as (2 pi / n)^2 ~ 4e-9 at n = 1e5
    assert a == pytest.approx(math.pi, rel=1e-8) and k == pytest.approx(math.pi / 4, rel=1e-8)


def _mujoco_mesh_mass(vertices, rho):
    import mujoco

    v = " ".join(repr(float(x)) for x in np.asarray(vertices).ravel())
    xml = (
        f'<mujoco><asset><mesh name="m" vertex="{v}"/></asset><worldbody><body><freejoint/>'
        f'<geom type="mesh" mesh="m" density="{rho}"/></body></worldbody></mujoco>'
    )
    m = mujoco.MjModel.from_xml_string(xml)
    return m.body_mass[1], m.body_ipos[1], np.sort(m.body_inertia[1])


@pytest.mark.parametrize("section", ["square", "circular"])
def test_drum_mass_properties_match_mujocos_mesh_inertia(section):
    col = MultiDrumColumn(section)
    drum = col.bodies[0]
    s0, s1 = col.width_at([0.0, 1.0])
    if section == "square":
        p = np.array([[1, 1], [-1, 1], [-1, -1], [1, -1]]) * 0.5
        r0, r1 = s0, s1
    else:
        p = col.bodies[0].shape.polygon() / (s0 / 2)
        r0, r1 = s0 / 2, s1 / 2
    verts = np.vstack([np.c_[p * r0, np.zeros(len(p))], np.c_[p * r1, np.ones(len(p))]])
    m, ipos, inertia = _mujoco_mesh_mass(verts, col.density)
    # 1e-7: MuJoCo integrates the mesh (float vertices), measured 3e-9
    assert drum.mass == pytest.approx(m, rel=1e-7)
    assert drum.com[2] == pytest.approx(ipos[2], rel=1e-7)
    assert np.sort(drum.inertia) == pytest.approx(inertia, rel=1e-7)


def test_paper_square_column_geometry_faces_and_points():
    col = MultiDrumColumn()
    assert len(col.bodies) == 10 and [b.name for b in col.bodies][::9] == ["D-1", "D-10"]
    assert col.interfaces == tuple((i - 1, i) for i in range(10))
    assert [p.name for p in col.monitoring_points] == [f"P-{i}" for i in range(1, 11)]
    # total mass = rho x frustum of a pyramid 10 m high, 1.65 -> 1.28 m (sum of drums = whole)
    A0, A1 = 1.65**2, 1.28**2
    assert col.mass == pytest.approx(2700 * 10 / 3 * (A0 + A1 + math.sqrt(A0 * A1)), rel=1e-12)
    assert col.front_x == -0.825
    for k, b in enumerate(col.bodies):
        assert b.com[2] + b.base_height == pytest.approx(k * 1.0, abs=1e-12)  # stacked base to top
        front = b.load_face
        s0, s1 = col.width_at([k, k + 1.0])
        # projected front area = the trapezoid (s0 + s1) / 2 x 1 m
        assert front.area * -front.normal[0] == pytest.approx((s0 + s1) / 2, rel=1e-12)
        for f in b.faces:  # outward: the normal points away from the centre of mass
            assert np.dot(f.normal, f.centre) > 0 and np.linalg.norm(f.normal) == pytest.approx(1, abs=1e-14)
        labels = {f.label: f.in_contact for f in b.faces}
        assert labels["bottom"] is True and labels["top"] is (k < 9) and labels["front"] is False
        p = col.monitoring_points[k]
        assert p.body == k and p.position == front.centre


def test_circular_drums_are_32_gons_loaded_on_diameter_x_height():
    col = MultiDrumColumn("circular")
    b = col.bodies[0]
    assert len([f for f in b.faces if f.label in ("front", "rear", "side")]) == 32
    s0, s1 = col.width_at([0.0, 1.0])
    assert b.load_face.area * -b.load_face.normal[0] == pytest.approx((s0 + s1) / 2 * 1.0, rel=1e-12)
    # the 32 facets close around the axis: their outward horizontal areas sum to zero
    side = np.array([np.array(f.normal) * f.area for f in b.faces if f.label != "top" and f.label != "bottom"])
    assert np.abs(side[:, :2].sum(axis=0)).max() < 1e-12


def test_block_has_the_same_interface():
    blk = RectangularBlock(10.0, 2.68, 1.0)
    (b,) = blk.bodies
    assert b.mass == blk.mass and b.inertia == blk.inertia_centroid and b.com == (0.0, 0.0, 5.0)
    assert b.toppling_angle == pytest.approx(blk.alpha, rel=1e-15)
    assert b.load_face.area == blk.front_area and b.load_face.normal == (-1.0, 0.0, 0.0)
    assert blk.interfaces == ((-1, 0),) and blk.front_x == -1.34 and blk.monitoring_points[0].name == "P-1"


def test_scaled_column_mass_and_inertia_follow_lambda_cubed_and_fifth():
    col = MultiDrumColumn(
        "circular", drum_heights=(1.5,) + (8.5 / 9,) * 9, extra_points=(MonitoringPoint("top", 9, (0.0, 0.0, 0.5)),)
    )
    lam, gam = 0.01, 0.5
    s = col.scaled(scaling_factors(lam, gam))
    for b, bs in zip(col.bodies, s.bodies):
        assert bs.mass == pytest.approx(b.mass * gam * lam**3, rel=1e-12)
        assert bs.inertia == pytest.approx(np.array(b.inertia) * gam * lam**5, rel=1e-12)
    assert s.monitoring_points[-1].position == pytest.approx((0.0, 0.0, 0.005))
    assert s.describe()["drum_heights_m"][0] == pytest.approx(0.015)


@pytest.mark.parametrize(
    "kwargs, word",
    [
        (dict(drums=0), "drums"),
        (dict(drums=2.5), "drums"),
        (dict(base_width=float("nan")), "base width"),
        (dict(base_width=-1.0), "base width"),
        (dict(top_width=2.0), "top width"),
        (dict(top_width=0.1), "top width"),
        (dict(section="hexagonal"), "section"),
        (dict(section="circular", sides=4), "sides"),
        (dict(drum_heights=(1.0,) * 9), "drum heights"),
        (dict(drum_heights=(1.1,) * 10), "drum heights"),
        (dict(height=0.0), "height"),
        (dict(density=float("inf")), "density"),
    ],
)
def test_column_rejects_bad_input_with_one_line_naming_it(kwargs, word):
    with pytest.raises(BlastscaleInputError) as e:
        MultiDrumColumn(**kwargs)
    msg = str(e.value)
    assert word in msg and len(msg.splitlines()) == 1
    assert "range" in msg or "valid" in msg or "must" in msg or "finite" in msg


@pytest.mark.parametrize(
    "structure",
    [
        RectangularBlock(height=3.0, width=1.0, depth=0.5),
        MultiDrumColumn(drums=3, height=3.0, top_width=1.4),
        MultiDrumColumn(section="circular", drums=2, height=2.0, sides=8),
    ],
    ids=["block", "square column", "circular column"],
)
def test_each_body_is_its_solid(structure):
    """Issue 29: a body's mass, volume, centre of mass and inertia are those of its solid (the convex hull of
    ``vertices``, integrated independently by the divergence theorem, 1e-12), and ``as_assembly`` keeps
    them (and the contact shape) exactly: a drum is its frustum, not the prism it collides as."""
    from blastscale.structures import as_assembly, polyhedron_mass_properties, rest_mass_properties

    rho = structure.density
    asm = as_assembly(structure)
    for b, a in zip(structure.bodies, asm.bodies):
        mp = polyhedron_mass_properties(b.vertices, rho)
        assert mp.volume == pytest.approx(b.volume, rel=1e-12) and mp.mass == pytest.approx(b.mass, rel=1e-12)
        assert np.allclose(mp.centroid, 0.0, atol=1e-12 * structure.height)  # body frame: at the centre of mass
        assert np.allclose(np.diag(mp.inertia), b.inertia, rtol=1e-12)
        assert (a.mass, a.volume, a.com, a.inertia, a.shape) == (b.mass, b.volume, b.com, b.inertia, b.shape)
    rest = rest_mass_properties(structure.bodies)
    assert rest.mass == asm.mass == pytest.approx(rho * rest.volume, rel=1e-14) and rest.volume == asm.volume
    assert rest.mass == pytest.approx(structure.mass, rel=1e-15)
