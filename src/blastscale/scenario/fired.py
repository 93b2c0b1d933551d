"""The ``[fired]`` table of a scenario: what the lab recorded after the shot (docs/fired.md).

Axes of the records: x horizontal along the blast, away from the charge; z up; the origin at the centre of
the specimen's footprint on the ground at rest (for a block, its front face at x = -width/2). Paths are
relative to the scenario file.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import AfterValidator, BaseModel, Field

from .fields import SPEC_CONFIG

__all__ = ["FiredSpec", "GaugeSpec", "MarkerSpec"]


def _point(v: list) -> list:
    if len(v) != 3 or not all(math.isfinite(float(x)) for x in v):
        raise ValueError(f"= {v!r} is not a point: give [x, y, z] in m")
    return [float(x) for x in v]


#: A point [x, y, z] [m] in the record axes.
Point = Annotated[list[float], AfterValidator(_point)]


class GaugeSpec(BaseModel):
    """One pressure gauge: where it is and what it sees."""

    model_config = SPEC_CONFIG
    position_m: Point = Field(description="Gauge position [x, y, z] [m] in the record axes")
    kind: Literal["reflected", "side-on"] = Field(
        "reflected", description="reflected: flush in a rigid plate facing the charge; side-on: incident pressure"
    )


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
    max_record_mb: float = Field(
        100.0,
        gt=0,
        le=10000,
        description="Largest record file read [MB]: raise it for a longer or faster record (a record is read whole)",
    )
    gauge: dict[str, GaugeSpec] = Field(default_factory=dict, description="[fired.gauge.NAME] tables")
    marker: dict[str, MarkerSpec] = Field(default_factory=dict, description="[fired.marker.NAME] tables")
