"""The outcome mode of a sweep: first-swing outcomes and largest rotations of planar block cases,
vectorised over the cases (the design in numpy, the pulse phases in the compiled kernel, the
first free swing in closed form)."""

from __future__ import annotations

import warnings

import numpy as np

from .._threads import interleave, map_interleaved
from .._validate import BlastscaleInputError
from ..analysis.planar import first_swing_under, planar_system
from ..rocking.solver import RockingSolver
from ..rocking.system import housner_restitution
from ..study.study import Study, design_of
from .spec import SweepSpec, _plain

__all__ = ["OUTCOME_KEYS", "VALID_KEY", "planar_outcomes"]

#: Key of every case's result: False where the Study refused the case (its other values are NaN).
VALID_KEY = "sweep.valid"

#: Keys of the outcome mode (:func:`planar_outcomes`), the Study's names where they mean the same.
OUTCOME_KEYS = (
    "planar.prototype.collapsed",
    "planar.prototype.max_rotation_rad",
    "planar.model.collapsed",
    "planar.model.max_rotation_rad",
    "planar.similarity.max_rotation_ratio",
    "planar.similarity.outcomes_agree",
    "design.model_charge_kg",
    "design.model_standoff_m",
    VALID_KEY,
)
#: Fields the outcome mode vectorises over; the others that matter group the cases (one body, scale,
#: law, blast model and pulse per group); the rest (friction, duration, samples, 3D settings, ...)
#: play no part in it.
_LOAD_PATHS = ("blast.charge_kg", "blast.standoff_m", "simulation.restitution")


def _outcome_field(path: str) -> bool:
    return (
        path.startswith(("structure.", "blast.", "scale.")) or path == "simulation.gravity_m_s2"
    ) and path not in _LOAD_PATHS + ("structure.friction", "blast.load", "blast.incidence")


def _groups(vals: dict, paths: list, n: int) -> list:
    """Index arrays of the cases sharing the values of ``paths`` (one group when none)."""
    if not paths:
        return [np.arange(n)]
    codes = []
    for p in paths:
        col = vals[p]
        try:
            _, inv = np.unique(col, return_inverse=True)
        except TypeError:  # unorderable mix (e.g. None and numbers): by first occurrence
            seen: dict = {}
            inv = np.array([seen.setdefault(v, len(seen)) for v in col.tolist()])
        codes.append(inv.ravel())
    _, inv = np.unique(np.stack(codes), axis=1, return_inverse=True)
    inv = inv.ravel()
    return [np.flatnonzero(inv == g) for g in range(int(inv.max()) + 1)]


def _outcome_group(sc, W, R, e) -> dict:
    """Outcome-mode arrays for n load cases ``W`` [kg], ``R`` [m], restitution ``e`` [-] (NaN:
    Housner's) of one scenario ``sc`` (body, scale, law, blast model and pulse): the Study's own
    design (:func:`~blastscale.study.study.design_of` over the arrays, without the blast effects),
    then the first swing of prototype and specimen."""

    n = W.size
    out = {k: np.full(n, np.nan) for k in OUTCOME_KEYS}
    out[VALID_KEY] = np.zeros(n, dtype=bool)
    bl, sim = sc.blast, sc.simulation
    structure = Study(sc).structure()
    try:  # the specimen system (block, gravity, load model) from the Study's own design, over the arrays
        d = design_of(sc, structure, W, R, effects=False)
    except BlastscaleInputError:  # e.g. a density ratio the Hopkinson-Cranz law refuses: every case
        return out
    ok = d.valid
    if not np.any(ok):
        return out
    proto = planar_system(structure, sim.gravity_m_s2)
    specimen = planar_system(d.specimen_block, d.specimen_gravity)
    e = np.where(np.isnan(e), housner_restitution(proto.alpha), e)[ok]
    solver = RockingSolver(threads=1)  # this share's cases on this thread (the shares: _outcome_group_threaded)
    fp = first_swing_under(
        proto,
        d.prototype.select(ok),
        bl.pulse_shape,
        restitution=e,
        load_model=d.load_model,  # clearing on the block's front, the negative phase (the Study's)
        extrapolate=bl.extrapolate,
        solver=solver,
    )
    fm = first_swing_under(
        specimen,
        d.specimen.select(ok),
        bl.pulse_shape,
        restitution=e,
        load_model=d.specimen_load_model,
        extrapolate=bl.extrapolate,
        solver=solver,
    )
    out["planar.prototype.collapsed"][ok] = fp.collapsed
    out["planar.prototype.max_rotation_rad"][ok] = fp.max_rotation
    out["planar.model.collapsed"][ok] = fm.collapsed
    out["planar.model.max_rotation_rad"][ok] = fm.max_rotation  # angles are not scaled (factor 1)
    out["planar.similarity.max_rotation_ratio"][ok] = fm.max_rotation / fp.max_rotation
    out["planar.similarity.outcomes_agree"][ok] = fp.collapsed == fm.collapsed
    out["design.model_charge_kg"][ok] = d.specimen.charge_kg[ok]
    out["design.model_standoff_m"][ok] = d.specimen.standoff_m[ok]
    out[VALID_KEY][ok] = True
    return out


#: Fewest cases a thread of the outcome mode takes (below, the threads cost more than they save).
MIN_CASES_PER_THREAD = 256


def _outcome_group_threaded(sc, W, R, e) -> dict:
    """:func:`_outcome_group` with the cases dealt out over ``sc.simulation.threads`` threads, alternately
    (:func:`~blastscale._threads.map_interleaved`): the design, the pulse phases and the first swings of
    each share run on a thread of their own. Every value is computed case by case, so the results are
    bitwise those of one thread."""
    parts = map_interleaved(
        lambda s: _outcome_group(sc, W[s], R[s], e[s]), W.size, sc.simulation.threads, MIN_CASES_PER_THREAD
    )
    return {key: interleave([(s, part[key]) for s, part in parts], W.size) for key in OUTCOME_KEYS}


def planar_outcomes(spec: SweepSpec, start: int, stop: int) -> dict:
    """The outcome mode: first-swing results of the planar block cases ``start .. stop - 1`` of a
    sweep, vectorised over the cases (the design in numpy, the pulse phases in the compiled
    kernel, the first free swing in closed form; :func:`blastscale.rocking.swing`).

    For the prototype and the model (designed by the Study's own mapping,
    :func:`~blastscale.study.study.design_of`, given the arrays of charges and stand-offs):
    ``collapsed`` (at any time), ``max_rotation_rad`` (the largest |theta| of the whole motion; pi/2
    where it overturns), their ratio (model / prototype) and outcome agreement, the model charge and
    stand-off, and ``sweep.valid`` (False where the Study would refuse the design: a scaled distance
    outside the blast fits; NaN values there).
    Cases are grouped by the fields that matter other than charge, stand-off and restitution
    (structure, blast model and pulse, scale, gravity: one body, scale and law per group; friction,
    duration, samples and the 3D settings play no part); within a group everything is array
    arithmetic.

    Returns
    -------
    dict
        :data:`OUTCOME_KEYS` -> array over the cases (booleans as floats with NaN where some case
        of the chunk is invalid).
    """

    vals = spec.value_arrays(start, stop)
    n = int(stop) - int(start)
    base = spec.base
    col = {
        p: (vals[p].astype(float) if p in vals else np.full(n, np.nan if v is None else float(v)))
        for p, v in zip(_LOAD_PATHS, (base.blast.charge_kg, base.blast.standoff_m, base.simulation.restitution))
    }
    others = [p for p in vals if _outcome_field(p)]
    out = {k: np.full(n, np.nan) for k in OUTCOME_KEYS}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for idx in _groups(vals, others, n):
            sc = base.with_values({p: _plain(vals[p][idx[0]]) for p in others}) if others else base
            res = _outcome_group_threaded(sc, *(col[p][idx] for p in _LOAD_PATHS))
            for k in OUTCOME_KEYS:
                out[k][idx] = res[k]
    valid = out[VALID_KEY] == 1.0
    for k in ("planar.prototype.collapsed", "planar.model.collapsed", "planar.similarity.outcomes_agree", VALID_KEY):
        if k == VALID_KEY or valid.all():
            out[k] = out[k] == 1.0
    return out
