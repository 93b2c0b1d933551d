"""The 3D run of a prototype alone (a study without ``[scale]``: no specimen, no comparison).

:func:`prototype_structure3d` runs one structure under its own blast parameters through the same path
as each side of :func:`~.structure3d.compare_structure3d` (:func:`~.systems.run_system`); under gravity
alone it runs until the stability rule decides (:mod:`.gravity_alone`). :class:`Prototype3D` gives the
same views as :class:`~.structure3d.Comparison3D` where they apply. The helpers below (a single block's
planar keys, the outcome attribute, the load model's record) serve both results.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from .._threads import map_threads
from ..sim3d.face_loads import load_arrival_spread
from ..structures.from_spec import is_block
from .block3d_similarity import block_view
from .gravity_alone import extended_keys, until_decided
from .systems import Settings3D, System3D, rest_of, run_system

__all__ = ["Prototype3D", "prototype_structure3d"]


def _merged(base: dict, extra: dict) -> dict:
    """``base`` with the keys of ``extra`` it does not have (added, never replacing one)."""
    return {**base, **{k: v for k, v in extra.items() if k not in base}}


def _block_keys(structure, prototype, model=None, specimen_structure=None, factors=None) -> dict:
    """The block3d keys of a single block's runs (:func:`~.block3d_similarity.block_view`), or
    empty dicts for any other structure."""
    if not is_block(structure):
        return {"prototype": {}, "model": {}, "similarity": {}}

    v = block_view(prototype, structure, model, specimen_structure, factors)
    return {k: v[k] or {} for k in ("prototype", "model", "similarity")}


def _with_outcome(ds, summary: dict):
    """The dataset with the run's outcome (``collapsed``) as an attribute, for the comparison."""
    if "collapsed" in ds.attrs or "collapsed" not in summary:
        return ds
    out = ds.copy()
    out.attrs["collapsed"] = int(bool(summary["collapsed"]))
    return out


def _load_model_setting(load_model) -> dict:
    """The settings' record of a load model other than the paper's (clearing, negative phase)."""
    if load_model is None or load_model.is_paper:
        return {}
    return {"clearing": bool(load_model.clearing), "negative_phase": bool(load_model.negative_phase)}


@dataclass(frozen=True, eq=False)
class Prototype3D:
    """The 3D run of a prototype alone (a study without ``[scale]``: no specimen, no comparison).

    The same views as :class:`~.structure3d.Comparison3D` where they apply: ``to_dict()`` gives the prototype's
    outcome (with a single block's planar keys) and ``model`` / ``similarity`` None;
    ``upscaled_dataset`` is None.

    Attributes
    ----------
    structure : structure
        The prototype.
    prototype : Response3D
        Its run [SI].
    prototype_dataset : xarray.Dataset
        Its response (with the outcome ``collapsed`` as an attribute).
    settings : dict
        Load method, pulse shape, incidence, duration [s], record interval, load end [s], arrival spread [s].
    rest : dict or None
        The prototype at rest before the blast (:func:`~.systems.rest_of`); None under gravity alone.
    """

    structure: object
    prototype: object
    prototype_dataset: object
    settings: dict = field(default_factory=dict)
    design: object = None
    specimen_structure: object = None
    model: object = None
    upscaled_dataset: object = None
    rest: object = None

    def to_dict(self) -> dict:
        """``prototype`` (the structure's keys and, for a single block, its planar keys; ``rest`` under a blast);
        ``model`` and ``similarity`` None."""
        blk = _block_keys(self.structure, self.prototype)
        p = {**_merged(self.prototype.summary(), blk["prototype"]), **extended_keys(self.settings)}
        if self.rest is not None:
            p["rest"] = dict(self.rest)
        return {"prototype": p, "model": None, "similarity": None}


def prototype_structure3d(system: System3D, settings: Settings3D = Settings3D(), *, threads=None) -> Prototype3D:
    """Run a prototype alone in 3D (no model design: a prototype-only study).

    Parameters
    ----------
    system : System3D
        The prototype: its structure, blast parameters (:func:`blastscale.blast.blast_parameters` of its charge
        and stand-off; None: gravity alone, run until the stability rule decides), gravity, contact (None: the
        engine's defaults for the structure), duration [s] and load model.
    settings : Settings3D
        As :func:`~.structure3d.compare_structure3d`.
    threads : int, optional
        The run and its check at rest (:func:`~.systems.rest_of`) at once on up to this many threads
        (:mod:`blastscale._threads`; default: this process's share of the cores); the results do not depend on it.

    Returns
    -------
    Prototype3D
    """

    asked = system.duration
    # gravity alone: run until the stability rule decides (docs/assemblies.md, analysis.gravity_alone); under a
    # blast the run and the check at rest before it at once
    (run, dur), rest = map_threads(
        lambda f: f(),
        (
            lambda: until_decided(
                lambda T: run_system(replace(system, duration=T), settings), asked, system.blast is None
            ),
            lambda: rest_of(system),
        ),
        threads,
    )
    resp = run.response
    return Prototype3D(
        rest=rest,
        structure=system.structure,
        prototype=resp,
        prototype_dataset=_with_outcome(resp.dataset, resp.summary()),
        settings={
            **settings.record(),
            "duration_s": dur,
            **({"duration_asked_s": asked} if dur != asked else {}),
            "record_every": int(settings.record_every),
            "load_end_s": run.load_duration_s,
            "extrapolate": bool(settings.extrapolate),
            "arrival_spread_prototype_s": load_arrival_spread(run.load),
            **_load_model_setting(system.load_model),
        },
    )
