"""The shot as fired, end to end through the Study (issue #25 acceptance, planar block).

The lab's records are made in the test: a block specimen (the paper's 10 m block at 1/20: 0.5 m, 1.0 g TNT
at 0.1 m, the paper's fits) fired with a charge 15 % above the designed one. The gauge trace is the
synthetic generator's (tests/_fired_synthetic.py); the track is a planar rocking simulation run here with
the solver directly (not through blastscale.fired), turned into marker positions by the generator's own
kinematics, with 0.05 mm noise at 2000 frames per second.

Tolerances (the issue's): the measured first peak within 2 % of the track's own (the simulation's first
peak event; the noise is 0.05 mm on a ~45 mm peak and the parabola over ~60 frames averages it), the
re-simulation within 6 % of the measurement (the first peak goes as ~W^1.9 here; the gauge, flush in the front
face at 26.6 deg from the charge on the floor (issue #36), gives W within ~2.6 %: its impulse's noise, 1.4 %
for seed 0, moves W by 1.3 x at that angle, and the generator's own reading of UFC Fig. 2-194 differs from the
package's by 0.6 % in W there; #25's 5 % was sized for a gauge read as facing the charge), the designed prediction visibly below (at least 10 % below: 15 % less charge gives
~24 % less first peak).
"""

from __future__ import annotations

import numpy as np
import pytest
from _fired_synthetic import camera_track, synthetic_trace, synthetic_track, write_gauge_csv, write_track_csv

from blastscale.blast import blast_parameters
from blastscale.fired.shot import as_fired
from blastscale.rocking import DEFAULT_SOLVER, RockingSystem
from blastscale.scenario import load_scenario
from blastscale.study import Study

pytestmark = pytest.mark.slow

FACTOR = 1.15
FPS = 2000.0

SCENARIO = """
title = "fired: the paper's block at 1/20"
[structure]
kind = "block"
height_m = 10.0
alpha_deg = 15.0
depth_m = 1.0
density_kg_m3 = 2000.0
[blast]
charge_kg = 50.0
standoff_m = 2.0
blast_model = "masi2021"
[scale]
length = "1/20"
[simulation]
engine = "planar"
duration_s = 2.0
critical_charge = false
[lab]
explosive = "c-4"
[fired]
gauges = "gauges.csv"
tracks = "tracks.csv"
charge_kg = {charge}
standoff_m = 0.1
[fired.gauge.g1]
position_m = [{gx}, 0.0, 0.05]
kind = "reflected"
[fired.marker.top]
point_m = [0.0, 0.0, 0.5]
"""


def write_shot(folder, factor=FACTOR, seed=0, restitution=None, fps=FPS):
    """The scenario, its gauge and track files (a camera at ``fps`` frames per second) in ``folder``; returns
    (path, truth)."""
    base = load_scenario_text(SCENARIO.format(charge=1e-3, gx=-0.05))
    d = Study(base).check().design
    block = d.specimen_block
    W = factor * d.specimen_charge_kg
    R = d.specimen.standoff_m
    charge_at = np.array([block.front_x - R, 0.0, 0.0])
    gauge = np.array([block.front_x, 0.0, 0.05])
    # flush in the front face (normal -x), the charge on the floor: the angle of incidence from the geometry
    to_charge = charge_at - gauge
    angle = float(np.degrees(np.arccos(-to_charge[0] / np.linalg.norm(to_charge))))
    t, p, _ = synthetic_trace(
        seed,
        W,
        float(np.linalg.norm(to_charge)),
        blast_model="masi2021",
        rate_hz=4e6,
        pre_s=1e-3,
        incidence_deg=angle,
    )
    write_gauge_csv(folder / "gauges.csv", t, p)
    bp = blast_parameters(W, R, "masi2021")
    system = RockingSystem.from_block(block, d.specimen_gravity, restitution)
    frames = np.arange(-0.01, d.specimen_duration, 1.0 / fps)
    after = np.clip(frames - bp.arrival_time, 0.0, None)
    res = DEFAULT_SOLVER.simulate(system, bp.pulse("friedlander"), d.specimen_duration, t_eval=after)
    x, z = synthetic_track(seed, frames, res.theta_eval, 0.0, 0.5, block.b)
    write_track_csv(folder / "tracks.csv", frames, {"top_x": x, "top_z": z})
    th0 = float(res.peak_angles[0])
    true_peak = block.b * (1 - np.cos(th0)) + 0.5 * np.sin(th0)  # the top centre, about the rear toe
    sc_path = folder / "shot.toml"
    init = base.lab.initiator_tnt_kg  # the lab's initiator (RP-80 by default: 0.22 g TNT) is part of W
    sc_path.write_text(SCENARIO.format(charge=(W - init) / 1.19, gx=block.front_x))  # C-4, impulse (UFC Table 2-1)
    return sc_path, {
        "first_peak_m": true_peak,
        "first_peak_time_s": float(res.peak_times[0]) + bp.arrival_time,
        "charge_tnt_kg": W,
        "designed_tnt_kg": d.specimen_charge_kg,
    }


def load_scenario_text(text):
    import tomllib

    from blastscale.scenario import Scenario

    return Scenario.from_dict(tomllib.loads(text), source="test")


def test_block_fired_15_percent_above_the_design(tmp_path):
    path, truth = write_shot(tmp_path)
    r = as_fired(load_scenario(path))
    s = r.summary
    m = s["markers"]["top"]
    assert m["first_peak_m"] == pytest.approx(truth["first_peak_m"], rel=0.02)
    assert m["first_peak_time_s"] == pytest.approx(truth["first_peak_time_s"], rel=0.02)
    assert s["effective_charge_tnt_kg"] == pytest.approx(truth["charge_tnt_kg"], rel=0.05)
    assert s["charge_ratio_impulse"] == pytest.approx(FACTOR, rel=0.05)
    # the refit carries the effective charge's own error (the gauge's impulse read within its interval), about
    # doubled on a first peak (~W^2, fired/gauges.py): bounded by it, plus 1 % for the rest of the chain
    charge_error = abs(s["effective_charge_tnt_kg"] / truth["charge_tnt_kg"] - 1.0)
    assert m["refit_first_peak_m"] == pytest.approx(m["first_peak_m"], rel=2.0 * charge_error + 0.01)
    assert m["predicted_first_peak_m"] < 0.90 * m["first_peak_m"]
    assert m["outcome_measured"] == m["outcome_refit"] == "stands"
    # the gauge is read at its angle of incidence, the normal of the face it is flush in
    g = s["gauges"]["g1"]
    assert g["incidence_deg"] == pytest.approx(np.degrees(np.arctan2(0.05, 0.1)), abs=1e-9)
    assert g["normal_from"] == "face 'front' of 'block'" and g["warnings"] == []
    # the implied TNT equivalence of the C-4 as weighed: 1.19 (UFC 3-340-02 Table 2-1, impulse)
    assert s["tnt_equivalence_impulse"] == pytest.approx(1.19, rel=0.05)
    # the monument: the measured first peak up-scaled (lambda = 1/20, time sqrt(1/20)), inside its band
    p = s["prototype_markers"]["top"]
    assert p["first_peak_m"] == pytest.approx(20.0 * m["first_peak_m"], rel=1e-12)
    assert p["first_peak_time_s"] == pytest.approx(m["first_peak_time_s"] * np.sqrt(20.0), rel=1e-12)
    assert p["first_peak_p05_m"] < p["first_peak_m"] < p["first_peak_p95_m"]
    assert s["verdict"].startswith("As fired: 1.1")


def test_one_shot_filmed_at_four_frame_rates(tmp_path):
    """Issue #36 item 3's acceptance through ``as_fired``: the same shot (the same gauge trace, the same rocking)
    filmed at 500, 1000, 2000 and 5000 frames per second with 0.05 mm noise: the measured first peaks within 2 %
    of each other and of the truth, and every 5-95 % band of the monument holds the truth up-scaled (x 20)."""
    peaks = []
    for fps in (500.0, 1000.0, 2000.0, 5000.0):
        folder = tmp_path / f"{fps:g}"
        folder.mkdir()
        path, truth = write_shot(folder, fps=fps)
        s = as_fired(load_scenario(path)).summary
        m, p = s["markers"]["top"], s["prototype_markers"]["top"]
        assert m["first_peak_m"] == pytest.approx(truth["first_peak_m"], rel=0.02), fps
        assert p["first_peak_p05_m"] <= 20.0 * truth["first_peak_m"] <= p["first_peak_p95_m"], fps
        assert m["smoothing_s"] == pytest.approx(0.1 * m["predicted_first_peak_time_s"], abs=1.0 / fps + 1e-12)
        peaks.append(m["first_peak_m"])
    assert (max(peaks) - min(peaks)) / truth["first_peak_m"] < 0.02


def test_refit_at_the_designed_load_is_the_studys_specimen(tmp_path):
    """The prediction path (the specimen written as a scenario) gives the Study's own specimen run."""
    sc = load_scenario_text(SCENARIO.format(charge=1e-3, gx=-0.05))
    from blastscale.fired.refit import simulate_specimen

    st = Study(sc).run()
    d = st.design
    run = simulate_specimen(sc, d, d.specimen_charge_kg, d.specimen.standoff_m)
    assert run.rocking.peak_angles[0] == pytest.approx(st.planar.model.peak_angles[0], rel=1e-9)
    assert run.rocking.peak_times[0] == pytest.approx(st.planar.model.peak_times[0], rel=1e-9)


COLUMN = """
title = "fired: a three-drum square column at 1/10, 3D"
[structure]
kind = "column"
section = "square"
drums = 3
height_m = 3.0
base_width_m = 0.6
top_width_m = 0.5
density_kg_m3 = 2700.0
[blast]
charge_kg = 20.0
standoff_m = 5.0
[scale]
length = "1/10"
[simulation]
engine = "3d"
duration_s = 2.0
critical_charge = false
[fired]
gauges = "gauges.csv"
tracks = "tracks.csv"
[fired.gauge.g1]
position_m = [{gx}, 0.0, 0.05]
[fired.marker.top]
point_m = [0.0, 0.0, 0.3]
"""


def test_column_in_3d_end_to_end(tmp_path):
    """A 3D case end to end: a three-drum column specimen (0.3 m, 4.2 g TNT at 0.5 m by design) fired 15 % over
    its design. The track is the specimen's own 3D run under that charge (the refit's path: this checks the
    pipeline and the effective charge, not the engine), resampled at 2000 frames per second with 0.05 mm noise;
    the gauge trace is the synthetic generator's. Tolerances as for the block; the top's first peak goes as
    ~W^1.9 here (24.1 mm at the design, 31.8 mm at 1.15 x)."""
    from blastscale.fired.refit import marker_history, simulate_specimen

    base = load_scenario_text(COLUMN.format(gx=-0.03))
    d = Study(base).check().design
    W = FACTOR * d.specimen_charge_kg
    R = d.specimen.standoff_m
    front = d.specimen_structure.front_x
    dist = float(np.hypot(R, 0.05))
    t, p, _ = synthetic_trace(1, W, dist, rate_hz=4e6, pre_s=1e-3, incidence_deg=float(np.degrees(np.arctan2(0.05, R))))
    write_gauge_csv(tmp_path / "gauges.csv", t, p)
    truth = marker_history(simulate_specimen(base, d, W, R, "3d"), (0.0, 0.0, 0.3))
    frames, u = camera_track(truth, fps=FPS, seed=1, noise_m=5e-5, components=("x", "z"))
    write_track_csv(tmp_path / "tracks.csv", frames, {"top_x": u["x"], "top_z": 0.3 + u["z"]})
    path = tmp_path / "shot.toml"
    path.write_text(COLUMN.format(gx=front))
    s = as_fired(load_scenario(path)).summary
    m = s["markers"]["top"]
    assert s["charge_ratio_impulse"] == pytest.approx(FACTOR, rel=0.05)
    assert m["first_peak_m"] == pytest.approx(truth["first_peak_m"], rel=0.02)
    assert m["refit_first_peak_m"] == pytest.approx(m["first_peak_m"], rel=0.05)
    assert m["predicted_first_peak_m"] < 0.90 * m["first_peak_m"]
    assert m["outcome_refit"] == m["outcome_predicted"] == m["outcome_measured"] == "stands"  # by its top drum
    assert s["prototype_markers"]["top"]["first_peak_m"] == pytest.approx(10.0 * m["first_peak_m"], rel=1e-12)


def test_calibrated_restitution_is_the_tracks(tmp_path):
    """Item 7: a track rocked with e = 0.80 (Housner's for alpha = 15 deg: 0.90) is calibrated back (the charge
    a nuisance parameter): within 0.005 (measured 0.0003 over seeds 0-2: the ~0.08 s after the first impact
    carry it, 0.05 mm noise), and the misfit at the optimum is the noise (0.05 mm)."""
    path, _ = write_shot(tmp_path, restitution=0.80)
    s = as_fired(load_scenario(path), calibrate=["restitution"]).summary
    c = s["calibration"]
    assert c["restitution"] == pytest.approx(0.80, abs=0.005)
    assert c["identifiable"] and c["restitution_low"] < 0.80 < c["restitution_high"]
    assert c["restitution_high"] - c["restitution_low"] < 0.05
    assert c["misfit_rms_m"] == pytest.approx(5e-5, rel=0.2)
    assert c["charge_factor"] * s["refit_charge_tnt_kg"] == pytest.approx(
        FACTOR * s["designed_charge_tnt_kg"], rel=0.01
    )
    assert c["prototype_outcome"] == "stands" and c["prototype_max_rotation_rad"] > 0


def test_calibrate_refuses_what_it_cannot_do():
    from blastscale._validate import BlastscaleInputError
    from blastscale.fired.calibrate import check_calibrate

    assert check_calibrate(["restitution", ""]) == ("restitution",)
    with pytest.raises(BlastscaleInputError, match="calibrate = 'stiffness' is not known"):
        check_calibrate(["stiffness"])
    assert check_calibrate(["friction"]) == ("friction",)
