"""See it move (issue 26): a result folder keeps the motion (poses and surfaces in histories.nc) and replays
it; ``blastscale show RESULT_DIR --animate`` draws it.

Short runs (0.2 s of prototype time) of a wall, an arch and a column, each written once by ``blastscale run``.
"""

import json
import re

import numpy as np
import pytest

from blastscale.cli import main

pytestmark = pytest.mark.system

SCENARIOS = {
    "wall": '[structure]\nkind = "wall"\ncourses = 3\nunits_per_course = 2\n'
    "[blast]\ncharge_kg = 20.0\nstandoff_m = 3.0\n",
    "arch": '[structure]\nkind = "arch"\nvoussoirs = 7\n[blast]\ncharge_kg = 20.0\nstandoff_m = 4.0\n',
    "column": '[structure]\nkind = "column"\ndrums = 4\nsection = "square"\n'
    "[blast]\ncharge_kg = 100.0\nstandoff_m = 5.0\n",
    "circular": '[structure]\nkind = "column"\ndrums = 3\nsection = "circular"\n'
    "[blast]\ncharge_kg = 100.0\nstandoff_m = 5.0\n",
}
DURATION_S = 0.2


def cli(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """name -> result folder of a short 3D run, prototype and 1/20 specimen."""
    base = tmp_path_factory.mktemp("motion")
    out = {}
    for name, text in SCENARIOS.items():
        sc = base / f"{name}.toml"
        sc.write_text(text + f'[scale]\nlength = "1/20"\n[simulation]\nengine = "3d"\nduration_s = {DURATION_S}\n')
        with pytest.raises(SystemExit) as e:
            main(["run", str(sc), "--out", str(base / name), "--json"])
        assert (e.value.code or 0) == 0
        out[name] = base / name
    return out


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_the_stored_poses_and_geometry_replay_the_monitoring_points(results, name):
    """Acceptance of issue 26: the monitoring points recomputed from the stored poses (positions,
    quaternions) and where each point sits on its body reproduce the simulated point histories within 1e-6 of
    the structure's height, for the prototype and the up-scaled specimen. The engine computed them in double
    precision from the same states, so only round-off separates them (measured: below 1e-15 m)."""
    import xarray as xr

    from blastscale.sim3d.replay import points_of, world_vertices

    tree = xr.open_datatree(results[name] / "histories.nc")
    ds = tree["sim3d"].ds
    height = json.loads((results[name] / "summary.json").read_text())["experiment"]["prototype"]["height_m"]
    assert ds["body_position"].attrs["units"] == "m" and ds["body_quaternion"].attrs["units"] == "1"
    assert ds["body_position"].dims == ("system", "time", "body", "component")
    assert ds["body_quaternion"].dims == ("system", "time", "body", "quaternion")
    for system in ("prototype", "model"):
        d = ds.sel(system=system)
        p = points_of(d)
        err = np.abs((p - p[0]) - d["point_displacement"].values).max()
        assert err < 1e-6 * height, (system, err)
        # the surfaces, placed by the poses at the first stored time, stand on the ground and reach the top
        # (independent of the engine: the structure's height from its description; 1e-3 H allows the contacts'
        # compliance at rest)
        v = world_vertices(d["body_position"].values[:1], d["body_quaternion"].values[:1], d["body_vertices"].values)
        assert np.nanmin(v[..., 2]) == pytest.approx(0.0, abs=1e-3 * height)
        assert np.nanmax(v[..., 2]) == pytest.approx(height, abs=1e-3 * height)
        faces = d["body_faces"].values
        assert faces.max() < d.sizes["vertex"] and (faces >= -1).all()


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_the_stored_surfaces_are_the_bodies_solids(results, name):
    """One geometry per structure (issues 26, 29): the stored vertices of every body are its solid's
    (``RigidBody.vertices`` of the structure the folder's scenario describes: a drum's frustum, not the prism
    the engine collides) in the body frame, and the stored triangles close that solid: their signed volumes
    (divergence theorem) add up to the body's ``volume``. The prototype's are the solids as built (1e-12 of the
    height: the same numbers written and read back); the model's are the specimen's solids up-scaled by
    1/lambda (round-off of two multiplications)."""
    import xarray as xr

    from blastscale.scenario.files import load_scenario
    from blastscale.structures.from_spec import from_spec

    structure = from_spec(load_scenario(results[name] / "scenario.toml").structure)
    height = json.loads((results[name] / "summary.json").read_text())["experiment"]["prototype"]["height_m"]
    ds = xr.open_datatree(results[name] / "histories.nc")["sim3d"].ds
    assert [str(b) for b in ds["body"].values] == [b.name for b in structure.bodies]
    for system in ("prototype", "model"):
        d = ds.sel(system=system)
        for k, body in enumerate(structure.bodies):
            solid = np.asarray(body.vertices, dtype=float)
            v = d["body_vertices"].values[k]
            assert np.isnan(v[len(solid) :]).all()
            np.testing.assert_allclose(v[: len(solid)], solid, rtol=0.0, atol=1e-12 * height)
            f = d["body_faces"].values[k]
            f = f[f[:, 0] >= 0]
            vol = np.einsum("ij,ij->i", v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]])).sum() / 6.0
            assert vol == pytest.approx(body.volume, rel=1e-12)


@pytest.mark.parametrize("name,fps,view", [("wall", 50, "iso"), ("arch", 25, "front"), ("column", 20, "side")])
def test_show_animate_writes_a_gif_of_fps_times_the_simulated_duration(results, capsys, tmp_path, name, fps, view):
    """Acceptance of issue 26: the GIF has --fps x the simulated duration (prototype time, 0.2 s here) frames,
    each shown 1/fps s (GIF keeps delays in hundredths of a second: these fps are exact); written through the one output mechanism (no partial file left beside it)."""
    from PIL import Image

    gif = tmp_path / f"{name}.gif"
    code, out, err = cli(capsys, "show", results[name], "--animate", gif, "--fps", fps, "--view", view)
    assert code == 0, err
    with Image.open(gif) as im:
        assert im.format == "GIF"
        assert im.n_frames == round(fps * DURATION_S)
        assert im.info["duration"] == round(1000 / fps)
        im.seek(0)
        first = np.asarray(im.convert("RGB"), dtype=int)
        im.seek(im.n_frames - 1)
        last = np.asarray(im.convert("RGB"), dtype=int)
    assert (np.abs(first - last).sum(axis=2) > 0).sum() > 50  # it moves (the time in the title at least)
    assert sorted(p.name for p in tmp_path.iterdir()) == [gif.name]
    assert "wrote" in err and "frames" in err


def test_show_animate_speed_divides_the_frames(results, capsys, tmp_path):
    """--speed 2 plays twice as fast: half the frames at the same fps."""
    from PIL import Image

    gif = tmp_path / "fast.gif"
    code, out, _ = cli(capsys, "show", results["wall"], "--animate", gif, "--fps", 40, "--speed", 2, "--json")
    assert code == 0 and json.loads(out)["frames"] == round(40 * DURATION_S / 2)
    with Image.open(gif) as im:
        assert im.n_frames == round(40 * DURATION_S / 2)


@pytest.mark.parametrize(
    "argv,word",
    [
        (["--animate", "{tmp}/a.avi"], "animate"),
        (["--animate", "{tmp}/missing/a.gif"], "animate"),
        (["--animate", "{tmp}"], "animate"),
        (["--animate", "{tmp}/a.gif", "--view", "back"], "view"),
        (["--animate", "{tmp}/a.gif", "--fps", "0"], "fps"),
        (["--animate", "{tmp}/a.gif", "--speed", "-1"], "speed"),
        (["--animate", "{tmp}/a.gif", "--fps", "120", "--speed", "0.01"], "at most 1000"),  # 2400 frames
        (["--animate", "{tmp}/a.gif", "--magnification", "0.5"], "magnification"),
        (["--animate", "{tmp}/a.gif", "--magnification", "nan"], "magnification"),
    ],
)
def test_show_animate_bad_path_or_option_is_one_line_exit_2(results, capsys, tmp_path, argv, word):
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    code, out, err = cli(capsys, "show", results["wall"], *argv)
    assert code == 2 and out == ""
    lines = [x for x in err.splitlines() if x.strip()]
    assert len(lines) == 1 and lines[0].startswith("error:") and word in lines[0], err
    assert list(tmp_path.iterdir()) == []


def test_gif_frames_are_magnified_coloured_at_their_time_and_not_dithered(results):
    """Issue 39 on the column (4 drums, 0.2 s): the animation's default magnification is the automatic one (> 1
    here, in each panel's title); at the first frame every block has not moved, so every face has the colour of
    a zero displacement (shaded: the same ratio in the three channels), and at the last frame they do not (the
    colour is the displacement at the frame shown, not the run's largest); the end-on axis of the side view has
    no ticks, the iso view's three axes have; the GIF maps each colour of a frame to one colour (no dithering:
    a dithered GIF gives one colour several), 99 % of the pixels within 12 levels of it, all within 64 (a
    256-colour palette for ~6000 colours: the rare ones, anti-aliased edges, land farther)."""
    import io

    import matplotlib.pyplot as plt
    from matplotlib import colormaps
    from PIL import Image

    from blastscale.cli.animate import _gif
    from blastscale.io.motion import read_motion
    from blastscale.plots.motion import COLORMAP, auto_magnification, motion_figure, render_frames

    motion, _ = read_motion(results["column"])
    idx, _ = motion.frame_indices(20.0)
    m = auto_magnification(motion)
    assert m > 1.0
    fig, update = motion_figure(motion, "side")
    try:
        assert all(f"motion drawn x {m:g}" in ax.get_title() for ax in fig.axes[: len(motion.labels)])
        assert len(fig.axes[0].get_yticks()) == 0 and len(fig.axes[0].get_zticks()) > 1
        coll = fig.axes[0].collections[1]
        update(int(idx[0]))
        fig.canvas.draw()  # the faces' colours as drawn (projected and sorted)
        ratio = coll.get_facecolor()[:, :3] / np.asarray(colormaps[COLORMAP](0.0)[:3])
        assert np.ptp(ratio, axis=1).max() < 1e-9
        update(int(idx[-1]))
        fig.canvas.draw()
        ratio = coll.get_facecolor()[:, :3] / np.asarray(colormaps[COLORMAP](0.0)[:3])
        assert np.ptp(ratio, axis=1).max() > 0.1
    finally:
        plt.close(fig)
    fig, _ = motion_figure(motion, "iso")
    assert all(len(t) > 1 for t in (fig.axes[0].get_xticks(), fig.axes[0].get_yticks(), fig.axes[0].get_zticks()))
    plt.close(fig)

    frames = list(render_frames(motion, idx, "iso"))
    with Image.open(io.BytesIO(_gif(iter(frames), 20.0))) as im:
        for k, src in enumerate(frames):
            im.seek(k)
            out = np.asarray(im.convert("RGB"))
            key = src.reshape(-1, 3).astype(np.int64) @ [65536, 256, 1]
            got = out.reshape(-1, 3).astype(np.int64) @ [65536, 256, 1]
            pairs = np.unique(np.stack([key, got]), axis=1)
            assert len(np.unique(pairs[0])) == pairs.shape[1]  # one colour out for each colour in
            err = np.abs(out.astype(int) - src).max(axis=2)
            assert np.percentile(err, 99) <= 12 and err.max() <= 64  # measured 8-10 and 39-56


def test_show_animate_of_a_folder_without_motion_is_one_line(capsys, tmp_path):
    code, out, err = cli(capsys, "show", tmp_path, "--animate", tmp_path / "a.gif")
    assert code == 2 and len(err.strip().splitlines()) == 1 and "histories.nc" in err


# -- the report's interactive view in headless Chromium -------------------------------------------------------
CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--enable-unsafe-swiftshader",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--hide-scrollbars",
    "--enable-logging=stderr",
    "--v=0",
    "--virtual-time-budget=8000",
]
#: Chromium's own diagnostics of software WebGL and canvas read-backs, printed as console lines: not the page's.
BROWSER_NOTES = ("[.WebGL-", "Canvas2D:", "[]Automatic fallback")
GROUND_RGB = (216, 210, 196)  # blastscale.report.motion.GROUND, unlit


def _chromium():
    import shutil

    return next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)), None)


def _open(page, tmp_path, tag, size=(1200, 700)):
    """Load ``page`` (a URL) in headless Chromium: (screenshot RGB array, page console lines, page requests).
    Page requests: the net log's URL requests whose initiator is the page (a file page's origin is "null";
    the browser's own have none)."""
    import os
    import subprocess

    from PIL import Image

    shot, net = tmp_path / f"{tag}.png", tmp_path / f"{tag}.json"
    cmd = [
        _chromium(),
        *CHROMIUM_FLAGS,
        f"--user-data-dir={tmp_path / 'profile'}",
        f"--screenshot={shot}",
        f"--window-size={size[0]},{size[1]}",
        f"--log-net-log={net}",
        page,
    ]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=180, env={**os.environ, "HOME": str(tmp_path)})
    assert proc.returncode == 0, proc.stderr[-2000:]
    console = [line.split("] ", 1)[1] for line in proc.stderr.splitlines() if ":CONSOLE" in line and "] " in line]
    console = [c for c in console if not c.strip('"').startswith(BROWSER_NOTES)]
    log = json.loads(net.read_text())
    start = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
    requests = [
        e["params"]["url"]
        for e in log["events"]
        if e["type"] == start
        and "url" in e.get("params", {})
        and e["params"].get("initiator") not in (None, "not an origin")
    ]
    with Image.open(shot) as im:
        return np.asarray(im.convert("RGB"), dtype=int), console, requests


@pytest.fixture(scope="module")
def column_shots(results, tmp_path_factory):
    """The column's report in headless Chromium, shared by the tests below (each opening costs ~1-2 CPU s):
    a page that requests a file and prints an error (the detector's check), then the report's 3D view at the
    first and the last slider time at the default magnification and at magnification 1. Each
    opening: (screenshot, the page's console lines, the page's requests)."""
    if _chromium() is None:
        pytest.skip("Chromium not found (Debian: apt-get install -y chromium)")
    tmp = tmp_path_factory.mktemp("shots")
    bad = tmp / "bad.html"
    bad.write_text('<script>console.error("boom")</script><img src="http://example.invalid/a.png">')
    report = results["column"] / "report.html"
    last = int(re.search(r"(\d+) frames of the \d+ recorded states", report.read_text()).group(1)) - 1
    pages = {
        "bad": (bad.as_uri(), (200, 100)),
        "first": (report.as_uri() + "#frame=0", (1200, 700)),
        "last": (report.as_uri() + f"#frame={last}", (1200, 700)),
        "first_m1": (report.as_uri() + "#frame=0&mag=1", (1200, 700)),
        "last_m1": (report.as_uri() + f"#frame={last}&mag=1", (1200, 700)),
    }
    return {k: _open(url, tmp, k, size) for k, (url, size) in pages.items()}


def _blocks(shot):
    """Where the blocks are: neither grey (white, text, axes) nor the ground."""
    grey = shot.max(axis=2) - shot.min(axis=2) < 40
    return ~grey & ~(np.abs(shot - GROUND_RGB).max(axis=2) <= 3)


@pytest.mark.slow
def test_report_view_loads_offline_without_errors_and_moves_the_blocks_not_the_ground(column_shots):
    """Acceptance of issue 26, in headless Chromium: the report (with its 3D view, its script inline) loads with
    no console message of the page and no network request; the screenshots at the first and the last slider
    time differ where blocks are (in either shot), not in the ground. The detector is checked on a page that
    requests a file and prints an error."""
    _, console, requests = column_shots["bad"]
    assert any("boom" in c for c in console) and requests == ["http://example.invalid/a.png"]
    for key in ("first", "last", "first_m1", "last_m1"):
        assert column_shots[key][1:] == ([], []), key
    a, b = column_shots["first"][0][SCENE], column_shots["last"][0][SCENE]
    ground_a = np.abs(a - GROUND_RGB).max(axis=2) <= 3
    ground_b = np.abs(b - GROUND_RGB).max(axis=2) <= 3
    block_a, block_b = _blocks(a), _blocks(b)
    diff = np.abs(a - b).max(axis=2) > 8
    assert ground_a.sum() > 10_000  # the ground is drawn (two scenes of ~10 000 pixels each, measured)
    # every difference lies where a block is in one of the shots, but for anti-aliased edges
    assert (diff & ~(block_a | block_b)).sum() < 0.1 * diff.sum()
    # the ground is the same ground: where it shows in one shot it shows in the other unless a block covers it
    assert ((ground_a & ~ground_b & ~block_b).sum() + (ground_b & ~ground_a & ~block_a).sum()) < 0.02 * ground_a.sum()


#: The two 3D scenes of a 1200 x 700 screenshot of the view put at the top of the page (below the stated
#: magnification, above the slider; the colour bar at the right left out).
SCENE = (slice(60, 560), slice(0, 1110))


@pytest.mark.slow
def test_column_view_at_two_times_differs_in_the_structure_at_the_default_magnification(results, column_shots):
    """Acceptance of issue 39, in headless Chromium: the column's 3D view at two slider times differs by at
    least 1 % of the pixels of the structure's region (the bounding box of the blocks in either shot) at the
    default magnification, stated on the page; drawn as it is (x 1, ``#frame=N&mag=1``) the same two times move
    the blocks' outline over fewer pixels (the colours, the displacement at each time, change in both)."""
    page = (results["column"] / "report.html").read_text()
    m = re.search(r"Displacements drawn x (\d+(?:\.\d+)?)", page)
    assert m and float(m.group(1)) > 1.0, "the default magnification is stated on the page"
    a, b, a1, b1 = (column_shots[k][0][SCENE] for k in ("first", "last", "first_m1", "last_m1"))
    region = _blocks(a) | _blocks(b)
    rows, cols = np.nonzero(region)
    box = (slice(rows.min(), rows.max() + 1), slice(cols.min(), cols.max() + 1))
    area = (rows.max() - rows.min() + 1) * (cols.max() - cols.min() + 1)
    moved = (np.abs(a - b).max(axis=2) > 8)[box].sum() / area
    outline = (_blocks(a) ^ _blocks(b)).sum()  # pixels the blocks entered or left
    outline_m1 = (_blocks(a1) ^ _blocks(b1)).sum()
    assert moved >= 0.01, moved
    assert outline > outline_m1, (outline, outline_m1)


def test_an_ensemble_keeps_and_replays_its_median_and_worst_members(capsys, tmp_path):
    """Issue 26 for ensembles: histories.nc keeps the motion of the member closest to the median and of the
    worst (largest |x| displacement of any point, prototype); replaying each member's stored poses gives its
    stored x displacements within 1e-6 of the height, prototype and up-scaled model; the report shows both."""

    import xarray as xr

    from blastscale.analysis.ensemble import motion_cases
    from blastscale.sim3d.replay import points_of

    sc = tmp_path / "ens.toml"
    sc.write_text(
        SCENARIOS["column"] + '[scale]\nlength = "1/20"\n[simulation]\nengine = "3d"\nduration_s = 0.2\n'
        "ensemble_members = 3\nensemble_perturbation = 0.1\n"
    )
    code, _, err = cli(capsys, "run", sc, "--out", tmp_path / "res", "--json")
    assert code == 0, err
    ens = xr.open_datatree(tmp_path / "res" / "histories.nc")["ensemble"].ds
    assert list(ens["case"].values) == ["median", "worst"]
    cases = motion_cases(ens["point_displacement_x"].sel(system="prototype").values)
    assert [int(m) for m in ens["case_member"].values] == [cases["median"], cases["worst"]]
    height = json.loads((tmp_path / "res" / "summary.json").read_text())["experiment"]["prototype"]["height_m"]
    for case, member in cases.items():
        for system in ("prototype", "model"):
            d = ens.sel(case=case, system=system)
            x = points_of(d)[..., 0]
            want = ens["point_displacement_x"].sel(system=system, member=member).values
            assert np.abs((x - x[0]) - want).max() < 1e-6 * height
    page = (tmp_path / "res" / "report.html").read_text()
    assert 'id="fig-motion3d-median"' in page and 'id="fig-motion3d-worst"' in page
    assert page.count("window.blastscaleView=") == 1  # the view's script embedded once for the three views


def test_motion_cases_are_the_median_and_the_largest_peak():
    from blastscale.analysis.ensemble import motion_cases

    members = np.zeros((5, 3, 2))
    for k, peak in enumerate([0.3, -0.9, 0.1, 0.5, 0.2]):  # |peak|: 0.3 0.9 0.1 0.5 0.2 -> median 0.3
        members[k, 1, 1] = peak
    assert motion_cases(members) == {"median": 0, "worst": 1}


def test_show_animate_html_is_the_report_view_alone_and_self_contained(results, capsys, tmp_path):
    page = tmp_path / "arch.html"
    code, out, err = cli(capsys, "show", results["arch"], "--animate", page, "--fps", 20, "--json")
    assert code == 0, err
    info = json.loads(out)
    text = page.read_text()
    assert info["frames"] == round(20 * DURATION_S) and text.count("window.blastscaleView=") == 1
    assert not re.search(r"""<(script|link|img)[^>]+(src|href)=["']?(https?:)?//""", text)  # nothing fetched
    data = json.loads(re.search(r'<script type="application/json" id="motion3d-data">(.*?)</script>', text).group(1))
    assert len(data["times"]) == info["frames"]  # one pose per body, system and state shown
    assert f"Displacements drawn x {info['magnification']:g}" in text


def test_show_animate_mp4_without_an_encoder_is_one_line(results, capsys, tmp_path, monkeypatch):
    import blastscale.cli.animate as animate

    monkeypatch.setattr(animate.shutil, "which", lambda name: None)  # as on a machine without ffmpeg
    code, out, err = cli(capsys, "show", results["wall"], "--animate", tmp_path / "a.mp4")
    assert code == 2 and "ffmpeg" in err and len(err.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(
    __import__("shutil").which("ffmpeg") is None, reason="no ffmpeg here (Debian: apt-get install ffmpeg)"
)
def test_show_animate_mp4_has_fps_times_duration_frames(results, capsys, tmp_path):
    """With ffmpeg: an H.264 MP4 of round(fps x duration) frames at fps (ffprobe counts them)."""
    import subprocess

    mp4 = tmp_path / "wall.mp4"
    code, out, err = cli(capsys, "show", results["wall"], "--animate", mp4, "--fps", 30)
    assert code == 0, err
    probe = subprocess.run(
        [
            "ffprobe",
            "-v",
            "error",
            "-count_frames",
            "-select_streams",
            "v:0",
            "-show_entries",
            "stream=nb_read_frames,r_frame_rate,codec_name",
            "-of",
            "json",
            str(mp4),
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    stream = json.loads(probe.stdout)["streams"][0]
    assert stream["codec_name"] == "h264" and stream["r_frame_rate"] == "30/1"
    assert int(stream["nb_read_frames"]) == round(30 * DURATION_S)


def test_the_views_data_is_the_surfaces_once_and_the_poses_per_frame(results):
    """Issue 41: the report's view carries each body's surface once and, per frame, 7 float32 per body and
    system (position, quaternion): the page's data of the column is its surfaces plus nframes x 2 x 4 x 28 bytes
    in base64 (x 4/3) and nothing else of size. Replaying the page's poses gives the stored vertices (float32:
    1e-6 of the height). (The default report's size: tests/system/test_report.py.)"""
    import base64

    import xarray as xr

    from blastscale.report.motion import REPORT_FPS, view_data, view_frames
    from blastscale.sim3d.replay import motion_of, world_vertices

    page = (results["column"] / "report.html").read_text()
    text = re.search(r'<script type="application/json" id="motion3d-data">(.*?)</script>', page).group(1)
    data = json.loads(text)
    with xr.open_datatree(results["column"] / "histories.nc") as tree:
        motion = motion_of(tree["sim3d"].to_dataset().load())
    idx, _ = view_frames(motion, REPORT_FPS)
    nf, nb = len(data["times"]), len(motion.bodies)
    assert nf == len(idx) and data == view_data(motion, idx, data["charge"])
    pos = np.frombuffer(base64.b64decode(data["position"]), np.float32).reshape(2, nf, nb, 3)
    quat = np.frombuffer(base64.b64decode(data["quaternion"]), np.float32).reshape(2, nf, nb, 4)
    poses = len(data["position"]) + len(data["quaternion"])
    assert poses == pytest.approx(2 * nf * nb * 28 * 4 / 3, abs=8)
    surfaces = len(data["vertices"]) + len(data["triangles"])
    assert len(text) < surfaces + poses + 2_000  # nothing else of size
    height = data["height_m"]
    for s in range(2):
        want = motion.world(s, idx)
        got = world_vertices(pos[s].astype(float), quat[s].astype(float), motion.vertices)
        assert np.nanmax(np.abs(got - want)) < 1e-6 * height
