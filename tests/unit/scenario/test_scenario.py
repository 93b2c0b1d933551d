"""Scenario files: validation with one-line errors, with_values, field_paths, the material library.

The CLI checks (exit status 2, one line, nothing written) run ``blastscale run`` in-process on
malformed files; each must name the offending field path.
"""

import math
import tomllib

import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.cli import main
from blastscale.scenario import Scenario, library_names, load_scenario, parse_ratio, to_toml as _to_toml
from blastscale.structures.materials import MATERIALS, material_density

EXAMPLES = library_names()  # the scenarios shipped with blastscale (package data)

GOOD = """
[structure]
kind = "block"
height_m = 10.0
alpha_deg = 15.0

[blast]
charge_kg = 50.0
standoff_m = 2.0

[scale]
length = 0.005
"""

# (name, TOML text, the field path the one-line error must name)
MALFORMED = [
    ("unknown key", GOOD.replace("height_m = 10.0", "heigth_m = 10.0"), "valid keys of [structure] are kind"),
    ("unknown table", GOOD + "\n[blasts]\ncharge_kg = 1.0\n", "blasts"),
    ("missing charge", GOOD.replace("charge_kg = 50.0", ""), "blast.charge_kg"),
    ("missing kind", GOOD.replace('kind = "block"', ""), "structure.kind"),
    ("missing scale length", GOOD.replace("[scale]\nlength = 0.005", "[scale]\ngravity_ratio = 1.0"), "scale.length"),
    ("wrong type string", GOOD.replace("charge_kg = 50.0", 'charge_kg = "50"'), "blast.charge_kg"),
    ("wrong type bool", GOOD.replace("standoff_m = 2.0", "standoff_m = true"), "blast.standoff_m"),
    ("wrong type table", GOOD.replace("[scale]\nlength = 0.005", "scale = 5"), "scale"),
    ("negative", GOOD.replace("height_m = 10.0", "height_m = -10.0"), "structure.height_m"),
    ("zero", GOOD.replace("standoff_m = 2.0", "standoff_m = 0.0"), "blast.standoff_m"),
    ("nan", GOOD.replace("charge_kg = 50.0", "charge_kg = nan"), "blast.charge_kg"),
    ("inf", GOOD.replace("length = 0.005", "length = inf"), "scale.length"),
    ("angle out of range", GOOD.replace("alpha_deg = 15.0", "alpha_deg = 95.0"), "structure.alpha_deg"),
    (
        "friction out of range",
        GOOD.replace("alpha_deg = 15.0", "alpha_deg = 15.0\nfriction = -0.1"),
        "structure.friction",
    ),
    ("bad enum pulse", GOOD.replace("standoff_m = 2.0", 'standoff_m = 2.0\npulse = "square"'), "blast.pulse"),
    ("bad enum kind", GOOD.replace('kind = "block"', 'kind = "tower"'), "structure.kind"),
    (
        "bad pulse shape",
        GOOD.replace("standoff_m = 2.0", 'standoff_m = 2.0\npulse_shape = "square"'),
        "blast.pulse_shape",
    ),
    ("bad blast_model", GOOD.replace("standoff_m = 2.0", 'standoff_m = 2.0\nblast_model = "kb"'), "blast.blast_model"),
    ("bad blast model", GOOD.replace("standoff_m = 2.0", 'standoff_m = 2.0\nmodel = "kb"'), "blast.model"),
    (
        "bad material",
        GOOD.replace("length = 0.005", 'length = 0.005\nmodel_material = "cheese"'),
        "scale.model_material",
    ),
    ("bad fraction", GOOD.replace("length = 0.005", 'length = "1/0"'), "scale.length"),
    ("both width and angle", GOOD.replace("alpha_deg = 15.0", "alpha_deg = 15.0\nwidth_m = 2.0"), "width_m"),
    ("integer wanted", GOOD + "\n[simulation]\nrecord_every = 2.5\n", "simulation.record_every"),
    ("bad engine", GOOD + '\n[simulation]\nengine = "fem"\n', "simulation.engine"),
    ("bad contact key", GOOD + "\n[simulation.contact]\nstiffness = 1e9\n", "simulation.contact.stiffness"),
    ("column key on a block", GOOD.replace("alpha_deg = 15.0", "alpha_deg = 15.0\ndrums = 10"), "structure.drums"),
    ("TOML syntax error", GOOD.replace("charge_kg = 50.0", "charge_kg = = 50.0"), "line 8"),
    ("TOML duplicate key", GOOD.replace("charge_kg = 50.0", "charge_kg = 50.0\ncharge_kg = 60.0"), "line"),
]


@pytest.mark.parametrize("name,text,field", MALFORMED, ids=[m[0] for m in MALFORMED])
def test_malformed_scenario_one_line_exit_2_nothing_written(tmp_path, capsys, name, text, field):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    out = tmp_path / "out"
    with pytest.raises(SystemExit) as e:
        main(["run", str(path), "--out", str(out)])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("error: bad.toml"), err
    assert field in err, err
    assert "Traceback" not in err
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_range_errors_give_the_valid_range():
    with pytest.raises(
        BlastscaleInputError,
        match=r"structure\.alpha_deg = 95 is out of range: valid range is "
        r"\(0, 90\) deg",
    ):
        Scenario.default().with_values({"alpha_deg": 95.0})
    with pytest.raises(
        BlastscaleInputError,
        match=r"blast\.charge_kg = nan is not a finite number: valid range is "
        r">= 0 kg",
    ):  # 0: gravity alone (issue 16)
        Scenario.default().with_values({"charge_kg": math.nan})


def test_missing_file_and_folder_are_one_line_errors(tmp_path):
    with pytest.raises(BlastscaleInputError, match="cannot be read"):
        load_scenario(tmp_path / "nope.toml")
    with pytest.raises(BlastscaleInputError, match="cannot be read"):
        load_scenario(tmp_path)


def test_default_is_the_paper_case_and_round_trips_through_toml(tmp_path):
    sc = Scenario.default()
    assert (sc.structure.height_m, sc.structure.alpha_deg, sc.structure.density_kg_m3) == (10.0, 15.0, 2000.0)
    assert (sc.blast.charge_kg, sc.blast.standoff_m, sc.blast.blast_model) == (50.0, 2.0, "masi2021")
    assert sc.scale.length == 1 / 200 and sc.structure.friction == 0.7 and sc.density_ratio == 1.0
    path = tmp_path / "s.toml"
    path.write_text(sc.to_toml())
    assert load_scenario(path) == sc


def test_minimal_file_takes_the_paper_defaults(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(GOOD)
    sc = load_scenario(path)
    assert sc.blast.pulse_shape == "friedlander" and sc.blast.load == "A" and sc.scale.gravity_ratio == 1.0
    assert sc.simulation.engine == "both" and sc.simulation.duration_s == 5.0
    assert sc.simulation.contact.time_constant_s is None  # left to the engine's structure-derived default


def test_with_values_dotted_and_bare_keys_validate_and_do_not_mutate():
    sc = Scenario.default()
    v = sc.with_values({"blast.charge_kg": 60.0, "friction": 0.5, "simulation.contact.cone": "pyramidal"})
    assert (v.blast.charge_kg, v.structure.friction, v.simulation.contact.cone) == (60.0, 0.5, "pyramidal")
    assert sc.blast.charge_kg == 50.0  # the original is untouched (frozen)
    import numpy as np

    assert sc.with_values({"charge_kg": np.float64(70.0)}).blast.charge_kg == 70.0  # sweeps pass numpy scalars
    with pytest.raises(BlastscaleInputError, match=r"key = 'frictoin' is not a scenario field"):
        sc.with_values({"frictoin": 0.5})
    with pytest.raises(BlastscaleInputError, match=r"^structure\.friction = -1 is out of range"):
        sc.with_values({"friction": -1.0})


def test_with_values_exclusive_keys_and_kind_change():
    sc = Scenario.default()
    w = sc.with_values({"width_m": 3.5})  # clears alpha_deg instead of refusing both
    assert w.structure.width_m == 3.5 and w.structure.alpha_deg is None
    b = sc.with_values({"model_material": "balsa"})
    assert b.scale.density_ratio is None and b.density_ratio == pytest.approx(0.07, rel=1e-12)  # paper: 140/2000
    c = sc.with_values({"structure.kind": "column", "drums": 5})
    assert c.structure.kind == "column" and c.structure.drums == 5 and c.structure.base_width_m == 1.65


def test_ambiguous_bare_key_is_refused(monkeypatch):
    sc = Scenario.default()
    monkeypatch.setattr(Scenario, "_paths", lambda self: ["a.x_m", "b.x_m"])
    with pytest.raises(BlastscaleInputError, match=r"key = 'x_m' is ambiguous: it may be a\.x_m, b\.x_m"):
        sc.resolve_key("x_m")


def test_field_paths_cover_every_table_and_resolve():
    paths = Scenario.field_paths()
    for p in (
        "structure.kind",
        "structure.drums",
        "blast.charge_kg",
        "scale.length",
        "simulation.duration_s",
        "simulation.contact.time_constant_s",
    ):
        assert p in paths
    assert len(paths) == len(set(paths))
    sc = Scenario.default()
    block_fields = {f"structure.{n}" for n in type(sc.structure).model_fields}
    for p in paths:  # every path of this kind (a block's structure keys, every other table) resolves to itself
        if not p.startswith("structure.") or p in block_fields:
            assert sc.resolve_key(p) == p


def test_fractions_are_exact_ratios():
    assert parse_ratio("1/200") == 0.005 and parse_ratio(" 1 / 20 ") == 0.05 and parse_ratio("0.07") == 0.07
    with pytest.raises(BlastscaleInputError):
        parse_ratio("one half")
    toml = GOOD.replace("length = 0.005", 'length = "1/200"')
    assert Scenario.from_dict(tomllib.loads(toml)).scale.length == 0.005


def test_material_library_is_cited_and_in_range():
    assert material_density("balsa") == 140.0  # the paper's balsa (gamma = 0.07 for 2000 kg/m^3)
    for m in MATERIALS.values():
        assert m.density_low <= m.density <= m.density_high and m.density_source
    with pytest.raises(BlastscaleInputError, match="valid values are marble"):
        material_density("cheese")


@pytest.mark.parametrize("path", EXAMPLES)
def test_example_scenarios_validate(path):
    sc = load_scenario(path)
    assert sc.title
    assert load_scenario(path) == Scenario.from_dict(
        tomllib.loads(_to_toml(sc.model_dump(mode="json", exclude_none=True)))
    )


def test_contact_ranges_are_the_engines_own():
    """[simulation.contact] takes its bounds from sim3d.contact_ranges.SETTING_RANGES: a value just outside an
    end is refused by the scenario and by ContactSettings alike, a value at a closed end accepted by both."""
    from blastscale.sim3d.contact import ContactSettings
    from blastscale.sim3d.contact_ranges import SETTING_RANGES

    keys = {
        "time_constant": "time_constant_s",
        "friction_time_constant": "friction_time_constant_s",
        "impedance_width": "impedance_width_m",
    }
    base = Scenario.default()
    for name, r in SETTING_RANGES.items():
        if name in ("friction", "timestep", "impedance_max"):
            continue  # friction and timestep are keys of [structure] / [simulation]; dmax also needs dmin
        key = f"simulation.contact.{keys.get(name, name)}"
        integer = name in ("iterations", "noslip_iterations")
        for end, is_open, outside in (
            (r.lo, r.lo_open, r.lo - (1 if integer else 1e-9)),
            (r.hi, r.hi_open, r.hi + (1 if integer else 1e-9 * max(1.0, r.hi))),
        ):
            for value, ok in ((outside, False), (end, not is_open)):
                value = int(value) if integer else float(value)
                try:
                    base.with_values({key: value})
                    scen_ok = True
                except BlastscaleInputError:
                    scen_ok = False
                kw = {name: value}
                if name == "time_constant" and ok:
                    kw["timestep"] = min(2e-4, value / 2)
                try:
                    ContactSettings(**kw)
                    lib_ok = True
                except BlastscaleInputError:
                    lib_ok = False
                assert scen_ok == lib_ok == ok, (key, value, scen_ok, lib_ok)


def test_deprecated_scenario_keys_are_read_and_the_new_ones_written(tmp_path):
    """``[blast] model``, ``[blast] pulse`` and ``[scale] model_material`` (the names before the
    glossary) are still read, in files, ``with_values`` (dotted and bare) and ``--set``; what
    blastscale writes uses ``blast_model``, ``pulse_shape`` and ``specimen_material``."""
    from blastscale.scenario.specs import LEGACY_SCENARIO_KEYS

    assert LEGACY_SCENARIO_KEYS == {
        "blast.model": "blast.blast_model",
        "blast.pulse": "blast.pulse_shape",
        "scale.model_material": "scale.specimen_material",
    }
    old = GOOD.replace("standoff_m = 2.0", 'standoff_m = 2.0\nmodel = "kingery-bulmash"\npulse = "triangular"')
    old = old.replace("length = 0.005", 'length = 0.005\nmodel_material = "balsa"')
    new = (
        old.replace("model = ", "blast_model = ")
        .replace("pulse = ", "pulse_shape = ")
        .replace("model_material = ", "specimen_material = ")
    )
    (tmp_path / "old.toml").write_text(old)
    (tmp_path / "new.toml").write_text(new)
    a, b = load_scenario(tmp_path / "old.toml"), load_scenario(tmp_path / "new.toml")
    assert a == b and a.blast.blast_model == "kingery-bulmash" and a.blast.pulse_shape == "triangular"
    assert a.scale.specimen_material == "balsa"
    text = a.to_toml()
    assert "blast_model = " in text and "pulse_shape = " in text and "specimen_material = " in text
    assert "\nmodel = " not in text and "\npulse = " not in text and "model_material" not in text
    base = Scenario.default()
    for key, new_key in (
        ("blast.model", "blast.blast_model"),
        ("model", "blast.blast_model"),
        ("blast.pulse", "blast.pulse_shape"),
        ("pulse", "blast.pulse_shape"),
        ("scale.model_material", "scale.specimen_material"),
        ("model_material", "scale.specimen_material"),
    ):
        assert base.resolve_key(key) == new_key
    c = base.with_values({"blast.model": "kingery-bulmash", "pulse": "impulsive", "model_material": "balsa"})
    assert (c.blast.blast_model, c.blast.pulse_shape, c.scale.specimen_material) == (
        "kingery-bulmash",
        "impulsive",
        "balsa",
    )
    assert c.scale.density_ratio is None  # the material replaced the density ratio (exclusive keys)


def test_deprecated_cli_set_and_flags(capsys, tmp_path):
    """``--set blast.model=...`` and ``--set pulse=...`` still work; ``--blast-model`` and
    ``--pulse-shape`` are the new names of ``--model`` and ``--pulse``."""
    import json

    def js(*argv):
        with pytest.raises(SystemExit) as e:
            main(list(argv))
        out = capsys.readouterr()
        assert (e.value.code or 0) == 0, out.err
        return json.loads(out.out)

    a = js(
        "run",
        "--set",
        "blast.model=kingery-bulmash",
        "--set",
        "pulse=impulsive",
        "--set",
        "engine=planar",
        "--set",
        "duration_s=0.2",
        "--set",
        "critical_charge=false",
        "--json",
    )
    assert a["scenario"]["blast"]["blast_model"] == "kingery-bulmash" == a["scenario"]["blast"]["model"]
    assert a["scenario"]["blast"]["pulse_shape"] == "impulsive" == a["scenario"]["blast"]["pulse"]
    b = js(
        "critical",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--standoff",
        "2",
        "--blast-model",
        "masi2021",
        "--pulse-shape",
        "triangular",
        "--json",
    )
    c = js(
        "critical",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--standoff",
        "2",
        "--model",
        "masi2021",
        "--pulse",
        "triangular",
        "--json",
    )
    assert b["critical_charge_kg"] == c["critical_charge_kg"] and b["blast_model"] == "masi2021" == b["model"]
    assert b["pulse_shape"] == "triangular" == b["pulse"]
