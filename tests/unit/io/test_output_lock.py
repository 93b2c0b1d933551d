"""Issue #23: the output lock (blastscale.io.output) is ``filelock``'s, not ``fcntl``'s: a second writer of the
same target is refused in one line naming the holder, the lock file goes when the writer ends, and the module
imports and locks where ``fcntl`` does not exist (filelock's soft lock there; its native lock on Windows)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.io.output import claim
from blastscale.io.targets import Kind

KIND = Kind("a test output", lambda p: True)
SRC = Path(__file__).resolve().parents[3] / "src"


def test_a_second_claim_is_refused_naming_the_holder_and_the_lock_goes(tmp_path):
    target = tmp_path / "x"
    with claim(target, KIND):
        assert sorted(p.name for p in tmp_path.iterdir()) == [".x.lock"]
        # a second lock on the same file, even from this process (another open file), is refused
        with pytest.raises(
            BlastscaleInputError,
            match=rf"is being written by another blastscale process "
            rf"\(pid {os.getpid()} on ",
        ):
            with claim(target, KIND):
                pass
    assert list(tmp_path.iterdir()) == []
    with claim(target, KIND):  # free again
        pass
    assert list(tmp_path.iterdir()) == []


def test_the_lock_works_without_fcntl(tmp_path):
    code = (
        f"import sys; sys.modules['fcntl'] = None; sys.path.insert(0, {str(SRC)!r})\n"
        "import warnings; warnings.simplefilter('ignore')\n"
        "from pathlib import Path\n"
        "from blastscale._validate import BlastscaleInputError\n"
        "from blastscale.io.output import Kind, claim\n"
        "k = Kind('a test output', lambda p: True)\n"
        "with claim(Path('x'), k):\n"
        "    try:\n"
        "        with claim(Path('x'), k):\n"
        "            print('not refused')\n"
        "    except BlastscaleInputError as e:\n"
        "        print('refused:', e)\n"
        "import os; print('left:', sorted(os.listdir('.')))\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "refused: out = 'x' is being written by another blastscale process" in proc.stdout, proc.stdout
    assert "left: []" in proc.stdout
