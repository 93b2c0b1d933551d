"""Sweeps: the planar batch path equals the Study bit for bit, a sweep equals the plain serial
loop over its cases, on a Dask cluster started as separate processes, after a kill -9 and a
re-run, and bad grids/distributions are one-line errors (exit 2)."""

from __future__ import annotations

import json
import math
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("zarr")
pytest.importorskip("distributed")
import xarray as xr  # noqa: E402

from blastscale._validate import BlastscaleInputError  # noqa: E402
from blastscale.cli import main  # noqa: E402
from blastscale.io.sweep_store import open_sweep  # noqa: E402
from blastscale.scenario import Scenario  # noqa: E402
from blastscale.sweeps import SweepSpec, select, store_location, study_scalars  # noqa: E402
from blastscale.sweeps.grids import parse_distribution  # noqa: E402
from blastscale.sweeps.run import run_sweep  # noqa: E402

BIN = Path(sys.executable).parent
# short planar runs (the paper's block): 1.5 s, 301 samples; critical charge on (searched once per stand-off)
BASE = Scenario.default().with_values({"engine": "planar", "duration_s": 1.5, "samples": 301})


def same(a, b) -> bool:
    """Bit-for-bit equality of two scalars (NaN equals NaN)."""
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


def test_a_case_the_study_refuses_is_marked_invalid_not_fatal():
    """lambda = 1e-5: the model's scaled distance leaves the blast fits; that case only is invalid."""
    cases = [BASE.with_values({"length": x, "critical_charge": False}) for x in (1e-5, 0.01)]
    got = [study_scalars(sc) for sc in cases]
    assert got[0] == {"sweep.valid": False} and got[1]["sweep.valid"] is True


def store_contents(tree) -> dict:
    """Everything a store holds, root attributes aside (they carry the chunk size and the time):
    (group, name) -> values, for data variables and coordinates ("var", the constants included) and
    group attributes ("attr", none expected)."""
    out = {}
    for node in tree.subtree:
        for name, v in node.to_dataset(inherit=False).variables.items():
            out[(node.path, name, "var")] = v.values
        if node.path != "/":
            for name, v in node.attrs.items():
                out[(node.path, name, "attr")] = v
    return out


def stored_names(tree) -> set:
    """(group, name) of every data variable of a store (the constants included)."""
    return {(node.path.strip("/"), n) for node in tree.subtree for n in node.data_vars}


def assert_store_equals_loop(path, spec):
    tree = open_sweep(path)
    assert tuple(tree.sizes[d] for d in spec.dims) == spec.shape
    places = set()
    for k in range(spec.n_cases):
        want = study_scalars(spec.scenario(k))  # the plain serial loop: one Study per case
        idx = np.unravel_index(k, spec.shape)
        for key, v in want.items():
            loc = store_location(key)
            if loc is None:  # a part that did not run (prototype only, an engine not asked for): a NaN marker
                assert math.isnan(v), key
                continue
            places.add((loc.group, loc.name))
            assert same(select(tree, key).values[idx].item(), v), (k, key)
    assert stored_names(tree) == places  # and nothing else
    return tree


def test_sweep_equals_the_serial_loop_with_monte_carlo(tmp_path):
    spec = SweepSpec.build(
        BASE, {"charge_kg": [40.0, 90.0]}, {"restitution": parse_distribution("uniform:0.3,0.9")}, samples=3, seed=7
    )
    run = run_sweep(spec, tmp_path / "s.zarr", workers=0, chunk=4)
    assert run.chunks_run == 2 and spec.dims == ("charge_kg", "sample")
    tree = assert_store_equals_loop(tmp_path / "s.zarr", spec)
    r = tree["restitution"].values  # the draws: coordinate on `sample`, the same at every charge
    assert r.shape == (3,) and np.all((r >= 0.3) & (r <= 0.9))
    assert tree["charge_kg"].attrs["units"] == "kg"
    # the layout: prototype and model on `system`, constants of the design once, as 0-d variables with units
    assert tree["planar"]["max_rotation"].dims == ("charge_kg", "sample", "system")
    assert list(tree["planar"]["system"].values) == ["prototype", "model"]
    assert tree["planar"]["max_rotation"].attrs == {"units": "rad", "long_name": "max rotation (planar rocking)"}
    assert "units" not in tree["planar"]["system"].attrs  # a label coordinate: no units
    scale = tree["design"]["scale"]
    assert scale.dims == () and scale.item() == 0.005 and scale.attrs["units"] == "1"
    height = tree["experiment"]["height"]  # the prototype's 10 m and the 1/200 specimen's 5 cm
    assert height.dims == ("system",) and height.attrs["units"] == "m"
    np.testing.assert_allclose(height.sel(system=["prototype", "model"]).values, [10.0, 0.05], rtol=1e-12)
    np.testing.assert_allclose(select(tree, "experiment.model.height_m").values, np.full((2, 3), 0.05), rtol=1e-12)
    assert "model_charge" in tree["design"].data_vars  # varies with the charge
    # a second run finds the finished store and does nothing
    assert run_sweep(spec, tmp_path / "s.zarr", workers=0).chunks_run == 0
    # the same sweep in the previous layout (store_version 2: constants as group attributes) is not taken for
    # this sweep's finished store: refused, replaced with force
    for name in (".zattrs", ".zmetadata"):
        f = tmp_path / "s.zarr" / name
        f.write_text(f.read_text().replace('"store_version": 3', '"store_version": 2'))
    with pytest.raises(BlastscaleInputError, match="--force"):
        run_sweep(spec, tmp_path / "s.zarr", workers=0)
    assert run_sweep(spec, tmp_path / "s.zarr", workers=0, chunk=4, force=True).chunks_run == 2
    assert open_sweep(tmp_path / "s.zarr").attrs["store_version"] == 3


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def cluster():
    """`dask scheduler` and one `dask worker` as separate processes on 127.0.0.1 (terminated after)."""
    from distributed import Client

    port = free_port()
    addr = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "DASK_DISTRIBUTED__WORKER__DAEMON": "False"}
    procs = [
        subprocess.Popen(
            [str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env=env,
        )
    ]
    try:
        procs.append(
            subprocess.Popen(
                [
                    str(BIN / "dask"),
                    "worker",
                    addr,
                    "--nthreads",
                    "1",
                    "--nworkers",
                    "1",
                    "--no-dashboard",
                    "--host",
                    "127.0.0.1",
                ],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                env=env,
            )
        )
        for _ in range(600):  # a start bounded in tries (a loaded machine starts it slower), not by a clock
            try:
                with Client(addr, timeout="2s") as c:
                    if c.scheduler_info()["workers"]:
                        break
            except OSError:
                pass
            time.sleep(0.3)
        else:
            pytest.fail("dask cluster did not start")
        yield addr
    finally:  # our two processes, by their ids: terminate, and kill what has not exited after 2 s
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(2)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def run_cli(capsys, *argv) -> dict:
    """`blastscale ...` in this process; returns its JSON."""
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    assert e.value.code in (0, None)
    return json.loads(capsys.readouterr().out)


def assert_same_stores(a, b):
    va, vb = store_contents(open_sweep(a)), store_contents(open_sweep(b))
    assert va.keys() == vb.keys()
    for k in va:
        np.testing.assert_array_equal(va[k], vb[k])  # bit for bit (NaN where both NaN)


def test_sweep_on_a_separate_dask_cluster_equals_the_local_result(tmp_path, capsys, cluster):
    toml = tmp_path / "planar.toml"
    toml.write_text(BASE.to_toml())
    remote = run_cli(
        capsys,
        "sweep",
        str(toml),
        "--vary",
        "charge_kg=40:120:3",
        "--vary",
        "standoff_m=2,3",
        "--sample",
        "restitution=triangular:0.3,0.8,0.9",
        "--samples",
        "2",
        "--seed",
        "3",
        "--chunk",
        "2",
        "--out",
        str(tmp_path / "remote.zarr"),
        "--scheduler",
        cluster,
        "--json",
    )
    assert remote["n_cases"] == 12 and remote["workers"] == 1 and remote["chunks_run"] == 6
    spec = SweepSpec.build(
        BASE,
        {"charge_kg": [40.0, 80.0, 120.0], "standoff_m": [2.0, 3.0]},
        {"restitution": parse_distribution("triangular:0.3,0.8,0.9")},
        samples=2,
        seed=3,
    )
    run_sweep(spec, tmp_path / "local.zarr", workers=0, chunk=5)  # another chunking, in this process
    assert_same_stores(tmp_path / "remote.zarr", tmp_path / "local.zarr")


def test_kill_9_midway_then_rerun_gives_the_uninterrupted_result(tmp_path, cluster):
    toml = tmp_path / "planar.toml"
    toml.write_text(BASE.to_toml())
    # 24 cases, one per task; each searches its own critical charge (distinct stand-offs): slow enough to stop
    store, parts = tmp_path / "k.zarr", tmp_path / "k.zarr.parts"
    # the sweep pauses after writing its second chunk (blastscale._hooks) and is killed there: always midway
    marker = tmp_path / "paused"
    env = {**os.environ, "BLASTSCALE_PAUSE_AT": "sweep:chunks=2", "BLASTSCALE_PAUSE_MARKER": str(marker)}
    p = subprocess.Popen(
        [
            str(BIN / "blastscale"),
            "sweep",
            str(toml),
            "--vary",
            "standoff_m=1.5:4:12",
            "--vary",
            "charge_kg=60,120",
            "--chunk",
            "1",
            "--out",
            str(store),
            "--scheduler",
            cluster,
        ],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env=env,
    )
    deadline = time.time() + 120
    while time.time() < deadline and not marker.exists() and p.poll() is None:
        time.sleep(0.01)
    assert marker.exists(), "the sweep did not reach its second chunk"
    os.kill(p.pid, signal.SIGKILL)
    p.wait()
    done = len(list(parts.glob("chunk-*.npz")))
    assert done == 2 and not store.exists()  # killed midway: two chunks written, no store yet
    spec = SweepSpec.build(BASE, {"standoff_m": np.linspace(1.5, 4, 12), "charge_kg": [60.0, 120.0]})
    again = run_sweep(spec, store, scheduler=cluster)  # the same sweep (the same fingerprint), resumed
    assert again.chunks_skipped == done and again.chunks_run + done == 24  # nothing lost or repeated
    assert not parts.exists()
    run_sweep(spec, tmp_path / "full.zarr", workers=0, chunk=24)  # uninterrupted, in one chunk
    assert_same_stores(store, tmp_path / "full.zarr")


@pytest.mark.parametrize(
    "argv, word",
    [
        (["--vary", "charge_kg=100:10:3"], "empty range"),
        (["--vary", "charge_kg=10:100:0"], "n = 0"),
        (["--vary", "charge_kg=10:100:-2"], "n = -2"),
        (["--vary", "no_such_field=1,2"], "no_such_field"),
        (["--vary", "charge_kg"], "FIELD=SPEC"),
        (["--sample", "friction=lognormal:0.6,-0.1", "--samples", "3"], "beta"),
        (["--sample", "friction=weibull:1,2", "--samples", "3"], "distribution"),
        (["--sample", "friction=uniform:0.8,0.5", "--samples", "3"], "empty range"),
        (["--sample", "friction=uniform:0.5,0.8"], "samples"),
        (["--vary", "charge_kg=-5,10"], "charge_kg"),
        (["--vary", "charge_kg=10,-5,20"], "charge_kg"),  # inside the grid, not only at its corners
        (["--sample", "restitution=normal:0.8,0.3", "--samples", "50"], "restitution"),  # draws beyond 1
        (["--set", "friction=-0.5"], "friction"),  # --set: validated by the scenario schema, as for `run`
        (["--set", "friction"], "KEY=VALUE"),
        (["--set", "no_such_key=1"], "no_such_key"),
    ],
)
def test_bad_grids_and_distributions_one_line_exit_2(tmp_path, capsys, argv, word):
    with pytest.raises(SystemExit) as e:
        main(["sweep", *argv, "--out", str(tmp_path / "x.zarr"), "--workers", "0"])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert word in err and "Traceback" not in err and len(err.strip().splitlines()) <= 2
    assert not (tmp_path / "x.zarr").exists() and not (tmp_path / "x.zarr.parts").exists()


def test_sweep_set_is_the_scenario_with_those_values(tmp_path, capsys):
    """``sweep --set KEY=VALUE`` reads the values as ``run --set`` does: the store is the sweep of the
    built-in scenario with those values (the same fingerprint, the plain loop of Studies), friction 0.6
    instead of the default's 0.7."""
    sets = ("engine=planar", "duration_s=1.5", "simulation.samples=301", "critical_charge=false", "friction=0.6")
    out = run_cli(
        capsys,
        "sweep",
        *[a for s in sets for a in ("--set", s)],
        "--vary",
        "charge_kg=40,120",
        "--out",
        str(tmp_path / "s.zarr"),
        "--workers",
        "0",
        "--json",
    )
    assert out["n_cases"] == 2
    spec = SweepSpec.build(BASE.with_values({"critical_charge": False, "friction": 0.6}), {"charge_kg": [40.0, 120.0]})
    tree = assert_store_equals_loop(tmp_path / "s.zarr", spec)
    assert tree.attrs["fingerprint"] == spec.fingerprint()


def test_default_local_cluster_path_equals_in_process(tmp_path):
    """The default path: a LocalCluster of worker processes (here one, on 127.0.0.1)."""
    spec = SweepSpec.build(BASE.with_values({"critical_charge": False}), {"charge_kg": [40.0, 100.0, 160.0]})
    run = run_sweep(spec, tmp_path / "lc.zarr", workers=1, chunk=2)
    assert run.workers == 1 and run.chunks_run == 2
    run_sweep(spec, tmp_path / "ip.zarr", workers=0)
    assert_same_stores(tmp_path / "lc.zarr", tmp_path / "ip.zarr")


def test_grid_and_distribution_strings():
    from blastscale.sweeps.grids import parse_grid

    np.testing.assert_array_equal(parse_grid("1:3:3"), [1.0, 2.0, 3.0])
    np.testing.assert_allclose(parse_grid("1:100:3:log"), [1.0, 10.0, 100.0], rtol=1e-15)
    np.testing.assert_array_equal(parse_grid("2.5"), [2.5])
    assert parse_grid("friedlander,impulsive", numeric=False).tolist() == ["friedlander", "impulsive"]
    assert parse_grid("1,2", numeric=False).dtype == float
    rng = np.random.default_rng(0)
    # sample moments against the closed forms: 1e5 draws, 5 standard errors of the mean
    n = 100_000
    for text, mean, sd in (
        ("normal:2,0.5", 2.0, 0.5),
        ("uniform:1,3", 2.0, 2 / math.sqrt(12)),
        ("triangular:0,1,4", 5 / 3, math.sqrt((0 + 1 + 16 - 0 - 0 - 4) / 18)),
        ("lognormal:2,0.3", 2 * math.exp(0.045), 2 * math.exp(0.045) * math.sqrt(math.expm1(0.09))),
    ):
        x = parse_distribution(text).sample(rng, n)
        assert abs(x.mean() - mean) < 5 * sd / math.sqrt(n), text
    x = parse_distribution("loguniform:1,100").sample(rng, n)
    assert x.min() >= 1 and x.max() <= 100 and abs(np.log10(x).mean() - 1.0) < 0.01


def test_one_friedlander_decay_is_the_array_bisection_bit_for_bit():
    """The one-decay path of friedlander_decay (float decisions away from the root, a stop once the
    bracket cannot move; the planar batch path calls it twice per design) returns the 90-step
    array bisection's value bit for bit: each scalar call against one array call over all the
    ratios (the array path is the plain bisection), across (0, e - 2), near k = 1/2 (d = 0, the
    series branch), near e - 2 (d = -1) and for tiny ratios (d up to ~1e12)."""
    import warnings

    from blastscale.blast.friedlander import MAX_IMPULSE_RATIO, friedlander_decay

    rng = np.random.default_rng(7)
    k = np.concatenate(
        [
            rng.uniform(1e-6, 0.999999 * MAX_IMPULSE_RATIO, 400),
            10 ** rng.uniform(-12, -0.3, 200),
            0.5 + rng.normal(0.0, 1e-4, 200),
            0.5 - 10 ** rng.uniform(-16, -1, 200),
            [0.5],
            MAX_IMPULSE_RATIO - 10 ** rng.uniform(-14, -2, 100),
        ]
    )
    P, t = rng.uniform(1e3, 1e7, k.size), rng.uniform(1e-5, 1e-1, k.size)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        whole = friedlander_decay(P, t, k * P * t)
        one = np.array([friedlander_decay(P[j], t[j], k[j] * P[j] * t[j]) for j in range(k.size)])
    assert np.array_equal(one, whole)


# -- the store's layout -------------------------------------------------------------------------


@pytest.mark.parametrize(
    "key, group, name, labels, units",
    [
        ("sweep.valid", "", "valid", (), "1"),
        ("planar.prototype.max_rotation_rad", "planar", "max_rotation", (("system", "prototype"),), "rad"),
        ("planar.similarity.first_peak_ratio", "planar", "first_peak_ratio", (), "1"),
        (
            "planar.similarity.max_abs_angular_velocity_diff_rad_s",
            "planar",
            "max_abs_angular_velocity_diff",
            (),
            "rad/s",
        ),
        (
            "3d.model.points.P-10.max_velocity_m_s",
            "sim3d",
            "max_velocity",
            (("system", "model"), ("point", "P-10")),
            "m/s",
        ),
        (
            "3d.prototype.delivered_impulse_Ns.1",
            "sim3d",
            "delivered_impulse",
            (("system", "prototype"), ("component", "y")),
            "N s",
        ),
        (
            "3d.similarity.points.P-2.max_abs_displacement_diff_rel_peak",
            "sim3d",
            "max_abs_displacement_diff_rel_peak",
            (("point", "P-2"),),
            "1",
        ),  # _rel_peak is part of the meaning, not a unit: kept
        ("3d.similarity.max_abs_top_displacement_diff_m", "sim3d", "max_abs_top_displacement_diff", (), "m"),
        ("3d.similarity.time_compared_s.1", "sim3d", "time_compared", (("bound", "end"),), "s"),
        ("experiment.model.drum_heights_m.3", "experiment", "drum_heights", (("system", "model"), ("drum", 3)), "m"),
        ("experiment.density_ratio", "experiment", "density_ratio", (), "1"),
        ("design.prototype.reflected_impulse_Pa_s", "design", "reflected_impulse", (("system", "prototype"),), "Pa s"),
        ("design.model.shock_front_velocity_m_s", "design", "shock_front_velocity", (("system", "model"),), "m/s"),
        ("design.model.scaled_distance_m_per_kg13", "design", "scaled_distance", (("system", "model"),), "m/kg^(1/3)"),
        ("design.model_charge_kg", "design", "model_charge", (), "kg"),
        ("design.factors.scaled_distance", "design/factors", "scaled_distance", (), "1"),
        ("design.impulsive.model_to_p", "design/impulsive", "model_to_p", (), "1"),
        ("critical.critical_charge_kg", "critical", "critical_charge", (), "kg"),
        ("ensemble.points.P-1.horizon_model_s", "ensemble", "horizon_model", (("point", "P-1"),), "s"),
    ],
)
def test_store_location_of_each_kind_of_key(key, group, name, labels, units):
    loc = store_location(key)
    assert (loc.group, loc.name, loc.labels, loc.units) == (group, name, labels, units)
    assert loc.long_name and loc.name.isidentifier()


def test_placeholders_have_no_place_and_unknown_sections_are_refused():
    for key in ("design", "3d", "ensemble", "planar.model", "planar.similarity", "experiment.model", "3d.similarity"):
        assert store_location(key) is None
    with pytest.raises(ValueError, match="section"):
        store_location("nonsense.max_rotation_rad")


def test_store_locations_are_one_to_one_over_every_study_key():
    """Every scalar key of real Studies (a column in 3D, a block with both engines and an ensemble,
    a prototype-only block, the outcome mode) has its own place: no two keys meet."""
    from blastscale.scenario import load_scenario
    from blastscale.sweeps import OUTCOME_KEYS

    keys = set(OUTCOME_KEYS)
    for sc in (
        load_scenario("paper_column_square_250kg").with_values({"duration_s": 0.2, "critical_charge": False}),
        Scenario.default().with_values({"engine": "both", "duration_s": 0.3, "samples": 101, "ensemble_members": 2}),
        prototype_only(BASE),
    ):
        keys |= set(study_scalars(sc))
    places = {}
    for k in keys:
        loc = store_location(k)
        if loc is not None:
            assert places.setdefault(loc[:3], k) == k, (k, places[loc[:3]])
    assert len(places) > 300


#: Units by key suffix, written out here as the oracle (independent of blastscale.units).
UNIT_ORACLE = (
    ("_rel_peak", "1"),
    ("_m_per_kg13", "m/kg^(1/3)"),
    ("_kg_m3", "kg/m^3"),
    ("_rad_s", "rad/s"),
    ("_m_s", "m/s"),
    ("_Pa_s", "Pa s"),
    ("_N_s", "N s"),
    ("_Ns", "N s"),
    ("_Pa", "Pa"),
    ("_rad", "rad"),
    ("_kg", "kg"),
    ("_m", "m"),
    ("_s", "s"),
)


def oracle_unit(key: str) -> str:
    leaf = [p for p in key.split(".") if not p.isdigit()][-1]
    return next((u for suffix, u in UNIT_ORACLE if leaf.endswith(suffix)), "1")


def prototype_only(scenario):
    data = scenario.to_dict()
    data.pop("scale")
    return Scenario.from_dict(data, source="test: no [scale]")


def assert_xarray_ready(path, keys) -> "xr.DataTree":
    """Opened with no warning (consolidated metadata); every variable and coordinate an identifier
    with a long name; every number (variables, numeric coordinates) with units, label coordinates
    (strings) without (CF conventions); no group attributes (constants are variables); each flat
    key's units those of its suffix."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tree = xr.open_datatree(path, engine="zarr")
        xr.open_zarr(path)  # the root alone, as a Dataset
    for node in tree.subtree:
        for name, v in node.to_dataset(inherit=False).variables.items():
            assert name.isidentifier() and v.attrs.get("long_name"), (node.path, name)
            if v.dtype.kind in "OUS":  # labels
                assert name in v.dims and "units" not in v.attrs, (node.path, name)
            else:
                assert v.attrs.get("units"), (node.path, name)
        if node.path != "/":
            assert not node.attrs, (node.path, dict(node.attrs))
    for key in keys:
        loc = store_location(key)
        if loc is None:
            continue
        node = tree[loc.group] if loc.group else tree
        got = node[loc.name].attrs["units"]
        assert got == oracle_unit(key), (key, got)
    return tree


def test_every_store_is_xarray_ready_with_the_right_units(tmp_path):
    """The Study path (a column in 3D: points, drums), a block with engine both and an ensemble,
    and the outcome mode: velocities m/s, specific impulse Pa s, momentum N s, lengths m, times s,
    angles rad, ratios 1, on every variable and constant."""
    from blastscale.scenario import load_scenario
    from blastscale.sweeps import OUTCOME_KEYS

    column = load_scenario("paper_column_square_250kg").with_values({"duration_s": 0.2, "critical_charge": False})
    both = Scenario.default().with_values(
        {"engine": "both", "duration_s": 0.3, "samples": 101, "ensemble_members": 2, "critical_charge": False}
    )
    for label, spec in (
        ("column", SweepSpec.build(column, {"charge_kg": [200.0, 250.0]})),
        ("both", SweepSpec.build(both, {"standoff_m": [2.0, 3.0]})),
        ("outcomes", SweepSpec.build(BASE, {"charge_kg": [40.0, 90.0]}, outcomes=True)),
    ):
        run_sweep(spec, tmp_path / f"{label}.zarr", workers=0)
        keys = OUTCOME_KEYS if spec.outcomes else study_scalars(spec.scenario(0))
        tree = assert_xarray_ready(tmp_path / f"{label}.zarr", keys)
        if label == "column":
            sim = tree["sim3d"]
            assert sim["max_velocity"].attrs["units"] == "m/s" and sim["max_velocity"].dims[-1] == "point"
            assert list(sim["point"].values) == [f"P-{i}" for i in range(1, 11)]  # natural order
            assert sim["delivered_impulse"].attrs["units"] == "N s" and list(sim["component"].values) == ["x", "y", "z"]
            drums = tree["experiment"]["drum_heights"]  # constant: stored once, on system and drum
            assert drums.dims == ("system", "drum") and drums.attrs["units"] == "m" and drums.sizes["drum"] == 10
            assert drums["drum"].attrs["units"] == "1" and list(drums["drum"].values) == list(range(10))
            np.testing.assert_allclose(
                drums.sel(system="model").sum().item(),
                tree["experiment"]["height"].sel(system="model").item(),
                rtol=1e-12,
            )
            assert tree["design"]["reflected_impulse"].attrs["units"] == "Pa s"
        if label == "both":
            assert tree["ensemble"]["first_peak_ratio"].dims == ("standoff_m", "point")
            assert tree["design"]["shock_front_velocity"].attrs["units"] == "m/s"
            assert set(tree.children) == {"experiment", "design", "planar", "sim3d", "ensemble", "verdict", "damage"}
            # issue #38: every case's damage state (0 intact .. 4 collapse), prototype and up-scaled model
            level = tree["damage"]["level"]
            assert level.dims == ("standoff_m", "system") and set(np.unique(level.values)) <= set(range(5))
            # issue #35: every case's verdict (the one criterion), the worst ratio a ratio ("1")
            assert tree["verdict"]["worst_ratio"].attrs["units"] == "1" and tree["verdict"]["similar"].size == 2


def test_prototype_only_sweep_through_the_cli_holds_the_prototype_alone(tmp_path, capsys):
    """A scenario without [scale]: the Study runs the prototype alone; the store has no design
    group and no model on `system`, and equals the plain loop of Studies."""
    toml = tmp_path / "prototype.toml"
    toml.write_text(prototype_only(BASE).to_toml())
    out = run_cli(
        capsys,
        "sweep",
        str(toml),
        "--vary",
        "charge_kg=40,120",
        "--out",
        str(tmp_path / "p.zarr"),
        "--workers",
        "0",
        "--json",
    )
    assert out["n_cases"] == 2 and out["chunks_run"] >= 1
    spec = SweepSpec.build(prototype_only(BASE), {"charge_kg": [40.0, 120.0]})
    tree = assert_store_equals_loop(tmp_path / "p.zarr", spec)
    assert set(tree.children) == {"experiment", "planar", "critical", "verdict", "damage"}
    # nothing compared: the verdict is NaN (null) in every case (issue #35: the scalars always carry it)
    assert np.isnan(tree["verdict"]["similar"].values).all() and np.isnan(tree["verdict"]["worst_ratio"].values).all()
    for group in ("experiment", "planar"):
        assert list(tree[group]["system"].values) == ["prototype"]
    assert list(tree["planar"]["collapsed"].sel(system="prototype").values) == [False, True]
    assert_xarray_ready(tmp_path / "p.zarr", study_scalars(spec.scenario(0)))
