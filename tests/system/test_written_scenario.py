"""Issue #23: the scenario a run writes (the result folder's scenario.toml and histories.nc's
``scenario_toml``) is valid TOML whatever the title holds, and reads back to the same scenario.

The hand-written writer it replaced escaped only backslash and quote: a title over two lines ran,
then neither copy could be read back (``Illegal character '\\n'``). The title below holds every
character that needs escaping in a TOML basic string (newline, tab, quote, backslash), a ``[`` that
would open a table if it started a line, ``#`` that would start a comment, and non-ASCII text.
"""

from __future__ import annotations

import tomllib

import pytest
import xarray as xr

from blastscale.cli import main
from blastscale.scenario import Scenario, load_scenario

HOSTILE = 'Two lines: "quoted" \\ back\\slash\n[blast] # not a table\tnor a comment, 50 kg à 2 m'


def test_a_hostile_title_round_trips_through_the_result_folder(capsys, tmp_path):
    given = Scenario.default().model_copy(update={"title": HOSTILE})
    src = tmp_path / "hostile.toml"
    src.write_text(given.to_toml(), encoding="utf-8")
    assert load_scenario(src).title == HOSTILE  # the file the user gives
    out = tmp_path / "r"
    with pytest.raises(SystemExit) as e:
        main(
            [
                "run",
                str(src),
                "--out",
                str(out),
                "--duration",
                "0.1",
                "--set",
                "engine=planar",
                "--set",
                "critical_charge=false",
            ]
        )
    assert (e.value.code or 0) == 0, capsys.readouterr().err
    written = (out / "scenario.toml").read_text(encoding="utf-8")
    assert tomllib.loads(written)["title"] == HOSTILE
    back = load_scenario(out / "scenario.toml")
    ran = given.model_copy(
        update={
            "simulation": given.simulation.model_copy(
                update={"engine": "planar", "duration_s": 0.1, "critical_charge": False}
            )
        }
    )
    assert back == ran  # every field, not only the title
    tree = xr.open_datatree(out / "histories.nc", engine="h5netcdf")
    try:
        stored = tree.attrs["scenario_toml"]
        assert tree.attrs["title"] == HOSTILE
    finally:
        tree.close()
    assert stored == written
    assert tomllib.loads(stored)["title"] == HOSTILE
