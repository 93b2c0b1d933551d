"""3D single block, prototype vs reduced-scale model (issue #4, paper Sec. "FEM simulations"):
exact scaling of the engine, the paper's cases at lambda = 1/200, the Hopkinson-Cranz law, the
impulsive limit and the delivered momentum.

The block is the one-body case of the structure engine: the model experiment runs through
:func:`~blastscale.analysis.structure3d.compare_structure3d` and is read through the block's planar
view (:func:`~blastscale.analysis.block3d_similarity.block_dataset`, ``block_summary``,
``block_similarity``), up-scaled by :func:`~blastscale.analysis.compare.upscale_dataset` /
``upscale_summary``.
"""

import math

import numpy as np
import pytest

from blastscale.analysis.block3d_similarity import block_dataset, block_similarity, block_summary
from blastscale.analysis.compare import upscale_dataset
from blastscale.analysis.structure3d import compare_structure3d
from blastscale.analysis.systems import Settings3D, Systems3D
from blastscale.analysis.upscale import upscale_summary
from blastscale.blast.parameters import blast_parameters
from blastscale.sim3d import ContactSettings, MethodA, simulate_structure
from blastscale.similitude import design_model, scaling_factors
from blastscale.structures.block import RectangularBlock

PAPER_BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0))


def paper_pulse(charge, standoff=2.0):
    return blast_parameters(charge, standoff, blast_model="masi2021").pulse("friedlander")


def run_block(block, pulse, duration, **kw):
    """The block under Method A (``pulse`` on its front face, t = 0 at arrival): its Response3D."""
    return simulate_structure(block, MethodA(block, pulse), duration, **kw)


def compare_block(
    block,
    charge,
    standoff,
    scale,
    *,
    density_ratio=1.0,
    law="general",
    pulse_shape="friedlander",
    contact=None,
    duration=5.0,
    record_every=1,
):
    """The prototype block and its model experiment (masi2021 fits, Method A) through the
    structure comparison, read through the block's planar view: (design, comparison, prototype
    summary, up-scaled model summary, similarity figures)."""
    design = design_model(
        charge, standoff, scale, density_ratio=density_ratio, law=law, blast_model="masi2021", geometry=block
    )
    c = compare_structure3d(
        Systems3D.of_design(design, contact=contact, duration=duration),
        Settings3D(pulse_shape=pulse_shape, record_every=record_every),
    )
    sim = block_similarity(block_dataset(c.prototype), upscale_dataset(block_dataset(c.model), design.factors))
    return design, c, block_summary(c.prototype), upscale_summary(block_summary(c.model), design.factors), sim


def test_scale_invariance_lambda_1_200_upscaled_equals_full_scale():
    """Regression test of the engine's reference-unit normalisation (reference_factors): a block and
    its exactly scaled model run as the same MuJoCo model, so the up-scaled model equals the
    prototype to round-off. It holds by construction; it guards the normalisation, not MuJoCo."""
    lam = 1 / 200
    lt = math.sqrt(lam)
    c = ContactSettings(friction=0.7)
    pulse = paper_pulse(50.0)
    proto = block_dataset(run_block(PAPER_BLOCK, pulse, 0.4, contact=c))
    # the exactly similar pulse: pressure x lambda (gamma = varsigma = 1), time x sqrt(lambda)
    model = run_block(
        PAPER_BLOCK.scaled(scaling_factors(lam)),
        pulse.scaled(scaling_factors(lam)),
        0.4 * lt,
        contact=c.scaled(scaling_factors(lam)),
    )
    up = upscale_dataset(block_dataset(model), scaling_factors(lam))
    assert np.allclose(up["time"].values, proto["time"].values, rtol=1e-12, atol=0)
    # 1e-6 relative to the response's size (issue); measured 1e-13 (round-off)
    for name in ("rotation_y", "sliding", "angular_velocity_y", "velocity_x"):
        p, u = proto[name].values, up[name].values
        assert np.max(np.abs(u - p)) <= 1e-6 * np.max(np.abs(p)), name


@pytest.mark.parametrize(
    "block, charge, standoff, duration",
    [
        (PAPER_BLOCK, 50.0, 2.0, 2.0),
        (PAPER_BLOCK, 100.0, 2.0, 2.0),
        # the paper's non-slender block is self-inconsistent (docs/sim3d.md): both readings
        (RectangularBlock(height=10.0, width=3.5, depth=3.5), 2500.0, 3.0, 1.0),  # 2b = 3.5 m (alpha = 19.3 deg)
        (RectangularBlock.from_slenderness(10.0, math.radians(35.0), depth=3.5), 2500.0, 3.0, 2.0),  # alpha = 35 deg
    ],
    ids=["slender-50kg", "slender-100kg", "non-slender-2500kg-2b3.5m", "non-slender-2500kg-alpha35"],
)
def test_paper_cases_mu_07_model_upscaled_sliding_within_1_percent(block, charge, standoff, duration):
    _, _, p, m, _ = compare_block(
        block, charge, standoff, 1 / 200, contact=ContactSettings(friction=0.7), duration=duration, record_every=5
    )
    # 1% (issue): the model's pulse is not exactly similar (the blast fixes only the impulse),
    # measured 0.08-0.5%
    assert m["max_sliding_m"] == pytest.approx(p["max_sliding_m"], rel=0.01)
    assert m["collapsed"] == p["collapsed"]


def test_hopkinson_cranz_model_with_imposed_density_ratio_is_similar():
    design, c, _, _, sim = compare_block(
        PAPER_BLOCK,
        50.0,
        2.0,
        1 / 20,
        density_ratio=None,
        law="hopkinson-cranz",
        contact=ContactSettings(friction=2.0),
        duration=1.0,
        record_every=5,
    )
    assert design.density_ratio == pytest.approx(20**0.5, rel=1e-12)  # gamma = 1/sqrt(lambda)
    # finite-pulse departure only (DESIGN: ~1e-4 rad); measured 5e-5 rad on a 0.069 rad peak
    assert sim["max_abs_rotation_diff_rad"] < 2e-4
    assert c.model.dataset.attrs["setting_gravity_m_s2"] == pytest.approx(9.81, rel=1e-15)


def test_similarity_is_exact_in_the_impulsive_limit():
    *_, sim = compare_block(
        PAPER_BLOCK,
        50.0,
        2.0,
        1 / 200,
        pulse_shape="impulsive",
        contact=ContactSettings(friction=2.0),
        duration=1.0,
        record_every=5,
    )
    # the general law matches the impulse exactly, so with a Dirac load the model is exactly
    # similar: round-off only (measured 4e-15 rad); 1e-9 rad leaves room for solver round-off
    assert sim["max_abs_rotation_diff_rad"] < 1e-9


def test_upscaled_model_receives_the_prototype_momentum():
    # The general law makes the model's delivered blast momentum (impulse x area = momentum factor
    # gamma lambda^(7/2) of the prototype's) scale exactly: up-scaled by the momentum factor it equals the
    # prototype's i_r S. The exact-impulse force routine delivers i S to round-off (1e-12 relative).
    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    design, _, p, m, _ = compare_block(block, 50.0, 2.0, 1 / 200, density_ratio=0.5, duration=0.05)
    expected = design.prototype.reflected_impulse * block.front_area
    assert np.linalg.norm(p["delivered_impulse_Ns"]) == pytest.approx(expected, rel=1e-12)
    assert np.linalg.norm(m["delivered_impulse_Ns"]) == pytest.approx(expected, rel=1e-9)
