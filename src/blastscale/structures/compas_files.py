"""COMPAS block models as COMPAS writes them: read (with or without COMPAS installed) and write back.

A ``compas_dem`` block model saved by ``compas.json_dump`` (compas 2, compas_model 0.9, compas_dem
0.6) is a ``BlockModel`` object::

    {"dtype": "compas_dem.models/BlockModel",
     "data": {"transformation": T or null,
              "elements": {guid: {"dtype": "compas_dem.elements/Block", "guid": guid,
                                  "data": {"name": str, "is_support": bool, "transformation": T or null,
                                           "geometry": {"dtype": "compas.datastructures/Mesh",
                                                        "data": {"vertex": {key: {"x", "y", "z"}},
                                                                 "face": {key: [vertex keys]}, ...}},
                                           ...}}},
              "tree": {"root": {"children": [{"element": guid, "children": [...]}, ...]}},
              "graph": {...}, "materials": {...}}}

with ``T = {"data": {"matrix": 4 x 4 rows}}`` (a COMPAS ``Transformation``, ``Rotation``,
``Translation``, ...). Each element's mesh is in its own frame; in model coordinates it is
``M_model @ ... @ M_parent @ M_element`` applied to the mesh's vertices, the product along the element
tree (``compas_model.elements.Element.compute_modeltransformation``). COMPAS's model coordinates are
ours: metres, z up, the ground at z = 0. Blocks flagged ``is_support`` become the assembly's supports
(fixed to the ground, :class:`~.assembly.Assembly`). A block's COMPAS material gives its density
(``{"data": {"density": kg/m^3}}``, compas_dem's ``GenericMaterial`` and ``Stone``); without one it has
the scenario's. Names are kept; a name used by several elements
(COMPAS names every element ``"Block"`` by default) gets ``-1``, ``-2``, ... in the tree's order.

:func:`read_compas_model` reads through COMPAS's own data model (``compas.json_load``) when
``compas_dem`` is installed (the optional ``compas`` extra) and with the plain JSON reader of this
module otherwise; both give the same blocks (tests/unit/structures/test_compas_files.py). A file
that is not a block model (bare COMPAS meshes anywhere in the JSON) is read mesh by mesh, as before.
:func:`compas_model_data` writes an :class:`~.assembly.Assembly` as such a block model (identity
transformations, every block's convex hull as its mesh), which COMPAS loads.
"""

from __future__ import annotations

import uuid

import numpy as np

from .._validate import BlastscaleInputError
from .polyhedron import polyhedron_faces

__all__ = [
    "COMPAS_BLOCK_DTYPE",
    "COMPAS_MODEL_DTYPE",
    "compas_model_data",
    "is_compas_model",
    "mesh_arrays",
    "read_compas_model",
]

#: The ``dtype`` of a compas_dem block model and of its blocks (compas_dem 0.6).
COMPAS_MODEL_DTYPE = "compas_dem.models/BlockModel"
COMPAS_BLOCK_DTYPE = "compas_dem.elements/Block"
_MESH_DTYPE = "compas.datastructures/Mesh"
_MATERIAL_DTYPE = "compas_dem.material/GenericMaterial"
_NAMESPACE = uuid.UUID("6f1c1d3e-8a52-4d0e-9b1f-23c0b1a5c0de")  # deterministic guids of written files


def _matrix(t, source: str, what: str) -> np.ndarray:
    """A COMPAS transformation's 4 x 4 matrix (identity for null)."""
    if t is None:
        return np.eye(4)
    try:
        m = np.asarray(t["data"]["matrix"] if "data" in t else t["matrix"], dtype=float)
    except (KeyError, TypeError, ValueError):
        raise BlastscaleInputError(f'{source}: {what}: transformation without a 4 x 4 "matrix"') from None
    if m.shape != (4, 4) or not np.all(np.isfinite(m)):
        raise BlastscaleInputError(
            f"{source}: {what}: transformation matrix of shape {m.shape}: give 4 x 4 finite numbers"
        )
    return m


def _transformed(v: np.ndarray, m: np.ndarray, source: str, name: str) -> np.ndarray:
    h = np.column_stack([v, np.ones(len(v))]) @ m.T
    if np.any(np.abs(h[:, 3]) < 1e-12):
        raise BlastscaleInputError(f"{source}: block {name!r}: its transformation sends vertices to infinity")
    return h[:, :3] / h[:, 3:4]


def mesh_arrays(m: dict, source: str, name: str) -> tuple:
    """(vertices (n, 3) [m], faces as lists of row indices) of a COMPAS mesh's data dict."""
    keys = list(m["vertex"])
    try:
        v = np.array([[float(m["vertex"][key][c]) for c in "xyz"] for key in keys]).reshape(-1, 3)
        index = {str(key): i for i, key in enumerate(keys)}
        faces = [[index[str(x)] for x in f] for f in m["face"].values()]
    except (KeyError, TypeError, ValueError, AttributeError):
        raise BlastscaleInputError(
            f"{source}: block {name!r}: COMPAS mesh without x, y, z vertices or valid faces"
        ) from None
    return v, faces


def _unique_names(names: list) -> list:
    """Names made unique: a repeated name gets -1, -2, ... in order (module docstring)."""
    count: dict = {}
    out = []
    for n in names:
        if names.count(n) > 1:
            count[n] = count.get(n, 0) + 1
            n = f"{n}-{count[n]}"
        while n in out:
            n += "'"
        out.append(n)
    return out


def _tree_order(tree, elements: dict) -> list:
    """(guid, parent guid or None) depth first along the element tree; elements outside it after."""
    out, seen = [], set()

    def walk(node, parent):
        for child in node.get("children", []) if isinstance(node, dict) else []:
            guid = child.get("element") if isinstance(child, dict) else None
            if guid in elements and guid not in seen:
                seen.add(guid)
                out.append((guid, parent))
                walk(child, guid)
            else:
                walk(child, parent)

    walk(tree.get("root", {}) if isinstance(tree, dict) else {}, None)
    return out + [(g, None) for g in elements if g not in seen]


def _density(material):
    """A COMPAS material's ``density`` [kg/m^3] (compas_dem's ``GenericMaterial``, ``Stone``), or None."""
    d = material.get("data", material).get("density") if isinstance(material, dict) else None
    return d if isinstance(d, (int, float)) and not isinstance(d, bool) else None


def _plain(data: dict, source: str) -> list:
    """(name, vertices in model coordinates, faces, is_support, density or None) of a block model's
    JSON, without COMPAS."""
    model = data["data"]
    elements = model.get("elements")
    if not isinstance(elements, dict):
        raise BlastscaleInputError(f'{source}: a COMPAS model without "elements"')
    m_model = _matrix(model.get("transformation"), source, "the model")
    order = _tree_order(model.get("tree"), elements)
    local = {}
    for guid, _ in order:
        el = elements[guid]
        ed = el.get("data", {}) if isinstance(el, dict) else {}
        local[guid] = _matrix(ed.get("transformation"), source, f"element {ed.get('name', guid)!r}")
    parents = dict(order)
    out = []
    for guid, _ in order:
        ed = elements[guid].get("data", {})
        name = str(ed.get("name") or elements[guid].get("name") or "Block")
        geo = ed.get("geometry")
        mesh = geo.get("data", geo) if isinstance(geo, dict) else None
        if not isinstance(mesh, dict) or not isinstance(mesh.get("vertex"), dict):
            raise BlastscaleInputError(f'{source}: element {name!r} has no mesh geometry ("vertex"/"face" data)')
        m, p = local[guid], parents[guid]
        while p is not None:  # M_parent @ ... @ M_element
            m, p = local[p] @ m, parents[p]
        v, faces = mesh_arrays(mesh, source, name)
        materials = model.get("materials") if isinstance(model.get("materials"), dict) else {}
        density = _density(materials.get(ed.get("material"))) if isinstance(ed.get("material"), str) else None
        out.append(
            (name, _transformed(v, m_model @ m, source, name), faces, bool(ed.get("is_support", False)), density)
        )
    return out


def _through_compas(path, source: str, strict: bool) -> list | None:
    """The same list as :func:`_plain`, read by COMPAS's own data model; None when compas_dem is not
    installed or COMPAS cannot read the file (``strict``: one line saying which)."""
    try:
        import compas_dem  # noqa: F401 - its dtypes must be importable for json_load
        from compas import json_load
        from compas_model.models import Model  # noqa: PLC0415 -- optional extra: ImportError handled here
    except ImportError:
        if strict:
            raise BlastscaleInputError(
                f"{source}: reading through COMPAS needs compas_dem: pip install 'blastscale[compas]'"
            ) from None
        return None
    try:
        model = json_load(str(path))
    except Exception as exc:  # noqa: BLE001 - COMPAS raises bare exceptions; the plain reader then names the problem
        if strict:
            raise BlastscaleInputError(f"{source}: COMPAS cannot read it: {type(exc).__name__}: {exc}") from None
        return None
    if not isinstance(model, Model):
        if strict:
            raise BlastscaleInputError(f"{source}: COMPAS reads a {type(model).__name__}, not a block model")
        return None
    out = []
    for node in model.tree.nodes:
        el = getattr(node, "element", None)
        if el is None:
            continue
        mesh = el.modelgeometry
        keys = list(mesh.vertices())
        index = {k: i for i, k in enumerate(keys)}
        v = np.array([mesh.vertex_coordinates(k) for k in keys], dtype=float).reshape(-1, 3)
        faces = [[index[k] for k in mesh.face_vertices(f)] for f in mesh.faces()]
        try:
            density = getattr(el.material, "density", None)
        except KeyError:  # a material guid the model does not hold
            density = None
        out.append((str(el.name), v, faces, bool(getattr(el, "is_support", False)), density))
    return out


def is_compas_model(data) -> bool:
    """Whether a JSON document is a COMPAS model (a ``dtype`` and ``data.elements``)."""
    return (
        isinstance(data, dict) and isinstance(data.get("data"), dict) and "elements" in data["data"] and "dtype" in data
    )


def read_compas_model(path, data: dict, source: str, use_compas: bool | None = None) -> list:
    """The blocks of a COMPAS block model: (name, vertices (n, 3) in model coordinates [m], faces,
    is_support, density [kg/m^3] of its COMPAS material or None), names made unique (module docstring).

    Parameters
    ----------
    path : str or Path
        The file (read again by COMPAS when it is used).
    data : dict
        Its JSON (:func:`is_compas_model`).
    source : str
        The file's name, for messages.
    use_compas : bool or None
        True: through COMPAS (an error when compas_dem is missing or COMPAS cannot read the file);
        False: the plain reader; None: COMPAS when installed and able, the plain reader otherwise.
    """
    blocks = None if use_compas is False else _through_compas(path, source, bool(use_compas))
    if blocks is None:
        blocks = _plain(data, source)
    if not blocks:
        raise BlastscaleInputError(f"{source}: the COMPAS model has no elements")
    names = _unique_names([b[0] for b in blocks])
    return [(n, *b[1:]) for n, b in zip(names, blocks)]


def _mesh_data(points: np.ndarray, name: str) -> dict:
    """A COMPAS ``Mesh`` data dict of a convex block: its hull's vertices and plane faces."""
    faces = polyhedron_faces(points, name)
    index: dict = {}
    for f in faces:
        for p in f.vertices:
            index.setdefault(tuple(float(x) for x in p), len(index))
    face = {str(k): [index[tuple(float(x) for x in p)] for p in f.vertices] for k, f in enumerate(faces)}
    return {
        "dtype": _MESH_DTYPE,
        "data": {
            "attributes": {},
            "default_vertex_attributes": {"x": 0.0, "y": 0.0, "z": 0.0},
            "default_edge_attributes": {},
            "default_face_attributes": {},
            "vertex": {str(i): {"x": p[0], "y": p[1], "z": p[2]} for p, i in index.items()},
            "face": face,
            "facedata": {str(k): {} for k in face},
            "edgedata": {},
            "max_vertex": len(index) - 1,
            "max_face": len(face) - 1,
        },
    }


def compas_model_data(assembly) -> dict:
    """An :class:`~.assembly.Assembly` as a compas_dem block model's JSON data (module docstring):
    one ``Block`` per block and per support (``is_support``), named as ours, its mesh the block's
    convex hull in model coordinates [m], every transformation the identity (null); guids derived from
    the names (the same assembly writes the same file); each density a compas_dem
    ``GenericMaterial`` (one per distinct density [kg/m^3])."""
    els, children, nodes, materials = {}, [], {}, {}
    everything = [(b, False) for b in assembly.blocks] + [(b, True) for b in getattr(assembly, "supports", ())]
    for k, (b, support) in enumerate(everything):
        guid = str(uuid.uuid5(_NAMESPACE, f"block/{k}/{b.name}"))
        mat = str(uuid.uuid5(_NAMESPACE, f"material/{b.density!r}"))
        materials[mat] = {
            "dtype": _MATERIAL_DTYPE,
            "guid": mat,
            "data": {"name": f"{b.density:g} kg/m^3", "density": b.density},
        }
        els[guid] = {
            "dtype": COMPAS_BLOCK_DTYPE,
            "guid": guid,
            "name": b.name,
            "data": {
                "name": b.name,
                "is_support": support,
                "transformation": None,
                "features": [],
                "material": mat,
                "geometry": _mesh_data(b.points, b.name),
            },
        }
        children.append({"name": "ElementNode", "element": guid})
        nodes[str(k)] = {"element": guid}
    graph = {
        "attributes": {},
        "default_node_attributes": {"element": None, "x": 0.0, "y": 0.0, "z": 0.0},
        "default_edge_attributes": {"contacts": None, "modifiers": None},
        "node": nodes,
        "edge": {k: {} for k in nodes},
        "max_node": len(nodes) - 1,
    }
    return {
        "dtype": COMPAS_MODEL_DTYPE,
        "guid": str(uuid.uuid5(_NAMESPACE, "model")),
        "name": "BlockModel",
        "data": {
            "transformation": None,
            "elements": els,
            "materials": materials,
            "graph": graph,
            "tree": {"attributes": {}, "root": {"name": "root", "children": children}},
        },
    }
