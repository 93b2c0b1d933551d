"""Rocking plots draw the data they are given (checked on the artists), take ax= and return it."""

from __future__ import annotations

import math

import numpy as np
import pytest

mpl = pytest.importorskip("matplotlib")
mpl.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from blastscale._validate import BlastscaleInputError  # noqa: E402
from blastscale.blast import blast_parameters  # noqa: E402
from blastscale.plots.rocking import (  # noqa: E402
    plot_angle,
    plot_phase_portrait,
    plot_pi_diagram,
    plot_planar_angular_velocity,
    plot_similarity,
    rocking_figure,
)
from blastscale.rocking import pi_diagram, simulate  # noqa: E402
from blastscale.scenario import Scenario  # noqa: E402
from blastscale.structures.block import RectangularBlock  # noqa: E402
from blastscale.study import Study  # noqa: E402

BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0))


def _planar(charge, duration, samples):
    """The Study's planar comparison of the paper's block at lambda = 1/20 (masi2021)."""
    sc = Scenario.default().with_values(
        {
            "engine": "planar",
            "critical_charge": False,
            "charge_kg": charge,
            "length": 1 / 20,
            "duration_s": duration,
            "samples": samples,
        }
    )
    return Study(sc).run().planar


@pytest.fixture(scope="module")
def run():
    return simulate(BLOCK, blast_parameters(50.0, 2.0, blast_model="masi2021").pulse(), 3.0)


def test_history_plots_draw_the_history(run):
    fig, axes = plt.subplots(1, 3)
    assert plot_angle(run, ax=axes[0]) is axes[0]
    assert plot_planar_angular_velocity(run, ax=axes[1]) is axes[1]
    assert plot_phase_portrait(run, ax=axes[2]) is axes[2]
    np.testing.assert_array_equal(axes[0].lines[0].get_ydata(), run.theta)
    np.testing.assert_array_equal(axes[1].lines[0].get_ydata(), run.theta_dot)
    np.testing.assert_array_equal(axes[2].lines[0].get_xdata(), run.theta)
    assert "[rad]" in axes[0].get_ylabel() and "[s]" in axes[0].get_xlabel()
    plt.close(fig)


def test_similarity_overlay_and_figure():
    sim = _planar(50.0, 2.0, 201)
    ax = plot_similarity(sim, "theta")
    np.testing.assert_array_equal(ax.lines[1].get_ydata(), sim.theta_model)
    assert "up-scaled" in ax.get_legend().get_texts()[1].get_text()
    fig = rocking_figure(sim.prototype, sim)
    assert len(fig.axes) == 3
    with pytest.raises(BlastscaleInputError, match="quantity"):
        plot_similarity(sim, "sliding")
    plt.close("all")
    # both overturn: the title gives the figures that measure similarity (rocking phase, fall)
    over = _planar(100.0, 4.0, 401)
    title = plot_similarity(over, "theta").get_title()
    assert f"to tipping {over.max_abs_rotation_diff_to_tipping:.2e}" in title and "tipping shift" in title
    plt.close("all")


def test_pi_plot_shows_curve_and_asymptotes():
    pi = pi_diagram(BLOCK, n=5)
    ax = plot_pi_diagram(pi)
    np.testing.assert_array_equal(ax.lines[0].get_xdata(), pi.critical_impulse)
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert len(ax.lines) == 3
    plt.close("all")


def _visible_tick_boxes(ax, axis):
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    labels = axis.get_ticklabels(minor=False) + axis.get_ticklabels(minor=True)
    lo, hi = sorted(ax.get_xlim() if axis is ax.xaxis else ax.get_ylim())
    boxes = []
    for lab in labels:
        x, y = lab.get_position()
        v = x if axis is ax.xaxis else y
        if lab.get_visible() and lab.get_text() and lo <= v <= hi:
            boxes.append(lab.get_window_extent(renderer))
    return boxes


@pytest.mark.parametrize("shape", ["triangular", "friedlander"])
def test_pi_plot_tick_labels_do_not_overlap(shape):
    """The triangular curve of the paper's block spans 1.46 decades of impulse, where
    matplotlib labelled the minor ticks (3x10^4 and 4x10^4 overlapped): every visible tick
    label must now stand clear of the others, and at least two are labelled per axis."""
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    plot_pi_diagram(pi_diagram(BLOCK, n=8, shape=shape), ax=ax)
    for axis in (ax.xaxis, ax.yaxis):
        boxes = _visible_tick_boxes(ax, axis)
        assert len(boxes) >= 2
        for a, b in zip(boxes, boxes[1:]):
            assert not any(a.overlaps(c) for c in boxes if c is not a)
    plt.close(fig)
