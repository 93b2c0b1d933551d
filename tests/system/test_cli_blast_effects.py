"""CLI: the burst type, clearing and the negative phase in `blast`, `design`, `critical`, `rock` and
`run` (scenario keys): their JSON keys, the load-model record, one-line errors with exit status 2."""

import json

import pytest

from blastscale.cli import main

EFFECT_KEYS = {
    "clearing_time_s",
    "cleared_impulse_Pa_s",
    "negative_pressure_Pa",
    "negative_duration_s",
    "negative_impulse_Pa_s",
    "load_model",
    "burst",
}


def run_json(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    assert e.value.code in (0, None)
    return json.loads(capsys.readouterr().out)


def run_error(capsys, *argv) -> str:
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error:") and "\n" not in err and "Traceback" not in err
    return err


def test_blast_json_has_the_effects_beside_todays_keys(capsys):
    out = run_json(
        capsys,
        "blast",
        "--charge",
        "1000",
        "--standoff",
        "70",
        "--clearing",
        "--face-width",
        "10",
        "--face-height",
        "4",
        "--negative-phase",
        "--json",
    )
    assert EFFECT_KEYS <= out.keys() and "reflected_impulse_Pa_s" in out
    assert out["cleared_impulse_Pa_s"] < out["reflected_impulse_Pa_s"]
    assert out["negative_impulse_Pa_s"] == pytest.approx(
        9 / 16 * out["negative_pressure_Pa"] * out["negative_duration_s"]
    )
    lm = out["load_model"]
    assert lm["clearing"] and lm["negative_phase"] and lm["face_width_m"] == 10.0 and lm["burst"] == "surface"
    plain = run_json(capsys, "blast", "--charge", "1000", "--standoff", "70", "--json")
    assert plain["reflected_impulse_Pa_s"] == out["reflected_impulse_Pa_s"]
    assert "clearing_time_s" not in plain and plain["load_model"]["clearing"] is False


def test_blast_free_air(capsys):
    out = run_json(capsys, "blast", "--charge", "50", "--standoff", "5", "--burst", "free-air", "--json")
    surf = run_json(capsys, "blast", "--charge", "50", "--standoff", "5", "--json")
    assert out["blast_model"] == "kingery-bulmash-free-air" and out["burst"] == "free-air"
    assert out["incident_pressure_Pa"] < surf["incident_pressure_Pa"]


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--face-width", "1", "--face-height", "2"], "apply only with --clearing"),
        (["--clearing"], "clearing needs the loaded face"),
        (["--clearing", "--face-width", "1"], "needs both"),
        (["--burst", "free-air", "--model", "masi2021"], "not available for blast model 'masi2021'"),
        (["--burst", "air"], "--burst = 'air' is not known"),
        (["--clearing", "--face-width", "-1", "--face-height", "2"], "--face-width = -1 m is out of range"),
    ],
)
def test_bad_combinations_are_one_line(capsys, argv, words):
    assert words in run_error(capsys, "blast", "--charge", "50", "--standoff", "2", *argv)


def test_critical_with_the_negative_phase(capsys):
    out = run_json(
        capsys, "critical", "--height", "10", "--alpha-deg", "15", "--standoff", "2", "--negative-phase", "--json"
    )
    assert out["critical_charge_kg"] == pytest.approx(108.367, abs=0.005)
    assert out["load_model"]["negative_phase"] is True


def test_rock_and_design_carry_the_load_model(capsys):
    out = run_json(
        capsys,
        "rock",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--charge",
        "50",
        "--standoff",
        "2",
        "--scale",
        "0.01",
        "--negative-phase",
        "--clearing",
        "--duration",
        "0.5",
        "--json",
    )
    assert out["load_model"]["model"]["face_width_m"] == pytest.approx(0.01)
    d = run_json(
        capsys,
        "design",
        "--charge",
        "50",
        "--standoff",
        "2",
        "--scale",
        "0.01",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--negative-phase",
        "--specimen-burst",
        "free-air",
        "--json",
    )
    e = d["blast_effects"]
    assert e["load_model"]["model"]["burst"] == "free-air" and "negative_phase" in e and d["notes"]
    assert "--specimen-charge-height needs" in run_error(
        capsys, "design", "--charge", "50", "--standoff", "2", "--scale", "0.01", "--specimen-charge-height", "0.01"
    )


def test_run_takes_the_scenario_keys(capsys, tmp_path):
    out = run_json(
        capsys,
        "run",
        "--out",
        str(tmp_path / "r"),
        "--set",
        "simulation.engine=planar",
        "--set",
        "simulation.duration_s=0.3",
        "--set",
        "blast.negative_phase=true",
        "--set",
        "simulation.critical_charge=false",
        "--json",
    )
    s = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert s["scenario"]["blast"]["negative_phase"] is True
    assert out["scenario"]["blast"]["negative_phase"] is True  # --json prints the summary that was written
    assert s["design"]["blast_effects"]["negative_phase"]["model"]["negative_impulse_Pa_s"] > 0


@pytest.mark.parametrize("standoff", ["15", "30"])
def test_blast_negative_phase_net_impulse_is_not_negative_far_out(capsys, standoff):
    """Issue #24: at Z = 15 the chart's suction impulse is 1.15 x the positive one; bounded, the net is 0."""
    for model in ("ufc-fig2-16-cubic", "friedlander-continued"):
        out = run_json(
            capsys,
            "blast",
            "--charge",
            "1",
            "--standoff",
            standoff,
            "--negative-phase",
            "--negative-phase-model",
            model,
            "--json",
        )
        assert out["net_reflected_impulse_Pa_s"] >= 0.0 and out["negative_impulse_bounded"] is True
        assert out["load_model"]["negative_phase_model"] == model


def test_blast_negative_phase_beyond_the_chart_refuses_or_is_bounded(capsys):
    """Z = 39: refused in one line naming the valid range; with --extrapolate, bounded (net 0)."""
    err = run_error(capsys, "blast", "--charge", "1", "--standoff", "39", "--negative-phase")
    assert "[0.07, 37.6] m/kg^(1/3)" in err
    out = run_json(capsys, "blast", "--charge", "1", "--standoff", "39", "--negative-phase", "--extrapolate", "--json")
    assert out["net_reflected_impulse_Pa_s"] >= 0.0


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--negative-phase-model", "friedlander-continued"], "applies only with --negative-phase"),
        (["--negative-phase", "--negative-phase-model", "cosine"], "negative phase model = 'cosine' is not known"),
    ],
)
def test_bad_negative_phase_model_is_one_line(capsys, argv, words):
    assert words in run_error(capsys, "blast", "--charge", "50", "--standoff", "2", *argv)


def test_critical_reports_the_suction_model_uncertainty(capsys):
    out = run_json(
        capsys,
        "critical",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--standoff",
        "2",
        "--negative-phase",
        "--model",
        "kingery-bulmash",
        "--json",
    )
    u = out["negative_phase_uncertainty"]
    assert u["ufc-fig2-16-cubic"]["over_positive_phase_only"] == pytest.approx(1.289, abs=1e-3)
    assert u["friedlander-continued"]["over_positive_phase_only"] == pytest.approx(1.030, abs=1e-3)


def test_rock_and_design_take_the_negative_phase_model(capsys):
    out = run_json(
        capsys,
        "rock",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--charge",
        "50",
        "--standoff",
        "2",
        "--negative-phase",
        "--negative-phase-model",
        "friedlander-continued",
        "--json",
    )
    assert out["load_model"]["prototype"]["negative_phase_model"] == "friedlander-continued"
    d = run_json(
        capsys,
        "design",
        "--charge",
        "50",
        "--standoff",
        "2",
        "--scale",
        "0.05",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--negative-phase",
        "--negative-phase-model",
        "friedlander-continued",
        "--json",
    )
    assert d["load_model"]["model"]["negative_phase_model"] == "friedlander-continued"
    assert d["blast_effects"]["negative_phase"]["prototype"]["negative_phase_model"] == "friedlander-continued"
    assert "applies only with --negative-phase" in run_error(
        capsys,
        "rock",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--charge",
        "50",
        "--standoff",
        "2",
        "--negative-phase-model",
        "friedlander-continued",
    )
