"""The test card of ``run`` with a [lab] table: summary.json's ``test_card`` keys, and the report's card
rendered in headless Chromium with every number it shows equal to summary.json."""

import json
import os
import re
import shutil
import subprocess
from html.parser import HTMLParser

import pytest

from blastscale.planning.odds import outcome_odds_text
from blastscale.report import write_study
from blastscale.report.card import shown
from blastscale.scenario import Scenario
from blastscale.study import Study

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
    data["lab"] = {"explosive": "c-4", "initiator_tnt_kg": 3e-8, "samples": 500, "seed": 2}
    write_study(Study(Scenario.from_dict(data)).run(), folder)
    return folder


def _get(card, key):
    for part in key.split("/"):
        card = card[part]
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
