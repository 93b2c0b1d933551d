"""Prototype-only scenarios (no ``[scale]``) on the 3D engine and its ensembles, through the Study:
the prototype alone, ``model`` and ``similarity`` None, histories with ``system = ["prototype"]``.

Independent check: the prototype does not depend on the specimen's design, so its run from its own
blast parameters must be the prototype side of the scaled study, bit for bit (the same blast
parameters, the same contact settings, the same engine).
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from blastscale.io.histories import write_netcdf
from blastscale.scenario import Scenario
from blastscale.study import Study

#: a short circular 3-drum column (16-gon drums), 200 kg at 10 m
COLUMN = {"kind": "column", "section": "circular", "sides": 16, "drums": 3, "height_m": 3.0, "top_width_m": 1.54}


def _prototype_only(structure: dict, simulation: dict, **blast) -> Scenario:
    return Scenario.from_dict(
        {
            "structure": structure,
            "blast": {"charge_kg": 200.0, "standoff_m": 10.0, **blast},
            "simulation": {"engine": "3d", "critical_charge": False, **simulation},
        }
    )


def test_a_column_without_scale_runs_3d_and_its_ensemble_on_the_prototype_alone(tmp_path):
    sc = _prototype_only(COLUMN, {"duration_s": 0.2, "ensemble_members": 2})
    r = Study(sc).run()
    assert r.design is None and r.specimen_structure is None
    s = r.summary()
    assert s["3d"]["model"] is None and s["3d"]["similarity"] is None
    assert {"collapsed", "max_top_displacement_m", "points"} <= set(s["3d"]["prototype"])
    e = s["ensemble"]
    assert e["n_members"] == 2 and e["collapse_probability_model"] is None
    assert (
        e["points"]["P-3"]["first_peak_prototype_mean_m"] > 0 and e["points"]["P-3"]["first_peak_model_mean_m"] is None
    )
    assert r.response3d.upscaled_dataset is None and r.ensemble.model_members is None
    # the histories: one system, the prototype, in each group; written and read back
    tree = r.to_datatree()
    assert list(tree["sim3d"].ds["system"].values) == ["prototype"]
    assert list(tree["ensemble"].ds["system"].values) == ["prototype"]
    assert tree["ensemble"].ds["point_displacement_x"].sizes["member"] == 2
    path = tmp_path / "h.nc"
    write_netcdf(tree, path)
    with xr.open_datatree(path) as back:
        np.testing.assert_array_equal(
            back["sim3d"]["point_displacement"].values, tree["sim3d"]["point_displacement"].values
        )
    # the study's own warnings: chaos is addressed by the ensemble, nothing compares a model
    assert not any("model" in w for w in r.warnings), r.warnings


@pytest.mark.parametrize(
    "structure, load",
    [(COLUMN, "A"), ({"kind": "block", "height_m": 10.0, "width_m": 2.0}, "C")],
    ids=["column-A", "block-C"],
)
def test_the_prototype_alone_is_the_prototype_side_of_the_scaled_study(structure, load):
    """Bit for bit: the prototype's run does not depend on the specimen (measured: identical)."""
    sc = _prototype_only(structure, {"duration_s": 0.15}, load=load)
    alone = Study(sc).run().summary()["3d"]
    scaled = Study(sc.with_values({"scale.length": 0.01})).run().summary()["3d"]
    assert alone["prototype"] == scaled["prototype"]
    if structure["kind"] == "block":  # the block's planar view is there, prototype only
        assert {"collapsed", "max_rotation_rad", "max_sliding_m", "collapsed"} <= set(alone["prototype"])
        assert {"max_abs_rotation_diff_rad", "top_first_peak_ratio"} <= set(scaled["similarity"])


def test_run_writes_a_prototype_only_3d_study_with_its_ensemble(tmp_path, capsys):
    """``blastscale run`` of a column scenario without ``[scale]`` (3D engine, a 2-member ensemble):
    summary, histories and report written; the ensemble figure shows the prototype alone."""
    import json

    from blastscale.cli import main

    sc = _prototype_only(COLUMN, {"duration_s": 0.1, "ensemble_members": 2})
    path = tmp_path / "column.toml"
    path.write_text(sc.to_toml())
    out = tmp_path / "out"
    with pytest.raises(SystemExit) as e:
        main(["run", str(path), "--out", str(out)])
    assert (e.value.code or 0) == 0, capsys.readouterr().err
    s = json.loads((out / "summary.json").read_text())
    assert s["design"] is None and s["3d"]["model"] is None and s["ensemble"]["collapse_probability_model"] is None
    for name in ("histories.nc", "report.html", "ensemble_envelopes.png", "response_3d.png"):
        assert (out / name).stat().st_size > 1000, name
