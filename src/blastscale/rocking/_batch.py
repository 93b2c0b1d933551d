"""A batch of planar rocking cases split over threads (the compiled kernel releases the GIL).

:func:`solve_batch` hands the cases to :func:`solve_into` (compiled, lock-free) in interleaved groups (case i in
group ``i mod g``, ``g = GROUPS_PER_THREAD x threads``) taken by ``threads`` threads as each
finishes its last (:func:`blastscale._threads.map_threads`): the cost of a case follows the charge
order of a sweep (contiguous halves gave nothing where alternate cases on 2 threads gave 2.03x,
issue #28), and the groups taken on demand balance what the interleaving leaves. Every case is
computed by the same compiled code on its own data, so the results are bitwise those of one
thread (tests/unit/rocking/test_batch_threads.py).

``threads``: :func:`blastscale._threads.resolve_threads` (None: the cores this process may use, or
its share ``cores // workers`` on a local Dask worker, 1 inside a parallel run). Batches smaller
than :data:`MIN_CASES_PER_THREAD` per thread run in the calling thread.

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import numpy as np

from .._jit import njit
from .._threads import map_threads, resolve_threads
from .kernel import solve_case
from .layout import N_SUMMARY

__all__ = ["GROUPS_PER_THREAD", "MIN_CASES_PER_THREAD", "solve_batch", "solve_into"]

#: Fewest cases per thread worth a thread (below: one call in the calling thread).
MIN_CASES_PER_THREAD = 16
#: Interleaved groups per thread (taken on demand: balances cases of unequal cost).
GROUPS_PER_THREAD = 4
#: Position of ``tau_eval`` among the ``case`` arguments of :func:`solve_batch` (the arguments of
#: :func:`solve_into` after ``idx``).
_TAU_EVAL = 10


def solve_batch(*case, threads=None):
    """Solve n encoded cases on up to ``threads`` threads.

    ``case``: the arguments of :func:`solve_into` between ``idx`` and the outputs, in its order
    (``alpha`` ... ``tab_off``, ``tau_eval`` (n, m), ``rtol`` ... ``record``): arrays of length n,
    ``par`` (n, PAR_SIZE), tabulated pulses at ``tab_off[i]:tab_off[i+1]`` of ``tab_t``/``tab_f``;
    the settings of :func:`.kernel.solve_case`. They are handed over unchanged to every group.

    Returns
    -------
    tuple
        Summaries (n, N_SUMMARY), theta (n, m) [rad] and w = theta_dot / p (n, m) [-].
    """
    n = int(np.size(case[0]))  # alpha
    m = case[_TAU_EVAL].shape[1]
    summ = np.empty((n, N_SUMMARY))
    th_out = np.empty((n, m))
    w_out = np.empty((n, m))
    nt = min(resolve_threads(threads), n // MIN_CASES_PER_THREAD)
    groups = (
        [np.arange(n, dtype=np.int64)]
        if nt <= 1
        else [np.arange(k, n, GROUPS_PER_THREAD * nt, dtype=np.int64) for k in range(GROUPS_PER_THREAD * nt)]
    )

    def run(idx):
        solve_into(idx, *case, summ, th_out, w_out)

    map_threads(run, groups, max(1, nt))
    return summ, th_out, w_out


@njit(cache=True, nogil=True)
def solve_into(
    idx,
    alpha,
    e,
    th0,
    w0,
    tau_end,
    kind,
    par,
    tab_t,
    tab_f,
    tab_off,
    tau_eval,
    rtol,
    atol,
    w_rest,
    max_impacts,
    stop_at_overturn,
    max_steps,
    record,
    summ,
    th_out,
    w_out,
):
    """Loop :func:`solve_case` over the cases ``idx`` (int64 indices into arrays of length n;
    ``par`` (n, PAR_SIZE); tabulated pulses concatenated in ``tab_t``/``tab_f`` with case i at
    ``tab_off[i]:tab_off[i+1]``; ``tau_eval`` (n, m)) and write row i of the summaries ``summ``
    (n, N_SUMMARY), theta ``th_out`` (n, m) and w ``w_out`` (n, m). Releases the GIL: calls on
    disjoint ``idx`` may run in parallel threads (:func:`solve_batch`); each case is the same sequence
    of operations whichever thread runs it."""
    m = tau_eval.shape[1]
    for j in range(idx.size):
        i = idx[j]
        tt = tab_t[tab_off[i] : tab_off[i + 1]].copy()
        tf = tab_f[tab_off[i] : tab_off[i + 1]].copy()
        te = tau_eval[i].copy()
        pr = par[i].copy()
        r = solve_case(
            alpha[i],
            e[i],
            th0[i],
            w0[i],
            tau_end[i],
            kind[i],
            pr,
            tt,
            tf,
            te,
            rtol,
            atol,
            w_rest,
            max_impacts,
            stop_at_overturn,
            max_steps,
            record,
        )
        for k in range(N_SUMMARY):  # plain loops: row slice assignments are slow to compile
            summ[i, k] = r[0][k]
        for k in range(m):
            th_out[i, k] = r[1][k]
            w_out[i, k] = r[2][k]
