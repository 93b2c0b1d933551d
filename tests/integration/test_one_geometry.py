"""A structure shown is the structure simulated (issue 29): one geometry per structure kind.

For every kind (block, square and circular column, wall, arch, portal, block-model file) at a few
sizes, the mass, volume and centre of mass that ``blastscale show --json`` prints equal those of the
bodies MuJoCo integrates (``body_mass`` summed, ``xipos`` at rest, divided by the engine's reference
factors), and the solid that ``show`` and the report draw (each block's vertices) has, by an independent
integration (divergence theorem, ``polyhedron_mass_properties``), the mass, centre of mass and principal
moments of inertia of the body simulated.

Tolerance 1e-9 relative (of the mass, of the volume, of the structure's height for the centre of mass,
whose x and y are 0 for symmetric kinds, of a body's largest moment for its moments): the engine
integrates the structure in reference units with its parameters rounded to 12 significant digits
(< 5e-13 relative, ``sim3d.reference``), and the two mass integrations differ by round-off (~1e-15);
the bug this guards against was 2.5 % (a drum's prism of its base section drawn and described instead
of its frustum).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from blastscale.cli import main
from blastscale.scenario import load_scenario
from blastscale.sim3d.reference import reference_scene
from blastscale.structures import as_assembly, polyhedron_mass_properties
from blastscale.study import Study

REL = 1e-9
GRAVITY_ONLY = "[blast]\ncharge_kg = 0.0\n"


def _box(name, x0, x1, y0, y1, z0, z1):
    return {"name": name, "vertices": [[x, y, z] for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]}


def _block_file(tmp_path, size):
    """A box on the ground, a box beside it and a wedge (not a box: a convex mesh) on the first."""
    s = size
    wedge = {"name": "W", "vertices": [[0, 0, s], [s, 0, s], [0, s, s], [s, s, s], [0, 0, 1.5 * s], [0, s, 1.5 * s]]}
    p = tmp_path / f"blocks_{size:g}.json"
    p.write_text(json.dumps({"blocks": [_box("A", 0, s, 0, s, 0, s), _box("B", 0, s, s, 2 * s, 0, 0.5 * s), wedge]}))
    return p.name


#: (case id, [structure] table; the density is 2300 kg/m^3 in every case)
CASES = [
    ("block_10m", 'kind = "block"\nheight_m = 10.0\nalpha_deg = 15.0\ndepth_m = 1.0'),
    ("block_0.3m", 'kind = "block"\nheight_m = 0.3\nwidth_m = 0.07\ndepth_m = 0.11'),
    ("column_square_10m", 'kind = "column"\nsection = "square"'),
    (
        "column_square_0.1m",
        'kind = "column"\nsection = "square"\ndrums = 3\nheight_m = 0.1\nbase_width_m = 0.0165\ntop_width_m = 0.0128',
    ),
    ("column_circular_10m", 'kind = "column"\nsection = "circular"'),
    (
        "column_circular_0.5m",
        'kind = "column"\nsection = "circular"\ndrums = 4\nheight_m = 0.5\nbase_width_m = 0.1\n'
        "top_width_m = 0.06\nsides = 12",
    ),
    ("wall_running", 'kind = "wall"\ncourses = 4\nunits_per_course = 3'),
    (
        "wall_stack_0.2m",
        'kind = "wall"\nlength_m = 0.3\nheight_m = 0.2\nthickness_m = 0.04\ncourses = 3\n'
        'units_per_course = 2\nbond = "stack"',
    ),
    (
        "arch",
        'kind = "arch"\nradius_m = 2.0\nthickness_m = 0.4\nvoussoirs = 7\nembrace_deg = 120.0\npier_height_m = 1.0',
    ),
    ("portal_drums", 'kind = "portal"\ndrums = 2'),
    ("assembly_1m", 'kind = "assembly"\nfile = "FILE1"'),
    ("assembly_0.05m", 'kind = "assembly"\nfile = "FILE0.05"'),
]


def _scenario(tmp_path, table):
    for size in (1.0, 0.05):
        table = table.replace(f'"FILE{size:g}"', f'"{_block_file(tmp_path, size)}"')
    p = tmp_path / "case.toml"
    p.write_text(f"[structure]\n{table}\ndensity_kg_m3 = 2300.0\n{GRAVITY_ONLY}")
    return p


def _show_json(capsys, path):
    with pytest.raises(SystemExit) as e:
        main(["show", str(path), "--json"])
    out = capsys.readouterr().out
    assert (e.value.code or 0) == 0
    return json.loads(out)


def _simulated(structure):
    """(mass [kg], centre of mass [m], per-body masses [kg], centres [m] and principal moments [kg m^2],
    ascending) of the MuJoCo model the engine integrates, back in the structure's units."""
    import mujoco

    scene, (a, _) = reference_scene(structure, None, 9.81)
    d = mujoco.MjData(scene.mj_model)
    mujoco.mj_forward(scene.mj_model, d)
    m = scene.mj_model.body_mass[scene.body_ids] / a**3
    c = d.xipos[scene.body_ids] / a
    moments = np.sort(scene.mj_model.body_inertia[scene.body_ids], axis=1) / a**5
    return float(m.sum()), m @ c / m.sum(), m, c, moments


@pytest.mark.parametrize("table", [t for _, t in CASES], ids=[c for c, _ in CASES])
def test_show_prints_the_mass_volume_and_centre_of_mass_simulated(capsys, tmp_path, table):
    path = _scenario(tmp_path, table)
    shown = _show_json(capsys, path)
    structure = Study(load_scenario(path)).structure()
    mass, com, masses, coms, moments = _simulated(structure)
    H = shown["height_m"]
    assert shown["mass_kg"] == pytest.approx(mass, rel=REL)
    assert shown["volume_m3"] == pytest.approx(mass / 2300.0, rel=REL)
    assert np.allclose(shown["centre_of_mass_m"], com, rtol=0.0, atol=REL * H)
    # what is drawn: each block's solid, integrated independently, is the body simulated
    asm = as_assembly(structure)
    assert len(asm.blocks) == len(masses) == shown["blocks"]
    for blk, m, c, j in zip(asm.blocks, masses, coms, moments):
        mp = polyhedron_mass_properties(blk.points, 2300.0, blk.name)
        assert mp.mass == pytest.approx(m, rel=REL), blk.name
        assert np.allclose(mp.centroid, c, rtol=0.0, atol=REL * H), blk.name
        assert np.allclose(np.linalg.eigvalsh(mp.inertia), j, rtol=0.0, atol=REL * j.max()), blk.name


def test_the_paper_column_shows_its_frustums():
    """The issue's numbers: the paper's square column (ten 1 m drums, 1.65 -> 1.28 m, 2700 kg/m^3) is
    58,256.1 kg and 21.5763 m^3 (frustum volume H/3 (A0 + A1 + sqrt(A0 A1)) per drum, closed form),
    drum 1 7187.1471 kg; ``show`` printed 59,726 kg and 22.121 m^3 (prisms of the base sections)."""
    from blastscale.cli.show import describe_structure
    from blastscale.structures import MultiDrumColumn

    w = np.linspace(1.65, 1.28, 11)
    A0, A1 = w[:-1] ** 2, w[1:] ** 2
    vols = (A0 + A1 + np.sqrt(A0 * A1)) / 3.0
    d = describe_structure(MultiDrumColumn())
    assert d["volume_m3"] == pytest.approx(vols.sum(), rel=1e-12)
    assert d["mass_kg"] == pytest.approx(2700.0 * vols.sum(), rel=1e-12)
    assert d["mass_kg"] == pytest.approx(58256.1, rel=1e-12)
    assert 2700.0 * vols[0] == pytest.approx(7187.1471, rel=1e-12)
    assert as_assembly(MultiDrumColumn()).bodies[0].mass == pytest.approx(7187.1471, rel=1e-12)


@pytest.mark.parametrize("charge", [(-3.0, 0.0, 12.0), (-1.5, 0.0, 0.3), (-1.0, 0.2, 2.0)])
@pytest.mark.parametrize("section", ["square", "circular"])
def test_method_c_sees_the_column_drawn(section, charge):
    """Method C's line of sight (``sim3d.exposure``) is cast against the drums' solids, the frustums drawn
    (the same fractions as past the column ``show`` draws, an assembly of the frustums). A linearly
    tapered column's frustums make one convex solid, so every face turned towards the charge is in sight
    (fraction 1, exactly); with the contact prisms, whose tops overhang the next drum by 18.5 mm per side,
    2-24 of these faces were shadowed by a close charge."""
    from blastscale.sim3d.exposure import visible_fractions
    from blastscale.structures import MultiDrumColumn

    col = (
        MultiDrumColumn(section=section, drums=3, height=3.0, top_width=1.2)
        if charge[2] > 10
        else MultiDrumColumn(section=section)
    )
    faces = [(i, f) for i, b in enumerate(col.bodies) for f in b.faces if not f.in_contact and f.area > 0.0]
    seen = visible_fractions(col, faces, charge)
    assert np.array_equal(seen, visible_fractions(as_assembly(col), faces, charge))
    assert np.all(seen == 1.0)
