"""The one rule by which a written scenario names its files (blastscale.scenario.paths): the block model, the
calibrated source and the lab's records alike; a folder moved with its neighbours reads the same files."""

import tomllib
from pathlib import Path

from blastscale.scenario import Scenario, load_scenario
from blastscale.scenario.paths import path_in

KEYS = (("structure", "file"), ("lab", "source"), ("fired", "gauges"), ("fired", "tracks"))


def _project(root: Path, paths: dict) -> Path:
    """A scenario file ``root/scenario.toml`` naming ``paths`` ("table.key" -> text as written), each file made."""
    data = Scenario.default().model_dump(mode="json", exclude_none=True)
    data["structure"] = {"kind": "assembly", "file": paths["structure.file"]}
    data["lab"] = {"source": paths["lab.source"]}
    data["fired"] = {"gauges": paths["fired.gauges"], "tracks": paths["fired.tracks"]}
    for text in paths.values():
        f = Path(text) if Path(text).is_absolute() else root / text
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_text("# a file\n", encoding="utf-8")
    from blastscale.scenario.text import to_toml

    (root / "scenario.toml").write_text(to_toml(data), encoding="utf-8")
    return root / "scenario.toml"


def _written(sc: Scenario, folder: Path) -> dict:
    d = tomllib.loads(sc.to_toml(folder))
    return {f"{t}.{k}": d[t][k] for t, k in KEYS}


def test_every_file_written_relative_stays_relative_and_the_moved_folder_reads_it(tmp_path):
    """Each of the four keys, written relative in the scenario file, is written relative to the result folder
    (``../data/...`` from ``project/out``); the project moved elsewhere, the written scenario reads the same
    files. Before the one rule, the block model was written absolute (the moved folder lost it)."""
    project = tmp_path / "project"
    given = {
        "structure.file": "data/blocks.json",
        "lab.source": "data/bank.toml",
        "fired.gauges": "../shared/gauges.csv",  # outside the folder's parent: written relative, so kept relative
        "fired.tracks": "tracks.csv",
    }
    sc = load_scenario(_project(project, given))
    out = project / "out"
    out.mkdir()
    written = _written(sc, out)
    assert written == {
        "structure.file": "../data/blocks.json",
        "lab.source": "../data/bank.toml",
        "fired.gauges": "../../shared/gauges.csv",
        "fired.tracks": "../tracks.csv",
    }
    (out / "scenario.toml").write_text(sc.to_toml(out), encoding="utf-8")
    moved = tmp_path / "moved"
    moved.mkdir()
    project.rename(moved / "project")
    (tmp_path / "shared").rename(moved / "shared")
    back = load_scenario(moved / "project" / "out" / "scenario.toml")
    for key, text in given.items():
        assert Path(back.file_path(key)).resolve() == (moved / "project" / text).resolve(), key
        assert Path(back.file_path(key)).is_file(), key


def test_a_file_written_absolute_stays_absolute_though_it_lies_beside(tmp_path):
    """The answer "no" to proximity: an absolute path as the user wrote it stays absolute, even for a file under
    the written folder's parent (where a path made in Python is made relative)."""
    project = tmp_path / "project"
    absolute = {k: str(project / "data" / f"{k.replace('.', '_')}.x") for k in ("structure.file", "lab.source")}
    given = {**absolute, "fired.gauges": "g.csv", "fired.tracks": str(project / "t.csv")}
    sc = load_scenario(_project(project, given))
    written = _written(sc, project / "out")
    assert written["structure.file"] == absolute["structure.file"]
    assert written["lab.source"] == absolute["lab.source"]
    assert written["fired.tracks"] == str(project / "t.csv")
    assert written["fired.gauges"] == "../g.csv"


def test_a_path_no_file_wrote_is_relative_beside_the_folder_and_absolute_elsewhere(tmp_path, monkeypatch):
    """Made in Python (or changed since the file): relative where the file lies under the written folder's
    parent; elsewhere absolute, also for a path given relative to the working directory (which the written file,
    read from its own folder, would otherwise misread)."""
    out = tmp_path / "project" / "out"
    assert path_in(out, str(tmp_path / "project" / "bank.toml")) == "../bank.toml"
    assert path_in(out, str(out / "d" / "bank.toml")) == "d/bank.toml"
    far = tmp_path / "elsewhere" / "bank.toml"
    assert path_in(out, str(far)) == str(far)
    monkeypatch.chdir(tmp_path / "..")
    relative_to_cwd = str(Path(tmp_path.name) / "elsewhere" / "bank.toml")
    assert path_in(out, relative_to_cwd) == str(far.resolve())


def test_a_changed_value_forgets_how_the_file_wrote_it_and_others_remember(tmp_path):
    """``with_values`` keeps the written form of the paths it does not change (the run's ``--set`` overrides);
    a path it changes is named by the rule for paths no file wrote."""
    project = tmp_path / "project"
    given = {
        "structure.file": str(project / "blocks.json"),
        "lab.source": "bank.toml",
        "fired.gauges": "g.csv",
        "fired.tracks": "t.csv",
    }
    sc = load_scenario(_project(project, given)).with_values({"blast.charge_kg": 2.0})
    assert _written(sc, project / "out")["structure.file"] == str(project / "blocks.json")  # still as written
    moved = sc.with_values({"fired.gauges": str(project / "g2.csv")})
    w = _written(moved, project / "out")
    assert w["fired.gauges"] == "../g2.csv" and w["fired.tracks"] == "../t.csv"
    assert w["structure.file"] == str(project / "blocks.json")
