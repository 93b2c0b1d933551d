"""The report's HTML building blocks: the page style, table cells, tables and embedded figures.

Shared by the study's report (:mod:`.html`), the "As fired" page (:mod:`.fired`), the plan's page
(:mod:`.plan_files`) and the reproduce page (:mod:`.reproduce`): a value becomes a cell (SI units, round-off
shown as 0, a TNT mass in the unit a test designer weighs it in), rows become a ``<table>``, a PNG becomes a
``<figure>`` embedded as base64.
"""

from __future__ import annotations

import base64
import html
import math
from typing import Any, Iterable

from ..units import split_unit
from .labels import label

__all__ = [
    "PAGE_CSS",
    "ROUND_OFF",
    "compare_table",
    "escape",
    "figure_html",
    "flatten",
    "format_charge",
    "charge_text",
    "format_value",
    "html_table",
    "split_unit_for_tables",
]

#: The style sheet of every page the report writes (study, "As fired", plan, reproduce).
PAGE_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,sans-serif;max-width:1100px;margin:2em auto;
padding:0 1em;color:#1d2329;line-height:1.45}
h1{font-size:1.6em;margin-bottom:.2em}h2{border-bottom:2px solid #d0d7de;padding-bottom:.2em;margin-top:1.8em}
table{border-collapse:collapse;margin:.6em 0 1em}th,td{border:1px solid #d0d7de;padding:.25em .6em}
th{background:#f3f5f7;text-align:left}td.n{text-align:right;font-variant-numeric:tabular-nums}
.lead{font-size:1.1em;background:#eef6ee;border-left:4px solid #3a8f3a;padding:.6em 1em}
.warn{background:#fff5e0;border-left:4px solid #d08a00;padding:.4em 1em}
.ok{color:#2b7a2b;font-weight:600}.bad{color:#b02a2a;font-weight:600}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #d0d7de}figcaption{font-size:.9em;color:#57606a}
pre{background:#f6f8fa;padding:.8em;overflow-x:auto;font-size:.85em}.muted{color:#57606a;font-size:.9em}
"""


def split_unit_for_tables(key: str) -> tuple[str, str]:
    """``"max_rotation_rad"`` -> (``"max rotation"``, ``"rad"``): label and unit from a key's suffix as a
    table shows them: :func:`blastscale.units.split_unit`, except that a difference relative to the peak
    (``_rel_peak``, unit ``"1"``) reads "of the peak"."""
    label, unit = split_unit(key)
    return label, ("of the peak" if key.endswith("_rel_peak") else unit)


#: A float below this (SI units) is round-off (a 3D difference of 3.3e-18 m): shown as 0.
ROUND_OFF = 1e-12


def format_value(x: Any, spec: str = ".4g") -> str:
    """A table cell: '-' for None/NaN, yes/no for booleans, numbers with ``spec``."""
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, (int, float)):
        if isinstance(x, float) and math.isnan(x):
            return "-"
        return format(0.0 if isinstance(x, float) and abs(x) < ROUND_OFF else x, spec)
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(format_value(v, spec) for v in x) + "]"
    return str(x)


def format_charge(kg: float) -> str:
    """A TNT mass in the unit a test designer weighs it in: kg, g, mg or ug (4 significant digits).

    The largest unit in which the value is at least 0.1 (the paper's 0.233 mg, 14.27 mg, 1.004 g).

    >>> format_charge(2.3318e-07), format_charge(1.0044e-3), format_charge(50.0)
    ('0.2332 mg', '1.004 g', '50 kg')
    """
    for unit, f in (("kg", 1.0), ("g", 1e-3), ("mg", 1e-6)):
        if kg >= 0.1 * f:
            return f"{kg / f:.4g} {unit}"
    return f"{kg / 1e-9:.4g} µg"


def charge_text(d: dict) -> str:
    """A planned design's charge as the lab sets it: ``"1.004 g c-4"``, or a calibrated source's setting
    (``"charge the bank to 1.85 kJ"``: the design's ``source``, docs/planning.md, "Sources")."""
    src = d.get("source")
    if src:
        return f"{src['setting']} ({format_charge(d['tnt_equivalent_kg'])} TNT by impulse)"
    return f"{format_charge(d['explosive_mass_kg'])} {d['explosive']}"


def escape(x: Any) -> str:
    """``str(x)`` escaped for HTML text and attribute values (quotes included)."""
    return html.escape(str(x), quote=True)


def html_table(header: Iterable[str], rows: Iterable[Iterable[Any]], numeric_from: int = 1) -> str:
    """A ``<table>`` of ``rows`` under ``header``: strings as given, other cells through :func:`format_value`,
    right-aligned (class ``n``) from column ``numeric_from`` on."""
    h = "".join(f"<th>{escape(c)}</th>" for c in header)
    body = []
    for r in rows:
        cells = []
        for i, c in enumerate(r):
            cls = ' class="n"' if i >= numeric_from and not isinstance(c, str) else ""
            cells.append(f"<td{cls}>{escape(format_value(c) if not isinstance(c, str) else c)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><thead><tr>{h}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def flatten(d: dict, prefix: str = "") -> list[tuple[str, Any]]:
    """The leaves of a nested dict as ``(dotted key, value)`` pairs, in order (``prefix`` before each key)."""
    out = []
    for k, v in d.items():
        if isinstance(v, dict):
            out.extend(flatten(v, f"{prefix}{k}."))
        else:
            out.append((f"{prefix}{k}", v))
    return out


def compare_table(prototype: dict, model: dict | None) -> str:
    """Prototype and up-scaled model side by side (the prototype alone when there is no model)."""
    mflat = dict(flatten(model or {}))
    rows = []
    for k, v in flatten(prototype):
        if isinstance(v, str):
            continue
        words, unit = label(k), split_unit_for_tables(k.split(".")[-1])[1]
        rows.append((words, v, unit) if model is None else (words, v, mflat.get(k), unit))
    head = (
        ("quantity", "prototype", "unit") if model is None else ("quantity", "prototype", "model (up-scaled)", "unit")
    )
    return html_table(head, rows)


def figure_html(png: bytes, title: str, caption: str, name: str) -> str:
    """A ``<figure>`` (id ``fig-<name>``) with the PNG embedded as base64, its title and caption."""
    data = base64.b64encode(png).decode("ascii")
    return (
        f'<figure id="fig-{escape(name)}"><img alt="{escape(title)}" src="data:image/png;base64,{data}">'
        f"<figcaption><b>{escape(title)}.</b> {escape(caption)}</figcaption></figure>"
    )
