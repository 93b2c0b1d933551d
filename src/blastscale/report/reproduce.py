"""``blastscale reproduce``: every table and figure of the paper blastscale can make, paper beside ours.

Each :class:`Item` computes its numbers with the library, writes its files into its own folder
and returns :class:`Row`s (quantity, the paper's printed value, blastscale's, unit, the slip of
docs/paper_slips.md that explains a difference). Items are:

* the paper's tables and numbers computed directly (geometry, blast loading, scaling factors,
  critical charge),
* every paper scenario shipped with blastscale (package data, :mod:`blastscale.scenario.library`,
  the names starting with ``paper_``)
  run through :class:`~blastscale.study.Study` (its own result folder and report),
* every script of the ``examples/`` gallery (its figures). The gallery ships with the source tree,
  not with the installed package: it is found next to the package in a source checkout or given
  explicitly (``reproduce --examples DIR``); :func:`skipped` says when it is not there.

Each item is written through a temporary folder renamed into place with an ``item.json``
marker: a second run skips the items already done (resumable after Ctrl-C), and
:func:`render_reproduce_report` puts every item's rows in one self-contained page.
"""

from __future__ import annotations

import base64
import hashlib
import html as _html
import json
import math
import os
import subprocess
import sys
import time
import tomllib
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Callable, Optional

from .._code import code_fingerprint
from ..analysis.planar import critical_of
from ..blast.load_model import LoadModel
from ..io.results import write_json
from ..scenario.files import load_scenario
from ..scenario.library import library_names, library_text
from ..similitude.design import design_model
from ..structures.block import RectangularBlock
from ..study.study import Study
from . import write_study
from .markup import PAGE_CSS, format_value
from .slips import SLIPS

__all__ = [
    "Item",
    "Row",
    "items",
    "skipped",
    "gallery_folder",
    "run_item",
    "item_done",
    "render_reproduce_report",
    "MARKER",
]

#: Marker written last into an item's folder: the item is complete.
MARKER = "item.json"

#: The gallery of a source checkout: src/blastscale/report -> the repository's examples/ (absent in a wheel).
_SOURCE_GALLERY = Path(__file__).resolve().parents[3] / "examples"


def gallery_folder(given: Optional[Path] = None) -> Optional[Path]:
    """The folder of the gallery scripts: ``given``, else the source checkout's ``examples/`` when
    this package runs from one (it holds ``_gallery.py``), else None."""
    folder = _SOURCE_GALLERY if given is None else Path(given)
    return folder if (folder / "_gallery.py").is_file() else None


@dataclass(frozen=True)
class Row:
    """One number of the paper beside blastscale's.

    Attributes
    ----------
    quantity : str
    paper : str
        As printed (text, with its printed unit), or "" when the paper gives no number.
    ours : float or str
    unit : str
        Unit of ``ours``.
    slip : int or None
        Row of docs/paper_slips.md explaining a difference.
    """

    quantity: str
    paper: str
    ours: object
    unit: str = ""
    slip: Optional[int] = None


# -- numbers computed directly ---------------------------------------------------------------
# The geometry of the prototype and models 1, 2 (Table "Geometry parameters"), the Table "Blast loading
# characteristics", the scaling factors quoted with Figures 5 and 8, and the critical charge of the slender block
# at 2 m (case c): each an Item's ``compute(folder, quick)``, computed with the library (design_model,
# critical_charge) and put beside the value the paper prints. Lengths, charges and ratios in the unit of each row.
_CHARGES = {"a": 50.0, "b": 100.0, "c": 79.8}
_PAPER_TABLE = {  # paper Table "Blast loading characteristics": (Z_p, W_m1 "mg", Z_m1, W_m2 "ug", Z_m2)
    "a": ("0.54", "1.0 mg", "0.99", "0.233 ug", "1.62"),
    "b": ("0.43", "2.06 mg", "0.78", "0.492 ug", "1.26"),
    "c": ("0.46", "1.635 mg", "0.85", "0.386 ug", "1.37"),
}


def _geometry(folder: Path, quick: bool) -> list:

    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0), density=2000.0)
    rows = [Row("prototype width 2b", "2.68 m", block.width, "m")]
    for lam, tag, paper in ((1 / 20, "model 1", ("50", "13.40", "10")), (1 / 200, "model 2", ("5", "1.34", "1"))):
        d = design_model(50.0, 2.0, lam, 1.0, blast_model="masi2021", geometry=block)
        mb = d.specimen_block
        rows += [
            Row(f"{tag} height", f"{paper[0]} cm", mb.height * 100, "cm"),
            Row(f"{tag} width", f"{paper[1]} cm", mb.width * 100, "cm"),
            Row(f"{tag} stand-off", f"{paper[2]} cm", d.specimen_standoff_m * 100, "cm"),
        ]
    return rows


def _blast_loading(folder: Path, quick: bool) -> list:

    rows = []
    for case, W in _CHARGES.items():
        zp, w1, z1, w2, z2 = _PAPER_TABLE[case]
        d1 = design_model(W, 2.0, 1 / 20, 1.0, blast_model="masi2021")
        d2 = design_model(W, 2.0, 1 / 200, 1.0, blast_model="masi2021")
        rows += [
            Row(f"({case}) W_p = {W:g} kg: Z_p", zp, d1.prototype.scaled_distance, "m/kg^(1/3)"),
            Row(f"({case}) model 1 (1/20) charge", w1, d1.specimen_charge_kg * 1e3, "g", 4),
            Row(f"({case}) model 1 Z", z1, d1.specimen.scaled_distance, "m/kg^(1/3)"),
            Row(f"({case}) model 2 (1/200) charge", w2, d2.specimen_charge_kg * 1e6, "mg", 4),
            Row(f"({case}) model 2 Z", z2, d2.specimen.scaled_distance, "m/kg^(1/3)"),
        ]
    ns = design_model(2500.0, 3.0, 1 / 200, 1.0, blast_model="masi2021")
    rows.append(Row("non-slender 2500 kg at 3 m: model charge (1/200)", "14.26 mg", ns.specimen_charge_kg * 1e6, "mg"))
    return rows


def _scaling_factors(folder: Path, quick: bool) -> list:

    d = design_model(50.0, 2.0, 1 / 200, 1.0, blast_model="masi2021")
    d05 = design_model(50.0, 2.0, 1 / 200, 0.05, blast_model="masi2021")
    return [
        Row("Fig. 5: pressure ratio, lambda = 1/200, gamma = 1", "5.8 %", d.pressure_ratio * 100, "%"),
        Row("Fig. 5: impulse ratio, general law", "0.3 %", d.impulse_ratio * 100, "%", 5),
        Row("Fig. 5: impulse ratio, Hopkinson-Cranz (= lambda)", "5 %", 100 / 200, "%", 5),
        Row("Fig. 8: pressure ratio, lambda = 1/200, gamma = 0.05", "0.18 %", d05.pressure_ratio * 100, "%"),
        Row("lambda_Z at lambda = 1/200 (Fig. 5b)", "", d.scaled_distance_factor, "-"),
    ]


def _critical(folder: Path, quick: bool) -> list:
    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0), density=2000.0)

    c = critical_of(block, standoff=2.0, blast_model="masi2021")
    neg = critical_of(block, standoff=2.0, blast_model="masi2021", load_model=LoadModel(negative_phase=True))
    return [
        Row("critical charge at 2 m (case c)", "79.8 kg", c.charge_kg, "kg"),
        Row(
            "the same with the negative phase (the paper neglects it; docs/blast_physics.md)",
            'larger ("stabilizing")',
            neg.charge_kg,
            "kg",
        ),
    ]


@dataclass(frozen=True)
class Item:
    """One reproducible table, figure or case: ``compute(folder, quick) -> list[Row]``."""

    name: str
    title: str
    paper_ref: str
    compute: Callable[[Path, bool], list]
    notes: str = ""
    kind: str = "number"
    source: "Optional[Path | str]" = None  # a script, or a shipped scenario's name: a change makes it run again

    def fingerprint(self) -> str:
        """SHA-256 of the fingerprint of blastscale's code (:func:`blastscale._code.code_fingerprint`) and
        of the item's source (a script's bytes, a shipped scenario's text; nothing more for the numbers
        computed directly here): an item done by other code, or from another source, runs again."""

        if self.source is None:
            source = b""
        elif isinstance(self.source, Path):
            source = self.source.read_bytes()
        else:
            source = library_text(self.source).encode("utf-8")
        return hashlib.sha256(code_fingerprint().encode() + b"\0" + source).hexdigest()


# -- scenarios --------------------------------------------------------------------------------
_SCENARIO_PAPER = {  # scenario file stem -> rows of (quantity, paper as printed, summary path, unit, slip)
    "paper_block_50kg_lambda20": [("model charge", "1.0 mg", "design.model_charge_kg", "g", 4)],
    "paper_block_50kg_lambda200": [
        ("model charge", "0.233 ug", "design.model_charge_kg", "mg", 4),
        ("prototype first impact (planar)", "1.3 ms", "planar.prototype.first_impact_time_s", "s", 10),
    ],
    "paper_block_100kg_lambda20": [("model charge", "2.06 mg", "design.model_charge_kg", "g", 4)],
    "paper_block_100kg_lambda200": [
        ("model charge", "0.492 ug", "design.model_charge_kg", "mg", 4),
        ("prototype overturns (planar)", "yes", "planar.prototype.collapsed", "", None),
    ],
    "paper_block_50kg_lambda200_balsa": [("density ratio gamma", "0.07", "experiment.density_ratio", "-", None)],
    "paper_block_non_slender_2500kg": [
        ("model charge", "14.26 mg", "design.model_charge_kg", "mg", None),
        ("sliding of the front face", "approximately 1 m", "3d.prototype.points.P-1.max_displacement_m", "m", 12),
    ],
}
_UNIT_FACTOR = {"g": 1e3, "mg": 1e6}


def _dig(d: dict, path: str):
    for part in path.split("."):
        if not isinstance(d, dict) or part not in d:
            return None
        d = d[part]
    return d


def _scenario_item(name: str) -> Item:
    def compute(folder: Path, quick: bool) -> list:

        sc = load_scenario(name)
        if quick:
            sc = sc.with_values({"duration_s": min(sc.simulation.duration_s, 0.2), "critical_charge": False})
        result = Study(sc).run()
        write_study(result, folder)
        s = result.summary()
        rows = []
        for q, paper, key, unit, slip in _SCENARIO_PAPER.get(name, []):
            v = _dig(s, key)
            if isinstance(v, (int, float)) and not isinstance(v, bool) and unit in _UNIT_FACTOR:
                v = v * _UNIT_FACTOR[unit]
            rows.append(Row(q, paper, v, unit, slip))
        if result.planar is not None:
            sim = s["planar"]["similarity"]
            rows.append(
                Row(
                    "planar: outcomes agree (prototype vs up-scaled model)",
                    "yes (curves coincide)",
                    sim["outcomes_agree"],
                    "",
                )
            )
            rows.append(
                Row(
                    "planar: max |angle difference| up to tipping",
                    "negligible",
                    sim["max_abs_rotation_diff_to_tipping_rad"],
                    "rad",
                )
            )
        if result.response3d is not None:
            sim = s["3d"]["similarity"]
            for k in ("outcomes_agree", "top_first_peak_ratio", "max_abs_top_displacement_diff_rel_peak"):
                if k in sim:
                    rows.append(Row(f"3D: {k.replace('_', ' ')}", "prototype and model coincide", sim[k], ""))
        if result.ensemble is not None:
            en = s["ensemble"]
            top = result.ensemble.top_point
            rows += [
                Row(
                    f"ensembles ({en['n_members']} members): collapse probability, prototype",
                    "",
                    en["collapse_probability_prototype"],
                    "",
                ),
                Row("ensembles: collapse probability, model (up-scaled)", "", en["collapse_probability_model"], ""),
                Row(
                    f"ensembles: first-peak ratio at {top} (model / prototype means)",
                    "prototype and model coincide",
                    en["points"][top]["first_peak_ratio"],
                    "",
                ),
            ]
        return rows

    title = tomllib.loads(library_text(name)).get("title") or name
    return Item(
        f"scenario-{name.replace('_', '-')}",
        f"Scenario: {title}",
        f"blastscale:{name}",
        compute,
        kind="scenario",
        source=name,
    )


# -- gallery scripts ---------------------------------------------------------------------------
def _script_item(path: Path) -> Item:
    def compute(folder: Path, quick: bool) -> list:
        cmd = [sys.executable, str(path), str(folder)] + (
            ["--quick"] if quick and "--quick" in path.read_text() else []
        )
        env = {**os.environ, "MPLBACKEND": "Agg"}
        proc = subprocess.run(cmd, capture_output=True, text=True, cwd=path.parent, env=env)
        (folder / "stdout.txt").write_text(proc.stdout)
        if proc.returncode != 0:
            tail = " ".join((proc.stderr or proc.stdout).strip().splitlines()[-1:])
            raise RuntimeError(f"{path.name} failed (exit {proc.returncode}): {tail}")
        figs = sorted(p.name for p in folder.glob("*.png"))
        return [Row("figures written", "", ", ".join(figs) or "none", "")]

    text = path.read_text()
    doc = text.split('"""')[1].strip().splitlines()[0] if '"""' in text else path.stem
    return Item(
        f"example-{path.stem.replace('_', '-')}", doc, f"examples/{path.name}", compute, kind="figures", source=path
    )


def items(examples: Optional[Path] = None) -> list[Item]:
    """Every reproducible item, in the paper's order (numbers first, the shipped scenarios, then the
    gallery of :func:`gallery_folder` when there is one)."""

    out = [
        Item(
            "table-geometry",
            'Table "Geometry parameters" (prototype and models 1, 2)',
            "Sec. Equations of motion",
            _geometry,
        ),
        Item(
            "table-blast-loading", 'Table "Blast loading characteristics"', "Sec. Equations of motion", _blast_loading
        ),
        Item("scaling-factors", "Figures 5 and 8, the numbers quoted in the text", "Secs. 5.1, 5.2", _scaling_factors),
        Item(
            "critical-charge",
            "Critical charge of the slender block at 2 m (case c)",
            "Sec. Equations of motion",
            _critical,
        ),
    ]
    out += [_scenario_item(name) for name in library_names() if name.startswith("paper_")]
    gallery = gallery_folder(examples)
    if gallery is not None:
        out += [_script_item(p) for p in sorted(gallery.glob("*.py")) if not p.name.startswith("_")]
    return out


def skipped(examples: Optional[Path] = None) -> list[str]:
    """What :func:`items` leaves out and why (one line each; empty when nothing is left out)."""
    if gallery_folder(examples) is not None:
        return []
    where = "the folder given" if examples is not None else "this installation (the gallery ships with the source tree)"
    return [f"the examples/ gallery (figure scripts): not found in {where}; give it with --examples DIR"]


def item_done(item: Item, out: Path, quick: bool) -> bool:
    """The item's folder is complete (its marker exists), made in the same mode from the same source."""
    marker = out / item.name / MARKER
    if not marker.is_file():
        return False
    try:
        info = json.loads(marker.read_text())
    except (OSError, ValueError):
        return False
    return bool(info.get("quick")) == bool(quick) and info.get("fingerprint", "") == item.fingerprint()


def run_item(item: Item, out: Path, quick: bool, output_folder) -> dict:
    """Compute ``item`` into ``out/<name>`` through ``output_folder`` (atomic, replaces an item
    made in the other mode); returns the marker's content."""

    dest = out / item.name
    with output_folder(dest, force=dest.exists(), markers=(MARKER,)) as tmp:
        t0 = time.perf_counter()
        rows = item.compute(Path(tmp), quick)
        info = {
            "name": item.name,
            "title": item.title,
            "paper_ref": item.paper_ref,
            "kind": item.kind,
            "quick": bool(quick),
            "fingerprint": item.fingerprint(),
            "wall_time_s": time.perf_counter() - t0,
            "rows": [asdict(r) for r in rows],
        }
        write_json(Path(tmp) / MARKER, info)
    return info


def _slip_link(slip) -> str:
    return f'<a href="#slip-{int(slip)}">#{int(slip)}</a>' if slip else ""


def _cell(v) -> str:

    if isinstance(v, float):
        return format_value(v, ".4g")
    return format_value(v)


def render_reproduce_report(out: Path, infos: list[dict], meta: dict) -> str:
    """One self-contained page: per item, the paper's values beside blastscale's, the slips, the figures."""

    e = lambda x: _html.escape(str(x), quote=True)  # noqa: E731
    slip_text = {s.number: f"#{s.number} {s.where}: {s.text}" for s in SLIPS}
    parts, used = [], set()
    toc = []
    for info in infos:
        rows = info.get("rows", [])
        body = []
        for r in rows:
            slip = r.get("slip")
            if slip:
                used.add(slip)
            body.append(
                f"<tr><td>{e(r['quantity'])}</td><td>{e(r['paper'] or '-')}</td>"
                f'<td class="n">{e(_cell(r["ours"]))}</td><td>{e(r["unit"])}</td>'
                f"<td>{_slip_link(slip)}</td></tr>"
            )
        table = (
            (
                "<table><thead><tr><th>quantity</th><th>paper (as printed)</th><th>blastscale</th><th>unit</th>"
                f"<th>slip</th></tr></thead><tbody>{''.join(body)}</tbody></table>"
            )
            if body
            else ""
        )
        folder = out / info["name"]
        figs = []
        if info.get("kind") == "figures":
            for png in sorted(folder.glob("*.png")):
                data = base64.b64encode(png.read_bytes()).decode("ascii")
                figs.append(
                    f'<figure><img alt="{e(png.name)}" src="data:image/png;base64,{data}">'
                    f"<figcaption>{e(png.name)}</figcaption></figure>"
                )
        link = (
            f'<p><a href="{e(info["name"])}/report.html">the full report of this scenario</a></p>'
            if (folder / "report.html").exists()
            else ""
        )
        mode = " (quick run: shortened durations)" if info.get("quick") else ""
        toc.append(f'<li><a href="#{e(info["name"])}">{e(info["title"])}</a></li>')
        parts.append(
            f'<section id="{e(info["name"])}"><h2>{e(info["title"])}</h2><p class="muted">'
            f"{e(info.get('paper_ref', ''))}; {info.get('wall_time_s', 0):.1f} s{e(mode)}</p>"
            f"{table}{link}{''.join(figs)}</section>"
        )
    slips = "".join(f'<li id="slip-{n}">{e(slip_text[n])}</li>' for n in sorted(used))
    v = meta.get("versions", {})
    return (
        '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>blastscale reproduce</title>'
        f"<style>{PAGE_CSS}</style></head><body><header><h1>The paper, reproduced by blastscale</h1>"
        '<p class="muted">Masi, Stefanou &amp; Maffi-Berthier, <i>Scaling laws for the rigid-body response of '
        "masonry structures under blast loads</i>. Each item puts the paper's printed value beside "
        "blastscale's; a slip number marks a known error of the printed paper (docs/paper_slips.md). "
        f"blastscale {e(v.get('blastscale', ''))}, git {e(meta.get('git_commit') or '-')}, "
        f"{e(meta.get('timestamp', ''))}.</p></header><nav><ol>{''.join(toc)}</ol></nav>"
        f'<main>{"".join(parts)}<section id="slips"><h2>Slips marked above</h2><ul>{slips}</ul></section>'
        "</main></body></html>\n"
    )
