"""The words of the 3D outcomes in the report and on the console: the stability rule under gravity
alone (:func:`blastscale.sim3d.results.stability_of`) and the first peaks at the monitoring points."""

from __future__ import annotations

import html

from ..analysis.gravity_alone import STABILITY_EXTENSION_CAP

__all__ = ["STABILITY_RULE", "stability_words", "stability_lead", "first_peak_rows"]

#: The rule behind "stands / settles / collapses / moving" (blastscale.sim3d.results.stability_of).
STABILITY_RULE = (
    "Collapses: a block fell (its centre of mass dropped by more than half its height, or it turned "
    "by more than 45 deg); stands: at rest at the end (every block slower than 1e-4 sqrt(g H) over "
    "the last tenth of the run) with no centre of mass displaced by more than 1e-3 of the height H; "
    "settles: at rest, displaced more, no block fallen; moving: neither at rest nor fallen by the "
    "end of a run extended until the rule decides, its duration doubled up to "
    f"{STABILITY_EXTENSION_CAP:g} x the one asked for (undecided). docs/assemblies.md."
)


def stability_words(stability: str) -> str:
    """The outcome under gravity alone as the end of a sentence ("the structure ...")."""
    return (
        f"is still moving at the end of a run extended to {STABILITY_EXTENSION_CAP:g} x its duration (undecided: "
        "run longer)"
        if stability == "moving"
        else stability
    )


def _g(x) -> str:
    return "-" if x is None else format(x, ".2g")


def stability_lead(prototype: dict) -> str:
    """The report's lead paragraph under gravity alone (HTML), or "" when the run had a load."""
    stab = (prototype or {}).get("stability")
    if stab is None:
        return ""
    cls = "ok" if stab in ("stands", "settles") else "bad"
    return (
        f'<p class="lead">Under gravity alone the structure <span class="{cls}">'
        f"{html.escape(stability_words(stab))}</span>. {html.escape(STABILITY_RULE)} Here: final speed "
        f"{_g(prototype.get('final_speed_rel_sqrt_gh'))} sqrt(g H), largest residual displacement "
        f"{_g(prototype.get('max_residual_displacement_rel_height'))} H.</p>"
    )


def first_peak_rows(sim):
    """(intro HTML, header, rows) of the first peaks of the x displacement at every monitoring point
    (prototype, model up-scaled, first_peak_ratio, time) with the outcome agreement; None without points."""
    if not sim or not sim.get("points"):
        return None
    rows = [
        (
            name,
            p.get("first_peak_prototype_m"),
            p.get("first_peak_model_m"),
            p.get("first_peak_ratio"),
            p.get("first_peak_time_s"),
        )
        for name, p in sim["points"].items()
    ]
    agree = sim.get("outcomes_agree")
    words = "-" if agree is None else ("yes" if agree else "<b>no</b>")
    intro = (
        "<p>First peaks of the x displacement at the monitoring points (model up-scaled to prototype units); "
        f"outcomes agree: {words}.</p>"
    )
    header = (
        "monitoring point",
        "prototype first peak [m]",
        "model first peak [m]",
        "first_peak_ratio [-]",
        "time of the prototype's peak [s]",
    )
    return intro, header, rows
