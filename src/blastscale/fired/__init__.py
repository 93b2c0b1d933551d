"""After the shot: the lab's records (gauge traces, marker tracks) -> the load as fired and the response.

Low levels (:mod:`.records`, :mod:`.gauges`, :mod:`.effective`) work on files and plain arrays in SI; the
re-simulation under the load as fired goes through the :class:`~blastscale.study.Study` (docs/fired.md):
:func:`blastscale.fired.shot.as_fired`, not imported here, so that the records and the shot's geometry
(:mod:`.inputs`) are checked before the engines load.
"""

from .effective import GAUGE_KINDS, effective_charge, predicted_at, tnt_equivalence
from .gauges import GaugeFit, fit_gauge
from .records import GaugeRecord, TrackRecord, read_gauges, read_tracks

__all__ = [
    "GAUGE_KINDS",
    "GaugeFit",
    "GaugeRecord",
    "TrackRecord",
    "effective_charge",
    "fit_gauge",
    "predicted_at",
    "read_gauges",
    "read_tracks",
    "tnt_equivalence",
]
