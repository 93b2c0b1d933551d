"""The ``[fired]`` table of a scenario: what the lab recorded after the shot (docs/fired.md).

Axes of the records: x horizontal along the blast, away from the charge; z up; the origin at the centre of
the specimen's footprint on the ground at rest (for a block, its front face at x = -width/2): the one frame
of the test card's layout, the plan and ``[fired]``. Paths are relative to the scenario file; a scenario
written again (``blastscale fired --out``) keeps a relative path relative (to the written file:
:func:`~blastscale.scenario.paths.path_in`).
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import AfterValidator, BaseModel, Field, model_validator

from .fields import SPEC_CONFIG

__all__ = ["FiredSpec", "GaugeSpec", "MarkerSpec"]


def _point(v: list) -> list:
    if len(v) != 3 or not all(math.isfinite(float(x)) for x in v):
        raise ValueError(f"= {v!r} is not a point: give [x, y, z] in m")
    return [float(x) for x in v]


#: A point [x, y, z] [m] in the record axes.
Point = Annotated[list[float], AfterValidator(_point)]


def _direction(v: list) -> list:
    p = _point(v)
    n = math.sqrt(sum(x * x for x in p))
    if not n > 0:
        raise ValueError(f"= {v!r} is not a direction: give [x, y, z], not all zero")
    return [x / n for x in p]


#: A direction [x, y, z] [-] in the record axes, made a unit vector.
Direction = Annotated[list[float], AfterValidator(_direction)]


class GaugeSpec(BaseModel):
    """One pressure gauge: where it is and what it sees."""

    model_config = SPEC_CONFIG
    position_m: Point = Field(description="Gauge position [x, y, z] [m] in the record axes")
    kind: Literal["reflected", "side-on"] = Field(
        "reflected",
        description="reflected: flush in a surface (its normal below); side-on: the incident pressure (a pencil gauge)",
    )
    normal: Direction | None = Field(
        None,
        description="Outward normal [x, y, z] of the surface a reflected gauge is flush in (made a unit vector); "
        "default: the normal of the specimen's face the gauge is in",
    )

    @model_validator(mode="after")
    def _normal_of_a_reflected_gauge(self):
        if self.normal is not None and self.kind != "reflected":
            raise ValueError(
                f"normal = {self.normal!r} with kind = {self.kind!r}: a normal is the surface a reflected gauge is "
                "flush in (a side-on gauge reads the incident pressure whatever its orientation)"
            )
        return self


class MarkerSpec(BaseModel):
    """One video marker on the specimen."""

    model_config = SPEC_CONFIG
    point_m: Point = Field(description="The marker's position [x, y, z] [m] on the specimen at rest")
    px_per_mm: float | None = Field(None, gt=0, le=1e6, description="Image scale for _px track columns [px/mm]")


class FiredSpec(BaseModel):
    """What the lab measured: gauge traces, marker tracks, the weighed charge and the measured stand-off."""

    model_config = SPEC_CONFIG
    gauges: str | None = Field(None, description="Gauge traces, CSV (relative to the scenario file)")
    tracks: str | None = Field(None, description="Marker tracks, CSV (relative to the scenario file)")
    charge_kg: float | None = Field(
        None, gt=0, le=10000, description="The charge as weighed [kg of the [lab] explosive]"
    )
    standoff_m: float | None = Field(None, gt=0, le=1000, description="The stand-off as measured [m]")
    control: float | None = Field(
        None,
        gt=0,
        le=1e12,
        description="The calibrated source's control value as set, with [lab] source (an exploding-wire bank's "
        "stored energy, in the source's unit): the shot's charge by the source's law; a source shot has no "
        "weighed charge",
    )
    max_record_mb: float = Field(
        100.0,
        gt=0,
        le=10000,
        description="Largest record file read [MB]: raise it for a longer or faster record (a record is read whole)",
    )
    gauge: dict[str, GaugeSpec] = Field(default_factory=dict, description="[fired.gauge.NAME] tables")
    marker: dict[str, MarkerSpec] = Field(default_factory=dict, description="[fired.marker.NAME] tables")
