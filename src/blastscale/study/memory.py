"""The memory a study's histories need, checked before any work (one line naming the duration)."""

from __future__ import annotations

from .._validate import BlastscaleInputError
from ..scenario import Scenario

__all__ = ["MEMORY_FRACTION", "estimate_memory", "check_memory"]

#: Fraction of the available memory a study may plan to use for its histories.
MEMORY_FRACTION = 0.5


def estimate_memory(scenario: Scenario, structure=None) -> int:
    """An upper estimate of the memory the histories of a study need [bytes].

    3D: per system (prototype, model) one flag per time step plus, per recorded state, the
    engine's raw state (7 + 6 doubles per body), the recorded histories (about 20 doubles per
    body and per monitoring point) kept about four times (result, up-scaled copy, dataset,
    alignment). Planar: the sampled histories (a few doubles per sample) and the solver's output.
    """
    sim = scenario.simulation
    total = 0
    if sim.engine in ("planar", "both"):
        total += sim.samples * 8 * 40
    if sim.engine in ("3d", "both"):
        nb = len(getattr(structure, "bodies", ())) or 1
        dt = sim.timestep_s if sim.timestep_s is not None else 2e-4
        steps = sim.duration_s / dt
        recs = steps / (sim.record_every or 4) + 1  # the default keeps one state per 4 or 5 steps
        runs = 1 + sim.ensemble_members  # an ensemble keeps every member's point histories too
        total += runs * 2 * (steps * 1 + recs * 8 * (13 * nb + 4 * 20 * (2 * nb)))
    return int(total)


def _available_memory() -> int:
    """Available memory [bytes] (Linux /proc/meminfo; 4 GiB when unknown)."""
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 4 * 2**30


def check_memory(scenario: Scenario, structure=None) -> None:
    """Refuse, before any work, a study whose histories would not fit in memory (one line naming
    ``simulation.duration_s``, the need and the longest duration that fits)."""
    need = estimate_memory(scenario, structure)
    limit = MEMORY_FRACTION * _available_memory()
    if need > limit:
        dur = scenario.simulation.duration_s
        fits = dur * limit / need
        raise BlastscaleInputError(
            f"simulation.duration_s = {dur:g} s is out of range: its histories would need about "
            f"{need / 2**30:.3g} GiB of memory, more than {limit / 2**30:.3g} GiB ({MEMORY_FRACTION:g} of the "
            f"available memory); valid range is <= {fits:.3g} s here (or raise simulation.record_every)"
        )
