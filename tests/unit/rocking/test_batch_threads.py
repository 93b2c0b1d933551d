"""A planar batch split over threads (issue #28): the compiled kernel releases the GIL and the cases
go to the threads in interleaved groups; every case is the same sequence of operations whichever
thread runs it, so the results must be bitwise those of one thread -- compared here on a mix of
pulse shapes, bodies, rocking and overturning cases, with more cases than one group per thread."""

from __future__ import annotations

import math
import threading

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.blast import Tabulated, blast_parameters
from blastscale.rocking import RockingSolver, RockingSystem, _batch, first_swing
from blastscale.structures.block import RectangularBlock

BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0))  # the paper's block


def _mix(n):
    charges = np.geomspace(20.0, 200.0, n)  # cost follows the charge: rocking at first, overturning at the end
    shapes = ("friedlander", "triangular", "impulsive")
    pulses = [blast_parameters(w, 2.0, blast_model="masi2021").pulse(shapes[k % 3]) for k, w in enumerate(charges)]
    pulses[5] = Tabulated([0, 1e-3, 3e-3], [4e6, 2e6, 0.0])
    bodies = [BLOCK if k % 4 else RectangularBlock(5.0, 1.5) for k in range(n)]
    return bodies, pulses


def test_batch_on_three_threads_is_bitwise_one_thread():
    n = 3 * _batch.MIN_CASES_PER_THREAD + 5  # three threads, twelve groups of unequal size
    bodies, pulses = _mix(n)
    t = np.linspace(0.0, 1.5, 31)
    one = RockingSolver(threads=1).simulate_batch(bodies, pulses, 1.5, t)
    three = RockingSolver(threads=3).simulate_batch(bodies, pulses, 1.5, t)
    assert 0 < one.collapsed.sum() < n  # both outcomes are in the mix
    for name in (
        "theta",
        "theta_dot",
        "collapsed",
        "max_rotation",
        "first_peak_angle",
        "n_steps",
        "n_impacts",
        "end_time",
        "collapse_time",
    ):
        np.testing.assert_array_equal(getattr(three, name), getattr(one, name), err_msg=name)


def test_batch_runs_on_several_threads(monkeypatch):
    """The split really uses threads: the kernel is entered from more than one thread. Each thread's first
    call waits (up to 60 s) until a second thread has entered too, so a busy machine on which one thread
    would otherwise take every group before the other starts cannot make the check pass or fail by chance."""
    seen = set()
    real = _batch.solve_into
    both = threading.Barrier(2, timeout=60.0)

    def spy(*args):
        me = threading.get_ident()
        if me not in seen:
            seen.add(me)
            if len(seen) <= 2:
                both.wait()
        return real(*args)

    bodies, pulses = _mix(2 * _batch.MIN_CASES_PER_THREAD)
    monkeypatch.setattr(_batch, "solve_into", spy)
    RockingSolver(threads=2).simulate_batch(bodies, pulses, 0.2, np.linspace(0.0, 0.2, 3))
    assert len(seen) == 2


@pytest.mark.parametrize("per_case_bodies", [False, True])
def test_first_swing_on_three_threads_is_bitwise_one_thread(monkeypatch, per_case_bodies):
    """The first swings of a batch dealt out over three threads in alternate shares of unequal size (blast
    parameters, pulse phases and free swings per share): every field bitwise one thread's, one body for every
    case or one per case; the shares are really three."""
    from blastscale import _threads
    from blastscale.rocking import swing

    n = 3 * swing.MIN_CASES_PER_THREAD + 7
    W = np.geomspace(40.0, 160.0, n)  # across the critical charge (~80 kg)
    system = RockingSystem.from_block(BLOCK)
    systems = [system if k % 3 else RockingSystem.from_block(RectangularBlock(5.0, 1.5)) for k in range(n)]
    bodies = systems if per_case_bodies else system
    a = first_swing(bodies, W, 2.0, blast_model="masi2021", solver=RockingSolver(threads=1))
    shares = []
    real = _threads.map_threads
    monkeypatch.setattr(_threads, "map_threads", lambda fn, items, k: shares.append(len(items)) or real(fn, items, k))
    b = first_swing(bodies, W, 2.0, blast_model="masi2021", solver=RockingSolver(threads=3))
    assert shares == [3]
    assert 0 < a.collapsed.sum() < W.size
    for name in ("collapsed", "max_rotation", "margin"):
        np.testing.assert_array_equal(getattr(b, name), getattr(a, name), err_msg=name)


@pytest.mark.parametrize("bad", [0, -1, 1.5, True])
def test_threads_is_checked(bad):
    with pytest.raises(BlastscaleInputError, match="threads"):
        RockingSolver(threads=bad)
