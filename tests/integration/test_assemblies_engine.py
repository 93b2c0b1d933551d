"""Assemblies on the 3D engine (issue 16): the same structure built two ways gives the same answer, the
sparse Jacobian chosen for large assemblies gives the dense histories, gravity alone, and the classical
minimum thickness of a semicircular arch (shortened runs; full lengths in docs/assemblies.md)."""

import dataclasses
import json

import numpy as np
import pytest

from blastscale.blast import blast_parameters
from blastscale.scenario import load_scenario
from blastscale.sim3d import make_load, simulate_structure
from blastscale.sim3d.contact import default_contact
from blastscale.structures import MultiDrumColumn, RectangularBlock, arch, read_block_model, wall
from blastscale.structures.generators import box_vertices_from_bounds


def _x_histories(r):
    return r.dataset["point_displacement"].values[:, :, 0]


def _agree(a, b, rel):
    peak = np.abs(a).max()
    assert np.abs(a - b).max() <= rel * peak, np.abs(a - b).max() / peak


def test_a_block_from_a_json_file_runs_as_kind_block(tmp_path):
    blk = RectangularBlock(height=10.0, width=10.0 * np.tan(np.radians(15)), depth=1.0, density=2000.0)
    p = tmp_path / "block.json"
    b, w = blk.b, blk.w
    p.write_text(
        json.dumps({"blocks": [{"name": "block", "vertices": box_vertices_from_bounds(-b, b, -w, w, 0, 10).tolist()}]})
    )
    asm = read_block_model(p, 2000.0)
    bp = blast_parameters(50.0, 2.0, "masi2021")
    r1 = simulate_structure(blk, make_load("A", blk, bp), 0.6, record_every=20)
    r2 = simulate_structure(asm, make_load("A", asm, bp), 0.6, record_every=20)
    _agree(_x_histories(r1), _x_histories(r2), 0.01)  # issue: 1 % of the peak (measured: 0 to round-off)


def test_ten_stacked_boxes_from_a_file_run_as_a_prismatic_column(tmp_path):
    col = MultiDrumColumn("square", drums=10, base_width=1.5, top_width=1.5)
    p = tmp_path / "stack.json"
    p.write_text(
        json.dumps(
            {
                "blocks": [
                    {
                        "name": f"D-{k + 1}",
                        "vertices": box_vertices_from_bounds(-0.75, 0.75, -0.75, 0.75, k, k + 1).tolist(),
                    }
                    for k in range(10)
                ]
            }
        )
    )
    asm = read_block_model(p, 2700.0)
    bp = blast_parameters(250.0, 10.0)
    r1 = simulate_structure(col, make_load("A", col, bp), 0.4, record_every=20)
    r2 = simulate_structure(asm, make_load("A", asm, bp), 0.4, record_every=20)
    _agree(_x_histories(r1), _x_histories(r2), 0.01)


def test_sparse_jacobian_gives_the_dense_histories_on_a_small_wall():
    w = wall(length_m=3.0, height_m=2.0, thickness_m=0.4, courses=4, units_per_course=3)  # 14 blocks: sparse
    load = make_load("A", w, blast_parameters(5.0, 5.0))
    base = default_contact(w)
    assert base.jacobian == "sparse"
    rs = simulate_structure(w, load, 0.3, contact=base, record_every=20)
    rd = simulate_structure(w, load, 0.3, contact=dataclasses.replace(base, jacobian="dense"), record_every=20)
    _agree(_x_histories(rd), _x_histories(rs), 1e-6)  # MuJoCo 4.0.0's sparse-factorisation bug would show here


def test_semicircular_arch_minimum_thickness_thick_stands_thin_collapses():
    """Heyman (1969): t/R = 0.106 for a semicircular arch under self-weight (0.1075 with radial joints,
    Milankovitch 1907, Ochsendorf 2002). Shortened: 1 s (the thick arch's 5 s run: docs/assemblies.md)."""
    kw = dict(radius_m=5.0, depth_m=1.0, voussoirs=20)
    thick, thin = arch(thickness_m=0.14 * 5.0, **kw), arch(thickness_m=0.08 * 5.0, **kw)
    r = simulate_structure(thick, None, 1.0, record_every=100, contact=default_contact(thick, friction=0.8))
    s = r.summary()
    assert not s["collapsed"] and s["max_residual_displacement_m"] < 1e-3
    # the stated rule (docs/assemblies.md): at rest (final speed < 1e-4 sqrt(g H); measured ~2e-5, the soft
    # contacts' creep) and residual displacement <= 1e-3 H (measured 3e-5 H at 1 s, 1.2e-4 H at 5 s): stands
    assert s["stability"] == "stands" and s["final_speed_rel_sqrt_gh"] < 1e-4
    r = simulate_structure(thin, None, 1.0, record_every=100, contact=default_contact(thin, friction=0.8))
    s = r.summary()
    assert s["collapsed"] and s["fallen_blocks"] > 10 and s["stability"] == "collapses"


def test_stability_rule_moving_when_neither_at_rest_nor_fallen():
    """A thin arch (t/R 0.08) 0.2 s into its collapse: no block has fallen yet, but it moves at
    ~1e-2 sqrt(g H): "moving" (run longer), never "stands"."""
    thin = arch(radius_m=5.0, thickness_m=0.08 * 5.0, depth_m=1.0, voussoirs=20)
    s = simulate_structure(thin, None, 0.2, record_every=50, contact=default_contact(thin, friction=0.8)).summary()
    assert s["fallen_blocks"] == 0 and s["stability"] == "moving" and s["final_speed_rel_sqrt_gh"] > 1e-3


def test_gravity_alone_scenario_stands(tmp_path):
    from blastscale.study import Study

    p = tmp_path / "w.toml"
    p.write_text('[structure]\nkind = "wall"\ncourses = 3\nunits_per_course = 2\n[simulation]\nduration_s = 0.2\n')
    res = Study(load_scenario(p)).run()
    s = res.summary()["3d"]["prototype"]
    assert s["stability"] == "stands" and s["fallen_blocks"] == 0 and res.design is None


@pytest.mark.slow
def test_a_stable_arch_is_not_left_moving():
    """Issue #24: the semicircular arch R = 5 m, t/R = 0.16, 20 voussoirs, friction 0.8 ends a 2 s
    gravity-alone run at 2.1e-4 sqrt(g H) (0.23 mm drift), above the 1e-4 of "at rest": "moving". The
    run is extended (doubled) until the rule decides: it stands at 4 s (1.6e-5 sqrt(g H), 0.45 mm,
    1e-4 H: below the 1e-3 H of "stands"). Measured at impratio 10, the assemblies' default before issue #41, and kept
    there: with the default now (ASSEMBLY_IMPRATIO = 20, half the creep) the arch stands at 2 s, and the case would no
    longer exercise the extension."""
    from blastscale.scenario import Scenario
    from blastscale.study import Study

    sc = Scenario.from_dict(
        {
            "structure": {"kind": "arch", "radius_m": 5.0, "thickness_m": 0.8, "voussoirs": 20, "friction": 0.8},
            "simulation": {"engine": "3d", "duration_s": 2.0, "contact": {"impratio": 10.0}},
        }
    )
    s = Study(sc).run().summary()["3d"]["prototype"]
    assert s["stability"] == "stands" and s["final_speed_rel_sqrt_gh"] < 1e-4
    assert (s["duration_asked_s"], s["duration_simulated_s"]) == (2.0, 4.0)
