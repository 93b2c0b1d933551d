"""The words of the 3D outcomes in the report and on the console: the stability rule under gravity
alone (:func:`blastscale.sim3d.results.stability_of`) and the first peaks at the monitoring points."""

from __future__ import annotations

import html

from ..analysis.gravity_alone import STABILITY_EXTENSION_CAP
from ..analysis.upscale import upscale
from ..planning.card import specimen_timing

__all__ = ["STABILITY_RULE", "stability_words", "stability_lead", "first_peak_rows", "timing_rows", "ARRIVAL_NOTE"]

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


#: Why the arrival time's ratio is not a scaling factor (the report's blast table).
ARRIVAL_NOTE = (
    "The arrival time is not expected to scale with the time factor: the shock crosses the stand-off "
    "at a speed set by the air and the charge, not by the scaling law; the response is timed from the "
    "arrival, so only the time after it must scale."
)

#: The camera records from the detonation to the arrival plus this many times the specimen's whole response.
RECORD_MARGIN = 1.1


def timing_rows(result) -> list:
    """Rows (quantity, prototype [s], expected on the specimen [ms], "ms") for "What to measure": the specimen's
    time from the shock's arrival to its first peak (what the camera must resolve) and the record window
    (detonation to the arrival plus :data:`RECORD_MARGIN` x the whole response: the test card's camera record),
    with or without a ``[lab]`` table. The prototype's value is the specimen's divided by the time factor."""

    tm = specimen_timing(result)
    if tm is None:
        return []
    d = result.design
    arrival = float(d.specimen.arrival_time)
    window = arrival + RECORD_MARGIN * tm.response_s
    return [
        (
            "time to the first peak, from the arrival (specimen)",
            upscale(tm.rise_s, d.factors, "time"),
            tm.rise_s / 1e-3,
            "ms",
        ),
        (f"record window: detonation to the arrival plus {RECORD_MARGIN:g} x the response", None, window / 1e-3, "ms"),
    ]
