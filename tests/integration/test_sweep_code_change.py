"""A sweep is resumed only by the code that computed its chunks (issue #30): after blastscale's code changes
(a ``git pull`` into an editable install keeps the version), neither a finished store nor unfinished chunks
are taken for this sweep's results: refused with one line, recomputed with ``force``."""

from __future__ import annotations

import pytest

pytest.importorskip("zarr")

import blastscale._code as code
from blastscale._validate import BlastscaleInputError
from blastscale.scenario import Scenario
from blastscale.sweeps import SweepSpec
from blastscale.sweeps.run import run_sweep

# short planar runs of the paper's block (0.5 s, 51 samples), two charges, one case per chunk
BASE = Scenario.default().with_values({"engine": "planar", "duration_s": 0.5, "samples": 51})
SPEC = SweepSpec.build(BASE, {"charge_kg": [40.0, 90.0]})


class Stop(Exception):
    pass


def _stop_after_one_chunk(done, n):
    if done >= 1:
        raise Stop


def _other_code(patch_everywhere):
    """As after a ``git pull`` that changed a module (the version unchanged)."""
    before = SPEC.fingerprint()
    patch_everywhere(code, "code_fingerprint", lambda: "0" * 64)
    assert SPEC.fingerprint() != before


def test_a_finished_store_of_other_code_is_not_this_sweep(tmp_path, patch_everywhere):
    store = tmp_path / "s.zarr"
    assert run_sweep(SPEC, store, workers=0, chunk=1).chunks_run == 2
    assert run_sweep(SPEC, store, workers=0).chunks_run == 0  # the same code: nothing to do
    _other_code(patch_everywhere)
    with pytest.raises(BlastscaleInputError, match="exists"):
        run_sweep(SPEC, store, workers=0)
    assert run_sweep(SPEC, store, workers=0, chunk=1, force=True).chunks_run == 2


def test_unfinished_chunks_of_other_code_are_not_resumed(tmp_path, patch_everywhere):
    store = tmp_path / "s.zarr"
    with pytest.raises(Stop):
        run_sweep(SPEC, store, workers=0, chunk=1, progress=_stop_after_one_chunk)
    parts = tmp_path / "s.zarr.parts"
    assert len(list(parts.glob("chunk-*.npz"))) == 1  # one chunk kept to resume from
    _other_code(patch_everywhere)
    with pytest.raises(BlastscaleInputError, match="computed by other blastscale code"):
        run_sweep(SPEC, store, workers=0, chunk=1)
    run = run_sweep(SPEC, store, workers=0, chunk=1, force=True)
    assert run.chunks_run == 2 and not parts.exists()  # both computed by this code
