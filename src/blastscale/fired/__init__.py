"""After the shot: the lab's records (gauge traces, marker tracks) -> the load as fired and the response.

Low levels (:mod:`.records`, :mod:`.gauges`, :mod:`.effective`) work on files and plain arrays in SI; the
re-simulation under the load as fired goes through the :class:`~blastscale.study.Study` (docs/fired.md).
"""

from .effective import GAUGE_KINDS, effective_charge, predicted_at, tnt_equivalence
from .gauges import GaugeFit, fit_gauge
from .records import GaugeRecord, TrackRecord, read_gauges, read_tracks
from .refit import OUTCOMES
from .shot import AsFired, as_fired

__all__ = [
    "GAUGE_KINDS",
    "OUTCOMES",
    "AsFired",
    "GaugeFit",
    "GaugeRecord",
    "TrackRecord",
    "as_fired",
    "effective_charge",
    "fit_gauge",
    "predicted_at",
    "read_gauges",
    "read_tracks",
    "tnt_equivalence",
]
