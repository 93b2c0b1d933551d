"""Similarity map: identity at lambda = gamma = 1, exactness of the impulsive limit, invalid
designs marked, CLI and plot."""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("zarr")

from blastscale.cli import main  # noqa: E402
from blastscale.scenario import Scenario  # noqa: E402
from blastscale.sweeps.similarity_map import similarity_map  # noqa: E402

BASE = Scenario.default().with_values({"duration_s": 2.0, "samples": 401})


def test_identity_and_impulsive_exactness():
    ds = similarity_map(BASE, [1e-5, 0.01, 1.0], [0.3, 1.0], [50.0], [2.0]).squeeze()
    # lambda = gamma = 1: the model is the prototype, up to the round-off of the design's root for
    # lambda_Z (observed 4e-16 rad)
    assert float(ds["error"].sel(length=1.0, density_ratio=1.0)) < 1e-12
    assert bool(ds["trustworthy"].sel(length=1.0, density_ratio=1.0))
    # lambda = 1e-5: the model's Z leaves the fits (no design): marked, not fatal
    assert not ds["valid"].sel(length=1e-5).any() and not ds["trustworthy"].sel(length=1e-5).any()
    # a Friedlander pulse at lambda = 0.01: ~1e-4 rad (the finite-pulse effect, docs/rocking.md)
    e = float(ds["error"].sel(length=0.01, density_ratio=1.0))
    assert 1e-6 < e < 5e-4
    imp = similarity_map(BASE.with_values({"pulse": "impulsive"}), [0.01, 0.1], [0.3, 1.0], [50.0], [2.0]).squeeze()
    # the impulsive limit is an exact similarity transform: round-off only (target 1e-10 rad)
    assert float(imp["error"].max()) < 1e-10 and bool(imp["trustworthy"].all())


def test_similarity_map_cli(tmp_path, capsys):
    png = tmp_path / "map.png"
    toml = tmp_path / "s.toml"
    toml.write_text(BASE.to_toml())
    with pytest.raises(SystemExit) as e:
        main(
            [
                "similarity-map",
                str(toml),
                "--scales",
                "0.01,0.1",
                "--density-ratios",
                "0.5,1",
                "--charges",
                "50",
                "--standoffs",
                "2,3",
                "--plot",
                str(png),
                "--json",
            ]
        )
    assert e.value.code in (0, None)
    out = json.loads(capsys.readouterr().out)
    assert out["n_cases"] == 8 and out["n_valid"] == 8 and out["n_outcomes_agree"] == 8
    assert np.asarray(out["error"]).shape == (2, 2, 1, 2) and out["error_units"] == "rad"
    assert png.stat().st_size > 10_000


def test_3d_map_on_a_coarse_grid():
    """The 3D engine (MuJoCo, paper block, 0.3 s): the model at lambda = 0.1 follows the prototype
    (a rocking start; the 3D comparison is documented in docs/sim3d.md), the map carries the 3D definition
    of its error, and its trustworthy cell is that design's Study verdict (issue #35: one criterion), with
    the verdict's worst ratio."""
    from blastscale.study import Study

    base = BASE.with_values({"duration_s": 0.3})
    ds = similarity_map(base, [0.1], [1.0], [50.0], [2.0], engine="3d").squeeze()
    assert ds.attrs["engine"] == "3d" and ds.attrs["error_units"] == "-"
    assert bool(ds["valid"]) and bool(ds["outcomes_agree"])
    assert 0.0 <= float(ds["error"]) < 0.05 and bool(ds["trustworthy"])
    case = base.with_values(
        {"engine": "3d", "critical_charge": False, "length": 0.1, "density_ratio": 1.0, "charge_kg": 50.0}
    )
    v = Study(case).run().summary()["verdict"]
    assert bool(ds["trustworthy"]) is v["similar"] is True
    assert float(ds["worst_ratio"]) == pytest.approx(v["worst"]["ratio"], rel=1e-12) and v["worst"]["ratio"] <= 1.0
    # a [verdict] table tighter than this design's worst error: the same map calls it untrustworthy
    tight = base.with_values({"verdict.peak": 1e-6, "verdict.displacement": 1e-6, "verdict.residual": 1e-6})
    assert not bool(similarity_map(tight, [0.1], [1.0], [50.0], [2.0], engine="3d").squeeze()["trustworthy"])


def test_map_through_a_store_and_of_a_prototype_only_scenario(tmp_path, capsys):
    """--out (the resumable store, read back as its tree) gives the JSON of the in-memory run; a
    scenario without [scale] maps the same (every case sets its own lambda and gamma)."""
    data = BASE.to_dict()
    data.pop("scale")
    outs = []
    for sc, extra in (
        (BASE, []),
        (BASE, ["--out", str(tmp_path / "m.zarr")]),
        (Scenario.from_dict(data, source="test: no [scale]"), []),
    ):
        toml = tmp_path / "s.toml"
        toml.write_text(sc.to_toml())
        with pytest.raises(SystemExit) as e:
            main(
                [
                    "similarity-map",
                    str(toml),
                    "--scales",
                    "0.01,0.1",
                    "--density-ratios",
                    "1",
                    "--charges",
                    "50",
                    "--standoffs",
                    "2",
                    "--json",
                    *extra,
                ]
            )
        assert e.value.code in (0, None)
        outs.append(json.loads(capsys.readouterr().out))
    assert outs[0] == outs[1] == outs[2] and outs[0]["n_valid"] == 2
    assert (tmp_path / "m.zarr" / ".zmetadata").exists()
