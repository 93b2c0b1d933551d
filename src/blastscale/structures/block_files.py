"""Block-model files: our JSON, meshes (OBJ, STL, PLY) and COMPAS block-model JSON -> :class:`~.assembly.Assembly`.

Our JSON (metres, z up, the ground at z = 0)::

    {"blocks": [{"name": "B1", "vertices": [[x, y, z], ...], "density_kg_m3": 2400}, ...],
     "points": [{"name": "crown", "block": "B1", "position": [x, y, z]}]}

``name`` (default ``B1``, ``B2``, ...) and ``density_kg_m3`` (default: the scenario's) are optional per
block; a block is the convex hull of its vertices. An optional ``"faces"`` (lists of vertex indices)
describes the block's own polyhedron: a block whose volume is less than its hull's by more than
:data:`NONCONVEX_TOLERANCE` is refused (its hull would add mass); less than that, it is replaced by
its hull with a warning. ``points`` are extra monitoring points, world position at rest.

Meshes: one block per object (OBJ ``o``/``g``, a scene's geometries) or, in a file of one mesh (STL,
PLY), per connected component (blocks whose corners coincide are then glued together: give them as
separate objects, or in our JSON), read by ``trimesh`` (the optional ``mesh`` extra; installed by
``make install``). The convexity rule is the same (the component's own volume against its hull's).

COMPAS JSON: a ``compas_dem`` block model as ``compas.json_dump`` writes it (:mod:`.compas_files`:
the model's and elements' transformations honoured, ``is_support`` blocks fixed to the ground, names
kept, a block's COMPAS material giving its density), through COMPAS when installed and without it otherwise; in any other JSON, every COMPAS mesh
found (a dict with ``"vertex"``: {key: {"x", "y", "z"}} and ``"face"``: {key: [vertex keys]}, the data
layout of ``compas.datastructures.Mesh``) is one block.

Every problem is one line naming the file, the block and the problem (:class:`BlastscaleInputError`).

Size: a file of more than :func:`max_blocks` blocks (:data:`MAX_BLOCKS`, ``BLASTSCALE_MAX_BLOCKS`` to change it)
is refused as soon as its blocks are counted, before any geometry: reading a block model costs about
:data:`READ_SECONDS_PER_BLOCK` per block (hulls, faces, interfaces; docs/performance.md), so the limit keeps
``blastscale show`` of any file within about a minute.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from pathlib import Path

import numpy as np

from .._extras import require
from .._validate import BlastscaleInputError
from .assembly import Assembly
from .base import MonitoringPoint
from .compas_files import is_compas_model, mesh_arrays, read_compas_model
from .convex_block import ConvexBlock
from .polyhedron import hull_of

__all__ = [
    "read_block_model",
    "NONCONVEX_TOLERANCE",
    "MESH_SUFFIXES",
    "MAX_BLOCKS",
    "READ_SECONDS_PER_BLOCK",
    "max_blocks",
]

#: A block whose own volume is below its hull's by more than this fraction is refused as non-convex [-].
NONCONVEX_TOLERANCE = 0.05
#: The most blocks of a block-model file (``BLASTSCALE_MAX_BLOCKS`` changes it) [-].
MAX_BLOCKS = 10_000
#: Time to read one block of a file: hull, faces, mass properties, interfaces, checks [s] (measured: 3000 blocks
#: in 6.7 s, 20,000 in 42 s of CPU; docs/performance.md).
READ_SECONDS_PER_BLOCK = 2.2e-3
#: File suffixes read as meshes.
MESH_SUFFIXES = (".obj", ".stl", ".ply", ".off", ".glb", ".gltf")


#: The farthest a block's vertex may lie from the origin [m] (a scenario's structures are at most 1000 m).
MAX_COORDINATE_M = 1.0e4


def max_blocks() -> int:
    """The most blocks a block-model file may hold: ``BLASTSCALE_MAX_BLOCKS`` (a whole number >= 1), else
    :data:`MAX_BLOCKS`."""
    try:
        n = float(os.environ.get("BLASTSCALE_MAX_BLOCKS", ""))
    except ValueError:
        return MAX_BLOCKS
    return int(n) if math.isfinite(n) and n >= 1 else MAX_BLOCKS


def _check_count(source: str, n: int) -> None:
    """Refuse a file of more than :func:`max_blocks` blocks (one line: the count, the limit, the time)."""
    limit = max_blocks()
    if n > limit:
        raise BlastscaleInputError(
            f"{source}: {n} blocks is out of range: reading them would take about "
            f"{n * READ_SECONDS_PER_BLOCK / 60:.2g} min before any simulation; valid range is <= {limit} blocks "
            "(BLASTSCALE_MAX_BLOCKS raises the limit)"
        )


def _mesh_volume(vertices: np.ndarray, faces) -> float:
    """Volume of a closed polygon mesh [m^3] (signed tetrahedra from the origin, faces fanned)."""
    v = np.asarray(vertices, dtype=float)
    c = v.mean(axis=0)
    vol = 0.0
    for f in faces:
        p = v[list(f)] - c
        for k in range(1, len(p) - 1):
            vol += float(np.dot(p[0], np.cross(p[k], p[k + 1]))) / 6.0
    return abs(vol)


def _convex_or_hull(source: str, name: str, vertices: np.ndarray, own_volume: float | None) -> np.ndarray:
    """The block's vertices, after the convexity rule (module docstring); coordinates finite and within
    :data:`MAX_COORDINATE_M` of the origin (1e308 m would overflow its volume to "zero")."""
    if any(ord(ch) < 32 or ord(ch) == 127 for ch in name):  # the name labels the result files: text only
        raise BlastscaleInputError(f"{source}: block name {name!r} holds a control character: give a name of text")
    v = np.asarray(vertices, dtype=float)
    if not np.all(np.isfinite(v) & (np.abs(v) <= MAX_COORDINATE_M)):
        bad = v[~(np.isfinite(v) & (np.abs(v) <= MAX_COORDINATE_M))][0]
        raise BlastscaleInputError(
            f"{source}: block {name!r} has a vertex coordinate {bad:g} m: out of range, valid "
            f"range is [-{MAX_COORDINATE_M:g}, {MAX_COORDINATE_M:g}] m"
        )
    hull = hull_of(vertices, name)
    if own_volume is None:
        return vertices
    if own_volume <= 0.0:
        raise BlastscaleInputError(f"{source}: block {name!r} has zero volume (its faces enclose nothing)")
    excess = hull.volume / own_volume - 1.0
    if excess > NONCONVEX_TOLERANCE:
        raise BlastscaleInputError(
            f"{source}: block {name!r} is not convex (its hull is {100 * excess:.3g} % larger than the block): split it "
            f"into convex blocks (valid: within {100 * NONCONVEX_TOLERANCE:g} %, replaced by the hull)"
        )
    if excess > 1e-6:
        warnings.warn(
            f"{source}: block {name!r} is slightly non-convex (hull {100 * excess:.2g} % larger): "
            "replaced by its convex hull",
            UserWarning,
            stacklevel=3,
        )
    return vertices


def _from_ours(data: dict, source: str, density: float) -> tuple:
    blocks_in = data.get("blocks")
    if not isinstance(blocks_in, list) or not blocks_in:
        raise BlastscaleInputError(f'{source}: no blocks: give "blocks": [{{"vertices": [[x, y, z], ...]}}, ...]')
    _check_count(source, len(blocks_in))
    blocks = []
    for k, b in enumerate(blocks_in):
        name = str(b.get("name", f"B{k + 1}")) if isinstance(b, dict) else f"B{k + 1}"
        if not isinstance(b, dict) or "vertices" not in b:
            raise BlastscaleInputError(f'{source}: block {name!r} has no "vertices"')
        extra = set(b) - {"name", "vertices", "density_kg_m3", "faces"}
        if extra:
            raise BlastscaleInputError(
                f"{source}: block {name!r} has unknown key {sorted(extra)[0]!r}: valid keys "
                "are name, vertices, density_kg_m3, faces"
            )
        try:
            v = np.asarray(b["vertices"], dtype=float)
        except (TypeError, ValueError):
            raise BlastscaleInputError(f"{source}: block {name!r}: vertices are not a list of [x, y, z]") from None
        if v.ndim != 2 or v.shape[1] != 3:
            raise BlastscaleInputError(f"{source}: block {name!r}: vertices of shape {v.shape}: give [[x, y, z], ...]")
        if len(v) < 4:
            raise BlastscaleInputError(
                f"{source}: block {name!r} is empty ({len(v)} vertices): a solid needs at least 4"
            )
        try:
            own = None if "faces" not in b else _mesh_volume(v, b["faces"])
        except (IndexError, TypeError, ValueError):
            raise BlastscaleInputError(f"{source}: block {name!r}: faces are not lists of vertex indices") from None
        dens = b.get("density_kg_m3", density)
        v = _convex_or_hull(source, name, v, own)
        blocks.append(ConvexBlock(name, v, _density(source, name, dens)))
    return tuple(blocks), data.get("points", [])


def _density(source, name, d) -> float:
    if isinstance(d, bool) or not isinstance(d, (int, float)) or not (0 < d <= 25000):
        raise BlastscaleInputError(
            f"{source}: block {name!r}: density_kg_m3 = {d!r} is out of range: valid range is (0, 25000] kg/m^3"
        )
    return float(d)


def _compas_meshes(obj, out: list) -> list:
    """Every COMPAS mesh data dict in a JSON tree (vertex/face dicts), depth first."""
    if isinstance(obj, dict):
        vx, fc = obj.get("vertex"), obj.get("face")
        if isinstance(vx, dict) and isinstance(fc, dict) and vx:
            out.append(obj)
            return out
        for v in obj.values():
            _compas_meshes(v, out)
    elif isinstance(obj, list):
        for v in obj:
            _compas_meshes(v, out)
    return out


def _from_compas(data, source: str, density: float) -> tuple:
    meshes = _compas_meshes(data, [])
    if not meshes:
        raise BlastscaleInputError(
            f'{source}: no blocks: neither "blocks" (blastscale JSON) nor COMPAS meshes ("vertex"/"face" data) found'
        )
    _check_count(source, len(meshes))
    blocks = []
    for k, m in enumerate(meshes):
        name = (
            str(m.get("attributes", {}).get("name", f"B{k + 1}"))
            if isinstance(m.get("attributes"), dict)
            else f"B{k + 1}"
        )
        v, faces = mesh_arrays(m, source, name)
        if len(v) < 4:
            raise BlastscaleInputError(f"{source}: block {name!r} is empty ({len(v)} vertices)")
        v = _convex_or_hull(source, name, v, _mesh_volume(v, faces))
        blocks.append(ConvexBlock(name if name not in [b.name for b in blocks] else f"B{k + 1}", v, density))
    return tuple(blocks), []


def _from_compas_model(path, data: dict, source: str, density: float, use_compas) -> tuple:
    """(blocks, supports) of a compas_dem block model (:mod:`.compas_files`)."""
    blocks, supports = [], []
    items = read_compas_model(path, data, source, use_compas)
    _check_count(source, len(items))
    for name, v, faces, support, own in items:
        if len(v) < 4:
            raise BlastscaleInputError(f"{source}: block {name!r} is empty ({len(v)} vertices)")
        v = _convex_or_hull(source, name, v, _mesh_volume(v, faces))
        d = density if own is None else _density(source, name, own)
        (supports if support else blocks).append(ConvexBlock(name, v, d))
    if not blocks:
        raise BlastscaleInputError(f"{source}: every block is a support (is_support): nothing to simulate")
    return tuple(blocks), tuple(supports)


def _from_mesh(path: Path, source: str, density: float) -> tuple:
    trimesh = require("trimesh", "mesh", f"reading {source} (a mesh)")
    try:
        loaded = (
            trimesh.load_scene(str(path), split_object=True, group_material=False, process=False)
            if hasattr(trimesh, "load_scene")
            else trimesh.load(str(path), process=False)
        )
    except Exception as exc:  # trimesh raises many kinds
        raise BlastscaleInputError(f"{source}: cannot be read as a mesh: {exc}") from None
    if isinstance(loaded, trimesh.Scene):
        parts = [(str(n), g) for n, g in loaded.geometry.items() if hasattr(g, "faces")]
    else:
        parts = [("B", loaded)]
    meshes = []  # (name, vertices, faces)
    for name, mesh in parts:
        # STL stores each triangle's own corners: merge them; OBJ/PLY keep their indices (objects stay apart)
        mesh = trimesh.Trimesh(mesh.vertices, mesh.faces, process=path.suffix.lower() == ".stl")
        v, f = np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=int)
        if len(parts) > 1 or len(f) == 0:
            meshes.append((name, v, f))
            continue
        n, lab = _components(len(v), f)
        for k in range(n):
            fk = f[lab[f[:, 0]] == k]
            used = np.unique(fk)
            remap = np.full(len(v), -1)
            remap[used] = np.arange(used.size)
            meshes.append((name if n == 1 else f"{name}-{k + 1}", v[used], remap[fk]))
    if not meshes:
        raise BlastscaleInputError(f"{source}: the mesh has no faces")
    _check_count(source, len(meshes))
    blocks = []
    for k, (name, v, f) in enumerate(meshes):
        if name == "B" or name.startswith("B-"):
            name = f"B{k + 1}"
        if len(v) < 4:
            raise BlastscaleInputError(f"{source}: block {name!r} is empty ({len(v)} vertices)")
        blocks.append(ConvexBlock(name, _convex_or_hull(source, name, v, _mesh_volume(v, f)), density))
    return tuple(blocks), []


def _components(nv: int, faces: np.ndarray) -> tuple:
    """Connected components of a triangle mesh's vertices (number, label per vertex)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    e = np.vstack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(nv, nv))
    return connected_components(g, directed=False)


def _points(raw, blocks, source: str) -> tuple:
    out = []
    names = [b.name for b in blocks]
    for k, p in enumerate(raw or []):
        if not isinstance(p, dict) or "block" not in p or "position" not in p:
            raise BlastscaleInputError(f'{source}: point {k + 1} needs "block" and "position" [x, y, z]')
        if p["block"] not in names:
            raise BlastscaleInputError(
                f"{source}: point {p.get('name', k + 1)!r} is on block {p['block']!r}, which does not exist"
            )
        out.append((str(p.get("name", f"U-{k + 1}")), names.index(p["block"]), np.asarray(p["position"], dtype=float)))
    return out


def read_block_model(
    path, density_kg_m3: float = 2000.0, *, check: bool = True, use_compas: bool | None = None
) -> Assembly:
    """Read a block-model file (module docstring) into an :class:`~.assembly.Assembly`.

    Parameters
    ----------
    path : str or Path
        ``.json`` (ours or COMPAS), or a mesh (``.obj``, ``.stl``, ``.ply``, ...).
    density_kg_m3 : float
        Density of blocks without their own [kg/m^3].
    check : bool
        Check the model (overlaps, floating blocks, millimetres).
    use_compas : bool or None
        A COMPAS block model through COMPAS (True), the plain reader (False), or COMPAS when installed
        (None; :func:`~.compas_files.read_compas_model`).

    Returns
    -------
    Assembly
    """
    p = Path(path)
    source = p.name
    if not p.is_file():
        why = "no such file" if not (p.exists() or p.is_symlink()) else "not a regular file (a folder or a device)"
        raise BlastscaleInputError(f"structure.file = {str(p)!r} cannot be read: {why}")
    supports = ()
    if p.suffix.lower() == ".json":
        try:
            data = json.loads(p.read_text(encoding="utf-8-sig"))
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
            raise BlastscaleInputError(f"{source}: not valid JSON: {exc}") from None
        except RecursionError:
            raise BlastscaleInputError(
                f"{source}: not a block model: arrays or objects nested too deep for the JSON "
                "reader (a block model nests 4 deep)"
            ) from None
        if isinstance(data, dict) and "blocks" in data:
            blocks, raw_points = _from_ours(data, source, density_kg_m3)
        elif is_compas_model(data):
            (blocks, supports), raw_points = _from_compas_model(p, data, source, density_kg_m3, use_compas), []
        else:
            blocks, raw_points = _from_compas(data, source, density_kg_m3)
    elif p.suffix.lower() in MESH_SUFFIXES:
        blocks, raw_points = _from_mesh(p, source, density_kg_m3)
    else:
        raise BlastscaleInputError(
            f"structure.file = {p.name!r} has an unknown type: valid suffixes are .json, {', '.join(MESH_SUFFIXES)}"
        )
    try:
        asm = Assembly(blocks, kind="assembly", parameters=(("file", p.name),), check=check, supports=supports)
    except BlastscaleInputError as exc:
        raise BlastscaleInputError(f"{source}: {exc}") from None
    pts = _points(raw_points, blocks, source)
    if pts:
        coms = [b.com for b in asm.bodies]
        extra = tuple(MonitoringPoint(n, i, tuple(float(x) for x in pos - np.asarray(coms[i]))) for n, i, pos in pts)
        asm = Assembly(blocks, extra, asm.kind, asm.parameters, check=False, supports=supports)
    return asm
