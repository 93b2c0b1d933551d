"""The report's figures, chosen from the study result (a registry: a new engine adds a builder).

Each :class:`Figure` says when it applies to a :class:`~blastscale.study.StudyResult` and
builds a matplotlib figure; :func:`render_figures` returns PNG bytes (Agg backend, no display).
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..plots.assembly import assembly_figure, snapshot_figure
from ..plots.column import plot_column_comparison, plot_ensemble_envelope, plot_point_histories, shared_legend
from ..plots.rocking import rocking_figure
from ..structures.assembly import Assembly
from .markup import format_charge

__all__ = ["Figure", "FIGURES", "render_figures", "png_bytes"]


@dataclass(frozen=True)
class Figure:
    """One figure of the report: file ``name`` (.png), ``title``, ``caption``, ``applies(result)``,
    ``build(result) -> matplotlib Figure``."""

    name: str
    title: str
    caption: str
    applies: Callable
    build: Callable


def _pulses(result):
    import matplotlib.pyplot as plt

    d, sc = result.design, result.scenario
    systems = [(result.blast, "prototype", "ms", 1e3, "MPa", 1e-6)]
    if d is not None:
        systems.append((d.specimen, "model", "us", 1e6, "MPa", 1e-6))
    fig, axes = plt.subplots(1, len(systems), figsize=(5.5 * len(systems), 3.6), layout="constrained", squeeze=False)
    for ax, (bp, who, tu, tf, pu, pf) in zip(axes[0], systems):
        p = bp.pulse(sc.blast.pulse_shape)
        dur = p.duration if np.isfinite(p.duration) and p.duration > 0 else bp.positive_duration
        t = np.linspace(0.0, 1.2 * dur, 400)
        ax.plot(t * tf, np.asarray(p.pressure(t)) * pf, color="C0" if who == "prototype" else "C1")
        ax.set_xlabel(f"time after arrival [{tu}]")
        ax.set_ylabel(f"reflected overpressure [{pu}]")
        ax.set_title(
            f"{who}: {format_charge(bp.charge_kg)} TNT at {bp.standoff_m:.4g} m (Z = "
            f"{bp.scaled_distance:.3g} m/kg$^{{1/3}}$)",
            fontsize=9,
        )
        ax.grid(alpha=0.3)
    return fig


def _planar(result):

    return rocking_figure(result.planar.prototype, similarity=None if result.design is None else result.planar)


def _three_d(result):
    cmp = result.response3d
    import matplotlib.pyplot as plt

    if result.scenario.structure.kind == "column":
        return plot_column_comparison(cmp.structure, cmp.prototype_dataset, cmp.upscaled_dataset)

    fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    plot_point_histories(cmp.prototype_dataset, cmp.upscaled_dataset, "point_displacement", ax=axes[0], legend=False)
    plot_point_histories(cmp.prototype_dataset, cmp.upscaled_dataset, "point_velocity", ax=axes[1], legend=False)
    shared_legend(fig, axes[0])
    return fig


def _ensemble(result):
    import matplotlib.pyplot as plt

    ens = result.ensemble
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    for ax, point in zip(axes, (ens.points[0], ens.top_point)):
        plot_ensemble_envelope(ens, point=point, ax=ax)
    return fig


def _is_assembly(result) -> bool:

    return isinstance(result.structure, Assembly)


def _assembly(result):

    sc = result.scenario
    standoff = None if result.blast is None else sc.blast.standoff_m
    return assembly_figure(result.structure, standoff_m=standoff)


def _snapshots(result):

    cmp = result.response3d
    sim = (result.summary()["3d"] or {}).get("similarity") or {}
    top = sim.get("top_point")
    t_peak = ((sim.get("points") or {}).get(top) or {}).get("first_peak_time_s") if top else None
    return snapshot_figure(result.structure, cmp.prototype_dataset, cmp.upscaled_dataset, first_peak_time_s=t_peak)


#: The report's figures, in order.
FIGURES: tuple[Figure, ...] = (
    Figure(
        "blast_pulses",
        "Blast loads of the prototype and the model",
        "Reflected pressure on the front face at the stand-off, each system in its own units: the model's "
        "pulse is shorter and weaker; only its impulse follows the scaling law exactly.",
        lambda r: r.blast is not None,
        _pulses,
    ),
    Figure(
        "planar_rocking",
        "Planar rocking: prototype and up-scaled model",
        "Rocking angle, angular velocity and phase portrait of the prototype (solid) and of the model "
        "up-scaled to prototype units (dashed).",
        lambda r: r.planar is not None,
        _planar,
    ),
    Figure(
        "assembly",
        "The structure: elevation and plan",
        "The assembly as built, seen from the charge (elevation) and from above (plan); interfaces found by "
        "geometry shaded (blue between blocks, green on the ground; a joint seen edge on is a thick line), "
        "monitoring points in red.",
        _is_assembly,
        _assembly,
    ),
    Figure(
        "snapshots_3d",
        "Snapshots of the response: prototype and up-scaled model",
        "Side sections (x-z, the blast from -x) at a few instants (the start, the top point's first peak, the "
        "end): each block turned by its rotation about y and moved by its centre of mass; prototype filled, "
        "model up-scaled to prototype units dashed; small motions amplified by the stated factor.",
        lambda r: _is_assembly(r) and r.response3d is not None,
        _snapshots,
    ),
    Figure(
        "response_3d",
        "3D rigid-body response (MuJoCo): prototype and up-scaled model",
        "Histories of the prototype (solid) and of the model up-scaled to prototype units (dashed).",
        lambda r: r.response3d is not None,
        _three_d,
    ),
    Figure(
        "ensemble_envelopes",
        "3D ensembles: envelopes of the prototype and of the up-scaled model",
        "Minimum-maximum envelopes and means of the x displacement over the members (loads perturbed by a "
        "relative 1e-6 or as set), lowest and highest monitoring points. For a chaotic structure the "
        "envelopes, not single histories, measure similarity.",
        lambda r: r.ensemble is not None,
        _ensemble,
    ),
)


def png_bytes(fig, dpi: int = 110) -> bytes:
    """The figure as PNG bytes (closed afterwards)."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    try:
        fig.savefig(buf, format="png", dpi=dpi)
    finally:
        plt.close(fig)
    return buf.getvalue()


def render_figures(result) -> list[tuple[Figure, bytes]]:
    """Every applicable figure of ``result`` as (Figure, PNG bytes), Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    return [(f, png_bytes(f.build(result))) for f in FIGURES if f.applies(result)]
