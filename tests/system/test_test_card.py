"""The test card of ``run`` with a [lab] table: summary.json's ``test_card`` keys, and the report's card
rendered in headless Chromium with every number it shows equal to summary.json."""

import json
import os
import re
import shutil
import subprocess
from html import unescape as html_unescape
from html.parser import HTMLParser
from pathlib import Path

import pytest

from blastscale.blast.faces import face_loads
from blastscale.blast.initiation import INITIATORS
from blastscale.planning.fragments import gurney_constant, gurney_sandwich
from blastscale.planning.odds import outcome_odds_text
from blastscale.report import write_study
from blastscale.report.card import shown
from blastscale.scenario import Scenario, load_scenario
from blastscale.study import Study

LIB = Path(__file__).resolve().parents[2] / "src" / "blastscale" / "scenario" / "library"
KEYS = (
    "explosive",
    "explosive_mass_kg",
    "tnt_equivalent_impulse_kg",
    "tnt_equivalent_pressure_kg",
    "safety_distances_m",
    "debris_radius_m",
    "camera_fps",
    "pressure_sampling_hz",
    "p_outcome_agree",
    "p_outcome_agree_low",
    "p_outcome_agree_high",
    "first_peak_spread",
)
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--hide-scrollbars",
]


@pytest.fixture(scope="module")
def card_dir(tmp_path_factory):
    folder = tmp_path_factory.mktemp("card")
    data = Scenario.default().with_values({"duration_s": 2.0, "engine": "planar"}).model_dump(exclude_none=True)
    data["lab"] = {"explosive": "c-4", "initiator_tnt_kg": 3e-8, "samples": 500, "seed": 2, "ensemble_3d": 2}
    write_study(Study(Scenario.from_dict(data)).run(), folder)
    return folder


#: the paper's square column, shortened (3 drums of 1 m, 0.25 s) at 1/10, PE4 and an RP-80, a 2-member 3D ensemble
COLUMN = {
    "structure": {"drums": 3, "height_m": 3.0, "top_width_m": 1.54},
    "scale": {"length": "1/10"},
    "simulation": {"duration_s": 0.25},
    "lab": {"explosive": "pe4", "initiator": "rp-80", "ensemble_3d": 2, "samples": 50, "seed": 1},
}


@pytest.fixture(scope="module")
def column_dir(tmp_path_factory):
    folder = tmp_path_factory.mktemp("column_card")
    data = load_scenario(LIB / "paper_column_square_250kg.toml").model_dump(exclude_none=True)
    for k, v in COLUMN.items():
        data[k] = {**data.get(k, {}), **v}
    write_study(Study(Scenario.from_dict(data)).run(), folder)
    return folder


def _get(card, key):
    for part in key.split("/"):
        card = card[int(part)] if isinstance(card, list) else card[part]
    return card


class _Numbers(HTMLParser):
    """The tagged numbers of the test card section, and the digits of its value cells outside them."""

    def __init__(self):
        super().__init__()
        self.depth = 0  # inside <section id="test_card">
        self.tag = None
        self.numbers, self.loose = [], []
        self.in_td = self.in_num = False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "section" and a.get("id") == "test_card":
            self.depth = 1
        elif self.depth and tag == "section":
            self.depth += 1
        if not self.depth:
            return
        if "num" in (a.get("class") or "").split():
            self.tag = [a["data-key"], a["data-unit"], a.get("data-prefix", ""), ""]
            self.in_num = True
        self.in_td = self.in_td or tag == "td"

    def handle_endtag(self, tag):
        if not self.depth:
            return
        if tag in ("span", "text") and self.in_num:
            self.numbers.append(tuple(self.tag))
            self.in_num = False
        if tag == "td":
            self.in_td = False
        if tag == "section":
            self.depth -= 1

    def handle_data(self, data):
        if self.in_num:
            self.tag[3] += data
        elif self.depth and self.in_td and re.search(r"\d", data):
            self.loose.append(data)


def test_summary_has_the_test_card(card_dir):
    s = json.loads((card_dir / "summary.json").read_text())
    card = s["test_card"]
    for k in KEYS:
        assert k in card
    assert card["explosive"] == "c-4"
    assert card["explosive_mass_kg"] == pytest.approx((2.3317976e-7 - 3e-8) / 1.19, rel=1e-6)
    assert card["tnt_equivalent_pressure_kg"] == pytest.approx(card["explosive_mass_kg"] * 1.37 + 3e-8, rel=1e-12)
    assert "6.9 kPa" in card["safety_distances_m"] and card["warnings"]  # the initiator is 13 % of the charge


def _chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    return None


@pytest.mark.skipif(_chromium() is None, reason="Chromium not found (Debian: apt-get install -y chromium)")
def test_card_renders_in_chromium_and_every_number_matches_summary(card_dir, tmp_path):
    env = {**os.environ, "HOME": str(tmp_path)}
    uri = (card_dir / "report.html").resolve().as_uri()
    dom = subprocess.run(
        [_chromium(), *FLAGS, f"--user-data-dir={tmp_path / 'p'}", "--dump-dom", uri],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
    )
    assert dom.returncode == 0, dom.stderr[-2000:]
    p = _Numbers()
    p.feed(dom.stdout)
    card = json.loads((card_dir / "summary.json").read_text())["test_card"]
    assert len(p.numbers) >= 50
    for key, unit, prefix, text in p.numbers:
        assert text == prefix + shown(_get(card, key), unit), (key, unit, text)
    # digits in the value cells outside the tagged numbers: only units and names
    # the odds in words are the summary's counts with their Wilson interval (not a tagged number)
    odds = {outcome_odds_text(card["odds"]), outcome_odds_text(card["odds_3d"])}
    assert set(p.loose) <= {" kg/m3", card["explosive"], *odds}, p.loose
    assert outcome_odds_text(card["odds"]) in p.loose
    shot = tmp_path / "shot.png"
    r = subprocess.run(
        [
            _chromium(),
            *FLAGS,
            f"--user-data-dir={tmp_path / 'q'}",
            f"--screenshot={shot}",
            "--window-size=1200,2400",
            uri,
        ],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
    )
    assert r.returncode == 0 and shot.stat().st_size > 100_000


def _card(folder):
    return json.loads((folder / "summary.json").read_text())["test_card"]


@pytest.mark.parametrize("which", ["card_dir", "column_dir"])
def test_the_card_a_range_safety_officer_signs(which, request):
    """Issue #37: the block's card and the column's each carry the fragment distance (a source per fragment, the
    largest their maximum), the pad (a steel plate at least 10 mm and 4 x what the charge cuts), the detonator's
    placement, one camera rate (the instruments'), the reflected gauge's own predicted peak (face_loads at its
    position, to 1e-12; below the face's, the gauge being beside it, obliquely), and the 3D odds with their Wilson
    interval (a 2-member ensemble)."""
    folder = request.getfixturevalue(which)
    c = _card(folder)
    f = c["fragments"]
    assert f["distance_m"] == max(x["distance_m"] for x in f["sources"]) > 0.0
    named = c["initiator"] if which == "column_dir" else None  # the block's initiator is a stated TNT figure
    bare = next(x for x in f["sources"] if x["source"].startswith("bare charge"))
    explosive = c["explosive_mass_kg"] + (INITIATORS[named].explosive_mass_kg if named else 0.0)
    v = gurney_sandwich(gurney_constant(c["explosive"]), 1e-3, explosive)  # a 1 g stone on the charge
    assert bare["velocity_m_s"] == pytest.approx(v, rel=1e-12) and bare["distance_m"] < v * v / 9.81
    assert any("shell" in x["source"] for x in f["sources"]) == (named is not None)
    assert c["pad"]["thickness_m"] >= max(0.01, 4 * c["pad"]["cut_thickness_m"]) and "steel" in c["pad"]["material"]
    assert c["pad"]["length_m"] > c["standoff_m"] and "none" in f["pad_fragments"]
    det = c["detonator"]
    assert "centre" in det["placement"] and det["insertion_depth_m"] == c["layout"]["charge_radius_m"]
    if named:
        assert det["used"] == INITIATORS[named].description and det["tnt_pressure_kg"] > det["tnt_impulse_kg"]
    assert c["camera_fps"] == c["instruments"]["camera_fps"]
    p, L = c["predicted"], c["layout"]
    g = face_loads(
        c["tnt_equivalent_impulse_kg"],
        L["charge"],
        [L["reflected_gauge"]],
        [[-1.0, 0.0, 0.0]],
        blast_model="kingery-bulmash",
    )
    assert p["reflected_gauge_pressure_Pa"] == pytest.approx(float(g.pressure[0]), rel=1e-12)
    assert p["reflected_gauge_impulse_Pa_s"] == pytest.approx(float(g.impulse[0]), rel=1e-12)
    assert p["reflected_gauge_pressure_Pa"] < p["reflected_pressure_Pa"] and 0 < p["reflected_gauge_angle_deg"] < 90
    # the gauges' ranges: 1.5 x their own predicted peaks (was the face's: 37 x too wide for the block at 1/20)
    assert c["instruments"]["reflected_gauge_range_Pa"] == pytest.approx(
        1.5 * p["reflected_gauge_pressure_Pa"], rel=1e-12
    )
    assert c["instruments"]["incident_gauge_range_Pa"] == pytest.approx(
        1.5 * p["incident_gauge_pressure_Pa"], rel=1e-12
    )
    o3 = c["odds_3d"]
    assert o3["trials"] == 2 and o3["p_outcome_agree_low"] < o3["p_outcome_agree_high"]
    assert c["tnt_equivalent_safety_kg"] == max(c["tnt_equivalent_pressure_kg"], c["tnt_equivalent_impulse_kg"])
    assert c["safety_distances_m"]["6.9 kPa"] == c["safety_radius_m"]
    html = (folder / "report.html").read_text()
    assert f"(95 %, {o3['agree_count']} of 2)" in html and "to weigh" in html and "fragment hazard distance" in html
    assert (
        "e+0"
        not in re.sub(r"<script.*?</script>", "", html, flags=re.S).split('id="test_card"')[1].split("</section>")[0]
    )  # no "5.592e+04 g": every mass in the unit it reads in


_OVERFLOW = """<script>window.addEventListener("load", () => {
  const s = document.getElementById("test_card"), w = window.innerWidth;
  const wide = [...s.querySelectorAll("*")].filter(e => e.getBoundingClientRect().right > w + 1);
  document.body.setAttribute("data-overflow", JSON.stringify({page: document.documentElement.scrollWidth, w: w,
    wide: wide.map(e => e.tagName + "." + (e.getAttribute("class") || "")).slice(0, 5)}));
});</script>"""


@pytest.mark.skipif(_chromium() is None, reason="Chromium not found (Debian: apt-get install -y chromium)")
def test_the_column_card_fits_1280_px_in_chromium(column_dir, tmp_path):
    """The column's card in headless Chromium at 1280 px: nothing in it reaches past the window's right edge and
    the page does not scroll sideways; every tagged number is summary.json's."""
    page = tmp_path / "report.html"
    page.write_text((column_dir / "report.html").read_text().replace("</body>", _OVERFLOW + "</body>"))
    for other in column_dir.iterdir():
        if other.name != "report.html" and other.is_file():
            shutil.copy(other, tmp_path / other.name)
    env = {**os.environ, "HOME": str(tmp_path)}
    dom = subprocess.run(
        [
            _chromium(),
            *FLAGS,
            f"--user-data-dir={tmp_path / 'p'}",
            "--window-size=1280,2000",
            "--virtual-time-budget=5000",
            "--dump-dom",
            page.as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
    )
    assert dom.returncode == 0, dom.stderr[-2000:]
    got = json.loads(html_unescape(re.search(r'data-overflow="([^"]*)"', dom.stdout).group(1)))
    assert got["page"] <= got["w"] == 1280 and got["wide"] == [], got
    p = _Numbers()
    p.feed(dom.stdout)
    card = _card(column_dir)
    assert len(p.numbers) >= 60
    for key, unit, prefix, text in p.numbers:
        assert text == prefix + shown(_get(card, key), unit), (key, unit, text)
