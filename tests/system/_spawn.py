"""Run the ``blastscale`` console script as a user does, paused at a named point (blastscale._hooks), for the
tests that interrupt or race a command: they wait for the pause's marker file, never for the clock."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

_SCRIPT = Path(sys.executable).with_name("blastscale")
BLASTSCALE = (
    [str(_SCRIPT)]
    if _SCRIPT.exists()
    else [sys.executable, "-c", "import sys; sys.argv[0] = 'blastscale'; from blastscale.cli import main; main()"]
)


def default_signals() -> None:
    """In the child, before it starts: SIGINT, SIGTERM and SIGHUP back to their defaults. A shell starts a
    background job (`pytest ... &`) with SIGINT ignored and `nohup` with SIGHUP ignored; blastscale keeps a
    signal it was started with ignored (as a background job must), so the tests would wait for nothing."""
    for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(s, signal.SIG_DFL)


def spawn(args, cwd, pause: str | None = None, marker: Path | None = None, group: bool = False):
    """Start ``blastscale ARGS`` in ``cwd``; with ``pause``, it writes ``marker`` and waits at that point."""
    # no plain progress lines: a command slowed by a loaded machine would print one every 30 s and the tests
    # that read standard error as "the one line and nothing else" would fail by the clock (seen at load 9)
    env = {**os.environ, "MPLBACKEND": "Agg", "BLASTSCALE_PROGRESS_SECONDS": "1e9"}
    if pause:
        env.update(BLASTSCALE_PAUSE_AT=pause, BLASTSCALE_PAUSE_MARKER=str(marker))
    return subprocess.Popen(
        BLASTSCALE + [str(a) for a in args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        env=env,
        start_new_session=group,
        preexec_fn=default_signals,
    )


def wait_for_marker(proc, marker: Path, limit: float = 120.0) -> None:
    """Until the paused command has written its marker (or has ended: then fail with its stderr)."""
    t0 = time.monotonic()
    while not marker.exists():
        if proc.poll() is not None:
            raise AssertionError(f"ended before its pause point (exit {proc.returncode}): {proc.stderr.read()}")
        if time.monotonic() - t0 > limit:
            proc.kill()
            raise AssertionError("the pause point was not reached")
        time.sleep(0.01)


def run(args, cwd, timeout: float = 300) -> subprocess.CompletedProcess:
    env = {**os.environ, "MPLBACKEND": "Agg"}
    return subprocess.run(
        BLASTSCALE + [str(a) for a in args], capture_output=True, text=True, cwd=cwd, env=env, timeout=timeout
    )
