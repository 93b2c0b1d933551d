"""Every figure type blastscale writes, rendered (Agg): no text clipped by the figure's edge, no two texts
overlapping (issue #39, deliverable 2), measured with matplotlib's own extents (``Text.get_window_extent``
with the canvas's renderer, after a full draw: the layout engine has run). The similarity map's cells carry
their values.

The figure functions, enumerated from ``src/blastscale/plots`` and the report (``FIGURE_TYPES`` below; a
new public figure function in plots/ fails ``test_every_figure_function_is_covered`` until it is added):

* report (``report.figures.FIGURES``): blast_pulses, planar_rocking, assembly, snapshots_3d, response_3d
  (a column and an assembly: ``plots.column.plot_column_snapshots``, ``plots.sim3d.finish_side_view``),
  ensemble_envelopes; ``report.fired.fired_figures`` (``plots.fired.plot_gauge``, ``plots.fired.plot_marker``);
* ``plots.plan.plot_plan`` (the plan's figure), ``plots.similarity_map.plot_similarity_map``,
  ``plots.fragility.plot_fragility``, ``plots.capacity.plot_capacity``, ``plots.rocking.plot_pi_diagram``
  (``capacity --plot``), ``plots.rocking.rocking_figure`` (``rocking --plot``), ``plots.column``
  (``column --plot``), ``plots.sim3d.plot_comparison``, ``plots.similitude.scaling_factors_figure``
  (``plot_scaling_factor``),
  ``plots.assembly.assembly_figure`` (``show --plot``, with a title), ``plots.motion.motion_figure`` (the
  GIF's frames, ``render_frames``; the iso and side views).

One small input per type, built once per module (three short studies: a planar block, a 3-drum column with
a 2-member ensemble, a 4-unit wall; 0.05 s simulated in 3D; a block's 3D datasets). Tolerance: two texts overlap when their boxes
share more than 1 px in both directions (antialiasing and rounding give a box a pixel's slack); a text is
clipped when its box passes the figure's edge by more than 1 px.
"""

from __future__ import annotations

import ast
import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

mpl = pytest.importorskip("matplotlib")
mpl.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.text import Text  # noqa: E402

from blastscale.scenario import Scenario, load_scenario  # noqa: E402
from blastscale.study import Study  # noqa: E402

SLACK_PX = 1.0


def _drawn_tick_labels(fig) -> tuple[set, set]:
    """(drawn, hidden) tick-label ids: matplotlib keeps tick objects outside the view limits, undrawn."""
    drawn, hidden = set(), set()
    for ax in fig.axes:
        axes = [ax.xaxis, ax.yaxis] + ([ax.zaxis] if hasattr(ax, "zaxis") else [])
        for axis in axes:
            lo, hi = sorted(axis.get_view_interval())
            span = hi - lo
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                loc = tick.get_loc()
                inside = loc is not None and lo - 1e-9 * abs(span) <= loc <= hi + 1e-9 * abs(span)
                for lab in (tick.label1, tick.label2):
                    (drawn if inside and lab.get_visible() else hidden).add(id(lab))
    return drawn, hidden


def text_problems(fig) -> list[str]:
    """Texts of ``fig`` clipped by its edge or overlapping another text, in words (empty: none)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    _, hidden = _drawn_tick_labels(fig)
    boxes = []
    for t in fig.findobj(Text):
        if id(t) in hidden or not t.get_visible() or not t.get_text().strip():
            continue
        if any(not a.get_visible() for a in _parents(t)):
            continue
        boxes.append((t.get_text(), t.get_window_extent(renderer)))
    fb = fig.bbox
    out = []
    for text, b in boxes:
        if b.x0 < fb.x0 - SLACK_PX or b.y0 < fb.y0 - SLACK_PX or b.x1 > fb.x1 + SLACK_PX or b.y1 > fb.y1 + SLACK_PX:
            out.append(f"clipped: {text!r} at {tuple(np.round(b.extents))} in {tuple(np.round(fb.extents))}")
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            (ta, a), (tb, b) = boxes[i], boxes[j]
            dx = min(a.x1, b.x1) - max(a.x0, b.x0)
            dy = min(a.y1, b.y1) - max(a.y0, b.y0)
            if dx > SLACK_PX and dy > SLACK_PX:
                out.append(f"overlap: {ta!r} and {tb!r} ({dx:.0f} x {dy:.0f} px)")
    return out


def _parents(artist):
    """The artists above ``artist`` (its axes, legend, ...)."""
    out, a = [], getattr(artist, "axes", None)
    if a is not None:
        out.append(a)
    return out


# -- the checker itself: it must say "no" where the answer is no ------------------------------------------


def test_checker_finds_overlap_and_clipping_and_passes_a_clean_figure():
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.text(0.5, 0.5, "first label", transform=ax.transAxes)
    ax.text(0.52, 0.5, "second label", transform=ax.transAxes)
    fig.text(0.9, 0.5, "runs off the right edge")
    found = text_problems(fig)
    plt.close(fig)
    assert any(p.startswith("overlap: 'first label'") for p in found)
    assert any(p.startswith("clipped: 'runs off") for p in found)
    fig, ax = plt.subplots(figsize=(3, 2), layout="constrained")
    ax.set_title("fits")
    ax.set_xlabel("x [m]")
    assert text_problems(fig) == []  # the edge case: ordinary ticks and labels, nothing wrong
    plt.close(fig)


# -- inputs, one per type ---------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def studies():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        planar = Study(
            Scenario.default().with_values(
                {"engine": "planar", "critical_charge": False, "duration_s": 1.0, "samples": 400}
            )
        ).run()
        column = Study(
            load_scenario("paper_column_square_250kg").with_values(
                {"structure.drums": 3, "simulation.duration_s": 0.05, "simulation.ensemble_members": 2}
            )
        ).run()
        wall = Study(
            load_scenario("wall_running_bond_lambda20").with_values(
                {"structure.courses": 2, "structure.units_per_course": 2, "simulation.duration_s": 0.05}
            )
        ).run()
    return SimpleNamespace(planar=planar, column=column, wall=wall)


def _block_comparison():
    """plots.sim3d's 2 x 2 figure of a block's datasets (as tests/system/test_sim3d_cli.py builds them)."""
    from blastscale.analysis.block3d_similarity import block_dataset
    from blastscale.plots.sim3d import plot_comparison
    from blastscale.sim3d import ContactSettings, simulate_structure
    from blastscale.structures.block import RectangularBlock

    block = RectangularBlock(2.0, 1.0)
    r = block_dataset(simulate_structure(block, None, 0.05, contact=ContactSettings(), initial_angular_velocity=0.5))
    return plot_comparison(block, r, r)


def similarity_map_dataset():
    """A 5 x 3 (lambda, gamma) map over two charges: errors over three decades, one case without a design,
    one whose outcome differs (the shapes and names of :func:`blastscale.sweeps.similarity_map.similarity_map`)."""
    import xarray as xr

    lam = np.array([1 / 200, 1 / 100, 1 / 50, 1 / 20, 1 / 10])
    gam = np.array([0.889, 0.95, 1.0])
    shape = (lam.size, gam.size, 2, 1)
    err = 10 ** np.random.default_rng(0).uniform(-4, -1, shape)
    valid = np.ones(shape, bool)
    valid[0, 0, 0, 0] = False
    agree = np.ones(shape, bool)
    agree[1, 2, 1, 0] = False
    dims = ("length", "density_ratio", "charge_kg", "standoff_m")
    data = {"error": err, "valid": valid, "outcomes_agree": agree, "worst_ratio": err / 0.01}
    return xr.Dataset(
        {k: (dims, v) for k, v in data.items()},
        coords={"length": lam, "density_ratio": gam, "charge_kg": [50.0, 100.0], "standoff_m": [2.0]},
        attrs={"engine": "planar", "error_units": "rad"},
    )


def plan_input(odds=(1.0,)):
    """Five materials at five scales: two scales feasible for four of them (odds cycling through ``odds``),
    the rest rejected by the lab's charge or height (the keys and values of :class:`blastscale.planning.Plan`)."""
    mats = {"marble": 1.0, "limestone": 0.85, "sandstone": 0.8, "granite": 1.03, "balsa": 0.06}
    designs, rejected, k = [], [], 0
    for n in (10, 20, 50, 100, 200):
        for m, g in mats.items():
            row = {"scale": 1 / n, "tnt_equivalent_kg": 250.0 * g / n**3, "material": m}
            if n in (20, 50) and m != "balsa":
                designs.append({**row, "p_outcome_agree": odds[k % len(odds)], "pareto": n == 20})
                k += 1
            else:
                rejected.append({**row, "constraints": ["charge_max_kg" if n < 20 else "specimen_min_height_m"]})
    return SimpleNamespace(
        designs=designs, rejected=rejected, recommendation={"design": 0}, prototype={"load_method": "C"}
    )


def _fragility_input():
    """A damage-state fragility as the command computes it (its real per-state fits, :func:`_state_fits`), from a
    drawn capacity per draw (lognormal, median 90 kg, beta 0.4) and levels by the charge over it."""
    from blastscale.analysis.damage import LEVELS
    from blastscale.sweeps.fragility import FragilityResult, _state_fits

    W = np.geomspace(20.0, 400.0, 8)
    cap = np.exp(np.random.default_rng(3).normal(np.log(90.0), 0.4, size=(8, 32)))
    r = W[:, None] / cap
    level = np.select([r > 2.0, r > 1.4, r > 1.1, r > 0.8], [LEVELS.index(n) for n in LEVELS[:0:-1]], 0)
    states = _state_fits(W, level, np.ones(level.shape, dtype=bool), "damage")
    c = states["collapse"]
    fields = {
        "blast.standoff_m": {
            "path": "blast.standoff_m",
            "distribution": "uniform",
            "params": [9.5, 10.5],
            "relative": False,
        },
        "structure.friction": {
            "path": "structure.friction",
            "distribution": "normal",
            "params": [0.7, 0.05],
            "relative": False,
        },
    }
    return FragilityResult(W, c.exceeded, 32, c.probability, c.fit, fields, 0, 1.0, criterion="damage", states=states)


def _capacity_figure():
    from blastscale.cli.capacity import _capacity_figure as build

    R = np.geomspace(2.0, 20.0, 12)
    curve = SimpleNamespace(
        standoff_m=R, critical_charge_kg=5.0 * R**2.2, blast_model="masi2021", pulse_shape="friedlander"
    )
    model = SimpleNamespace(upscaled_charge_kg=5.3 * R**2.2, scale=0.05, density_ratio=1.0)
    return build(SimpleNamespace(curve=curve, model=model, safe_standoff_m=7.3), 200.0)


def _capacity_3d_figure():
    """plot_capacity_3d: W_c(R) of a column at three stand-offs with intervals, and its P-I points."""
    from blastscale.plots.capacity import plot_capacity_3d

    R = np.array([10.0, 15.0, 20.0])
    W = np.array([554.2, 1120.4, 1950.0])
    results = [
        SimpleNamespace(standoff_m=r, critical_charge_kg=w, interval_kg=[0.99 * w, 1.01 * w]) for r, w in zip(R, W)
    ]
    p, i = 2.0e6 * (R / 10.0) ** -1.5, 4.0e3 * (R / 10.0) ** -0.3
    pi = {
        "reflected_pressure_Pa": list(p),
        "reflected_impulse_Pa_s": list(i),
        "interval_pressure_Pa": [[0.98 * x, 1.02 * x] for x in p],
        "interval_impulse_Pa_s": [[0.99 * x, 1.01 * x] for x in i],
    }
    return plot_capacity_3d(results, pi).figure


def _pi_figure():
    from blastscale.plots.rocking import plot_pi_diagram

    i = np.geomspace(200.0, 2e4, 30)
    pi = SimpleNamespace(
        critical_impulse=i,
        peak_pressure=1.2e3 + 4e6 / (i - 150.0),
        impulse_asymptote=150.0,
        pressure_asymptote=1.2e3,
        shape="friedlander",
    )
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    plot_pi_diagram(pi, ax=ax)
    ax.plot([900.0], [9e3], "o", color="C3", label="critical: 79.87 kg at 2 m")
    ax.legend(fontsize=8)
    return fig


def _fired_figures(design, monkeypatch):
    """The report's fired figures (gauge, marker) of a synthetic shot, captured before they become PNGs."""
    from blastscale.blast.pulses import Friedlander
    from blastscale.report import fired

    got = []
    monkeypatch.setattr(fired, "png_bytes", lambda fig: got.append(fig) or b"")
    t = np.linspace(0.0, 4e-3, 800)
    fit = SimpleNamespace(
        arrival_time_s=1e-3, positive_duration_s=4e-4, pressure=lambda tt: 1e5 * np.exp(-(((tt - 1.2e-3) / 3e-4) ** 2))
    )
    ts = np.linspace(0.0, 0.2, 200)
    track = {"t": ts, "ux": 1e-3 * np.sin(20 * ts)}
    peak = SimpleNamespace(first_peak_m=1e-3, first_peak_time_s=0.078)
    result = SimpleNamespace(
        summary={
            "gauges": {
                "G1": {
                    "predicted_peak_pressure_Pa": 9e4,
                    "predicted_impulse_Pa_s": 0.3 * 9e4 * design.specimen.positive_duration,
                    "predicted_arrival_time_s": 1e-3,
                }
            }
        },
        design=design,
        gauges={"G1": (fit, t, fit.pressure(t))},
        markers={"M1": {"measured": {**track, "peak": peak}, "predicted": track, "refit": track}},
    )
    assert Friedlander is fired.Friedlander
    fired.fired_figures(result)
    return got


def _figure_of(build):
    out = build()
    return out.figure if hasattr(out, "figure") and not hasattr(out, "savefig") else out


def _report(name, which):
    from blastscale.report.figures import FIGURES

    fig = next(f for f in FIGURES if f.name == name)
    return lambda s: (
        (fig.applies(getattr(s, which)) or pytest.fail(f"{name} does not apply")) and fig.build(getattr(s, which))
    )


#: Figure type -> builder of one figure from the module's studies (the functions each covers in the comment).
FIGURE_TYPES = {
    "blast_pulses": _report("blast_pulses", "column"),
    "planar_rocking": _report("planar_rocking", "planar"),  # rocking_figure: plot_angle, _velocity, _phase, _similarity
    "assembly": _report("assembly", "wall"),  # assembly_figure, draw_view
    "snapshots_3d": _report("snapshots_3d", "wall"),  # snapshot_figure
    "response_3d_column": _report("response_3d", "column"),  # plot_column_comparison, _snapshots, _point_histories
    "response_3d_assembly": _report("response_3d", "wall"),  # plot_point_histories, shared_legend
    "ensemble_envelopes": _report("ensemble_envelopes", "column"),  # plot_ensemble_envelope
    "block_comparison_3d": lambda s: (
        _block_comparison()
    ),  # plot_comparison: plot_history, plot_rotation, plot_sliding, plot_velocity, plot_block_angular_velocity, plot_snapshots
    "show_plot": lambda s: __import__("blastscale.plots.assembly", fromlist=["x"]).assembly_figure(
        s.wall.structure, title="My wall: a running-bond wall of four units under 10 kg at 5 m", standoff_m=5.0
    ),
    "similarity_map": lambda s: __import__("blastscale.plots.similarity_map", fromlist=["x"]).plot_similarity_map(
        similarity_map_dataset()
    ),
    "plan_odds_vary": lambda s: __import__("blastscale.plots.plan", fromlist=["x"]).plot_plan(
        plan_input((0.4, 0.9, 1.0))
    ),
    "fragility": lambda s: __import__("blastscale.plots.fragility", fromlist=["x"]).plot_fragility(_fragility_input()),
    "capacity": lambda s: _capacity_figure(),
    "capacity_3d": lambda s: _capacity_3d_figure(),
    "pi_diagram": lambda s: _pi_figure(),
    "scaling_factors": lambda s: __import__("blastscale.plots.similitude", fromlist=["x"]).scaling_factors_figure(
        __import__("blastscale.similitude.curves", fromlist=["x"]).scaling_curves(
            50.0, 2.0, np.geomspace(0.005, 1.0, 8)
        )
    ),
}


#: Figures another helper of issue #38/#39 changes in this round: checked here as they are, expected to fail
#: until their owner's change lands (the lead re-checks at merge; strict=False: a pass is welcome).
@pytest.mark.parametrize("kind", sorted(FIGURE_TYPES))
def test_no_text_overlaps_or_is_clipped(kind, studies):
    fig = _figure_of(lambda: FIGURE_TYPES[kind](studies))
    try:
        assert text_problems(fig) == []
    finally:
        plt.close(fig)


def test_fired_figures_text(studies, monkeypatch):
    figs = _fired_figures(studies.column.design, monkeypatch)
    assert len(figs) == 2  # the gauge's and the marker's
    for fig in figs:
        try:
            assert text_problems(fig) == []
        finally:
            plt.close(fig)


@pytest.mark.parametrize("view", ["iso", "side"])
def test_motion_frames_text(view, studies):
    from blastscale.plots.motion import motion_figure
    from blastscale.sim3d.replay import motion_of

    fig, update = motion_figure(motion_of(studies.column.response3d.prototype_dataset), view=view)
    update(0)
    try:
        assert text_problems(fig) == []
    finally:
        plt.close(fig)


def test_similarity_map_cells_carry_their_values():
    from blastscale.plots.similarity_map import plot_similarity_map

    ds = similarity_map_dataset()
    fig = plot_similarity_map(ds)
    try:
        texts = [[t.get_text() for t in ax.texts] for ax in fig.axes if ax.get_label() != "<colorbar>"]
        assert len(texts) == 2 and all(len(t) == 15 for t in texts)  # every cell of both panels labelled
        assert texts[0].count("no\ndesign") == 1  # the case without a design says so
        assert sum(t.startswith("\u00d7") for t in texts[1]) == 1  # the outcome that differs is marked
        e = ds["error"].values[3, 1, 0, 0]  # lambda 1/20, gamma 0.95, 50 kg: its value, 2 digits, in its cell
        assert f"{e:.2g}".replace("e-0", "e-") in texts[0]
        ticks = [t.get_text() for t in fig.axes[0].get_xticklabels()]
        assert ticks == ["1/200", "1/100", "1/50", "1/20", "1/10"]  # the grid's own values, no log ticks
        assert [t.get_text() for t in fig.axes[0].get_yticklabels()] == ["0.889", "0.95", "1"]
    finally:
        plt.close(fig)


def test_plan_odds_visible_and_colour_bar_only_when_they_vary():
    from blastscale.plots.plan import plot_plan

    fig = plot_plan(plan_input((1.0,)))
    try:
        panels = [ax for ax in fig.axes if ax.get_visible() and ax.get_label() != "<colorbar>"]
        assert len(panels) == 5  # one per material
        assert not any(ax.get_label() == "<colorbar>" for ax in fig.axes)  # all odds 1: no colour bar ...
        labels = [t.get_text() for t in panels[0].get_legend().get_texts()]
        assert any("with odds 1.00" in t for t in labels)  # ... the odds in the legend instead
        star = next(c for c in panels[0].collections if c.get_label() == "recommended")
        odds = next(c for c in panels[0].collections if c.get_label().startswith("with odds"))
        assert star.get_zorder() < odds.get_zorder()  # the star behind the design's marker
        assert "Method C" in fig._suptitle.get_text()  # the load method the plan assumed
    finally:
        plt.close(fig)
    fig = plot_plan(plan_input((0.4, 0.9, 1.0)))
    try:
        assert any(ax.get_label() == "<colorbar>" for ax in fig.axes)
    finally:
        plt.close(fig)


def test_every_figure_function_is_covered():
    """Each public function of plots/ that draws is named in this module (directly or by the figure it is
    part of, in ``FIGURE_TYPES``' comments and the module docstring)."""
    here = Path(__file__).read_text()
    plots = Path(__import__("blastscale.plots", fromlist=["x"]).__file__).parent
    missing = []
    for f in sorted(plots.glob("*.py")):
        tree = ast.parse(f.read_text())
        for node in tree.body:
            if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                src = ast.get_source_segment(f.read_text(), node) or ""
                draws = any(k in src for k in ("ax.", "fig.", "plt.", "axes_or_new"))
                if draws and node.name not in here:
                    missing.append(f"{f.stem}.{node.name}")
    assert missing == [], missing
