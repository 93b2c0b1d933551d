"""The instrument rules of docs/planning.md."""

import math

import pytest

from blastscale.planning.instruments import instrument_settings, round_up_125, top_corner_displacement


def test_round_up_125():
    assert [round_up_125(x) for x in (1.0, 1.01, 2.0, 2.1, 5.0, 5.5, 0.3, 7e5)] == [
        1.0,
        2.0,
        2.0,
        5.0,
        5.0,
        10.0,
        0.5,
        1e6,
    ]


def test_rules():
    s = instrument_settings(
        reflected_pressure_Pa=1e6,
        incident_pressure_Pa=3e5,
        positive_duration_s=1e-5,
        friedlander_decay=4.0,
        arrival_time_s=5e-6,
        rise_time_s=0.05,
        response_time_s=0.2,
        top_displacement_m=0.004,
        camera_max_fps=1e4,
    )
    assert s.reflected_gauge_range_Pa == 1.5e6 and s.incident_gauge_range_Pa == 4.5e5
    assert s.pressure_rise_time_s == pytest.approx(0.1 * 1e-5 / 5.0)
    assert s.pressure_sampling_hz == round_up_125(max(2 / s.pressure_rise_time_s, 50 / 1e-5)) == 1e7
    assert s.camera_fps_required == pytest.approx(20 / 0.05) and s.camera_fps == 500.0
    assert s.frames_over_rise == pytest.approx(25.0) and s.frames_over_response == pytest.approx(100.0)
    assert s.displacement_range_m == pytest.approx(0.006) and s.trigger_delay_s == 5e-6
    capped = instrument_settings(
        reflected_pressure_Pa=1e6,
        incident_pressure_Pa=3e5,
        positive_duration_s=1e-5,
        friedlander_decay=4.0,
        arrival_time_s=5e-6,
        rise_time_s=0.05,
        response_time_s=0.2,
        top_displacement_m=0.004,
        camera_max_fps=450.0,
    )
    assert capped.camera_fps == 450.0  # the camera's own top rate when the 1-2-5 step would exceed it


def test_top_corner_of_a_rotated_block():
    assert top_corner_displacement(1.0, 4.0, 0.0) == 0.0
    assert top_corner_displacement(1.0, 4.0, math.pi / 2) == pytest.approx(5.0)
