"""The fingerprint of blastscale's code (:mod:`blastscale._code`, issue #30), which keys the results reused
from one run to the next (a resumed sweep's chunks, reproduce's items done)."""

from __future__ import annotations

import shutil
from pathlib import Path

import blastscale
from blastscale._code import code_files, code_fingerprint

SRC = Path(blastscale.__file__).resolve().parent


def test_any_source_or_data_change_changes_it_and_caches_do_not(tmp_path):
    copy = tmp_path / "blastscale"
    shutil.copytree(SRC, copy, ignore=shutil.ignore_patterns("__pycache__"))
    names = {f.relative_to(copy).as_posix() for f in code_files(copy)}
    assert {"rocking/_load.py", "blast/data/ufc_3_340_02_fig2_193.csv", "__init__.py"} <= names
    assert not any("__pycache__" in n or n.endswith(".pyc") for n in names)

    def fp():
        code_fingerprint.cache_clear()
        return code_fingerprint(copy)

    try:
        original = fp()
        (copy / "rocking" / "__pycache__" / "numba").mkdir(parents=True)  # Python's and numba's caches: not code
        (copy / "rocking" / "__pycache__" / "numba" / "x.nbi").write_bytes(b"index")
        assert fp() == original
        load = copy / "rocking" / "_load.py"
        text = load.read_text()
        load.write_text(text.replace("f = base_ratio(", "f = 2.0 * base_ratio(", 1))
        assert fp() != original
        load.write_text(text)
        assert fp() == original
        table = copy / "blast" / "data" / "ufc_3_340_02_fig2_193.csv"
        table.write_bytes(table.read_bytes() + b"\n")
        assert fp() != original
    finally:
        code_fingerprint.cache_clear()
