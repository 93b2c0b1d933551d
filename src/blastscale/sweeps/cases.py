"""The scalars of a sweep's cases: the Study path (one Study per case) and the planar batch path
for planar block cases (one compiled kernel call per chunk), and :func:`evaluate_chunk`, what a
worker runs. A case's values never depend on the other cases of its chunk."""

from __future__ import annotations

import math

import numpy as np

from .._validate import BlastscaleInputError
from .outcomes import VALID_KEY, planar_outcomes
from .spec import SweepSpec, planar_case

__all__ = ["PLANAR_KEYS", "VALID_KEY", "study_scalars", "planar_scalars", "evaluate_chunk"]


#: Planar keys of the batch path (besides the Study's experiment.*, design.*, critical.*, 3d).
PLANAR_KEYS = tuple(
    [f"planar.{who}.{k}" for who in ("prototype", "model")
     for k in ("overturned", "max_angle_rad", "overturn_time_s", "first_impact_time_s", "n_impacts", "end_time_s")]
    + [f"planar.similarity.{k}" for k in ("max_abs_angle_diff_rad", "max_abs_angular_velocity_diff_rad_s",
                                          "max_abs_angle_diff_to_tipping_rad", "max_fall_phase_diff_rad",
                                          "overturn_time_diff_s", "tipping_angular_velocity_diff_rad_s",
                                          "peak_ratio", "outcomes_agree")]
)



def study_scalars(scenario) -> dict:
    """The Study path: ``Study(scenario).run().scalars()`` plus ``sweep.valid`` (warnings
    silenced: a sweep reports results, not one warning per case). A case the Study refuses
    (e.g. a model scaled distance outside the blast fits) gives ``{"sweep.valid": False}``:
    its other values are NaN in the store."""
    import warnings

    from ..study import Study

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return {**Study(scenario).run().scalars(), VALID_KEY: True}
        except BlastscaleInputError:
            return {VALID_KEY: False}


def _block_key(b) -> tuple:
    return (b.height, b.width, b.depth, b.density)


def planar_scalars(scenarios) -> list[dict]:
    """The planar batch path for a list of planar block scenarios (module docstring): one dict of
    scalars per scenario, from one compiled kernel call per sampling size for all prototypes and
    models.

    Parameters
    ----------
    scenarios : sequence of Scenario
        Each with ``simulation.engine == "planar"`` and a block structure.

    Returns
    -------
    list of dict
        The Study's ``experiment.*``, ``design.*``, ``critical.*``, ``3d`` keys,
        :data:`PLANAR_KEYS` (SI; NaN where not applicable) and ``sweep.valid`` (True; a case
        whose design the blast fits refuse gives only ``{"sweep.valid": False}``).
    """
    import warnings

    from ..rocking import _kernel as K
    from ..analysis.rocking_similarity import _fall_phase_diff
    from ..rocking import critical_charge
    from ..rocking import DEFAULT_SOLVER, encode_pulse
    from ..rocking.system import RockingSystem
    from ..study import Study, StudyResult

    solver = DEFAULT_SOLVER
    designs: dict = {}
    criticals: dict = {}
    bases: dict = {}
    rows = []  # per case: (scenario, structure, design, base scalars, sys_p, sys_m, t)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for sc in scenarios:
            if not planar_case(sc):
                raise BlastscaleInputError(f"simulation.engine = {sc.simulation.engine!r}: the planar batch path "
                                           "takes planar block scenarios only")
            st = Study(sc)
            structure = st.structure()
            sim, bl = sc.simulation, sc.blast
            dkey = (_block_key(structure), bl.charge_kg, bl.standoff_m, sc.scale.length, sc.density_ratio,
                    sc.scale.gravity_ratio, sc.scale.law, bl.model, sim.gravity_m_s2, bl.extrapolate)
            if dkey not in designs:
                try:
                    designs[dkey] = st.design(structure)
                except BlastscaleInputError as exc:  # e.g. the model's Z outside the blast fits
                    designs[dkey] = exc
            d = designs[dkey]
            if isinstance(d, BlastscaleInputError):
                rows.append((sc, structure, None, {VALID_KEY: False}))
                continue
            crit, ckey = None, None
            if sim.critical_charge:
                ckey = (_block_key(structure), sim.gravity_m_s2, sim.restitution, bl.standoff_m, bl.pulse, bl.model,
                        bl.extrapolate)
                if ckey not in criticals:
                    system = RockingSystem.from_block(structure, sim.gravity_m_s2, sim.restitution)
                    criticals[ckey] = critical_charge(system, bl.standoff_m, pulse=bl.pulse, model=bl.model,
                                                      extrapolate=bl.extrapolate)
                crit = criticals[ckey]
            if (dkey, ckey) not in bases:  # experiment.*, design.*, critical.*: functions of these keys only
                b = StudyResult(scenario=sc, structure=structure, model_structure=structure.scaled(d.scale, d.density_ratio),
                                design=d, critical=crit).scalars()
                b.pop("planar", None)
                b[VALID_KEY] = True
                bases[(dkey, ckey)] = b
            rows.append((sc, structure, d, bases[(dkey, ckey)]))
    # the kernel inputs, exactly as RockingSolver.simulate builds them in compare_rocking
    per = {"alpha": [], "e": [], "w0": [], "tau_end": [], "kind": [], "par": [], "tt": [], "tf": [], "tev": [], "p": []}
    times = []
    ok_rows = [r for r in rows if r[2] is not None]
    n = len(ok_rows)
    for sc, structure, d, _ in ok_rows:
        sim = sc.simulation
        dur = float(sim.duration_s)
        t = np.linspace(0.0, dur, int(sim.samples))
        f = d.factors
        dur_m = dur * f.time
        t_m = np.minimum(t * f.time, dur_m)
        times.append(t)
        for system, pulse, du, tt in (
            (RockingSystem.from_block(structure, sim.gravity_m_s2, sim.restitution), d.prototype.pulse(sc.blast.pulse), dur, t),
            (RockingSystem.from_block(d.model_block, sim.gravity_m_s2 * d.gravity_ratio, sim.restitution),
             d.model.pulse(sc.blast.pulse), dur_m, t_m),
        ):
            p = system.frequency_parameter
            kind, par, tab_t, tab_f, dw = encode_pulse(pulse, system, 0.0)
            per["alpha"].append(system.alpha)
            per["e"].append(system.coefficient_of_restitution)
            per["w0"].append(0.0 / p + dw)
            per["tau_end"].append(du * p)
            per["kind"].append(kind)
            per["par"].append(par)
            per["tt"].append(tab_t)
            per["tf"].append(tab_f)
            per["tev"].append(np.ascontiguousarray(tt) * p)
            per["p"].append(p)
    summ = np.empty((2 * n, K.N_SUMMARY))
    theta = [None] * (2 * n)
    wdot = [None] * (2 * n)
    sizes = np.array([x.size for x in per["tev"]], dtype=np.int64)
    for m in np.unique(sizes):  # one compiled call per sampling size
        idx = np.flatnonzero(sizes == m)
        off = np.zeros(idx.size + 1, dtype=np.int64)
        off[1:] = np.cumsum([per["tt"][i].size for i in idx])
        tab_t = np.concatenate([per["tt"][i] for i in idx]) if off[-1] else np.zeros(0)
        tab_f = np.concatenate([per["tf"][i] for i in idx]) if off[-1] else np.zeros(0)
        s, th, w = K.solve_batch(
            np.array([per["alpha"][i] for i in idx]), np.array([per["e"][i] for i in idx]), np.zeros(idx.size),
            np.array([per["w0"][i] for i in idx]), np.array([per["tau_end"][i] for i in idx]),
            np.array([per["kind"][i] for i in idx], dtype=np.int64), np.ascontiguousarray([per["par"][i] for i in idx]),
            tab_t, tab_f, off, np.ascontiguousarray([per["tev"][i] for i in idx]),
            float(solver.rtol), float(solver.atol), float(solver.rest_velocity), -1, False, int(solver.max_steps), False,
        )
        bad = s[:, K.S_STATUS] != 0
        if np.any(bad):
            solver._check_status(s[np.argmax(bad), K.S_STATUS], int(idx[np.argmax(bad)] // 2))
        summ[idx] = s
        for j, i in enumerate(idx):
            theta[i], wdot[i] = th[j], w[j]
    out = []
    c = -1
    for sc, structure, d, base in rows:
        if d is None:
            out.append(dict(base))
            continue
        c += 1
        f = d.factors
        ip, im = 2 * c, 2 * c + 1
        pp, pm = per["p"][ip], per["p"][im]
        sp, sm = summ[ip], summ[im]
        res = dict(base)

        def summary(s, p, ft):
            # RockingResult.summary() (model: upscaled_summary, times / f.time, angles / f.angle)
            ot, fi = s[K.S_OVERTURN_TAU] / p, s[K.S_FIRST_IMPACT_TAU] / p
            fa, ft = (f.angle, ft) if ft else (1.0, 1.0)  # x / 1.0 is x: the prototype is unchanged
            return {
                "overturned": bool(s[K.S_OVERTURNED]),
                "max_angle_rad": float(s[K.S_MAX_ABS_THETA]) / fa,
                "overturn_time_s": float(ot) / ft if math.isfinite(ot) else math.nan,
                "first_impact_time_s": float(fi) / ft if math.isfinite(fi) else math.nan,
                "n_impacts": int(s[K.S_N_IMPACTS]),
                "end_time_s": float(s[K.S_END_TAU] / p) / ft,
            }

        sp_d, sm_d = summary(sp, pp, None), summary(sm, pm, f.time)
        for who, dd in (("prototype", sp_d), ("model", sm_d)):
            for k, v in dd.items():
                res[f"planar.{who}.{k}"] = v
        t = times[c]
        th_p, om_p = theta[ip], wdot[ip] * pp
        th_m, om_m = theta[im] / f.angle, wdot[im] * pm / f.angular_velocity
        diff = np.abs(th_m - th_p)
        ot_p, ot_m = sp[K.S_OVERTURN_TAU] / pp, sm[K.S_OVERTURN_TAU] / pm
        tips = [x for x in (ot_p, ot_m / f.time) if math.isfinite(x)]
        upto = t <= min(tips) if tips else np.ones(t.size, dtype=bool)
        both = sp_d["overturned"] and sm_d["overturned"]
        if both:
            ratio = 1.0
        elif sp[K.S_N_PEAKS] > 0 and sm[K.S_N_PEAKS] > 0:
            ratio = float(abs(sm[K.S_FIRST_PEAK]) / abs(sp[K.S_FIRST_PEAK]))
        else:
            ratio = float(sm[K.S_MAX_ABS_THETA] / sp[K.S_MAX_ABS_THETA]) if sp[K.S_MAX_ABS_THETA] > 0 else math.nan
        fall = _fall_phase_diff(t, th_p, om_p, th_m, om_m, max(ot_p, ot_m / f.time), pp) if both else None
        res.update({
            "planar.similarity.max_abs_angle_diff_rad": float(np.max(diff)),
            "planar.similarity.max_abs_angular_velocity_diff_rad_s": float(np.max(np.abs(om_m - om_p))),
            "planar.similarity.max_fall_phase_diff_rad": math.nan if fall is None else fall,
            "planar.similarity.max_abs_angle_diff_to_tipping_rad": float(np.max(diff[upto])),
            "planar.similarity.overturn_time_diff_s": ot_m / f.time - ot_p if both else math.nan,
            "planar.similarity.tipping_angular_velocity_diff_rad_s":
                (sm[K.S_W_AT_ALPHA] * pm) / f.angular_velocity - sp[K.S_W_AT_ALPHA] * pp if both else math.nan,
            "planar.similarity.peak_ratio": ratio,
            "planar.similarity.outcomes_agree": sp_d["overturned"] == sm_d["overturned"],
        })
        out.append({k: (v.item() if hasattr(v, "item") else v) for k, v in res.items()})
    return out


def evaluate_chunk(payload: dict, start: int, stop: int) -> dict:
    """Scalars of the cases ``start .. stop - 1`` of a sweep (``payload`` from
    :meth:`SweepSpec.to_payload`): ``{"start", "stop", "values": {key: list}}``. Planar block
    cases take the batch path, the others the Study path; a case's values never depend on the
    other cases of its chunk."""
    spec = SweepSpec.from_payload(payload)
    if spec.outcomes:
        return {"start": start, "stop": stop, "values": planar_outcomes(spec, start, stop)}
    scen = [spec.scenario(k) for k in range(start, stop)]
    planar = [i for i, sc in enumerate(scen) if planar_case(sc)]
    rows: list = [None] * len(scen)
    if planar:
        for i, r in zip(planar, planar_scalars([scen[i] for i in planar])):
            rows[i] = r
    for i, sc in enumerate(scen):
        if rows[i] is None:
            rows[i] = study_scalars(sc)
    keys = sorted({k for r in rows for k in r})
    return {"start": start, "stop": stop,
            "values": {k: [r.get(k, math.nan) for r in rows] for k in keys}}
