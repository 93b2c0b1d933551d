"""COMPAS block models as COMPAS writes them (issue 23, deliverable 4): the model's and elements'
transformations, ``is_support`` blocks and names, read with and without COMPAS, and written back.

``tests/data/compas_dem_arch_rotated.json`` was written by compas_dem 0.6.0 (compas 2.15.1,
compas_model 0.9.3) with :func:`compas_arch` below: ``ArchTemplate(rise=2, span=4, thickness=0.3,
depth=0.5, n=4)`` (a semicircular arch in the x-z plane, intrados radius 2 m, voussoirs V1-V4), the
voussoirs raised 0.4 m by their own transformations (V4 a child of V1 in the element tree, raised by
its parent's), two abutments ``is_support`` (0.7 x 0.5 x 0.6 m, z from -0.2 to 0.4 m: below the
ground) under the springers, and the model turned 90 deg about z (``model.transformation``): the arch
then stands in the y-z plane, facing a charge on -x. Its extents follow from that construction alone:
x from -0.5 to 0 (the depth), y from -2.5 to 2.5 (the abutments' outer faces at 2.15 + 0.35), z up to
0.4 + 2.3 (the crown joint's extrados).
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.structures import read_block_model
from blastscale.structures.compas_files import compas_model_data

DATA = Path(__file__).resolve().parents[2] / "data" / "compas_dem_arch_rotated.json"
#: Coordinates here are sums and rotations of a few exact decimals: 1e-12 m is round-off at 2.7 m.
TOL = 1e-12


def compas_arch(path) -> None:
    """Write the test arch with compas_dem itself (module docstring)."""
    from compas import json_dump
    from compas.geometry import Box, Frame, Rotation, Translation
    from compas_dem.elements import Block
    from compas_dem.models import BlockModel
    from compas_dem.templates import ArchTemplate

    model = BlockModel()
    raised = Translation.from_vector([0.0, 0.0, 0.4])
    first = None
    for k, mesh in enumerate(ArchTemplate(rise=2.0, span=4.0, thickness=0.3, depth=0.5, n=4).blocks()):
        if k < 3:
            block = Block.from_mesh(mesh, transformation=raised, name=f"V{k + 1}")
            model.add_element(block)
            first = first or block
        else:  # a child of V1: raised by its parent's transformation
            model.add_element(Block.from_mesh(mesh, name=f"V{k + 1}"), parent=first)
    for name, x in (("abutment-W", -2.15), ("abutment-E", 2.15)):
        box = Box(0.7, 0.5, 0.6, Frame([x, 0.25, 0.1], [1, 0, 0], [0, 1, 0]))
        model.add_element(Block.from_box(box, is_support=True, name=name))
    model.transformation = Rotation.from_axis_and_angle([0.0, 0.0, 1.0], math.pi / 2)
    json_dump(model, str(path))


def _extents(asm):
    v = np.vstack([b.points for b in asm.blocks + asm.supports])
    return v.min(axis=0), v.max(axis=0)


def _same_blocks(a, b, tol=TOL):
    """Names, support flags and every block's hull vertices (as sets) agree to ``tol`` [m]."""
    assert [x.name for x in a.blocks] == [x.name for x in b.blocks]
    assert [x.name for x in a.supports] == [x.name for x in b.supports]
    assert [x.density for x in a.blocks + a.supports] == [x.density for x in b.blocks + b.supports]
    for x, y in zip(a.blocks + a.supports, b.blocks + b.supports):
        px, py = np.unique(np.round(x.points, 9), axis=0), np.unique(np.round(y.points, 9), axis=0)
        assert px.shape == py.shape
        d = np.abs(x.points[:, None, :] - y.points[None, :, :]).max(axis=2)
        assert d.min(axis=1).max() <= tol and d.min(axis=0).max() <= tol


def test_the_shipped_arch_is_read_rotated_with_its_supports_and_names_without_compas():
    a = read_block_model(DATA, 2000.0, use_compas=False)
    assert [b.name for b in a.blocks] == ["V1", "V4", "V2", "V3"]  # the element tree's order
    assert [b.name for b in a.supports] == ["abutment-W", "abutment-E"]
    lo, hi = _extents(a)
    np.testing.assert_allclose(lo, [-0.5, -2.5, -0.2], atol=TOL)
    np.testing.assert_allclose(hi, [0.0, 2.5, 2.7], atol=TOL)
    # four chord voussoirs of 45 deg between radii 2 and 2.3, 0.5 m deep, 2000 kg/m^3; supports not counted
    assert a.mass == pytest.approx(2000.0 * 4 * 0.5 * 0.5 * (2.3**2 - 2.0**2) * math.sin(math.pi / 4), rel=1e-12)
    # the springers stand on the abutments: interfaces with the ground (-1); the supports are not bodies
    assert a.interfaces == ((-1, 0), (-1, 1), (0, 2), (1, 3), (2, 3))
    assert len(a.bodies) == 4 and [n for n, _, _ in a.fixed_shapes] == ["abutment-W", "abutment-E"]


def test_without_the_model_transformation_the_arch_stands_edge_on(tmp_path):
    """The rotation is what turns the arch: without it (COMPAS's x-z plane) x and y swap."""
    data = json.loads(DATA.read_text())
    data["data"]["transformation"] = None
    p = tmp_path / "edge_on.json"
    p.write_text(json.dumps(data))
    lo, hi = _extents(read_block_model(p, use_compas=False))
    np.testing.assert_allclose(lo, [-2.5, 0.0, -0.2], atol=TOL)
    np.testing.assert_allclose(hi, [2.5, 0.5, 2.7], atol=TOL)


def test_a_file_written_by_compas_dem_reads_the_same_through_compas_and_without(tmp_path):
    pytest.importorskip("compas_dem", reason="compas_dem is not installed (the optional 'compas' extra)")
    p = tmp_path / "arch.json"
    compas_arch(p)
    through, plain = read_block_model(p, use_compas=True), read_block_model(p, use_compas=False)
    _same_blocks(through, plain)
    _same_blocks(through, read_block_model(DATA, use_compas=False))  # the shipped file is this one


def test_default_names_are_made_unique_in_the_tree_order(tmp_path):
    data = json.loads(DATA.read_text())
    for el in data["data"]["elements"].values():
        el["data"]["name"] = "Block"  # COMPAS's default name
    p = tmp_path / "unnamed.json"
    p.write_text(json.dumps(data))
    a = read_block_model(p, use_compas=False)
    assert [b.name for b in a.blocks + a.supports] == [f"Block-{k}" for k in (1, 2, 3, 4, 5, 6)]


def test_an_assembly_written_to_compas_reads_back_the_same(tmp_path):
    a = read_block_model(DATA, use_compas=False)
    p = tmp_path / "back.json"
    p.write_text(json.dumps(compas_model_data(a)))
    _same_blocks(a, read_block_model(p, use_compas=False))
    if _has_compas():
        from compas import json_load

        model = json_load(str(p))  # COMPAS's own reader accepts what we write
        assert [(e.name, e.is_support) for e in model.elements()] == [(b.name, False) for b in a.blocks] + [
            (b.name, True) for b in a.supports
        ]
        _same_blocks(a, read_block_model(p, use_compas=True))


def _has_compas() -> bool:
    try:
        import compas_dem  # noqa: F401
    except ImportError:
        return False
    return True


@pytest.mark.parametrize(
    "change, word",
    [
        (
            lambda d: [e["data"].update(is_support=True) for e in d["data"]["elements"].values()],
            "every block is a support",
        ),
        (lambda d: d["data"].update(transformation={"data": {"matrix": [[1, 0, 0], [0, 1, 0]]}}), "4 x 4"),
        (lambda d: [e["data"].update(is_support=False) for e in d["data"]["elements"].values()], "below the ground"),
    ],
)
def test_bad_compas_models_are_one_line(tmp_path, change, word):
    data = json.loads(DATA.read_text())
    change(data)
    p = tmp_path / "bad.json"
    p.write_text(json.dumps(data))
    with pytest.raises(BlastscaleInputError, match=word) as e:
        read_block_model(p, use_compas=False)
    assert "\n" not in str(e.value) and "bad.json" in str(e.value)


@pytest.mark.parametrize(
    "angle_deg, shift", [(0.0, (1.0, 0.0, 0.0)), (30.0, (0.0, 0.0, 0.0)), (-135.0, (2.5, -1.25, 0.0))]
)
def test_any_rigid_model_transformation_moves_every_block_with_it(tmp_path, angle_deg, shift):
    """A model transformation (rotation about z, then a horizontal shift) composed onto the shipped
    one moves every block's vertices by exactly that map (to round-off)."""
    data = json.loads(DATA.read_text())
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    extra = np.array([[c, -s, 0, shift[0]], [s, c, 0, shift[1]], [0, 0, 1, shift[2]], [0, 0, 0, 1.0]])
    m = np.asarray(data["data"]["transformation"]["data"]["matrix"], dtype=float)
    data["data"]["transformation"]["data"]["matrix"] = (extra @ m).tolist()
    p = tmp_path / "moved.json"
    p.write_text(json.dumps(data))
    base, moved = read_block_model(DATA, use_compas=False), read_block_model(p, use_compas=False)
    for x, y in zip(base.blocks + base.supports, moved.blocks + moved.supports):
        np.testing.assert_allclose(y.points, x.points @ extra[:3, :3].T + extra[:3, 3], atol=TOL)


def test_a_compas_material_gives_the_block_its_density(tmp_path):
    """compas_dem's materials (``GenericMaterial``, ``Stone``) carry a density [kg/m^3]; a block
    without one takes the scenario's; the density survives the round trip through ``--to-compas``."""
    data = json.loads(DATA.read_text())
    data["data"]["materials"] = {
        "5647853b-fb41-4e05-b174-461694fd36ee": {
            "dtype": "compas_dem.material/Stone",
            "guid": "5647853b-fb41-4e05-b174-461694fd36ee",
            "data": {"name": "Stone", "density": 2650.0},
        }
    }
    v2 = next(e for e in data["data"]["elements"].values() if e["data"]["name"] == "V2")
    v2["data"]["material"] = "5647853b-fb41-4e05-b174-461694fd36ee"
    p = tmp_path / "stone.json"
    p.write_text(json.dumps(data))
    a = read_block_model(p, 2000.0, use_compas=False)
    assert {b.name: b.density for b in a.blocks} == {"V1": 2000.0, "V4": 2000.0, "V2": 2650.0, "V3": 2000.0}
    back = tmp_path / "back.json"
    back.write_text(json.dumps(compas_model_data(a)))
    _same_blocks(a, read_block_model(back, 1000.0, use_compas=False))  # every density from the file
    if _has_compas():
        _same_blocks(a, read_block_model(p, 2000.0, use_compas=True))
        _same_blocks(a, read_block_model(back, 1000.0, use_compas=True))
