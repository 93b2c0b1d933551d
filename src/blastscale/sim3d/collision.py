"""Which surfaces may touch, and the order in which the engine numbers the bodies
(docs/sim3d.md, "Contacts and body order").

1. **Interfaces** (faces in contact at rest, ``structure.interfaces``; the ground is -1) are explicit
   MuJoCo ``<pair>`` elements that engage at contact (margin 0), listed first so that their contacts
   keep their order in the solver.
2. **Every other two surfaces** (two bodies, or a body and the ground) may touch once the structure
   moves (falling drums, blocks thrown onto others). They collide through MuJoCo's broad phase
   (sort-and-prune, ~N log N) with the same contact settings, instead of N (N + 1) / 2 explicit pairs
   (20,100 pairs for 200 blocks: 12 % of a step spent checking them), and the body pairs of rule 1 are
   excluded from it (``<exclude>``) so that no two surfaces are counted twice. They engage once the
   surfaces overlap by :func:`engagement_depth` = g tau^2, the static penetration of a soft contact
   carrying its body's weight (``time_constant`` tau; 9.8 um in the 10 m reference of a stack). Why:
   neighbours that are not an interface but touch along an edge or at a corner at rest (the diagonal
   neighbours of a stack-bonded wall) overlap by the interfaces' own penetration, and MuJoCo's box
   collider reports them a contact along the axis of least overlap (a horizontal force from a
   vertical overlap) that comes and goes with 1e-7 m motions. At margin 0 a 20 x 10 stack-bonded wall
   swayed in its plane at 3 mm/s "at rest" and never settled; with the depth it settles as with its
   interfaces alone (bitwise the same motion). A collision that really happens (a block falling on
   another at v ~ 1 m/s penetrates ~ v tau = 1 mm) starts 1 % later in penetration.
   MuJoCo geoms carry no ``solreffriction``: with ``friction_time_constant`` set on a structure of
   several bodies, rule 2's pairs are explicit ``<pair>`` elements instead (the same settings).
3. **Body order**: MuJoCo's sparse factorisation of the Newton solver's Hessian works in the order of
   the degrees of freedom, i.e. of the bodies. When the reverse Cuthill-McKee ordering of the
   interface graph (Cuthill & McKee 1969; George 1971) has a smaller profile than the structure's own
   order, the bodies are numbered in it (a 20-course stack-bonded wall listed course by course: 1.6x
   faster, docs/performance.md); a column (a chain) keeps its order. Results are always given in the
   structure's order (:attr:`~.model.Scene.body_ids`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["BROAD_PHASE", "body_order", "engagement_depth", "profile"]

#: The geom attributes that put every body and the ground in MuJoCo's broad phase (rule 2).
BROAD_PHASE = 'contype="1" conaffinity="1"'


def engagement_depth(time_constant: float, gravity: float) -> float:
    """Overlap [m] at which two surfaces that are not an interface start to push: g tau^2, the static
    penetration scale of MuJoCo's soft contact (stiffness ~ 1 / tau^2 per unit mass) under gravity g
    [m/s^2], contact time constant tau [s] (module docstring, rule 2)."""
    return float(gravity) * float(time_constant) ** 2


def _graph(interfaces, nbody: int) -> list:
    adj = [set() for _ in range(nbody)]
    for i, j in interfaces:
        if i >= 0 and j >= 0 and i != j:
            adj[i].add(j)
            adj[j].add(i)
    return adj


def profile(order, adj) -> int:
    """The profile (envelope size) of the interface graph's matrix with the bodies numbered in
    ``order``: the sum over rows of the distance to the row's first non-zero."""
    pos = np.empty(len(order), dtype=int)
    pos[np.asarray(order, dtype=int)] = np.arange(len(order))
    return int(sum(pos[k] - min([pos[k]] + [pos[j] for j in adj[k]]) for k in range(len(adj))))


def body_order(interfaces, nbody: int) -> np.ndarray:
    """The engine's numbering of the bodies (rule 3): ``order[p]`` is the structure's index of the
    body that MuJoCo numbers ``p + 1``; the identity unless reverse Cuthill-McKee lowers the profile.

    Parameters
    ----------
    interfaces : sequence of (int, int)
        Bodies in contact at rest, by index (-1 = ground, ignored here).
    nbody : int
        Number of bodies.

    Returns
    -------
    ndarray of int (nbody,)
    """
    natural = np.arange(nbody)
    if nbody <= 2:
        return natural
    adj = _graph(interfaces, nbody)
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    rows = [i for i in range(nbody) for _ in adj[i]]
    cols = [j for i in range(nbody) for j in sorted(adj[i])]
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(nbody, nbody)).tocsr()
    rcm = np.asarray(reverse_cuthill_mckee(graph, symmetric_mode=True), dtype=int)
    return rcm if profile(rcm, adj) < profile(natural, adj) else natural
