"""Prototype vs reduced-scale model of any 3D structure (block, multi-drum column) on MuJoCo.

:func:`compare_structure3d` runs a structure and its model experiment through the same path:

1. the model system is the one the design carries (:meth:`.systems.Systems3D.of_design`): its structure
   ``design.specimen_structure``, gravity ``varsigma g``, load model ``design.specimen_load_model``, contact
   settings ``design.specimen_contact`` or the engine's scale-consistent defaults (None; a design made without
   them: completed by :func:`blastscale.similitude.specimen.specimen_system`, as the design does);
2. each is loaded by :func:`blastscale.sim3d.load_methods.make_load` from its own blast
   parameters (``design.prototype``, ``design.specimen``: the design's, never recomputed) and
   simulated by :func:`blastscale.sim3d.simulate_structure` (the model for ``duration *
   lambda_t``): one :func:`~.systems.run_system` each;
3. the model's dataset is up-scaled by :func:`~.compare.upscale_dataset` and compared with the
   prototype's by :func:`~.compare.compare_responses` (the package's one comparison); the
   arrival-time spreads are read from the two loads as run.

A single block also gets its planar view (:mod:`.block3d_similarity`: rotation, sliding, uplift)
in the summary, next to the structure's keys. :func:`~.prototype3d.prototype_structure3d` runs the
prototype alone (a prototype-only study: no design, no comparison; re-exported here).

Reference: Masi, Stefanou & Maffi-Berthier, Sec. 6 (multi-drum columns, lambda = 1/100,
Method A) and Sec. "FEM simulations" (single blocks).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .._threads import map_threads
from .._validate import BlastscaleInputError
from ..sim3d.face_loads import load_arrival_spread
from .compare import align, compare_responses, upscale_dataset
from .prototype3d import _block_keys, _load_model_setting, _merged, _with_outcome
from .systems import Settings3D, Systems3D, rest_of, run_system
from .upscale import upscale, upscale_summary

__all__ = ["Comparison3D", "compare_structure3d", "arrival_spread_similarity"]


def _top_point(ds) -> str:
    """The monitoring point compared as "the top": the recorder's (the highest at rest,
    :func:`~blastscale.structures.base.top_monitoring_point`); the last one in a dataset without it."""
    return str(ds.attrs.get("top_point", ds["point"].values[-1]))


@dataclass(frozen=True, eq=False)
class Comparison3D:
    """Result of :func:`compare_structure3d` (SI, prototype units unless said).

    Attributes
    ----------
    design : ModelDesign
        The model experiment (charges, stand-offs, factors).
    structure, specimen_structure : structure
        Prototype and model structures.
    prototype, model : Response3D
        The two runs, each in its own units.
    prototype_dataset : xarray.Dataset
        The prototype's response.
    upscaled_dataset : xarray.Dataset
        The model's response in prototype units (:func:`~.compare.upscale_dataset`).
    comparison : dict
        :func:`~.compare.compare_responses` of ``point_displacement``, ``point_velocity``,
        ``com_displacement``, ``rotation_y`` (x components, rotation about y).
    settings : dict
        Load method, pulse shape, incidence, duration [s], record interval.
    arrival_spreads : dict
        ``arrival_spread_prototype_s``, ``arrival_spread_model_upscaled_s`` [s], from the two runs'
        loads (:func:`arrival_spread_similarity`).
    rest : dict
        ``prototype`` and ``model``: each system at rest before the blast (:func:`~.systems.rest_of`), in its
        own units (the model's up-scaled in :meth:`to_dict`); None under gravity alone.
    """

    design: object
    structure: object
    specimen_structure: object
    prototype: object
    model: object
    prototype_dataset: object
    upscaled_dataset: object
    comparison: dict
    settings: dict = field(default_factory=dict)
    arrival_spreads: dict = field(default_factory=dict)
    rest: dict = field(default_factory=dict)

    @property
    def top_point(self) -> str:
        """Name of the monitoring point reported as the top (the highest at rest: an arch's crown)."""
        return _top_point(self.prototype_dataset)

    def similarity(self) -> dict:
        """Per-point and top figures of the comparison (prototype units).

        Returns
        -------
        dict
            ``top_point``; ``top_first_peak_ratio`` [-] (model / prototype first peak of the top
            point's x displacement); ``max_abs_top_displacement_diff_m`` [m];
            ``max_abs_top_displacement_diff_rel_peak`` [-]; ``outcomes_agree``; ``points``:
            name -> ``first_peak_prototype_m``, ``first_peak_model_m``, ``first_peak_time_s``,
            ``first_peak_ratio``, ``max_abs_displacement_diff_m``,
            ``max_abs_displacement_diff_rel_peak``, ``max_abs_velocity_diff_m_s``,
            ``max_abs_velocity_diff_rel_peak`` (velocities after the load, ``load_end_s``: during a
            finite pulse they rise over the blast's own duration, whose model/prototype ratio is
            not the time factor); ``time_compared_s``; ``load_end_s``. When either collapses:
            ``collapse_time_diff_s`` (model up-scaled minus prototype; None unless both collapse),
            ``compared_to_collapse_s`` (the earlier collapse time), and per point the first peaks
            taken up to it and ``max_abs_displacement_diff_to_collapse_m`` / ``_rel_peak`` (the fall
            amplifies any time shift, as a rocking block's after tipping).
        """
        c = self.comparison["variables"]
        disp = c["point_displacement"]
        vel = self.comparison.get("after_load", self.comparison)["variables"]["point_velocity"]
        points = {
            name: {
                "first_peak_prototype_m": d["first_peak_prototype"],
                "first_peak_model_m": d["first_peak_model"],
                "first_peak_time_s": d["first_peak_time_prototype_s"],
                "first_peak_ratio": d["first_peak_ratio"],
                "max_abs_displacement_diff_m": d["max_abs_diff"],
                "max_abs_displacement_diff_rel_peak": d["max_abs_diff_rel_peak"],
                "max_abs_velocity_diff_m_s": vel[name]["max_abs_diff"],
                "max_abs_velocity_diff_rel_peak": vel[name]["max_abs_diff_rel_peak"],
            }
            for name, d in disp.items()
        }
        top = self.top_point
        ps, ms = self.prototype.summary(), upscale_summary(self.model.summary(), self.design.factors)
        tcp, tcm = ps.get("collapse_time_s"), ms.get("collapse_time_s")
        coll = self.comparison.get("to_collapse")
        if coll is not None:  # first peaks and differences up to the earlier collapse
            for name, d in coll["variables"]["point_displacement"].items():
                points[name].update(
                    {
                        "first_peak_prototype_m": d["first_peak_prototype"],
                        "first_peak_model_m": d["first_peak_model"],
                        "first_peak_time_s": d["first_peak_time_prototype_s"],
                        "first_peak_ratio": d["first_peak_ratio"],
                        "max_abs_displacement_diff_to_collapse_m": d["max_abs_diff"],
                        "max_abs_displacement_diff_to_collapse_rel_peak": d["max_abs_diff_rel_peak"],
                    }
                )
        return {
            "top_point": top,
            "collapse_time_diff_s": None if tcp is None or tcm is None else tcm - tcp,
            "compared_to_collapse_s": None if coll is None else coll["end_s"],
            "top_first_peak_ratio": points[top]["first_peak_ratio"],
            "max_abs_top_displacement_diff_m": points[top]["max_abs_displacement_diff_m"],
            "max_abs_top_displacement_diff_rel_peak": points[top]["max_abs_displacement_diff_rel_peak"],
            "outcomes_agree": self.comparison["outcomes_agree"],
            "points": points,
            "time_compared_s": self.comparison["time_compared_s"],
            "load_end_s": self.settings.get("load_end_s"),
            **self._arrival_spreads(),
        }

    def _arrival_spreads(self) -> dict:
        """``arrival_spread_prototype_s`` and ``arrival_spread_model_upscaled_s`` [s]: first to last
        shock arrival over the loaded faces, the model's divided by the time factor (issue 9,
        :func:`arrival_spread_similarity`; 0 for Method A), read
        from the loads the runs used."""
        return dict(self.arrival_spreads)

    def to_dict(self) -> dict:
        """``prototype`` and ``model`` (up-scaled) outcomes and the ``similarity`` block; for a
        single block each also carries the block's planar keys (``max_sliding_m``,
        ``max_uplift_m``, ``peak_angular_velocity_rad_s``, ...; similarity ``max_abs_rotation_diff_rad``, ...:
        :func:`~.block3d_similarity.block_view`), added next to the structure's keys; each carries ``rest`` (the
        system at rest before the blast, :func:`~.systems.rest_of`; the model's up-scaled) when it was checked."""
        blk = _block_keys(self.structure, self.prototype, self.model, self.specimen_structure, self.design.factors)
        rest_p, rest_m = (_rest_keys(self.rest.get(k)) for k in ("prototype", "model"))
        return {
            "prototype": {**_merged(self.prototype.summary(), blk["prototype"]), **rest_p},
            "model": _merged(upscale_summary({**self.model.summary(), **rest_m}, self.design.factors), blk["model"]),
            "similarity": _merged(self.similarity(), blk["similarity"]),
        }

    def to_dataset(self):
        """Prototype and up-scaled model on the prototype's common times, stacked along a
        dimension ``system`` = ["prototype", "model"]; the scalar similarity figures as
        attributes (NetCDF-ready)."""
        import xarray as xr

        p, m = align(self.prototype_dataset, self.upscaled_dataset)
        keep = [n for n in p.data_vars if n in m.data_vars]
        ds = xr.concat([p[keep], m[keep]], dim="system", combine_attrs="override")  # the prototype's attributes
        ds = ds.assign_coords(system=["prototype", "model"])
        ds.attrs.pop("upscaled", None)
        ds.attrs["model_first_arrival_time_s"] = self.upscaled_dataset.attrs.get("first_arrival_time_s", "none")
        s = self.similarity()
        attrs = {k: v for k, v in s.items() if isinstance(v, (int, float, str)) and not isinstance(v, bool)}
        attrs["outcomes_agree"] = "none" if s["outcomes_agree"] is None else int(s["outcomes_agree"])
        attrs.update({f"factor_{k}": v for k, v in self.design.factors.to_dict().items() if v is not None})
        attrs.update(
            {
                k: int(v) if isinstance(v, bool) else v
                for k, v in self.settings.items()
                if isinstance(v, (int, float, str))
            }
        )  # NetCDF has no booleans
        ds.attrs.update(attrs)
        return ds


def compare_structure3d(systems: Systems3D, settings: Settings3D = Settings3D(), *, threads=None) -> Comparison3D:
    """Run a structure and its reduced-scale model in 3D and compare them in prototype units.

    Parameters
    ----------
    systems : Systems3D
        The prototype and the specimen of a design (:meth:`~.systems.Systems3D.of_design`: the design's
        specimen structure, blast parameters, load model, gravity, contact and duration ``duration * lambda_t``;
        ``design.factors`` give lambda, gamma, varsigma, lambda_t).
    settings : Settings3D
        Load method, pulse shape, incidence, recording interval (the same at both scales, so the grids
        correspond), extrapolation (:class:`~.systems.Settings3D`).
    threads : int, optional
        Prototype and model run at once on up to this many threads (:mod:`blastscale._threads`;
        default: this process's share of the cores); the results do not depend on it (bitwise).

    Returns
    -------
    Comparison3D
    """
    design = systems.design
    if systems.specimen is None or design is None:
        raise BlastscaleInputError(
            "systems without a specimen: compare_structure3d needs a design's systems (Systems3D.of_design(design)); "
            "a prototype alone runs through prototype_structure3d"
        )
    # the two blast runs and the prototype at rest at once; the specimen's rest check is then (mostly) the
    # prototype's, cached (an exactly scaled specimen is the same engine model, sim3d.rest)
    p_run, m_run, p_rest = map_threads(
        lambda f: f(),
        (
            lambda: run_system(systems.prototype, settings),
            lambda: run_system(systems.specimen, settings),
            lambda: rest_of(systems.prototype),
        ),
        threads,
    )
    proto, mod = p_run.response, m_run.response
    # the later of the two loads' ends [s after the first arrival, prototype time]
    load_end = max(p_run.load_duration_s, upscale(m_run.load_duration_s, design.factors, "time"))
    pds, up, cmp = _compared(proto, mod, design.factors, load_end)
    return Comparison3D(
        design=design,
        structure=systems.prototype.structure,
        specimen_structure=m_run.structure,
        prototype=proto,
        model=mod,
        prototype_dataset=pds,
        upscaled_dataset=up,
        comparison=cmp,
        settings={
            **settings.record(),
            "duration_s": systems.prototype.duration,
            "record_every": int(settings.record_every),
            "load_end_s": load_end,
            "extrapolate": bool(settings.extrapolate),
            **_load_model_setting(systems.prototype.load_model),
        },
        arrival_spreads=arrival_spread_similarity(p_run.load, m_run.load, factors=design.factors),
        rest={"prototype": p_rest, "model": rest_of(systems.specimen)},
    )


def _rest_keys(rest) -> dict:
    """``{"rest": rest}``, or nothing when the system was not checked (gravity alone)."""
    return {} if rest is None else {"rest": dict(rest)}


def _compared(proto, mod, factors, load_end: float) -> tuple:
    """(prototype dataset, up-scaled model dataset, comparison) of two runs (:func:`~.compare.compare_responses`):
    the whole runs; the velocities after the load's end ``load_end`` [s]; the displacements up to the earlier
    collapse (the fall amplifies any time shift)."""
    ps, ms = proto.summary(), mod.summary()
    pds = _with_outcome(proto.dataset, ps)
    up = upscale_dataset(_with_outcome(mod.dataset, ms), factors)
    cmp = compare_responses(pds, up, variables=_COMPARED, outcome="collapsed")
    if load_end < pds["time"].values[-1]:  # velocities after the load (see compare_responses' start)
        cmp["after_load"] = compare_responses(pds, up, variables=("point_velocity",), start=load_end)
        cmp["after_load"]["start_s"] = load_end
    tc = [x for x in (ps.get("collapse_time_s"), upscale_summary(ms, factors).get("collapse_time_s")) if x is not None]
    if tc:  # up to the earlier collapse: the fall amplifies any time shift
        cmp["to_collapse"] = compare_responses(pds, up, variables=("point_displacement",), end=min(tc))
        cmp["to_collapse"]["end_s"] = min(tc)
    return pds, up, cmp


#: Variables compared by :func:`compare_structure3d` (x components; rotation about y).
_COMPARED = ("point_displacement", "point_velocity", "com_displacement", "rotation_y")


def arrival_spread_similarity(prototype_load, model_load, factors) -> dict:
    """Arrival-time spreads of a model experiment, for a comparison's ``similarity`` block, from
    the loads its two runs used (nothing is rebuilt).

    Parameters
    ----------
    prototype_load, model_load : LoadStrategy
        The prototype's load and the specimen's (at the specimen's size), as run.
    factors : ScalingFactors
        Specimen / prototype factors (``factors.time``: lambda_t).

    Returns
    -------
    dict
        ``arrival_spread_prototype_s`` (first to last arrival over the loaded faces [s]) and
        ``arrival_spread_model_upscaled_s`` (the specimen's, divided by the time factor lambda_t,
        :func:`~.upscale.upscale`, in prototype seconds [s]). Under exact similarity the two are equal; see
        ``docs/face_loads.md`` for why the general law's model does not keep them equal.
    """
    return {
        "arrival_spread_prototype_s": load_arrival_spread(prototype_load),
        "arrival_spread_model_upscaled_s": upscale(load_arrival_spread(model_load), factors, "time"),
    }
