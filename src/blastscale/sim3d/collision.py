"""Which surfaces may touch, and the order in which the engine numbers the bodies
(docs/sim3d.md, "Contacts and body order").

1. **Interfaces** (faces in contact at rest, ``structure.interfaces``; the ground is -1) are explicit
   MuJoCo ``<pair>`` elements, listed first so that their contacts keep their order in the solver. A
   **bed joint** engages at contact (margin 0). A **side joint** (:func:`side_joints`: every face of the pair
   in a vertical plane, between blocks that rest on level beds only) carries no weight at rest: its faces
   touch at zero overlap, and at margin 0 MuJoCo counts them a contact or not by round-off, the solver's
   active set changes from step to step and the wall never rests (a 50 x 60 stack-bonded wall "at rest" kept
   its bodies at 2-6e-2 m/s in the 10 m reference with 6-30 Newton iterations and 1.6 CPU s a step; a 40 x 5
   wall 1e-2 m/s, where 40 x 1 to 40 x 3, without side contacts at rest, decay to 1e-11 m/s). A side joint
   therefore engages as rule 2 does, once its faces overlap by :func:`engagement_depth`: both walls rest
   (1e-11 m/s; one Newton iteration and 32 ms a step on the 3000-block wall; docs/performance.md, "Side
   joints"). A vertical joint between blocks on inclined joints (the crown joint of an arch of an even number
   of voussoirs) carries the thrust at rest and keeps engaging at contact: engaging it late lets the arch move
   before the joint bears.
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

import math

import numpy as np

__all__ = ["BROAD_PHASE", "SIDE_JOINT_TILT", "body_order", "engagement_depth", "level_stack", "profile", "side_joints"]

#: The geom attributes that put every body and the ground in MuJoCo's broad phase (rule 2).
BROAD_PHASE = 'contype="1" conaffinity="1"'


#: Tilt [rad] within which a joint's plane counts as vertical (a side joint) or horizontal (a level bed): the largest
#: vertical, resp. horizontal, component of its unit normal (rule 1; the 1e-6 of the geometry spread a wall's outcomes
#: are read against, docs/performance.md).
SIDE_JOINT_TILT = 1e-6


def _level(itf) -> bool:
    """Whether an interface's plane is horizontal within :data:`SIDE_JOINT_TILT` (its unit normal's horizontal part)."""
    return math.hypot(float(itf.normal[0]), float(itf.normal[1])) <= SIDE_JOINT_TILT


def side_joints(details) -> frozenset:
    """The unloaded side joints among an assembly's interfaces (rule 1): the pairs ``(first, second)`` whose every
    :class:`~blastscale.structures.interfaces.Interface` lies in a vertical plane and whose blocks rest on level beds
    only (every other interface of each block horizontal), all within :data:`SIDE_JOINT_TILT`. Such a block is held
    up by its beds: gravity puts no force on its side faces at rest (the head joints of a wall of rectangular blocks).
    A vertical joint between blocks on inclined joints (the crown joint of an arch of an even number of voussoirs)
    carries the thrust at rest and is not one. ``details``: the interfaces with their normals
    (``interface_details``; a structure without them, a block or a column, has beds only: pass ())."""
    vertical: dict = {}
    for itf in details:
        vertical[itf.pair] = vertical.get(itf.pair, True) and abs(float(itf.normal[2])) <= SIDE_JOINT_TILT
    level: dict = {}
    for itf in details:
        if vertical[itf.pair]:
            continue
        flat = _level(itf)
        for k in itf.pair:
            level[k] = level.get(k, True) and flat
    return frozenset(p for p, v in vertical.items() if v and all(level.get(k, False) for k in p if k >= 0))


def level_stack(details) -> bool:
    """Whether an assembly is a stack on level beds: every interface horizontal or a side joint
    (:func:`side_joints`), all within :data:`SIDE_JOINT_TILT` (the walls of rectangular blocks in any bond, a
    portal's posts and lintel; not an arch, whose joints are inclined). ``details``: ``interface_details`` (empty:
    False). Such a stack settles kinetically (:attr:`~.contact.ContactSettings.settling`)."""
    details = tuple(details)
    side = side_joints(details)
    return bool(details) and all(itf.pair in side or _level(itf) for itf in details)


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
