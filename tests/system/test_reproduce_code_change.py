"""``reproduce`` skips an item done only when the same blastscale code did it (issue #30): after the code
changes (a ``git pull`` into an editable install keeps the version) every item runs again."""

from __future__ import annotations

import json

import pytest

import blastscale._code as code
from blastscale.cli import main


def _reproduce(capsys, out) -> str:
    with pytest.raises(SystemExit) as e:
        main(["reproduce", "--out", str(out), "--quick", "--only", "scaling-factors", "--only", "table-geometry"])
    assert (e.value.code or 0) == 0
    return capsys.readouterr().out


def test_items_done_by_other_code_run_again(capsys, tmp_path, monkeypatch, patch_everywhere):
    out = tmp_path / "paper"
    _reproduce(capsys, out)
    assert _reproduce(capsys, out).count("skipped (done)") == 2  # the same code: nothing to do
    marker = json.loads((out / "scaling-factors" / "item.json").read_text())
    patch_everywhere(code, "code_fingerprint", lambda: "0" * 64)  # as after a git pull
    assert "skipped (done)" not in _reproduce(capsys, out)
    again = json.loads((out / "scaling-factors" / "item.json").read_text())
    assert again["fingerprint"] != marker["fingerprint"] and again["rows"] == marker["rows"]
