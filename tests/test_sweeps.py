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

from blastscale.sweeps.grids import parse_distribution  # noqa: E402
from blastscale.io.sweep_store import run_sweep  # noqa: E402
from blastscale.sweeps import SweepSpec, study_scalars  # noqa: E402
from blastscale.cli import main  # noqa: E402
from blastscale.scenario import Scenario  # noqa: E402

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


def sweep_store_values(path) -> dict:
    ds = xr.open_zarr(path, consolidated=False)
    return {k: ds[k].values for k in ds.data_vars}, ds


def assert_store_equals_loop(path, spec):
    vals, ds = sweep_store_values(path)
    assert tuple(ds.sizes[d] for d in spec.dims) == spec.shape
    for k in range(spec.n_cases):
        want = study_scalars(spec.scenario(k))  # the plain serial loop: one Study per case
        idx = np.unravel_index(k, spec.shape)
        for key, v in want.items():
            assert same(vals[key][idx].item(), v), (k, key)


def test_sweep_equals_the_serial_loop_with_monte_carlo(tmp_path):
    spec = SweepSpec.build(BASE, {"charge_kg": [40.0, 90.0]}, {"restitution": parse_distribution("uniform:0.3,0.9")},
                           samples=3, seed=7)
    run = run_sweep(spec, tmp_path / "s.zarr", workers=0, chunk=4)
    assert run.chunks_run == 2 and spec.dims == ("charge_kg", "sample")
    assert_store_equals_loop(tmp_path / "s.zarr", spec)
    _, ds = sweep_store_values(tmp_path / "s.zarr")
    r = ds["restitution"].values  # the draws: coordinate on `sample`, the same at every charge
    assert r.shape == (3,) and np.all((r >= 0.3) & (r <= 0.9))
    assert ds["charge_kg"].attrs["units"] == "kg"
    # a second run finds the finished store and does nothing
    assert run_sweep(spec, tmp_path / "s.zarr", workers=0).chunks_run == 0


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
    procs = [subprocess.Popen([str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)]
    try:
        procs.append(subprocess.Popen([str(BIN / "dask"), "worker", addr, "--nthreads", "1", "--nworkers", "1",
                                       "--no-dashboard", "--host", "127.0.0.1"],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env))
        deadline = time.time() + 60
        while True:
            try:
                with Client(addr, timeout="2s") as c:
                    if c.scheduler_info()["workers"]:
                        break
            except OSError:
                pass
            assert time.time() < deadline, "dask cluster did not start"
            time.sleep(0.3)
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
    va, _ = sweep_store_values(a)
    vb, _ = sweep_store_values(b)
    assert va.keys() == vb.keys()
    for k in va:
        np.testing.assert_array_equal(va[k], vb[k])  # bit for bit (NaN where both NaN)


def test_sweep_on_a_separate_dask_cluster_equals_the_local_result(tmp_path, capsys, cluster):
    toml = tmp_path / "planar.toml"
    toml.write_text(BASE.to_toml())
    remote = run_cli(capsys, "sweep", str(toml), "--vary", "charge_kg=40:120:3", "--vary", "standoff_m=2,3",
                     "--sample", "restitution=triangular:0.3,0.8,0.9", "--samples", "2", "--seed", "3", "--chunk", "2",
                     "--out", str(tmp_path / "remote.zarr"), "--scheduler", cluster, "--json")
    assert remote["n_cases"] == 12 and remote["workers"] == 1 and remote["chunks_run"] == 6
    spec = SweepSpec.build(BASE, {"charge_kg": [40.0, 80.0, 120.0], "standoff_m": [2.0, 3.0]},
                           {"restitution": parse_distribution("triangular:0.3,0.8,0.9")}, samples=2, seed=3)
    run_sweep(spec, tmp_path / "local.zarr", workers=0, chunk=5)  # another chunking, in this process
    assert_same_stores(tmp_path / "remote.zarr", tmp_path / "local.zarr")


def test_kill_9_midway_then_rerun_gives_the_uninterrupted_result(tmp_path, cluster):
    toml = tmp_path / "planar.toml"
    toml.write_text(BASE.to_toml())
    # 24 cases, one per task; each searches its own critical charge (distinct stand-offs): slow enough to stop
    store, parts = tmp_path / "k.zarr", tmp_path / "k.zarr.parts"
    p = subprocess.Popen([str(BIN / "blastscale"), "sweep", str(toml), "--vary", "standoff_m=1.5:4:12", "--vary",
                          "charge_kg=60,120", "--chunk", "1", "--out", str(store), "--scheduler", cluster],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    while time.time() < deadline and len(list(parts.glob("chunk-*.npz"))) < 2 and p.poll() is None:
        time.sleep(0.005)
    os.kill(p.pid, signal.SIGKILL)
    p.wait()
    done = len(list(parts.glob("chunk-*.npz")))
    assert 2 <= done < 24 and not store.exists()  # killed midway: some chunks written, no store yet
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
    ],
)
def test_bad_grids_and_distributions_one_line_exit_2(tmp_path, capsys, argv, word):
    with pytest.raises(SystemExit) as e:
        main(["sweep", *argv, "--out", str(tmp_path / "x.zarr"), "--workers", "0"])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert word in err and "Traceback" not in err and len(err.strip().splitlines()) <= 2
    assert not (tmp_path / "x.zarr").exists() and not (tmp_path / "x.zarr.parts").exists()


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
    for text, mean, sd in (("normal:2,0.5", 2.0, 0.5), ("uniform:1,3", 2.0, 2 / math.sqrt(12)),
                           ("triangular:0,1,4", 5 / 3, math.sqrt((0 + 1 + 16 - 0 - 0 - 4) / 18)),
                           ("lognormal:2,0.3", 2 * math.exp(0.045), 2 * math.exp(0.045) * math.sqrt(math.expm1(0.09)))):
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
    k = np.concatenate([rng.uniform(1e-6, 0.999999 * MAX_IMPULSE_RATIO, 400), 10 ** rng.uniform(-12, -0.3, 200),
                        0.5 + rng.normal(0.0, 1e-4, 200), 0.5 - 10 ** rng.uniform(-16, -1, 200), [0.5],
                        MAX_IMPULSE_RATIO - 10 ** rng.uniform(-14, -2, 100)])
    P, t = rng.uniform(1e3, 1e7, k.size), rng.uniform(1e-5, 1e-1, k.size)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        whole = friedlander_decay(P, t, k * P * t)
        one = np.array([friedlander_decay(P[j], t[j], k[j] * P[j] * t[j]) for j in range(k.size)])
    assert np.array_equal(one, whole)
