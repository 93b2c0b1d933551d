"""The result folder of ``blastscale fired --out``: ``summary.json`` (key ``as_fired``), ``scenario.toml``, the
figures and ``report.html`` with the "As fired" section (docs/fired.md)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..blast.pulses import Friedlander
from ..io.results import jsonable, provenance, write_atomic, write_json
from ..plots.fired import plot_gauge, plot_marker
from .figures import png_bytes
from .markup import PAGE_CSS, escape, figure_html, format_value, html_table

__all__ = ["fired_figures", "fired_section", "write_fired"]


def fired_figures(result) -> list[tuple[str, str, str, bytes]]:
    """(name, title, caption, PNG) of the gauge traces over their fits and the predicted pulse, and of the
    marker histories over the prediction and the re-simulation, in the specimen's and the prototype's units."""
    import matplotlib.pyplot as plt

    out = []
    s = result.summary
    for name, (fit, t, p) in result.gauges.items():
        g = s["gauges"][name]
        pred = Friedlander.from_impulse(
            g["predicted_peak_pressure_Pa"], result.design.specimen.positive_duration, g["predicted_impulse_Pa_s"]
        )
        fig, ax = plt.subplots(figsize=(7, 3.6))
        plot_gauge(
            t, p, fit.pressure(t), pred.pressure(np.asarray(t) - g["predicted_arrival_time_s"]), name=name, ax=ax
        )
        lo = fit.arrival_time_s - 0.5 * fit.positive_duration_s
        ax.set_xlim(1e3 * lo, 1e3 * (fit.arrival_time_s + 2.5 * fit.positive_duration_s))
        fig.tight_layout()
        out.append(
            (
                f"fired_gauge_{name}",
                f"Gauge {name}",
                (
                    "The record (baselined), its Friedlander fit and the "
                    "pulse predicted for the designed charge at the gauge."
                ),
                png_bytes(fig),
            )
        )
    f = result.design.factors
    for name, h in result.markers.items():
        m, pr, rf = h["measured"], h["predicted"], h["refit"]
        fig, axes = plt.subplots(1, 2, figsize=(11, 3.6))
        args = ((m["t"], m["ux"]), (pr["t"], pr["ux"]), (rf["t"], rf["ux"]))
        plot_marker(*args, name=name, ax=axes[0])
        plot_marker(*args, name=name, factors=f, units="prototype", ax=axes[1])
        fig.tight_layout()
        out.append(
            (
                f"fired_marker_{name}",
                f"Marker {name}",
                (
                    "Measured, predicted for the designed load and "
                    "re-simulated under the load as fired; left the specimen, right up-scaled to the prototype."
                ),
                png_bytes(fig),
            )
        )
    return out


def fired_section(result, figures) -> str:
    """The "As fired" section as HTML: the verdict, the load, the gauges, the markers, the monument, the figures."""
    s = result.summary
    load = [
        ("effective charge, by impulse", format_value(s["effective_charge_tnt_kg"]), "kg TNT"),
        ("effective charge, by peak", format_value(s["effective_charge_from_pressure_tnt_kg"]), "kg TNT"),
        ("designed charge", format_value(s["designed_charge_tnt_kg"]), "kg TNT"),
        ("charge as weighed", format_value(s["charge_kg"]), f"kg {s['explosive'] or ''}"),
        (
            "TNT equivalence implied (impulse / peak)",
            (f"{format_value(s['tnt_equivalence_impulse'])} / {format_value(s['tnt_equivalence_pressure'])}"),
            "-",
        ),
        (
            "stand-off as measured / designed",
            (f"{format_value(s['standoff_m'])} / {format_value(s['designed_standoff_m'])}"),
            "m",
        ),
    ]
    gkeys = (
        "peak_pressure_Pa",
        "predicted_peak_pressure_Pa",
        "impulse_Pa_s",
        "predicted_impulse_Pa_s",
        "arrival_time_s",
        "positive_duration_s",
        "decay",
        "effective_charge_tnt_kg",
    )
    mkeys = (
        "first_peak_m",
        "predicted_first_peak_m",
        "refit_first_peak_m",
        "first_peak_time_s",
        "max_displacement_m",
        "outcome_measured",
        "outcome_refit",
    )
    pkeys = (
        "first_peak_m",
        "first_peak_p05_m",
        "first_peak_p95_m",
        "first_peak_time_s",
        "first_peak_time_p05_s",
        "first_peak_time_p95_s",
    )
    return (
        f'<p class="lead"><b>{escape(s["verdict"])}</b></p>'
        + _similarity(s.get("similarity_verdict"))
        + html_table(("quantity", "value", "unit"), load)
        + _named_rows("Gauges (specimen)", "gauge", gkeys, s["gauges"])
        + _named_rows("Markers (specimen)", "marker", mkeys, s["markers"])
        + _named_rows(
            "What the monument would do (measured, up-scaled; 5-95 %)", "marker", pkeys, s["prototype_markers"]
        )
        + _calibration(s.get("calibration"))
        + "".join(figure_html(png, title, caption, name) for name, title, caption, png in figures)
    )


def _named_rows(title: str, name: str, keys: tuple, entries: dict) -> str:
    """A heading ``title`` and a table of one row per entry of ``entries`` (its name, then the values of
    ``keys``, formatted); "" when there is none."""
    rows = [(n, *(format_value(x[k]) for k in keys)) for n, x in entries.items()]
    return f"<h3>{title}</h3>" + html_table((name,) + keys, rows) if rows else ""


def _similarity(v) -> str:
    """The similarity verdict of the specimen as fired against the prototype under the design's event (the one
    criterion, :func:`blastscale.study.criterion.judge`): its line, which names the worst quantity and where."""
    if v is None:
        return ""
    cls = {True: "lead", False: "warn", None: "muted"}[v["similar"]]
    return f'<p id="similarity_verdict" class="{cls}"><b>{escape(v["line"])}</b></p>'


def _calibration(c) -> str:
    """The calibration's line, then its values (one row per marker for a per-marker value) and its misfit
    profile (parameter, RMS misfit)."""
    if c is None:
        return ""
    rows = []
    for k, v in c.items():  # a value per marker (friction's prototype first peaks): one row each
        if k in ("line", "profile"):
            continue
        rows += (
            [(f"{k} ({n})", format_value(x)) for n, x in v.items()] if isinstance(v, dict) else [(k, format_value(v))]
        )
    profile = "; ".join(f"{x:.4g}: {1e3 * m:.3g} mm" for x, m in c.get("profile", ()))
    return (
        f"<h3>Calibration (the measured response)</h3><p>{escape(c['line'])}</p>"
        + html_table(("quantity", "value"), rows)
        + (f"<p>Misfit profile (value: RMS misfit): {escape(profile)}</p>" if profile else "")
    )


def write_fired(result, scenario, folder) -> list[str]:
    """Write ``summary.json`` (``as_fired`` and the provenance), ``scenario.toml``, the figures (PNG) and
    ``report.html`` into ``folder`` (which must exist). Returns the file names."""

    folder = Path(folder)
    meta = provenance()
    figures = fired_figures(result)
    for name, _, _, png in figures:
        write_atomic(folder / f"{name}.png", png)
    write_atomic(folder / "scenario.toml", scenario.to_toml())
    title = scenario.title or "blast experiment"
    page = (
        '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>blastscale: as fired: '
        f"{escape(title)}</title><style>{PAGE_CSS}</style></head><body><header><h1>blastscale: as fired: {escape(title)}</h1>"
        f'</header><main><section id="as_fired"><h2>As fired</h2>{fired_section(result, figures)}</section>'
        f'<section id="scenario"><h2>Scenario (inputs)</h2><pre>{escape(scenario.to_toml())}</pre></section>'
        "</main></body></html>\n"
    )
    write_atomic(folder / "report.html", page)
    write_json(folder / "summary.json", jsonable({"as_fired": result.summary, **meta}))
    return ["summary.json", "scenario.toml", "report.html"] + [f"{n}.png" for n, _, _, _ in figures]
