"""The constraint Jacobian by structure size and MuJoCo version (docs/performance.md).

Measured on the paper's 10-drum columns (250 kg at 10 m, 4 s, Newton, tolerance 1e-10): the sparse
Jacobian runs the square column 2.8x and the circular 1.8x faster than the dense one, with the dense
histories to 1.4e-12 of the peak (square; the circular column is chaotic); CG and PGS, with either
Jacobian, and looser tolerances either depart from the reference by more than 1e-6 of the peak
(CG: 1.5e-3, PGS: 3.4e-4) or are no faster. One body: dense (40 vs 36 simulated s per wall s).

MuJoCo 4.0.0's sparse Cholesky factorisation merged rows with different descendants into one supernode
and gave the Newton solver a wrong Hessian factor when the constraint Jacobian is sparse (MuJoCo issue
3767, fixed in 4.0.1). tests/integration/test_sparse_factorisation.py re-evaluates our scenes' states
(square and circular columns rocking and collapsing, walls of 10 and 50 blocks under a blast) with
both Jacobians: the same Newton iterations at every state and accelerations equal to round-off, i.e.
those scenes do not reach the bug. Every blastscale scene is of that one family (free bodies, one
free joint each, on a ground plane: the Hessian's sparsity pattern is the same block pattern for a
column, a wall or a portal), so the default is sparse for every stack on 4.0.0 as well, guarded by that
test on the installed version. On a MuJoCo older than 4.0.0 (not supported by the project's pins, but
possible in a user's environment) stacks up to :data:`DENSE_JACOBIAN_MAX_BODIES` bodies stay dense.
"""

from __future__ import annotations

import functools
from importlib.metadata import PackageNotFoundError, version as _version

__all__ = ["DENSE_JACOBIAN_MAX_BODIES", "SPARSE_FIXED_MUJOCO", "default_jacobian", "sparse_factorisation_fixed"]

#: On a MuJoCo without the probe (older than 4.0.0), structures with more bodies than this get the sparse
#: constraint Jacobian: measured on stack-bonded walls (Newton, 0.25 ms, benchmarks/bench_assemblies.py)
#: the dense one costs 12x more at 50 blocks and runs out of memory at 200.
DENSE_JACOBIAN_MAX_BODIES = 10

#: The first MuJoCo release with the sparse factorisation fixed (issue 3767).
SPARSE_FIXED_MUJOCO = (4, 0, 1)

#: The release whose bug our scenes were probed for (tests/integration/test_sparse_factorisation.py).
SPARSE_PROBED_MUJOCO = (4, 0, 0)


def _parse(version: str) -> tuple:
    out = []
    for part in version.split(".")[:3]:
        digits = "".join(ch for ch in part if ch.isdigit())
        out.append(int(digits) if digits else 0)
    return tuple(out + [0] * (3 - len(out)))


@functools.lru_cache(maxsize=None)
def sparse_factorisation_fixed(version: str | None = None) -> bool:
    """Whether MuJoCo ``version`` (default: the installed one) is at least :data:`SPARSE_FIXED_MUJOCO`."""
    return _released_at_least(version, SPARSE_FIXED_MUJOCO)


def default_jacobian(nbody: int, version: str | None = None) -> str:
    """The constraint Jacobian of a structure of ``nbody`` bodies: "dense" for one body (40 vs 36
    simulated s per wall s); for a stack "sparse" (the square column 2.8x, the circular 1.8x faster) on
    MuJoCo 4.0.0, whose factorisation bug our scenes were shown not to reach, and on every fixed release
    (>= 4.0.1); on older releases sparse only above :data:`DENSE_JACOBIAN_MAX_BODIES` bodies."""
    if nbody <= 1:
        return "dense"
    if nbody > DENSE_JACOBIAN_MAX_BODIES or _released_at_least(version, SPARSE_PROBED_MUJOCO):
        return "sparse"
    return "dense"


def _released_at_least(version: str | None, release: tuple) -> bool:
    if version is None:
        try:
            version = _version("mujoco")
        except PackageNotFoundError:  # pragma: no cover - the engine needs MuJoCo anyway
            return False
    return _parse(version) >= release
