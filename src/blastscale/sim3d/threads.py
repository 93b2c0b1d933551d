"""Independent 3D runs in parallel native threads: ensemble members, the 3D cases of a sweep chunk.

MuJoCo releases Python's GIL inside ``mj_step`` (measured: 4 runs of the 10-drum column on 2
threads take 1/1.94 of their serial time), and after the pulse the engine steps in native chunks
(``mj_step(m, d, nstep)``, :mod:`.integrate`), so runs that each own their ``MjModel`` and
``MjData`` proceed in parallel; the short Python load phase of one run interleaves with the native
stepping of the others. Each run is the same sequence of floating-point operations as in a serial
loop (no state is shared; MuJoCo's own thread pool is not used, so no reduction order changes): the
members' histories are bitwise those of the serial run (tests/integration/test_parallel_members.py).

The mechanism (one knob, ``threads``; its default the process's share of the cores, through
:data:`THREADS_ENV` on local Dask workers; 1 inside a parallel run) lives in :mod:`blastscale._threads`,
shared with the planar batch kernels; this module re-exports it for the 3D callers.
"""

from __future__ import annotations

from .._threads import (
    THREADS_ENV,
    available_cores,
    default_threads,
    map_threads,
    resolve_threads,
)

__all__ = ["THREADS_ENV", "available_cores", "default_threads", "map_threads", "resolve_threads"]
