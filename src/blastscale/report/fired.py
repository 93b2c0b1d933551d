"""The result folder of ``blastscale fired --out``: ``summary.json`` (key ``as_fired``), ``scenario.toml``, the
figures and ``report.html`` with the "As fired" section (docs/fired.md)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..blast.pulses import Friedlander
from ..io.results import jsonable, provenance, write_atomic, write_json
from ..plots.fired import plot_gauge, plot_marker
from .figures import png_bytes
from .markup import PAGE_CSS, escape, figure_html, format_charge, format_value, html_table, split_unit_for_tables

__all__ = ["fired_figures", "fired_section", "write_fired"]


#: The gauge table's columns: (header in words and unit, summary key, factor from SI).
GAUGE_COLUMNS = (
    ("peak pressure [kPa]", "peak_pressure_Pa", 1e-3),
    ("predicted peak [kPa]", "predicted_peak_pressure_Pa", 1e-3),
    ("impulse [kPa ms]", "impulse_Pa_s", 1.0),
    ("predicted impulse [kPa ms]", "predicted_impulse_Pa_s", 1.0),
    ("arrival [ms]", "arrival_time_s", 1e3),
    ("positive phase [ms]", "positive_duration_s", 1e3),
    ("decay [-]", "decay", 1.0),
    ("effective charge [g TNT]", "effective_charge_tnt_kg", 1e3),
)
#: The marker table's columns (specimen units: mm, s).
MARKER_COLUMNS = (
    ("first peak [mm]", "first_peak_m", 1e3),
    ("its 1-sigma [mm]", "first_peak_sigma_m", 1e3),
    ("at [s]", "first_peak_time_s", 1.0),
    ("predicted [mm]", "predicted_first_peak_m", 1e3),
    ("re-simulated [mm]", "refit_first_peak_m", 1e3),
    ("re-simulated vs measured [%]", "refit_vs_measured", 1e2),
    ("largest [mm]", "max_displacement_m", 1e3),
    ("outcome (measured)", "outcome_measured", 1.0),
    ("outcome (re-simulated)", "outcome_refit", 1.0),
)
#: The monument's table's columns (prototype units: m, s).
PROTOTYPE_COLUMNS = (
    ("first peak [m]", "first_peak_m", 1.0),
    ("5 % [m]", "first_peak_p05_m", 1.0),
    ("95 % [m]", "first_peak_p95_m", 1.0),
    ("at [s]", "first_peak_time_s", 1.0),
    ("5 % [s]", "first_peak_time_p05_s", 1.0),
    ("95 % [s]", "first_peak_time_p95_s", 1.0),
)


#: The designed event's table's columns (prototype units: m, s).
EVENT_COLUMNS = (
    ("first peak [m]", "first_peak_m", 1.0),
    ("5 % [m]", "first_peak_p05_m", 1.0),
    ("95 % [m]", "first_peak_p95_m", 1.0),
    ("at [s]", "first_peak_time_s", 1.0),
    ("residual [m]", "residual_displacement_m", 1.0),
    ("residual 5 % [m]", "residual_displacement_p05_m", 1.0),
    ("residual 95 % [m]", "residual_displacement_p95_m", 1.0),
)


def _event_titles(s: dict) -> tuple[str, str]:
    """The two monument tables' titles: under the shot's event (the similar charge) and under the designed event,
    each naming its charge and stand-off (docs/fired.md)."""
    ws, rs = s.get("similar_prototype_charge_tnt_kg"), s.get("similar_prototype_standoff_m")
    shot = "the charge the shot represents" if ws is None else f"{format_value(ws)} kg TNT at {format_value(rs)} m"
    ev = s.get("designed_event") or {}
    wd, rd = ev.get("charge_tnt_kg"), ev.get("standoff_m")
    designed = "the designed event" if wd is None else f"the designed {format_value(wd)} kg TNT at {format_value(rd)} m"
    return (
        f"The monument under the shot's event ({shot}: the measurement up-scaled; 5-95 %)",
        f"The monument under {designed} (the measurement corrected by its sensitivity to the charge, up-scaled; "
        "5-95 % with the gauge, track, refit, similarity and ensemble terms)",
    )


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
        pk = m["peak"]
        found = None if pk.first_peak_m is None else (pk.first_peak_time_s, pk.first_peak_m)
        plot_marker(*args, name=name, peak=found, ax=axes[0])
        plot_marker(*args, name=name, factors=f, units="prototype", peak=found, ax=axes[1])
        fig.tight_layout()
        out.append(
            (
                f"fired_marker_{name}",
                f"Marker {name}",
                (
                    "Measured, predicted for the designed load and "
                    "re-simulated under the load as fired; left the specimen, right up-scaled to the prototype; "
                    "the cross is the first peak found in the track (docs/fired.md: smoothed and searched over "
                    "spans set in seconds from the predicted time to the first peak)."
                ),
                png_bytes(fig),
            )
        )
    return out


def fired_section(result, figures) -> str:
    """The "As fired" section as HTML: the verdict, the load, the gauges, the markers, the monument, the figures."""
    s = result.summary
    load = [
        ("effective charge, by impulse", _charge(s["effective_charge_tnt_kg"]), "TNT"),
        ("effective charge, by peak", _charge(s["effective_charge_from_pressure_tnt_kg"]), "TNT"),
        ("designed charge", _charge(s["designed_charge_tnt_kg"]), "TNT"),
        (
            "prototype charge the shot represents (its similar charge)",
            _charge(s.get("similar_prototype_charge_tnt_kg")),
            "TNT",
        ),
        ("charge as weighed", _charge(s["charge_kg"]), s["explosive"] or ""),
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
    shot_title, designed_title = _event_titles(s)
    return (
        f'<p class="lead"><b>{escape(s["verdict"])}</b></p>'
        + _similarity(s.get("similarity_verdict"))
        + html_table(("quantity", "value", "unit"), load)
        + _named_rows("Gauges (specimen)", "gauge", GAUGE_COLUMNS, s["gauges"])
        + _named_rows("Markers (specimen)", "marker", MARKER_COLUMNS, s["markers"])
        + _named_rows(shot_title, "marker", PROTOTYPE_COLUMNS, s["prototype_markers"])
        + _named_rows(designed_title, "marker", EVENT_COLUMNS, (s.get("designed_event") or {}).get("markers") or {})
        + _calibration(s.get("calibration"))
        + "".join(figure_html(png, title, caption, name) for name, title, caption, png in figures)
    )


def _named_rows(title: str, name: str, columns: tuple, entries: dict) -> str:
    """A heading ``title`` and a table of one row per entry of ``entries``: its name under the header ``name``,
    then one column per ``(header, key, factor)`` of ``columns`` (the summary's SI value times ``factor``, shown
    to 4 significant digits; text as given); "" when there is none."""
    rows = [(n, *(_cell(x.get(k), f) for _, k, f in columns)) for n, x in entries.items()]
    return f"<h3>{title}</h3>" + html_table((name,) + tuple(h for h, _, _ in columns), rows) if rows else ""


def _charge(kg) -> str:
    """A charge in the unit it is weighed in (:func:`~.markup.format_charge`: kg, g, mg), "-" when None."""
    return "-" if kg is None else format_charge(kg)


def _cell(v, unit_size: float):
    """A summary value in the column's unit: a number (SI) times ``unit_size`` (1e3 for mm), anything else as it is."""
    return v * unit_size if isinstance(v, (int, float)) and not isinstance(v, bool) else v


def _similarity(v) -> str:
    """The similarity verdict of the specimen as fired against the prototype under the design's event (the one
    criterion, :func:`blastscale.study.criterion.judge`): its line, which names the worst quantity and where."""
    if v is None:
        return ""
    cls = {True: "lead", False: "warn", None: "muted"}[v["similar"]]
    return f'<p id="similarity_verdict" class="{cls}"><b>{escape(v["line"])}</b></p>'


#: The calibration's rows in words (summary key -> label); any other key by its words and unit suffix.
CALIBRATION_LABELS = {
    "restitution": "restitution (calibrated)",
    "restitution_low": "restitution, interval low",
    "restitution_high": "restitution, interval high",
    "best_restitution": "restitution of least misfit",
    "friction": "friction coefficient (calibrated)",
    "friction_low": "friction, interval low",
    "friction_high": "friction, interval high",
    "best_friction": "friction of least misfit",
    "identifiable": "identified by the record",
    "misfit_noise_multiple": "accepted misfit, x the noise",
    "charge_factor": "factor on the charge as fired",
    "charge_factor_ci95": "its 95 % half-width",
    "samples": "frames fitted",
    "evaluations": "re-simulations run",
    "window": "frames fitted over",
    "prototype_outcome": "the prototype with that value",
}


def _calibration(c) -> str:
    """The calibration's line, then its values in words with their units (one row per marker for a per-marker
    value) and its misfit profile (parameter, RMS misfit)."""
    if c is None:
        return ""
    rows = []
    for k, v in c.items():  # a value per marker (friction's prototype first peaks): one row each
        if k in ("line", "profile"):
            continue
        label, unit = split_unit_for_tables(k)
        label = CALIBRATION_LABELS.get(k, label)
        if isinstance(v, dict):
            rows += [(f"{label} ({n})", format_value(x), unit) for n, x in v.items()]
        else:
            rows.append((label, format_value(v), unit))
    profile = "; ".join(f"{x:.4g}: {1e3 * m:.3g} mm" for x, m in c.get("profile", ()))
    return (
        f"<h3>Calibration (the measured response)</h3><p>{escape(c['line'])}</p>"
        + html_table(("quantity", "value", "unit"), rows)
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
    write_atomic(folder / "scenario.toml", scenario.to_toml(folder))  # a record path given relative stays so
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
