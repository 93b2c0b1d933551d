"""Work in a forked child (blastscale._fork, issue #28: a result folder's figures drawn beside its histories):
the value is the child's when all goes well and the same value computed in the caller whenever the child fails,
hangs or is turned off; a child never outlives its ``with`` block."""

from __future__ import annotations

import os
import sys
import time

import pytest

from blastscale._fork import FORK_ENV, Forked, fork_available

PARENT = os.getpid()

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the child is forked on Linux only")


def where(x):
    """x and the process that computed it."""
    return x, os.getpid()


def fails_in_child(x):
    if os.getpid() != PARENT:
        raise RuntimeError("boom")
    return x


def dies_in_child(x):
    if os.getpid() != PARENT:
        os._exit(3)
    return x


def hangs_in_child(x):
    if os.getpid() != PARENT:
        time.sleep(60)
    return x


def _gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


def test_the_value_comes_from_a_child():
    with Forked(where, 41) as job:
        assert job.forked and fork_available()
        value, pid = job.result()
    assert value == 41 and pid != PARENT and job.fell_back == ""


@pytest.mark.parametrize("fn, why", [(fails_in_child, "RuntimeError: boom"), (dies_in_child, "EOFError")])
def test_a_failing_child_gives_the_value_computed_here(fn, why):
    with Forked(fn, [1, 2]) as job:
        assert job.result() == [1, 2]
    assert job.fell_back.startswith(why)


def test_a_hanging_child_is_killed_and_the_value_computed_here():
    """The wait ended by the timeout (``fell_back`` says so), not by the clock of this test."""
    with Forked(hangs_in_child, "x") as job:
        pid = job._pid
        assert job.result(timeout=0.5) == "x"
    assert "TimeoutError" in job.fell_back
    assert _gone(pid)  # killed and reaped: no zombie either


def test_a_child_not_collected_dies_with_its_block():
    with pytest.raises(KeyboardInterrupt):
        with Forked(hangs_in_child, 1) as job:
            pid = job._pid
            raise KeyboardInterrupt
    assert _gone(pid)


def test_turned_off_it_runs_here(monkeypatch):
    monkeypatch.setenv(FORK_ENV, "0")
    with Forked(where, 5) as job:
        assert not job.forked
        assert job.result() == (5, PARENT)


def noisy(x):
    """Prints, warns and logs (in the child: all to nowhere)."""
    import logging
    import warnings

    print("from the child")
    warnings.warn("a warning from the child", UserWarning)
    logging.getLogger("blastscale.test").error("a log record from the child")
    sys.stderr.write("to stderr\n")
    return x


def test_the_child_prints_nothing(capfd):
    with Forked(noisy, 7) as job:
        assert job.result() == 7 and job.fell_back == ""
    out, err = capfd.readouterr()
    assert "child" not in out + err and "stderr" not in out + err
