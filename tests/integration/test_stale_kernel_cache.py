"""No stale compiled kernels (issue #30): on a copy of the package, a planar case is run, a helper in
another module than the compiled caller is changed (the load doubled in ``rocking/_load.py``'s
``load_ratio``, inlined into ``kernel.solve_case``), the case is run again, the helper restored and
the case run a third time. Before the fix the second run silently reused the old machine code
(0.0687 rad, stands); now it compiles and the block falls; the third run gives the first run's
result bit for bit, loaded from the first run's cache (numba counts a hit and no miss, its index
file is not rewritten).

The copy starts with this tree's key folders (their keys depend on the sources' bytes, not on where
they are), so only the changed run compiles (~20 s on the project's 2-core machine)."""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import blastscale
from blastscale.blast import blast_parameters
from blastscale.rocking import RockingSystem, simulate
from blastscale.structures.block import RectangularBlock

pytestmark = pytest.mark.slow

SRC = Path(blastscale.__file__).resolve().parent

#: The paper's block (2h = 10 m, alpha = 15 deg, rho = 2000 kg/m^3) under 50 kg at 2 m (masi2021,
#: Friedlander): it stands (0.0687 rad, tests/data/cli_golden/rock_50.json); twice the load topples it.
CASE = """
import json, math
from blastscale.blast import blast_parameters
from blastscale.rocking import RockingSystem, simulate
from blastscale.rocking import kernel as K
from blastscale.structures.block import RectangularBlock

block = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
pulse = blast_parameters(50.0, 2.0, blast_model="masi2021").pulse("friedlander")
res = simulate(RockingSystem.from_block(block), pulse, 5.0)
st = K.solve_case.stats
print(json.dumps({"max_rotation": res.max_rotation.hex(), "collapsed": res.collapsed,
                  "hits": sum(st.cache_hits.values()), "misses": sum(st.cache_misses.values()),
                  "cache_path": st.cache_path, "module": K.__file__}))
"""


def _run(root: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "NUMBA_CACHE_LOCATOR_CLASSES")}
    env.update(PYTHONPATH=str(root), PYTHONDONTWRITEBYTECODE="1")  # no .pyc of the edited file in play
    out = subprocess.run([sys.executable, "-c", CASE], env=env, capture_output=True, text=True, timeout=600, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_a_changed_helper_is_compiled_again_and_the_original_comes_back_from_its_cache(tmp_path):
    # this tree's own result (compiled or from this tree's cache): its key folders warm the copy
    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    here = simulate(
        RockingSystem.from_block(block), blast_parameters(50.0, 2.0, blast_model="masi2021").pulse("friedlander"), 5.0
    )
    pkg = tmp_path / "blastscale"
    shutil.copytree(SRC, pkg, ignore=shutil.ignore_patterns("__pycache__"))
    warm = SRC / "rocking" / "__pycache__" / "numba"
    if warm.is_dir():
        shutil.copytree(warm, pkg / "rocking" / "__pycache__" / "numba")

    first = _run(tmp_path)
    assert Path(first["module"]).resolve().parent == pkg.resolve() / "rocking"  # the copy ran, not this tree
    assert first["max_rotation"] == here.max_rotation.hex() and not first["collapsed"]
    assert float.fromhex(first["max_rotation"]) == pytest.approx(0.0687373, abs=1e-7)  # rock_50.json
    index = sorted(Path(first["cache_path"]).glob("kernel.solve_case-*.nbi"))
    assert len(index) == 1
    stamp = index[0].stat().st_mtime_ns

    load = pkg / "rocking" / "_load.py"
    text = load.read_text()
    assert text.count("f = base_ratio(") == 1
    load.write_text(text.replace("f = base_ratio(", "f = 2.0 * base_ratio(", 1))
    doubled = _run(tmp_path)
    assert doubled["misses"] >= 1 and doubled["hits"] == 0  # compiled again, not the old code
    assert doubled["cache_path"] != first["cache_path"]
    assert doubled["collapsed"] and float.fromhex(doubled["max_rotation"]) == pytest.approx(math.pi / 2, abs=1e-9)

    load.write_text(text)
    restored = _run(tmp_path)
    assert restored["max_rotation"] == first["max_rotation"]  # bit for bit (float.hex)
    assert restored["cache_path"] == first["cache_path"]
    assert restored["hits"] >= 1 and restored["misses"] == 0  # from the first run's cache, not compiled
    assert index[0].stat().st_mtime_ns == stamp  # its index was read, not rewritten
    assert Path(doubled["cache_path"]).is_dir()  # both keys kept: an undone edit is found again
