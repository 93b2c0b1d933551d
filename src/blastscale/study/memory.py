"""The one size and time guard of every command that simulates: the memory and the computing time a
job needs, estimated and checked before any work (one line naming the key or flag, the need and the
valid range).

Rule (:func:`check_budget`): a job may plan at most :data:`MEMORY_FRACTION` of the available memory
and at most :func:`max_seconds` of computing (24 h by default, ``BLASTSCALE_MAX_HOURS`` to change it).
The estimates are deliberately rough (within a factor of 2 of the CPU time on the 2-core development machine,
cold and warm: ``benchmarks/bench_first_use.py``): their purpose is to refuse a run that would exhaust the memory
or never end and to say how long to wait, compiling on first use included (:func:`compile_seconds`).

Every run says its size before it starts (:func:`estimate_run`, :class:`RunSize`: one line, "about 40 s and
12 MB: 210 bodies, 1719 contacts, ..."), from the cost model of docs/performance.md ("The size of a run, said
first"), checked against measured runs by ``benchmarks/bench_estimate.py``.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

from .._validate import BlastscaleInputError
from ..scenario.scenario import Scenario
from ..sim3d.contact import default_contact
from ..sim3d.integrate import settle_steps, step_factor_after_load
from ..sim3d.rest import rest_contact, rest_time
from ..structures.assembly import as_assembly
from ..units import format_size
from .engines import contact_settings, record_every

__all__ = [
    "MEMORY_FRACTION",
    "estimate_memory",
    "check_memory",
    "estimate_seconds",
    "check_budget",
    "check_study_budget",
    "max_seconds",
    "format_duration",
    "STEP_SECONDS",
    "RunSize",
    "estimate_run",
    "contacts_of",
    "STEP_BASE_SECONDS",
    "CONTACT_STEP_SECONDS",
    "CONTACT_STEP_UNITS",
    "CONTACT_STEP_EXPONENT",
    "STATE_BYTES_PER_BODY",
    "STATE_BYTES_PER_POINT",
    "REPORT_BYTES",
    "REPORT_BYTES_PER_BODY",
    "WRITE_SECONDS",
    "WRITE_SECONDS_PER_BYTE",
    "BODY_SECONDS",
    "BODY_EXPONENT",
    "REST_CHECK_SECONDS",
    "rest_check_size",
    "step_seconds",
    "STARTUP_SECONDS",
    "COMPILE_SECONDS",
    "KERNEL_MODULES",
    "SEARCH_KERNEL_MODULES",
    "compile_seconds",
]

#: Fraction of the available memory a job may plan to use.
MEMORY_FRACTION = 0.5

#: The old per-step constant (a one-body step [s]; a stack of n bodies was taken as n^1.5 times more): kept for
#: callers; the estimate now uses the cost model below.
STEP_SECONDS = 5e-6

#: Cost model of a 3D run on one core (docs/performance.md, "The size of a run, said first"; fitted to
#: ``benchmarks/bench_estimate.py``, 1-3000 bodies): a fixed part per step and run [s] ...
STEP_BASE_SECONDS = 4e-6
#: ... plus this per step, run and body or contact (an interface between bodies or with the ground) [s]: MuJoCo's
#: constraint solve and collision grow with the contacts (3-8 contact points per interface), the recording and
#: the loads with the bodies; measured 2.5-3.5 us under a blast ...
CONTACT_STEP_SECONDS = 3e-6
#: ... times (u / CONTACT_STEP_UNITS)^CONTACT_STEP_EXPONENT for u = bodies + contacts above CONTACT_STEP_UNITS:
#: the cost of a contact grows with their number under a blast (the constraint solve couples them, the contacts
#: that change state cost Newton iterations). Measured (``benchmarks/bench_contact_cost.py``: CPU time per step
#: after the load, two durations of one structure differenced) on stack-bonded walls of 25, 100 and 400 blocks under
#: 100 kg at 10 m: 3.75, 10.95 and 5.63 us per body or contact at u = 70, 290 and 1180 since their side joints engage
#: at the collision depth (issue #39: 3.4, 9.8 and 14.6 us before, 0.45), the least-squares exponent of the three
#: 0.33, taken 0.35: the model 0.90, 0.51 and 1.60 of them.
CONTACT_STEP_UNITS, CONTACT_STEP_EXPONENT = 50, 0.35
#: ... plus, once per run of a structure of n bodies, BODY_SECONDS n^BODY_EXPONENT [s]: the engine's model
#: built, the histories compared and drawn per body (measured: 13 s for 210 bodies, 290 s for 3000).
BODY_SECONDS, BODY_EXPONENT = 0.025, 1.17
#: The check at rest before the blast (:func:`blastscale.sim3d.rest.rest_check`: every 3D run under a charge, the
#: structure under gravity alone for its rest time, 3 sqrt(H / g), at the step after the load) costs its steps at
#: the cost of a step at rest, STEP_BASE_SECONDS + CONTACT_STEP_SECONDS u (:func:`step_seconds`: no growth with u;
#: a structure at rest changes no contact state, its Newton solve takes one iteration a step: the 3000-block
#: stack-bonded wall 26 ms a step measured by py-spy, 27 ms by the model, where the growth factor would say 165 ms)
#: plus this once per check [s]: a second engine model compiled and settled (the 10-drum columns: 1.04-1.09 CPU s
#: measured, 0.39 s of steps by the model). A specimen that is its prototype's exact model reuses the check.
REST_CHECK_SECONDS = 0.65
#: Start-up of a command that simulates (Python, MuJoCo, xarray, the design, the check, the tables printed) [s]:
#: measured 1.2-1.3 s of imports and 0.4-0.5 s of check in-process, ~3 s of CPU by the CLI (issue #39,
#: ``benchmarks/bench_first_use.py``; it was 2 s).
STARTUP_SECONDS = 3.0
#: Compiling the rocking kernels (:data:`KERNEL_MODULES`: the planar engine and the critical-charge search) on
#: first use, when numba's on-disk cache of the current sources is cold [s of one core]: measured 47 s of CPU
#: (the default run, 56 s cold against 9 s warm, ``benchmarks/bench_first_use.py``, a shared 2-core machine).
#: The 3D engine (MuJoCo) compiles nothing. Each cold module counts its share.
COMPILE_SECONDS = 47.0
#: The compiled modules of the planar path (:mod:`blastscale._jit`: each keyed on its sources).
KERNEL_MODULES = ("kernel", "_load", "_events", "_free", "_dopri", "_batch", "_series")
#: Of :data:`KERNEL_MODULES`, those only the critical-charge search loads (``simulation.critical_charge``): a planar
#: run without the search compiles the other six (measured: an empty ``NUMBA_CACHE_DIR`` after ``blastscale run`` of
#: the default scenario, planar, ``critical_charge = false``, holds every module but ``_batch``).
SEARCH_KERNEL_MODULES = ("_batch",)
#: Bytes of histories per recorded state, run and body (19 doubles: displacement, velocity, angular velocity,
#: tilt, rotation, uplift, position, quaternion) and per monitoring point (6 doubles).
STATE_BYTES_PER_BODY, STATE_BYTES_PER_POINT = 19 * 8, 6 * 8
#: The report, figures and summary of a result folder [bytes] (the 3D view's poses at most 1 MB,
#: :data:`blastscale.report.motion.FRAME_BYTES`; no plotting library in the page since issue 41, where plotly's 4.7 MB
#: made this 6.5 MB) ...
REPORT_BYTES = 0.6e6
#: ... plus this per body (the summary's and the report's rows of each body, their figures) [bytes]. Fitted to
#: ``benchmarks/bench_estimate.py`` (28 Nov 2026, evening): the folders besides the histories measured 0.41 MB (the
#: block), 0.94 (the 10-drum column), 0.95, 1.34, 2.48 MB (running-bond walls of 22, 55, 210 blocks); the whole
#: folder then estimated at 0.92-1.25 times its measured size, the 3000-block file 42.0 MB against 38.6 (1.09).
REPORT_BYTES_PER_BODY = 9e3
#: Writing a result folder: a fixed time (figures, report) [s] and a rate [s per byte of histories]. The fixed
#: time measured 3.7 s of CPU for the default run's folder and 3.9 s for the square column's (issue #39: the
#: report's figures and its 3D view have grown since the 1.3 s of issue #27).
WRITE_SECONDS, WRITE_SECONDS_PER_BYTE = 3.5, 2e-8


def max_seconds() -> float:
    """Longest computing time a job may plan [s]: ``BLASTSCALE_MAX_HOURS`` (hours, > 0), else 24 h."""
    text = os.environ.get("BLASTSCALE_MAX_HOURS", "")
    try:
        hours = float(text)
    except ValueError:
        hours = 24.0
    return hours * 3600.0 if math.isfinite(hours) and hours > 0 else 24 * 3600.0


def format_duration(seconds: float) -> str:
    """Seconds in words: ``40 s``, ``12 min``, ``3.2 h``, ``4.1 days``."""
    if seconds < 90:
        return f"{seconds:.2g} s" if seconds < 10 else f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    if seconds < 3 * 86400:
        return f"{seconds / 3600:.2g} h"
    return f"{seconds / 86400:.3g} days"


def _timestep(scenario: Scenario, structure, contact=None) -> float:
    """The prototype's 3D time step [s]: the scenario's, else that of ``contact`` (the study's resolved
    contact settings) when given, else the one derived from the structure."""
    sim = scenario.simulation
    if sim.timestep_s is not None:
        return sim.timestep_s
    if contact is not None:
        return contact.timestep
    if structure is not None:
        try:
            return contact_settings(scenario, structure).timestep
        except BlastscaleInputError:  # reported by the engine's own check
            pass
    return 2e-4


def _derived_timestep(scenario: Scenario, structure) -> float:
    """The time step the engine derives from the structure's size [s] (no time step given)."""

    try:
        return default_contact(
            structure, friction=scenario.structure.friction, gravity=scenario.simulation.gravity_m_s2
        ).timestep
    except BlastscaleInputError:
        return 2e-4


def _bodies(structure) -> int:
    return len(getattr(structure, "bodies", ())) or 1


def estimate_memory(scenario: Scenario, structure=None, contact=None) -> int:
    """An upper estimate of the memory the histories of a study need [bytes] (``contact``: the study's
    resolved 3D contact settings, when known: their time step).

    3D: per system (prototype, model) one flag per time step plus, per recorded state, the
    engine's raw state (7 + 6 doubles per body), the recorded histories (about 20 doubles per
    body and per monitoring point, and the motion's 7 per body: position and quaternion) kept about four times (result, up-scaled copy, dataset,
    alignment). Planar: the sampled histories (a few doubles per sample) and the solver's output.
    """
    sim = scenario.simulation
    total = 0
    if sim.engine in ("planar", "both"):
        total += sim.samples * 8 * 40
    if sim.engine in ("3d", "both"):
        nb = _bodies(structure)
        steps = sim.duration_s / _timestep(scenario, structure, contact)
        recs = steps / (sim.record_every or 4) + 1  # the default keeps one state per 4 or 5 steps
        runs = 1 + sim.ensemble_members  # an ensemble keeps every member's point histories too
        total += runs * 2 * (steps * 1 + recs * 8 * (13 * nb + 4 * 20 * (2 * nb) + 4 * 7 * nb))
    return int(total)


def estimate_seconds(scenario: Scenario, structure=None, contact=None, contacts: int | None = None) -> float:
    """A rough estimate of a study's computing time on one core [s] (module docstring; docs/performance.md): 3D,
    the steps of every run (prototype and model, ensemble members; the settling before the load included; the
    longer steps after the load counted as such) times the cost of a step under a blast (:func:`step_seconds`, u =
    bodies + contacts), plus :data:`BODY_SECONDS` x bodies^:data:`BODY_EXPONENT`, plus the checks at rest before the
    blast (:func:`rest_check_size`: their steps at the cost of a step at rest, plus :data:`REST_CHECK_SECONDS` each);
    planar, ~2 us per sample and system plus the critical-charge search (~0.1 s);
    ``contact`` as in :func:`estimate_memory`; ``contacts``: the structure's contacts at rest when already counted
    (:func:`contacts_of`, e.g. a :class:`~.study.StudyPlan`'s), else counted here."""
    sim = scenario.simulation
    systems = 1 if scenario.scale is None else 2
    total = 0.0
    if sim.engine in ("planar", "both"):
        total += systems * sim.samples * 2e-6 + (0.1 if sim.critical_charge else 0.0)
    if sim.engine in ("3d", "both"):
        nb = _bodies(structure)
        sides = getattr(structure, "sides", 4) if getattr(structure, "section", "") == "circular" else 4
        resolved = contact if contact is not None else _contact_or_none(scenario, structure)
        dt = _timestep(scenario, structure, contact if structure is None else resolved)
        # the steps after the load are longer (issue #28, step_factor_after_load); the load's own ms are neglected
        if resolved is None:
            steps = sim.duration_s / dt
        else:
            factor = step_factor_after_load(resolved, nb)
            steps = sim.duration_s / (dt * factor) + settle_steps(resolved, dt)
        runs = systems * (1 + sim.ensemble_members)
        nc = contacts_of(structure) if contacts is None else contacts
        units = nb + nc
        shape = max(1.0, sides / 4) ** (1 / 3)
        total += runs * steps * step_seconds(units) * shape + BODY_SECONDS * nb**BODY_EXPONENT
        checks, rest_steps, _ = rest_check_size(scenario, structure, resolved)
        total += checks * (rest_steps * step_seconds(units, at_rest=True) * shape + REST_CHECK_SECONDS)
    return total


def step_seconds(units: int, at_rest: bool = False) -> float:
    """One engine step of a structure of ``units`` bodies + contacts [s of one core] (module constants): under a
    blast :data:`STEP_BASE_SECONDS` + :data:`CONTACT_STEP_SECONDS` x u x max(1, u / :data:`CONTACT_STEP_UNITS`)^
    :data:`CONTACT_STEP_EXPONENT` (contacts changing state cost Newton iterations); at rest (``at_rest``, the check
    before the blast) without the growth factor (one iteration a step, :data:`REST_CHECK_SECONDS`)."""
    u = float(units)
    growth = 1.0 if at_rest else max(1.0, u / CONTACT_STEP_UNITS) ** CONTACT_STEP_EXPONENT
    return STEP_BASE_SECONDS + CONTACT_STEP_SECONDS * u * growth


def rest_check_size(scenario: Scenario, structure=None, contact=None) -> tuple:
    """The checks at rest a 3D run makes before its blast (:func:`blastscale.sim3d.rest.rest_check`):
    ``(checks, steps, rest_s)``: how many (0 under gravity alone or without a structure, where the run itself is
    the check; 1 for a prototype, and for a specimen that is its exact model, sharing the check; 2 for a specimen of
    another friction, ``scale.specimen_material``), the engine's steps of each (its rest time at the step after the
    load, the settling included) and the rest time [s] of the prototype. ``contact``: the study's resolved contact
    settings (None: derived)."""
    if structure is None or not scenario.blast.charge_kg or scenario.simulation.engine not in ("3d", "both"):
        return 0, 0.0, 0.0
    g = scenario.simulation.gravity_m_s2
    resolved = contact if contact is not None else _contact_or_none(scenario, structure)
    if resolved is None:
        return 0, 0.0, 0.0
    c = rest_contact(structure, resolved, g)
    T = rest_time(structure, g)
    steps = T / c.timestep + settle_steps(c)
    checks = 1 if scenario.scale is None or scenario.friction_ratio == 1.0 else 2
    return checks, steps, T


def compile_seconds(scenario: Scenario, structure=None) -> float:
    """The compiling a run will do first [s of one core]: :data:`COMPILE_SECONDS` times the share of
    :data:`KERNEL_MODULES` it loads (without the critical-charge search, not :data:`SEARCH_KERNEL_MODULES`) whose
    on-disk cache is cold (:func:`blastscale._jit.is_cached`), when the run uses the
    planar engine (a block: ``planar`` or ``both``); 0 when warm, or for a 3D-only run (MuJoCo compiles nothing).
    Said apart in the run's size line ("compiling kernels, first use only, ~N s")."""
    if scenario.simulation.engine not in ("planar", "both"):
        return 0.0
    if structure is not None and getattr(structure, "bodies", None) is not None and len(structure.bodies) != 1:
        return 0.0  # planar rocking applies to a single block: skipped here
    from .._jit import is_cached  # noqa: PLC0415 -- numba loads only for a run of the planar kernels (tests/system/test_run.py)

    folder = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "rocking")
    search = scenario.simulation.critical_charge
    used = [m for m in KERNEL_MODULES if search or m not in SEARCH_KERNEL_MODULES]
    cold = [m for m in used if not is_cached(os.path.join(folder, f"{m}.py"))]
    return COMPILE_SECONDS * len(cold) / len(KERNEL_MODULES)


def _contact_or_none(scenario: Scenario, structure):
    """The study's contact settings (:func:`~.engines.contact_settings`), or None where the engine's own check
    will report why there are none; the settling before the load lasts
    :func:`blastscale.sim3d.integrate.settle_steps` steps."""
    try:
        return contact_settings(scenario, structure)
    except BlastscaleInputError:
        return None


def contacts_of(structure) -> int:
    """The contacts of a structure at rest: its interfaces between bodies and with the ground, found by
    geometry (:func:`~blastscale.structures.as_assembly`); 1 without a structure. A study counts them once, in its
    check (:attr:`~.study.StudyPlan.contacts`), and hands the count to the estimates."""
    if structure is None:
        return 1
    try:
        return max(1, len(as_assembly(structure).interface_details))
    except (BlastscaleInputError, AttributeError, ValueError):
        return _bodies(structure)


@dataclass(frozen=True)
class RunSize:
    """What a run will cost, said before it starts (:func:`estimate_run`).

    Attributes
    ----------
    seconds : float
        Computing and writing time on one core [s].
    result_bytes : float
        Size of the result folder [bytes] (0 when nothing is written).
    memory_bytes : float
        Memory of the histories [bytes] (:func:`estimate_memory`).
    bodies, contacts : int
        Bodies simulated and contacts at rest (:func:`contacts_of`; 0 for a planar run).
    duration_s : float
        Simulated time of the prototype [s].
    samples : int
        Recorded states (3D) or samples (planar) per run.
    runs : int
        Simulations (prototype and specimen, ensemble members).
    compile_s : float
        Of ``seconds``, compiling the kernels on first use [s] (:func:`compile_seconds`; 0: the cache is warm).
    rest_s : float
        The prototype's time under gravity alone in the check at rest before the blast [s] (:func:`rest_check_size`;
        0: none).
    """

    seconds: float
    result_bytes: float
    memory_bytes: float
    bodies: int
    contacts: int
    duration_s: float
    samples: int
    runs: int
    compile_s: float = 0.0
    rest_s: float = 0.0

    def line(self) -> str:
        """One line: ``about 40 s and 12 MB: 210 bodies, 1719 contacts, 0.5 s simulated (and 2.2 s at rest before the
        blast), ...``; on first use
        ``about 56 s (compiling kernels, first use only, ~47 s) and 8.9 MB: ...``."""
        size = f" and {format_size(self.result_bytes)}" if self.result_bytes else ""
        if self.compile_s > 0:
            size = f" (compiling kernels, first use only, ~{format_duration(self.compile_s)}){size}"
        what = f"{self.bodies} bod{'y' if self.bodies == 1 else 'ies'}"
        if self.contacts:
            what += f", {self.contacts} contact{'' if self.contacts == 1 else 's'}"
        return (
            f"about {format_duration(self.seconds)}{size}: {what}, {self.duration_s:g} s simulated"
            + (f" (and {self.rest_s:.2g} s at rest before the blast)" if self.rest_s else "")
            + ", "
            f"{self.samples} samples x {self.runs} run{'' if self.runs == 1 else 's'}"
        )


def estimate_run(
    scenario: Scenario, structure=None, contact=None, writes: bool = True, contacts: int | None = None
) -> RunSize:
    """The size of a study's run, before it starts: the start-up and the computing time (:func:`estimate_seconds`)
    plus, when
    ``writes``, the time to write its result folder and that folder's size (histories: per recorded state, run
    and body :data:`STATE_BYTES_PER_BODY`, per monitoring point :data:`STATE_BYTES_PER_POINT`; the report
    :data:`REPORT_BYTES` plus :data:`REPORT_BYTES_PER_BODY` per body). Cost model and its check against
    measured runs: docs/performance.md. ``contacts`` as in :func:`estimate_seconds`."""
    sim = scenario.simulation
    systems = 1 if scenario.scale is None else 2
    if sim.engine in ("3d", "both"):
        if contacts is None:
            contacts = contacts_of(structure)
        if contact is None and structure is not None:  # resolved once for the time, memory and rest check below
            contact = _contact_or_none(scenario, structure)
    compiling = compile_seconds(scenario, structure)
    seconds = STARTUP_SECONDS + compiling + estimate_seconds(scenario, structure, contact, contacts)
    nb, nc, samples, runs, hist = _bodies(structure), 0, int(sim.samples), systems, 0.0
    if sim.engine in ("planar", "both"):
        hist += systems * sim.samples * 8 * 12
    if sim.engine in ("3d", "both"):
        nc = contacts
        every = record_every(scenario, structure) if structure is not None else (sim.record_every or 4)
        samples = int(sim.duration_s / _timestep(scenario, structure, contact) / every) + 1
        runs = systems * (1 + sim.ensemble_members)
        points = len(getattr(structure, "monitoring_points", ())) or nb
        hist += runs * samples * (STATE_BYTES_PER_BODY * nb + STATE_BYTES_PER_POINT * points)
    size = 0.0
    if writes:
        size = hist + REPORT_BYTES + REPORT_BYTES_PER_BODY * nb
        seconds += WRITE_SECONDS + WRITE_SECONDS_PER_BYTE * hist
    return RunSize(
        seconds=seconds,
        result_bytes=size,
        memory_bytes=estimate_memory(scenario, structure, contact),
        bodies=nb,
        contacts=nc,
        duration_s=float(sim.duration_s),
        samples=samples,
        runs=runs,
        compile_s=compiling,
        rest_s=rest_check_size(scenario, structure, contact)[2],
    )


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


def check_budget(
    name: str, value: float, unit: str, need_bytes: float, seconds: float, grows: int = 1, hint: str = ""
) -> None:
    """The shared rule: refuse a job needing more than :data:`MEMORY_FRACTION` of the available memory
    or more than :func:`max_seconds` of computing, in one line.

    Parameters
    ----------
    name : str
        The key or flag that sets the job's size (``simulation.duration_s``, ``--samples``).
    value : float
        Its value; ``unit`` its unit ("" for counts).
    need_bytes, seconds : float
        The job's estimated memory [bytes] and computing time [s].
    grows : {1, -1}
        Whether the need grows with ``value`` (a duration, a count) or with its inverse (a time step):
        the valid range given is then ``<=`` or ``>=`` the value that fits.
    hint : str
        Appended in parentheses (e.g. another way out).
    """
    mem_limit, time_limit = MEMORY_FRACTION * _available_memory(), max_seconds()
    if need_bytes <= mem_limit and seconds <= time_limit:
        return
    room = min(
        mem_limit / need_bytes if need_bytes > 0 else math.inf, time_limit / seconds if seconds > 0 else math.inf
    )
    fits = value * room if grows > 0 else value / room
    if float(fits).is_integer() or unit == "":
        fits = math.floor(fits) if grows > 0 else math.ceil(fits)
    why = []
    if need_bytes > mem_limit:
        why.append(
            f"about {need_bytes / 2**30:.3g} GiB of memory, more than {mem_limit / 2**30:.3g} GiB "
            f"({MEMORY_FRACTION:g} of the available memory)"
        )
    if seconds > time_limit:
        why.append(
            f"about {format_duration(seconds)} of computing, more than {format_duration(time_limit)} "
            "(BLASTSCALE_MAX_HOURS raises the limit)"
        )
    u = f" {unit}" if unit else ""
    raise BlastscaleInputError(
        f"{name} = {value:g}{u} is out of range: it would need {' and '.join(why)}; valid range is "
        f"{'<=' if grows > 0 else '>='} {fits:.3g}{u} here" + (f" ({hint})" if hint else "")
    )


def check_study_budget(scenario: Scenario, structure=None, contact=None, contacts: int | None = None) -> None:
    """Refuse, before any work, a study whose histories would not fit in memory or whose computing would
    outlast :func:`max_seconds` (:func:`check_budget`), naming ``simulation.timestep_s`` when a time step
    shorter than the derived one was given, else ``simulation.duration_s``. ``contact``: the study's
    resolved 3D contact settings, when known (not derived again); ``contacts`` as in :func:`estimate_seconds`."""
    sim = scenario.simulation
    need, secs = estimate_memory(scenario, structure, contact), estimate_seconds(scenario, structure, contact, contacts)
    if sim.engine == "planar" and sim.samples * 8 * 40 > MEMORY_FRACTION * _available_memory():
        check_budget("simulation.samples", sim.samples, "", need, secs)
    given_step = sim.timestep_s is not None and sim.engine in ("3d", "both")
    if given_step:
        given_step = structure is None or sim.timestep_s < _derived_timestep(scenario, structure)
    if given_step:
        check_budget("simulation.timestep_s", sim.timestep_s, "s", need, secs, grows=-1)
    hint = "or raise simulation.record_every" if sim.engine in ("3d", "both") else ""
    nb = _bodies(structure)
    if hint and nb > 1:  # the cost grows about linearly with the bodies (and their contacts): the largest that fits
        room = min(MEMORY_FRACTION * _available_memory() / max(need, 1.0), max_seconds() / max(secs, 1e-12))
        if room < 1.0 and math.floor(nb * room) >= 2:
            hint += f"; or a structure of <= {math.floor(nb * room)} bodies at this duration"
    check_budget("simulation.duration_s", sim.duration_s, "s", need, secs, hint=hint)


def check_memory(scenario: Scenario, structure=None) -> None:
    """:func:`check_study_budget` (the name from before the time estimate)."""
    check_study_budget(scenario, structure)
