"""Supports of a COMPAS block model are fixed to the ground in the 3D engine (issue 23, deliverable 4).

The arch of tests/data/compas_dem_arch_rotated.json (written by compas_dem; see
tests/unit/structures/test_compas_files.py) stands on two ``is_support`` abutments whose tops are
0.4 m above the ground. Welded to the world (geoms of MuJoCo's world body, no joint), they carry the
arch: under gravity alone it stands. Without them the same voussoirs fall freely, 0.2 m in 0.2 s
(g t^2 / 2), so the test can tell the two apart by three orders of magnitude.
"""

from pathlib import Path

import numpy as np
import pytest

from blastscale.sim3d import default_contact, simulate_structure, structure_scene
from blastscale.structures import Assembly, read_block_model

pytest.importorskip("mujoco")

DATA = Path(__file__).resolve().parents[1] / "data" / "compas_dem_arch_rotated.json"
#: 0.2 s is past the settling and long enough for an unsupported springer to drop ~0.2 m [s].
RUN_S = 0.2


def test_supports_are_part_of_the_ground_not_free_bodies():
    a = read_block_model(DATA, 2000.0)
    scene = structure_scene(a, default_contact(a))
    m = scene.mj_model
    assert m.nbody == 1 + 4 and m.nq == 7 * 4  # the world and the four voussoirs, each on a free joint
    for name in ("abutment-W_geom", "abutment-E_geom"):
        assert m.geom_bodyid[m.geom(name).id] == 0  # a geom of the world body: fixed


def test_the_arch_stands_on_its_supports_and_falls_without_them():
    a = read_block_model(DATA, 2000.0)
    r = simulate_structure(a, None, RUN_S, record_every=50)
    d = np.abs(r.dataset["com_displacement"].values).max()
    # soft contact settling at this size is ~1e-6 m (measured 1.3e-6 m over 0.3 s); 1e-4 m leaves room
    assert d < 1e-4
    assert list(r.dataset["body"].values) == ["V1", "V4", "V2", "V3"]  # COMPAS's names are the bodies' names

    loose = Assembly(a.blocks, kind="assembly", check=False)  # the same voussoirs, without their supports
    r2 = simulate_structure(loose, None, RUN_S, record_every=50)
    assert np.abs(r2.dataset["com_displacement"].values[..., 2]).max() > 0.05
