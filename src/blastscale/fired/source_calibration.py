"""A blast source calibrated from the lab's own shots (``blastscale source calibrate``; docs/planning.md, "Sources").

The calibration set (SHOTS.toml) names the source (``[source]``: its kind, control variable, limits, the blast model
and burst its equivalence is read against, the wire for an exploding-wire bank, ``synthetic`` for a made-up set)
and its shots (``[[shot]]``: the control value set, the gauge record, and ``[shot.gauge.NAME]`` with each gauge's
distance from the source and kind). Each record is read as the fired test reads its records: the file by
:func:`blastscale.fired.records.read_gauges`, each trace by :func:`blastscale.fired.gauges.fit_gauge` (baseline,
arrival, Friedlander fit, impulse), the effective TNT charge by impulse and by peak by
:func:`blastscale.fired.effective.effective_charge` (the blast model inverted at the gauge's distance).

**The fit.** A shot's effective charge on each basis is the geometric mean over its gauges (one yield per shot);
``ln W_s = alpha + k ln(x_s / x_ref) + e_s`` over the n shots by least squares, x_ref the shots' geometric mean
control value, the parameters' covariance ``C = s^2 (X^T X)^-1`` with ``s^2 = sum e_s^2 / (n - 2)``; s is the
source's repeatability (one shot's scatter about the law; it holds the bank's charging precision and the gauges'
noise). The law's 95 % interval at x uses Student's t with n - 2 degrees of freedom
(:class:`blastscale.blast.sources.PowerLaw`). At least three shots at two control values or more.

**Self-similarity.** Blasts of one source collapse on the scaled distance Z = R / W^(1/3) (Hopkinson-Cranz) when
the equivalence is a property of the source alone (arXiv:2410.07221): a record's effective charge then depends on
the control value only, not on where it was measured. Each record's residual ``r = ln W_record - ln W(x)`` is
regressed on the control and the scaled distance (Z with the law's W at the shot's control value),
``r = c0 + c1 ln x + c2 ln Z + c3 ln^2 Z``, and the scaled distance's terms are tested against the fit without
them (``r = c0 + c1 ln x``) by the F test of the nested fits, ``F = ((RSS_0 - RSS_1) / 2) / (RSS_1 / (m - 4))`` on
(2, m - 4) degrees of freedom (m records; Draper & Smith 1998, *Applied Regression Analysis*, 3rd ed.: the extra sum of squares):
at a given control value ln Z is ln R less a constant, so a trend with Z or one distance off the others is caught
alike. Below :data:`SELF_SIMILARITY_P` the records do not collapse and the result says so in one line; the
source is written still (marked ``self_similar = false``). With fewer than :data:`MIN_RECORDS_FOR_TREND` records
the test is not made (said so).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal, Optional

import numpy as np
from pydantic import BaseModel, Field, ValidationError, model_validator
from scipy.stats import f as f_dist

from .._validate import BlastscaleInputError
from ..blast.inverse import INCIDENCE_RANGE_DEG
from ..blast.parameters import BLAST_MODELS, BURSTS, DEFAULT_BLAST_MODEL, model_for_burst
from ..blast.sources import SOURCE_KINDS, TNT_ENERGY_J_PER_KG, CalibratedSource, PowerLaw, source_to_dict
from ..io.source_file import read_toml
from ..scenario.fields import SPEC_CONFIG
from ..scenario.messages import one_line
from .effective import effective_charge
from .gauges import fit_gauge
from .records import MAX_RECORD_MB, read_gauges, record_fault

__all__ = [
    "MIN_RECORDS_FOR_TREND",
    "SELF_SIMILARITY_P",
    "CalibrationSet",
    "SourceCalibration",
    "calibrate_source",
    "read_calibration_set",
]

#: The F test's level below which the records do not collapse on Z (1 %: a clean campaign is flagged once in a
#: hundred, a bias of a tenth on one distance's impulse over 12 records with 3 % scatter almost always).
SELF_SIMILARITY_P = 0.01
#: Fewest records for the self-similarity test (four terms and a residual of m - 4 >= 3 degrees of freedom).
MIN_RECORDS_FOR_TREND = 7


class WireSpec(BaseModel):
    """The exploding wire (recorded with the source; no number of it enters the law)."""

    model_config = SPEC_CONFIG
    material: str = Field(description="The wire's material (e.g. aluminium)")
    length_m: float = Field(gt=0, le=10, description="The wire's length [m]")
    diameter_m: Optional[float] = Field(None, gt=0, le=0.1, description="The wire's diameter [m]")


class SourceInfoSpec(BaseModel):
    """``[source]`` of a calibration set: what the source is and what the equivalence is read against."""

    model_config = SPEC_CONFIG
    name: str = Field(description="The source's name")
    kind: Literal["exploding-wire", "other"] = Field("exploding-wire", description="exploding-wire or other")
    control: Optional[str] = Field(None, description="The control variable (default: stored_energy for a wire)")
    control_unit: Optional[str] = Field(None, description="The control's unit (default: J for a wire)")
    control_min: Optional[float] = Field(
        None, gt=0, le=1e12, description="Least control value the lab may set [control unit] (default: the shots')"
    )
    control_max: Optional[float] = Field(
        None, gt=0, le=1e12, description="Largest control value the lab may set [control unit] (default: the shots')"
    )
    synthetic: bool = Field(False, description="True for a made-up calibration (never a real source)")
    blast_model: Literal[tuple(BLAST_MODELS)] = Field(  # type: ignore[valid-type]
        DEFAULT_BLAST_MODEL, description="The blast model the effective charges are inverted with"
    )
    burst: Literal[BURSTS] = Field("surface", description="The source's burst: surface or free-air")  # type: ignore[valid-type]
    wire: Optional[WireSpec] = Field(None, description="[source.wire]: the exploding wire")
    notes: str = Field("", description="Anything else the lab records")

    @model_validator(mode="after")
    def _kind(self) -> "SourceInfoSpec":
        if self.kind == "exploding-wire" and self.wire is None:
            raise ValueError(
                "kind = 'exploding-wire' needs [source.wire] with material and length_m (recorded with the source)"
            )
        if self.kind == "other" and (self.control is None or self.control_unit is None):
            raise ValueError("kind = 'other' needs control and control_unit (the control variable and its unit)")
        if self.control_min is not None and self.control_max is not None and self.control_min > self.control_max:
            raise ValueError(f"control_min = {self.control_min:g} is above control_max = {self.control_max:g}")
        return self


class ShotGaugeSpec(BaseModel):
    """``[shot.gauge.NAME]``: one gauge of a calibration shot."""

    model_config = SPEC_CONFIG
    distance_m: float = Field(gt=0, le=1000, description="Distance from the source's centre to the gauge [m]")
    kind: Literal["reflected", "side-on"] = Field("side-on", description="reflected (flush in a surface) or side-on")
    incidence_deg: float = Field(
        0.0,
        ge=INCIDENCE_RANGE_DEG[0],
        le=INCIDENCE_RANGE_DEG[1],
        description="A reflected gauge's angle of incidence [deg] (0: facing the source)",
    )


class ShotSpec(BaseModel):
    """``[[shot]]``: one calibration shot."""

    model_config = SPEC_CONFIG
    name: Optional[str] = Field(None, description="The shot's name (default: shot N)")
    control: float = Field(gt=0, le=1e12, description="The control value set for the shot [control unit]")
    gauges: str = Field(description="The shot's gauge traces, CSV (relative to the calibration file)")
    gauge: dict[str, ShotGaugeSpec] = Field(description="[shot.gauge.NAME] tables, one per gauge column")
    max_record_mb: float = Field(MAX_RECORD_MB, gt=0, le=10000, description="Largest record file read [MB]")


class CalibrationSet(BaseModel):
    """A calibration set (SHOTS.toml): the source and its shots."""

    model_config = SPEC_CONFIG
    source: SourceInfoSpec
    shot: list[ShotSpec] = Field(description="[[shot]] tables: at least 3, at 2 control values or more")

    @model_validator(mode="after")
    def _shots(self) -> "CalibrationSet":
        if len(self.shot) < 3:
            raise ValueError(f"= {len(self.shot)} shots: at least 3 are needed for a power law and its scatter")
        if len({s.control for s in self.shot}) < 2:
            raise ValueError(
                f"every shot has control = {self.shot[0].control:g}: give shots at 2 control values or more"
            )
        for i, s in enumerate(self.shot):
            if not s.gauge:
                raise ValueError(f"shot {i + 1} has no [shot.gauge.NAME] table: give one per gauge column")
        return self

    @property
    def control(self) -> tuple[str, str]:
        """(the control variable, its unit)."""
        c, u = SOURCE_KINDS[self.source.kind]
        return self.source.control or c, self.source.control_unit or u


def read_calibration_set(path) -> CalibrationSet:
    """The calibration set of the TOML file ``path``, its record paths made relative to the file's folder.

    Raises
    ------
    BlastscaleInputError
        An unreadable file, a TOML error or a bad key (one line: the file, the key, its value and valid range).
    """
    p = Path(path)
    data = read_toml(p, "calibration set")
    shots = data.get("shot")
    if isinstance(shots, list):
        data["shot"] = [
            {**s, "gauges": str(p.resolve().parent / s["gauges"])}
            if isinstance(s, dict) and isinstance(s.get("gauges"), str) and not Path(s["gauges"]).is_absolute()
            else s
            for s in shots
        ]
    for i, shot in enumerate(shots if isinstance(shots, list) else []):  # each shot alone: its own key path
        try:
            ShotSpec.model_validate(shot)
        except ValidationError as exc:
            name = f" ({shot['name']})" if isinstance(shot, dict) and isinstance(shot.get("name"), str) else ""
            raise BlastscaleInputError(f"{p.name}: [[shot]] {i + 1}{name}: {one_line(exc, ShotSpec, {})}") from None
    try:
        return CalibrationSet.model_validate(data)
    except ValidationError as exc:
        raise BlastscaleInputError(f"{p.name}: {one_line(exc, CalibrationSet, {})}") from None


@dataclass(frozen=True)
class SourceCalibration:
    """The calibration's answer: the source, every record's figures (``records``: dicts), every shot's
    (``shots``), the self-similarity test and the gauges' warnings."""

    source: CalibratedSource
    records: list
    shots: list
    self_similarity: dict
    warnings: list = field(default_factory=list)

    def summary(self) -> dict:
        """The ``source_calibration`` summary (docs/planning.md, "Sources"), SI and the control's unit."""
        s = self.source
        grid = sorted({r["control"] for r in self.shots})
        laws = {}
        for basis in ("impulse", "pressure"):
            law = s.law(basis)
            lo, hi = law.interval(np.array(grid))
            laws[basis] = {
                "tnt_kg_at_reference": law.tnt_kg_at_reference,
                "reference": law.reference,
                "exponent": law.exponent,
                "ci95_exponent": law.quantile() * math.sqrt(law.covariance[1][1]),
                "repeatability": law.repeatability,
                "degrees_of_freedom": law.dof,
                "at_control": [
                    {
                        "control": x,
                        "tnt_kg": float(law.tnt_kg(x)),
                        "ci95_tnt_kg": [float(a), float(b)],
                        "energy_fraction": float(law.tnt_kg(x) * TNT_ENERGY_J_PER_KG / x)
                        if s.control_unit == "J"
                        else None,
                    }
                    for x, a, b in zip(grid, lo, hi)
                ],
            }
        return {
            "source": source_to_dict(s)["source"],
            "equivalence": laws,
            "self_similarity": dict(self.self_similarity),
            "shots": list(self.shots),
            "records": list(self.records),
            "warnings": list(self.warnings),
        }


def _records(cs: CalibrationSet) -> tuple[list, list]:
    """Every record's fit and effective charges, and the gauges' warnings (records read as ``fired`` reads them)."""
    out, notes = [], []
    model, burst = cs.source.blast_model, cs.source.burst
    for i, shot in enumerate(cs.shot):
        name = shot.name or f"shot {i + 1}"
        rec = read_gauges(shot.gauges, max_mb=shot.max_record_mb)
        for g in shot.gauge:
            if g not in rec.pressure_Pa:
                raise record_fault(rec.path, "", 1, f"gauge {g!r} of [shot.gauge.{g}] has no column (NAME_kPa, ...)")
        for g, col in rec.columns.items():
            if g not in shot.gauge:
                raise record_fault(
                    rec.path, col, 1, f"gauge {g!r} has no [shot.gauge.{g}] table in {name} (give its distance_m)"
                )
        for g, p in rec.pressure_Pa.items():
            spec = shot.gauge[g]
            fit = fit_gauge(rec.time_s, p, g, source=rec.path, column=rec.columns[g])
            notes += [f"{name}: {w}" for w in fit.warnings]
            w = {}
            for basis, value in (("impulse", fit.impulse_Pa_s), ("pressure", fit.peak_pressure_Pa)):
                try:
                    w[basis] = effective_charge(
                        value, spec.distance_m, spec.kind, basis, model, burst, spec.incidence_deg
                    )
                except BlastscaleInputError as exc:
                    raise BlastscaleInputError(f"{name}, gauge {g!r} ({Path(rec.path).name}): {exc}") from None
            out.append(
                {
                    "shot": name,
                    "shot_index": i,
                    "gauge": g,
                    "control": shot.control,
                    "distance_m": spec.distance_m,
                    "kind": spec.kind,
                    "peak_pressure_Pa": fit.peak_pressure_Pa,
                    "impulse_Pa_s": fit.impulse_Pa_s,
                    "tnt_kg_impulse": w["impulse"],
                    "tnt_kg_pressure": w["pressure"],
                }
            )
    return out, notes


def _fit(x: np.ndarray, y: np.ndarray, reference: float) -> PowerLaw:
    """The least-squares power law of ``y = ln W`` on ``x`` (control values) about ``reference`` (module docstring)."""
    X = np.column_stack([np.ones(x.size), np.log(x / reference)])
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    e = y - X @ coef
    dof = x.size - 2
    s2 = float(e @ e) / dof
    cov = np.linalg.inv(X.T @ X) * s2
    return PowerLaw(
        float(reference),
        float(math.exp(coef[0])),
        float(coef[1]),
        tuple(tuple(float(v) for v in row) for row in cov),
        int(dof),
        math.sqrt(s2),
    )


def _laws(x: np.ndarray, records: list) -> tuple[dict, list]:
    """({basis: PowerLaw}, [ln W per shot, per basis]) of the shots at control values ``x`` from their records
    (a shot's ln W the mean over its gauges), about the geometric mean control value (module docstring)."""
    ref = float(np.exp(np.mean(np.log(x))))
    laws, shots = {}, []
    for basis in ("impulse", "pressure"):
        y = np.array(
            [np.mean([np.log(r[f"tnt_kg_{basis}"]) for r in records if r["shot_index"] == i]) for i in range(x.size)]
        )
        laws[basis] = _fit(x, y, ref)
        shots.append(y)
    k = min(law.exponent for law in laws.values())
    if not k > 0:
        raise BlastscaleInputError(
            f"the fitted exponent = {k:.3g} is out of range: valid range is > 0 (a source whose blast grows with its "
            "control value); check the shots' control values and records"
        )
    return laws, shots


def _self_similarity(records: list, laws: dict) -> dict:
    """The F test of the records' residuals against ln Z (module docstring), per basis; one line."""
    m = len(records)
    if m < MIN_RECORDS_FOR_TREND:
        return {
            "similar": None,
            "line": f"self-similarity not tested: {m} records, at least {MIN_RECORDS_FOR_TREND} are needed",
            "tests": {},
        }
    tests, bad = {}, []
    for basis, law in laws.items():
        x = np.array([r["control"] for r in records])
        z = np.array([r["distance_m"] for r in records]) / np.cbrt(law.tnt_kg(x))
        r = np.log([rec[f"tnt_kg_{basis}"] for rec in records]) - np.log(law.tnt_kg(x))
        lz, lx = np.log(z), np.log(x)
        X0 = np.column_stack([np.ones(m), lx])
        X1 = np.column_stack([X0, lz, lz * lz])
        rss0, rss1 = (float(np.sum((r - X @ np.linalg.lstsq(X, r, rcond=None)[0]) ** 2)) for X in (X0, X1))
        F = ((rss0 - rss1) / 2.0) / max(rss1 / (m - 4), 1e-300)
        p = float(f_dist.sf(F, 2, m - 4))
        slope = float(np.linalg.lstsq(np.column_stack([X0, lz]), r, rcond=None)[0][2])  # at a given control
        tests[basis] = {
            "F": F,
            "p": p,
            "slope_per_ln_Z": slope,
            "scaled_distance_range": [float(z.min()), float(z.max())],
        }
        if p < SELF_SIMILARITY_P:
            bad.append(
                f"by {basis}, the residuals vary with Z (F = {F:.3g}, p = {p:.2g} < {SELF_SIMILARITY_P:g}; "
                f"{100 * slope:+.2g} % per unit ln Z)"
            )
    if bad:
        line = (
            "the records do not collapse on scaled distance: "
            + "; ".join(bad)
            + ": the equivalence depends on the distance (a gauge or its distance off, or a source that is not "
            "self-similar); check the records before using the source"
        )
    else:
        line = (
            f"the records collapse on scaled distance (F test against ln Z, p >= {SELF_SIMILARITY_P:g} by impulse "
            "and by peak)"
        )
    return {"similar": not bad, "line": line, "tests": tests}


def calibrate_source(cs: CalibrationSet) -> SourceCalibration:
    """Calibrate the source of ``cs`` from its shots (module docstring).

    Parameters
    ----------
    cs : CalibrationSet
        From :func:`read_calibration_set`.

    Returns
    -------
    SourceCalibration

    Raises
    ------
    BlastscaleInputError
        A bad record (file, column, row), a value the blast model cannot invert (the gauge and its range), a
        fit that cannot be made (one line each).
    """
    model_for_burst(cs.source.blast_model, cs.source.burst)  # a burst the model has a fit for, before any record
    src, (control, unit) = cs.source, cs.control
    lo, hi = float(min(s.control for s in cs.shot)), float(max(s.control for s in cs.shot))
    c_min = src.control_min if src.control_min is not None else lo
    c_max = src.control_max if src.control_max is not None else hi
    if c_min > c_max:
        raise BlastscaleInputError(
            f"source.control_min = {c_min:g} {unit} is above control_max = {c_max:g} {unit} (the shots' largest "
            "control value unless given): give a minimum at or below the maximum"
        )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        records, notes = _records(cs)
    n = len(cs.shot)
    x = np.array([s.control for s in cs.shot], dtype=float)
    laws, shots = _laws(x, records)
    similarity = _self_similarity(records, laws)
    z_all = [r["distance_m"] / float(np.cbrt(laws["impulse"].tnt_kg(r["control"]))) for r in records]
    details = {} if src.wire is None else {f"wire_{k}": v for k, v in src.wire.model_dump().items() if v is not None}
    if src.notes:
        details["notes"] = src.notes
    source = CalibratedSource(
        name=src.name,
        kind=src.kind,
        control=control,
        control_unit=unit,
        control_min=c_min,
        control_max=c_max,
        impulse=laws["impulse"],
        pressure=laws["pressure"],
        blast_model=src.blast_model,
        burst=src.burst,
        calibrated_control=(lo, hi),
        calibrated_scaled_distance=(float(min(z_all)), float(max(z_all))),
        shots=n,
        synthetic=src.synthetic,
        self_similar=similarity["similar"] is not False,
        self_similarity=similarity["line"],
        details=details,
    )
    shot_rows = [
        {
            "shot": cs.shot[i].name or f"shot {i + 1}",
            "control": float(x[i]),
            "tnt_kg_impulse": float(np.exp(shots[0][i])),
            "tnt_kg_pressure": float(np.exp(shots[1][i])),
            "residual_ln_impulse": float(shots[0][i] - np.log(laws["impulse"].tnt_kg(x[i]))),
            "residual_ln_pressure": float(shots[1][i] - np.log(laws["pressure"].tnt_kg(x[i]))),
        }
        for i in range(n)
    ]
    for r, z in zip(records, z_all):
        r["scaled_distance"] = z
    return SourceCalibration(source, records, shot_rows, similarity, notes)
