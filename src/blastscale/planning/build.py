"""What the lab builds: a specimen's overall dimensions and one of its units (a drum, a brick, a
voussoir), for the planner and the test card [m, kg]."""

from __future__ import annotations

from collections import Counter

import numpy as np

from ..similitude.factors import to_specimen

__all__ = ["spec_dims", "specimen_unit", "specimen_mass", "specimen_density"]


def spec_dims(spec) -> tuple:
    """(height, width along the blast, depth) of a specimen [m]: a block's own; a column's height and
    base width; any other structure's bounding box at rest (its extent along x, the blast's, and y)."""
    if hasattr(spec, "width"):
        return float(spec.height), float(spec.width), float(spec.depth)
    if hasattr(spec, "base_width"):
        w = float(spec.base_width)
        return float(spec.height), w, w
    if hasattr(spec, "blocks"):  # an assembly: its blocks' points (its bodies would find every interface)
        v = np.vstack([b.points for b in spec.blocks])
    else:
        v = np.vstack([np.asarray(b.vertices) + np.asarray(b.com) for b in spec.bodies])
    return float(v[:, 2].max()), float(np.ptp(v[:, 0])), float(np.ptp(v[:, 1]))


def specimen_unit(spec) -> dict:
    """One unit of the specimen (a drum, a brick, a voussoir): the most frequent body by size (its
    bounding box along x, y, z, ``size_x_m``, ``size_y_m``, ``size_z_m`` [m], rounded to 1e-9 of the
    structure's height), its ``mass_kg`` [kg], and how many ``bodies`` the specimen has."""

    h = spec_dims(spec)[0]
    sizes = [tuple(round(float(x) / h, 9) * h for x in np.ptp(np.asarray(b.vertices), axis=0)) for b in spec.bodies]
    size = Counter(sizes).most_common(1)[0][0]
    body = spec.bodies[sizes.index(size)]
    return {
        "name": body.name,
        **{f"size_{a}_m": float(x) for a, x in zip("xyz", size)},
        "mass_kg": float(body.mass),
        "bodies": len(spec.bodies),
    }


def specimen_mass(design) -> float:
    """The specimen's mass [kg]: a block's own; any other structure's lambda^3 gamma x its prototype's
    (lengths x lambda, densities x gamma: exact, without integrating every block of the specimen again)."""
    spec, proto = design.specimen_structure, design.prototype_structure
    if hasattr(spec, "width") or proto is None:
        return float(spec.mass)
    return to_specimen(float(proto.mass), design.factors, "mass")


def specimen_density(design) -> float:
    """The specimen's (mean) density [kg/m^3]: its material's, or gamma x the prototype's mean density."""
    spec, proto = design.specimen_structure, design.prototype_structure
    if getattr(spec, "density", None):
        return float(spec.density)
    return to_specimen(float(proto.mass) / float(proto.volume), design.factors, "density")
