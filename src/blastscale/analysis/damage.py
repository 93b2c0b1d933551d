"""Damage states of any structure from the verdict's judged quantities: intact, damaged (slight, moderate,
severe) or collapse (docs/sweeps.md, "Damage states").

One definition for every structure (block, column, wall, arch, portal, block model), every run (prototype, the
specimen up-scaled, each ensemble member) and every command (run, report, fragility), on the quantities the
verdict judges per body (:mod:`blastscale.study.criterion`): the residual displacement and residual rotation of
every body and whether it fell. With H the structure's height,

.. math:: \\delta = \\max_k \\frac{u_{\\mathrm{res},k}}{H}, \\qquad \\phi = \\max_k |\\varphi_{\\mathrm{res},k}|

(the residual drift and the largest residual rotation), the state is

* **collapse**: a body fell (the engine's fall rule), or the structure collapsed;
* **intact**: ``delta <= intact_drift`` and ``phi <= intact_rotation_rad``;
* **damaged**, in bands of the residual drift: *slight* below ``moderate_drift``, *moderate* below
  ``severe_drift``, *severe* from there.

The limits are the scenario's ``[damage]`` table (:class:`blastscale.scenario.specs.DamageSpec`; passed in
here, this layer does not read scenarios). Their defaults follow the permanent drifts of unreinforced masonry in
FEMA 356 (2000), Table C1-3, and the residual-dislocation performance levels of multi-drum classical columns of
Psycharis, Fragiadakis & Stefanou (2013); docs/sweeps.md says how.

The states are ordered (:data:`LEVELS`): a run *reaches* a state when its level is at least that state's, and a
fragility curve gives the probability of reaching each state (:mod:`blastscale.sweeps.fragility`).

References
----------
.. [1] Psycharis, I. N., Fragiadakis, M., Stefanou, I. (2013). Seismic reliability assessment of classical
   columns subjected to near-fault ground motions. Earthquake Engng Struct. Dyn. 42(14), 2061-2079.
   doi:10.1002/eqe.2312
.. [2] FEMA 356 (2000). Prestandard and commentary for the seismic rehabilitation of buildings, Table C1-3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping, Optional

from .._validate import BlastscaleInputError

__all__ = ["LEVELS", "BANDS", "DamageState", "damage_state", "damage_summary"]

#: The damage states in order of severity (a state's level is its index).
LEVELS = ("intact", "slight", "moderate", "severe", "collapse")
#: The bands of the damaged state.
BANDS = LEVELS[1:-1]


@dataclass(frozen=True)
class DamageState:
    """A run's damage state (SI): ``state`` (``intact``, ``damaged``, ``collapse``), ``band`` (``slight``,
    ``moderate``, ``severe`` when damaged, else None), ``level`` (index in :data:`LEVELS`), the
    ``residual_drift`` [-] and ``residual_rotation_rad`` [rad] it was judged on (NaN when the run gives none:
    a planar run, a collapse) and the bodies that fell."""

    state: str
    band: Optional[str]
    level: int
    residual_drift: float
    residual_rotation_rad: float
    fallen: tuple = ()

    @property
    def name(self) -> str:
        """The level's name: the band when damaged, else the state."""
        return LEVELS[self.level]

    def to_dict(self) -> dict:
        return {
            "state": self.state,
            "band": self.band,
            "name": self.name,
            "level": self.level,
            "residual_drift": self.residual_drift,
            "residual_rotation_rad": self.residual_rotation_rad,
            "fallen": list(self.fallen),
        }


def _finite(v: Any) -> Optional[float]:
    if v is None or isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    return float(v) if math.isfinite(v) else None


def damage_state(bodies: Optional[Mapping[str, Mapping]], height_m: Optional[float], limits, *, collapsed=False):
    """The damage state of one run (module docstring).

    Parameters
    ----------
    bodies : mapping or None
        Body name -> ``residual_displacement_m`` [m], ``residual_rotation_rad`` [rad], ``fallen`` (a 3D run's
        ``bodies`` summary, up-scaled for a specimen); None for an engine without bodies (planar rocking: a
        rocking block comes back upright, so it is intact unless it overturned).
    height_m : float or None
        The structure's height H [m] > 0 (needed when a body has a residual displacement).
    limits : DamageSpec
        The scenario's ``[damage]`` table: ``intact_drift``, ``intact_rotation_rad``, ``moderate_drift``,
        ``severe_drift``.
    collapsed : bool
        The structure collapsed (overturned), whatever its bodies say.

    Returns
    -------
    DamageState

    Raises
    ------
    BlastscaleInputError
        ``height_m`` not > 0 where a residual displacement must be divided by it.

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> lim = NS(intact_drift=1e-3, intact_rotation_rad=1e-3, moderate_drift=6e-3, severe_drift=1e-2)
    >>> b = {"D-1": {"residual_displacement_m": 0.002, "residual_rotation_rad": 0.0, "fallen": False},
    ...      "D-2": {"residual_displacement_m": 0.07, "residual_rotation_rad": 0.0, "fallen": False}}
    >>> s = damage_state(b, 10.0, lim)
    >>> s.state, s.band, round(s.residual_drift, 6)
    ('damaged', 'moderate', 0.007)
    >>> damage_state({"D-2": {**b["D-2"], "fallen": True}}, 10.0, lim).name
    'collapse'
    """
    bodies = dict(bodies or {})
    fallen = tuple(n for n, b in bodies.items() if b.get("fallen"))
    disp = [_finite(b.get("residual_displacement_m")) for b in bodies.values()]
    rot = [_finite(b.get("residual_rotation_rad")) for b in bodies.values()]
    disp, rot = [abs(d) for d in disp if d is not None], [abs(r) for r in rot if r is not None]
    if disp and not (height_m is not None and math.isfinite(height_m) and height_m > 0):
        raise BlastscaleInputError(f"height_m = {height_m!r} is out of range: the structure's height must be > 0 m")
    drift = max(disp) / height_m if disp else math.nan
    phi = max(rot) if rot else math.nan
    if collapsed or fallen:
        return DamageState("collapse", None, len(LEVELS) - 1, drift, phi, fallen)
    d, r = (0.0 if math.isnan(drift) else drift), (0.0 if math.isnan(phi) else phi)
    if d <= limits.intact_drift and r <= limits.intact_rotation_rad:
        return DamageState("intact", None, 0, drift, phi)
    band = "severe" if d >= limits.severe_drift else "moderate" if d >= limits.moderate_drift else "slight"
    return DamageState("damaged", band, LEVELS.index(band), drift, phi)


def _members(stats: Optional[dict], height_m, limits) -> Optional[dict]:
    """Per ensemble member of one system: the level names and their counts (None without members' bodies)."""
    if not stats or stats.get("member_bodies") is None:
        return None
    states = [
        damage_state(b, height_m, limits, collapsed=c)
        for b, c in zip(stats["member_bodies"], stats["member_collapsed"])
    ]
    return {"members": [s.name for s in states], "counts": {n: sum(s.name == n for s in states) for n in LEVELS}}


def damage_summary(summary: dict, limits, height_m: Optional[float], ensemble=None) -> Optional[dict]:
    """The ``damage`` section of a study's summary: the state of the prototype and of the up-scaled model
    (``model``: None without a specimen), from the 3D runs where they ran, else from planar rocking
    (``engine`` says which); with an ensemble, each member's state and the counts per state (``ensemble``:
    ``prototype`` and ``model``, each ``members`` and ``counts``). None when no engine ran.

    Parameters
    ----------
    summary : dict
        A study's summary (``planar``, ``3d``; the model's results up-scaled to prototype units).
    limits : DamageSpec
        The scenario's ``[damage]`` table.
    height_m : float or None
        The structure's height H [m] (:func:`blastscale.study.criterion.structure_height`).
    ensemble : EnsembleComparison, optional
        The study's 3D ensembles (their members' bodies).
    """
    out: dict = {}
    sec3, planar = summary.get("3d") or {}, summary.get("planar") or {}
    for system in ("prototype", "model"):
        run = sec3.get(system)
        if run is not None:
            s = damage_state(run.get("bodies"), height_m, limits, collapsed=bool(run.get("collapsed")))
            out[system], out["engine"] = s.to_dict(), "3d"
        elif planar.get(system) is not None and "collapsed" in planar[system]:
            s = damage_state(None, height_m, limits, collapsed=bool(planar[system]["collapsed"]))
            out[system] = s.to_dict()
            out.setdefault("engine", "planar")
        else:
            out[system] = None
    if out["prototype"] is None:
        return None
    if ensemble is not None:
        out["ensemble"] = {s: _members(getattr(ensemble, s, None), height_m, limits) for s in ("prototype", "model")}
    return out
