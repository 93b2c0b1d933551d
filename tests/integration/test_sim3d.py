"""3D single-block response on MuJoCo (issue #4) against closed forms and the planar equation
(paper Eq. eom, as solved by :mod:`blastscale.rocking`).

The block is the one-body case of the structure engine: every run here is
``simulate_structure(block, MethodA(block, pulse), ...)`` (the reflected pulse on the whole front
face at once, arriving at t = 0), read through the block's planar view
(:func:`~blastscale.analysis.block3d_similarity.block_dataset` / ``block_summary``).

Reference block of the paper: 2h = 10 m, alpha = 15 deg, rho = 2000 kg/m^3, depth 1 m
(depth cancels). Loads: paper Appendix A fits (model="masi2021"), Friedlander pulse.
Prototype vs model: tests/test_sim3d_similarity.py.
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.block3d_similarity import block_dataset, block_summary
from blastscale.analysis.compare import upscale_dataset
from blastscale.blast.parameters import blast_parameters
from blastscale.blast.pulses import Friedlander, Impulsive, Triangular
from blastscale.constants import STANDARD_GRAVITY as G
from blastscale.sim3d import (
    ContactSettings,
    MethodA,
    block_scene,
    pivot_friction_threshold,
    quaternion_to_matrix,
    simulate_structure,
    step_forces,
)
from blastscale.similitude import scaling_factors
from blastscale.structures.block import RectangularBlock

PAPER_BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
SQUAT_BLOCK = RectangularBlock(height=0.5, width=1.0, depth=1.0)  # the "1 m squat block", 1000 kg
SQUAT_I = 1.8 * SQUAT_BLOCK.mass / SQUAT_BLOCK.front_area  # impulse [Pa s] giving v0 = i S / m = 1.8 m/s


def paper_pulse(charge, standoff=2.0):
    return blast_parameters(charge, standoff, blast_model="masi2021").pulse("friedlander")


def run_block(block, pulse=None, duration=5.0, **kw):
    """The block under Method A (``pulse`` on its front face, t = 0 at arrival; None: no blast),
    as the one-body structure run: its Response3D."""
    return simulate_structure(block, None if pulse is None else MethodA(block, pulse), duration, **kw)


def planar(response):
    """The block's planar view of a run: its block_dataset histories as arrays (``time``,
    ``rotation_y``, ``sliding``, ``uplift``, ``angular_velocity_y``, ``velocity_x``, ``com_x``,
    ``com_z``), its ``summary`` (block_summary) and the run ``settings`` (dataset attributes)."""
    ds = block_dataset(response)
    return SimpleNamespace(
        time=ds["time"].values,
        **{k: ds[k].values[:, 0] for k in ds.data_vars},
        summary=block_summary(response),
        settings={k[len("setting_") :]: v for k, v in response.dataset.attrs.items() if k.startswith("setting_")},
    )


# -- settings and load ------------------------------------------------------------------
def test_contact_settings_scale_times_by_sqrt_lambda_and_width_by_lambda():
    c = ContactSettings()
    lam = 1 / 200
    s = c.scaled(scaling_factors(lam))
    assert s.timestep == pytest.approx(c.timestep * math.sqrt(lam), rel=1e-15)
    assert s.time_constant == pytest.approx(c.time_constant * math.sqrt(lam), rel=1e-15)
    assert s.friction_time_constant == pytest.approx(c.friction_time_constant * math.sqrt(lam), rel=1e-15)
    assert s.impedance_width == pytest.approx(c.impedance_width * lam, rel=1e-15)
    assert (s.friction, s.damping_ratio, s.impratio, s.cone) == (c.friction, c.damping_ratio, c.impratio, c.cone)
    # MuJoCo stiffness k [1/s^2] scales like g/l = 1/lambda_t^2
    assert s.stiffness == pytest.approx(c.stiffness / lam, rel=1e-12)


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(friction=-0.1),
        dict(time_constant=1e-4, timestep=1e-4),
        dict(cone="round"),
        dict(solver="X"),
        dict(impedance_max=1.0),
        dict(friction_time_constant=0.0),
        dict(friction=float("nan")),
        dict(timestep=float("inf")),
        dict(iterations=2.5),
        dict(friction=np.array([0.5, 0.6])),
    ],
)
def test_contact_settings_reject_bad_input(kwargs):
    with pytest.raises(BlastscaleInputError) as e:
        ContactSettings(**kwargs)
    assert len(str(e.value).splitlines()) == 1


@pytest.mark.parametrize(
    "call, word",
    [
        (lambda: simulate_structure(PAPER_BLOCK, "friedlander", 0.01), "load"),
        (lambda: MethodA(PAPER_BLOCK, "friedlander"), "pulse"),
        (lambda: simulate_structure(None, None, 0.01), "structure"),
        (lambda: run_block(PAPER_BLOCK, None, 0.01, record_every=1.5), "record_every"),
        (lambda: run_block(PAPER_BLOCK, None, float("nan")), "duration"),
        (lambda: run_block(PAPER_BLOCK, None, 0.01, initial_rotation=2.0), "initial rotation"),
        (lambda: run_block(PAPER_BLOCK, None, 0.01, initial_velocity=(1.0, 0.0)), "initial velocity"),
        (lambda: run_block(PAPER_BLOCK, None, 0.01, blast_mode="push"), "blast_mode"),
        (lambda: step_forces(Impulsive(1.0), 1.0, [0.0, 2e-3, 1e-3]), "step times"),
        (lambda: step_forces(Impulsive(1.0), 1.0, [0.0]), "step times"),
        (lambda: upscale_dataset(block_dataset(run_block(PAPER_BLOCK, None, 1e-3)), scaling_factors(0.0)), "scale"),
    ],
    ids=[
        "load",
        "pulse",
        "block",
        "record_every",
        "duration",
        "rotation",
        "velocity",
        "mode",
        "times-order",
        "times-size",
        "upscale",
    ],
)
def test_simulation_rejects_bad_input_with_one_line_naming_it(call, word):
    with pytest.raises(BlastscaleInputError) as e:
        call()
    assert word in str(e.value) and len(str(e.value).splitlines()) == 1


def test_step_forces_carry_exact_impulse_of_friedlander_pulse():
    p = Friedlander(5e6, 1.1e-3, 1.3)
    t = np.arange(0, 12) * 2e-4  # steps do not resolve the pulse and do not divide t_o
    F = step_forces(p, 2.5, t)
    # the sum telescopes: exact to round-off (1e-12 relative)
    assert np.sum(F * np.diff(t)) == pytest.approx(p.impulse * 2.5, rel=1e-12)
    assert np.all(F[t[1:] > p.duration + 2e-4] == 0.0)


def test_step_forces_put_a_dirac_into_the_first_step():
    F = step_forces(Impulsive(100.0), 2.0, [0.0, 1e-3, 2e-3])
    assert F[0] == pytest.approx(100.0 * 2.0 / 1e-3, rel=1e-15) and F[1] == 0.0


def test_tilted_scene_rests_on_its_edge_with_rotation_theta0():
    import mujoco

    th0 = 0.1
    sc = block_scene(PAPER_BLOCK, ContactSettings(), rotation=th0)
    d = mujoco.MjData(sc.mj_model)
    mujoco.mj_forward(sc.mj_model, d)
    R = quaternion_to_matrix(d.qpos[3:7])
    corners_z = d.qpos[2] + sc.bodies[0].shape.base_points() @ R[2]
    assert corners_z.min() == pytest.approx(0.0, abs=1e-12)  # rests exactly on the +x edge
    # ... which stays where the upright block had it, x = b (so the sliding recorder reads 0)
    edge_x = d.qpos[0] + sc.bodies[0].shape.pivot_points()[0] @ R[0]
    assert edge_x == pytest.approx(PAPER_BLOCK.b, abs=1e-12)
    assert math.atan2(R[0, 2], R[2, 2]) == pytest.approx(th0, rel=1e-14)


# -- closed forms -----------------------------------------------------------------------
@pytest.mark.parametrize("mu", [0.3, 0.7])
def test_pure_sliding_distance_v0_squared_over_2_mu_g(mu):
    v0 = 1.8
    i = v0 * SQUAT_BLOCK.mass / SQUAT_BLOCK.front_area  # v0 = i S / m
    r = planar(run_block(SQUAT_BLOCK, Triangular(2 * i / 1e-3, i), 1.0, contact=ContactSettings(friction=mu)))
    expected = v0**2 / (2 * mu * G)
    # 3% (issue): covers friction during the 1 ms pulse (mu g t_o / v0 = 0.4%) and the viscous
    # creep below mu g / b_f at the end of the slide (~0.1%); measured -0.09% / -0.13%
    assert r.summary["final_sliding_m"] == pytest.approx(expected, rel=0.03)
    # the blast momentum |sum F dt| (the force stays along the front face's normal)
    assert np.linalg.norm(r.summary["delivered_impulse_Ns"]) == pytest.approx(i * SQUAT_BLOCK.front_area, rel=1e-12)


def test_spurious_hop_of_a_sliding_block_below_2_mm():
    v0 = 1.8
    i = v0 * SQUAT_BLOCK.mass / SQUAT_BLOCK.front_area
    pulse = Triangular(2 * i / 1e-3, i)
    fixed = block_summary(run_block(SQUAT_BLOCK, pulse, 0.5, contact=ContactSettings(friction=0.7)))
    # issue #4 target: <= 2 mm; measured 0.02 mm
    assert fixed["max_uplift_m"] <= 2e-3
    # the hop is a solver artefact, reproduced by MuJoCo's defaults: blast as a force while the
    # contact slides (4.4 mm measured) -- shows this test can fail
    raw = block_summary(
        run_block(
            SQUAT_BLOCK,
            pulse,
            0.5,
            contact=ContactSettings(friction=0.7, friction_time_constant=None),
            blast_mode="force",
        )
    )
    assert raw["max_uplift_m"] > 3e-3


def test_pivot_threshold_decides_stick_or_slip_during_the_pulse():
    b, h = PAPER_BLOCK.b, PAPER_BLOCK.h
    mu_star = pivot_friction_threshold(b, h)
    assert mu_star == pytest.approx(1.60, abs=0.01)  # the paper's block (issue: 1.6)
    # independent: the impulsive equations about the rear edge (J_o w = P h, m v = P + F_x,
    # N = m w b) need |F_x| / N = (1 - m h^2 / J_o) / (m h b / J_o) <= mu
    m_over_J = 3 / (4 * (b * b + h * h))
    assert mu_star == pytest.approx((1 - m_over_J * h * h) / (m_over_J * h * b), rel=1e-12)
    assert pivot_friction_threshold(0.5, 1.0) == pytest.approx(4 / 3, rel=1e-12)  # the minimum, b = h / 2
    pulse = paper_pulse(50.0)
    stick = planar(run_block(PAPER_BLOCK, pulse, 0.01, contact=ContactSettings(friction=2.0)))
    slip = planar(run_block(PAPER_BLOCK, pulse, 0.01, contact=ContactSettings(friction=0.7)))
    assert stick.settings["blast_mode"] == "auto"  # the default for one body
    assert stick.settings["kick_steps"] == 0 and abs(stick.sliding[-1]) < 1e-4
    # no kick: "auto" is plain force mode, bitwise, for a sticking pivot (the pivoting cases)
    force = planar(run_block(PAPER_BLOCK, pulse, 0.01, contact=ContactSettings(friction=2.0), blast_mode="force"))
    assert np.array_equal(force.rotation_y, stick.rotation_y) and np.array_equal(force.sliding, stick.sliding)
    assert slip.settings["kick_steps"] > 0 and slip.sliding[-1] > 1e-3
    # near mu* "auto" is not reliable (up to 3% low on the peak rotation, docs/sim3d.md): it says so
    with pytest.warns(RuntimeWarning, match="pivoting threshold"):
        run_block(PAPER_BLOCK, pulse, 1e-3, contact=ContactSettings(friction=mu_star))


def _velocity_after_pulse(block, pulse, contact, mode):
    """COM velocity x [m/s] at the first recorded time after the last load step, and that time [s]."""
    t_end = pulse.duration + contact.timestep
    r = planar(run_block(block, pulse, t_end + 2 * contact.timestep, contact=contact, blast_mode=mode))
    k = int(np.searchsorted(r.time, t_end))
    return r.velocity_x[k], r.time[k]


@pytest.mark.parametrize(
    "block, pulse",
    [(SQUAT_BLOCK, Triangular(2 * SQUAT_I / 1e-3, SQUAT_I)), (PAPER_BLOCK, paper_pulse(50.0))],
    ids=["squat-1.8m/s", "slender-50kg"],
)
def test_blast_mode_auto_matches_force_mode_where_force_mode_is_accurate(block, pulse):
    # mu = 0.7 < the pivoting threshold: in the rigid-body solution both blocks slip from the
    # first instant with no impulsive normal force, so until the pulse ends
    # v(t) = I(t) S / m - mu g t (Coulomb), and after it (still sliding) v = i S / m - mu g t.
    mu = 0.7
    exact = lambda t: pulse.impulse * block.front_area / block.mass - mu * G * t  # noqa: E731
    # Plain force mode is accurate when the normal contact is hard compared with the pulse
    # (tau = 20 us << t_o ~ 1 ms, dt = tau / 10) and friction keeps its default soft reference
    # (tau_f = 20 ms; with tau_f = tau = 20 us the friction reference term b_f |v_t| makes
    # force mode 4-5% low again, docs/sim3d.md):
    hard = ContactSettings(friction=mu, time_constant=2e-5, timestep=2e-6)
    v, t = _velocity_after_pulse(block, pulse, hard, "force")
    # 0.3%: measured +0.01% (squat) / -0.18% (slender)
    assert v == pytest.approx(exact(t), rel=3e-3)
    # The default ("auto" at tau = 2 ms, dt = 0.2 ms) reproduces that answer: 1%, measured
    # -0.5% / -0.2% (the extra is the 2 ms contact's short settling during the kicked steps)
    v_auto, t_auto = _velocity_after_pulse(block, pulse, ContactSettings(friction=mu), "auto")
    assert v_auto == pytest.approx(exact(t_auto), rel=1e-2)
    # Plain force mode with the soft default contact loses 11-13% of the momentum to the
    # spurious normal impulse (the hop) ...
    v_force, t_force = _velocity_after_pulse(block, pulse, ContactSettings(friction=mu), "force")
    assert v_force < 0.95 * exact(t_force)
    # ... and still 2-3% at dt = 10 us: the artefact comes from the contact being soft
    # compared with the pulse (tau > t_o), not from the time step
    fine = ContactSettings(friction=mu, timestep=1e-5)
    v_fine, t_fine = _velocity_after_pulse(block, pulse, fine, "force")
    assert v_fine < 0.99 * exact(t_fine)
    v_fine_auto, t_fine_auto = _velocity_after_pulse(block, pulse, fine, "auto")
    assert v_fine_auto == pytest.approx(exact(t_fine_auto), rel=3e-3)  # measured -0.1% / -0.24%


def test_pivoting_50kg_peak_rotation_and_first_impact_match_planar_equation():
    from blastscale.rocking import simulate as planar_rocking

    pulse = paper_pulse(50.0)
    ref = planar_rocking(PAPER_BLOCK, pulse, 3.0)  # paper Eq. (eom), blastscale.rocking
    assert not ref.collapsed
    r = planar(run_block(PAPER_BLOCK, pulse, 1.5, contact=ContactSettings(friction=2.0)))
    # 3% (issue); measured 0.001%: the pivot sticks (mu = 2 > 1.6), no uplift
    assert r.summary["max_rotation_rad"] == pytest.approx(ref.max_rotation, rel=0.03)
    assert not r.summary["collapsed"]
    # the pivot (rear edge) does not slip: 1 mm; measured 0.08 mm of soft-contact creep, while
    # the lifting front edge moves 2b (1 - cos theta) = 6.3 mm (a recorder on the wrong edge fails)
    assert r.summary["max_sliding_m"] < 1e-3
    # first impact (theta back to 0, 1.38 s): 1% covers the soft contact's ms-scale settling
    t_impact = r.time[int(np.argmax((r.time > 0.1) & (r.rotation_y <= 0.0)))]
    assert t_impact == pytest.approx(ref.first_impact_time, rel=0.01)


def test_pivoting_100kg_overturns_like_planar_equation():
    from blastscale.rocking import simulate as planar_rocking

    pulse = paper_pulse(100.0)
    ref = planar_rocking(PAPER_BLOCK, pulse, 3.0)
    assert ref.collapsed
    r = block_summary(run_block(PAPER_BLOCK, pulse, 1.5, contact=ContactSettings(friction=2.0), record_every=10))
    assert r["collapsed"]
    # theta passes alpha at the planar solution's time (0.99 s); 2% (record_every = 10 steps = 2 ms)
    assert r["collapse_time_s"] == pytest.approx(ref.collapse_time, rel=0.02)


def test_housner_restitution_emerges_from_inelastic_contact():
    from blastscale.rocking import housner_restitution

    a = PAPER_BLOCK.alpha
    e_housner = 1 - 1.5 * math.sin(a) ** 2
    assert housner_restitution(a) == pytest.approx(e_housner, rel=1e-12)
    th0 = 0.5 * a
    r = planar(run_block(PAPER_BLOCK, None, 3.0, contact=ContactSettings(friction=2.0), initial_rotation=th0))
    th = r.rotation_y
    k = int(np.argmax(th < 0))  # first impact
    th1 = -th[k:][: int(np.argmax(np.diff(th[k:]) > 0)) + 1].min()  # peak on the other side
    # energy after one impact: cos(a - th1) - cos(a) = e^2 [cos(a - th0) - cos(a)]
    e_eff = math.sqrt((math.cos(a - th1) - math.cos(a)) / (math.cos(a - th0) - math.cos(a)))
    # 2% (issue); measured +0.04%
    assert e_eff == pytest.approx(e_housner, rel=0.02)
    # Housner's impact is plastic: no bounce off the new edge. 1 mm; measured 0.10 mm (the
    # ratio e is insensitive to the contact damping down to zeta = 0.2, but the bounce is not:
    # zeta = 0.5 / 0.2 lift the block 2.2 / 9.5 mm)
    assert r.summary["max_uplift_m"] < 1e-3


@pytest.mark.parametrize("factor, overturns", [(0.97, False), (1.03, True)])
def test_overturning_threshold_within_3_percent(factor, overturns):
    from blastscale.rocking import simulate as planar_rocking

    a = PAPER_BLOCK.alpha
    crit = PAPER_BLOCK.frequency_parameter(G) * math.sqrt(2 * (1 - math.cos(a)))  # Housner 1963
    ref = planar_rocking(PAPER_BLOCK, None, 4.0, theta_dot0=factor * crit)
    assert ref.collapsed is overturns
    # stop 0.1 s after the planar solution passes alpha: the 3D block must have passed it too
    # (|theta| > alpha is the criterion, not a fall far beyond it)
    T = 4.0 if ref.collapse_time is None else ref.collapse_time + 0.1
    r = block_summary(
        run_block(
            PAPER_BLOCK,
            None,
            T,
            contact=ContactSettings(friction=2.0),
            initial_angular_velocity=factor * crit,
            record_every=20,
        )
    )
    assert r["collapsed"] is overturns
    if overturns:
        # 1% (the time to creep over the unstable top is sensitive): measured +0.07%
        assert r["collapse_time_s"] == pytest.approx(ref.collapse_time, rel=0.01)
        assert r["max_rotation_rad"] < 1.2 * a


def test_block_at_rest_stays_put_for_5_seconds():
    r = planar(run_block(PAPER_BLOCK, None, 5.0, contact=ContactSettings(friction=0.7), record_every=50))
    # 1 um / 1 urad: far below anything reported (the ~1 um static penetration is constant)
    assert np.max(np.abs(r.sliding)) < 1e-6
    assert np.max(np.abs(r.rotation_y)) < 1e-6
    assert np.ptp(r.uplift) < 1e-6


# -- results ----------------------------------------------------------------------------
def test_numpy_scalars_are_accepted_in_the_mjcf():
    # numpy 2 reprs scalars as np.float64(...): the MJCF writer must print plain numbers
    blk = RectangularBlock(np.float64(2.0), np.float64(1.0))
    c = ContactSettings(friction=np.float64(0.5), timestep=np.float64(1e-4))
    r = planar(run_block(blk, None, 0.01, contact=c))
    assert abs(r.rotation_y[-1]) < 1e-9


def test_block_dataset_carries_units_and_dimensions():
    r = run_block(PAPER_BLOCK, None, 0.01, contact=ContactSettings())
    ds = block_dataset(r)
    assert ds["rotation_y"].attrs["units"] == "rad" and ds["time"].attrs["units"] == "s"
    assert ds["velocity_x"].attrs["dimension"] == "velocity" and ds["sliding"].attrs["dimension"] == "length"
    assert ds.sizes["time"] == r.time.size and ds.attrs["collapsed"] == 0


def test_summary_is_strict_json_with_overturn_time_none_like_rocking():
    import json

    from blastscale.rocking import simulate as planar_rocking

    still = block_summary(run_block(PAPER_BLOCK, None, 0.01, contact=ContactSettings()))
    assert still["collapse_time_s"] is None
    assert planar_rocking(PAPER_BLOCK, None, 0.01).collapse_time is None  # the same convention
    json.dumps(still, allow_nan=False)  # strict JSON: no NaN anywhere
    # a fall: the first recorded time with |theta| > alpha
    crit = PAPER_BLOCK.frequency_parameter(G) * math.sqrt(2 * (1 - math.cos(PAPER_BLOCK.alpha)))
    fall = planar(
        run_block(
            PAPER_BLOCK,
            None,
            2.0,
            contact=ContactSettings(friction=2.0),
            initial_angular_velocity=1.2 * crit,
            record_every=10,
        )
    )
    k = int(np.argmax(np.abs(fall.rotation_y) > PAPER_BLOCK.alpha))
    assert k > 0 and fall.summary["collapse_time_s"] == fall.time[k]
