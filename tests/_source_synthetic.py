"""A synthetic exploding-wire calibration campaign with a known power law, made without blastscale's code.

Nothing here imports blastscale: the blast of a TNT mass W at R is the paper's Appendix A (Masi, Stefanou &
Maffi-Berthier; hemispherical surface burst), typed here from the paper's text: the normally reflected peak
P_ro(Z) [MPa], the scaled reflected impulse i_rw(Z) [MPa ms/kg^(1/3)] and the scaled arrival time t_Aw(Z)
[ms/kg^(1/3)], Z = R / W^(1/3). The trace is the Friedlander form ``P (1 - tau/t_o) exp(-d tau/t_o)`` (paper Eq. 1)
with a fixed decay d = :data:`DECAY` and the positive duration that gives the fit's impulse exactly,
``t_o = i / (P (e^-d + d - 1)/d^2)`` (paper Eq. 2; the paper's duration fit holds only to Z = 6.5, and the
records' impulse and peak, not their duration, carry the equivalence), with a gauge's noise, offset, ringing and
pre-trigger. The truth (:data:`TRUTH`): W by impulse and by peak as power laws of the stored energy; each shot's
yield scattered by ``exp(scatter z)`` (one draw per shot, both bases), z ~ N(0, 1), seed given.
The shipped example (src/blastscale/fired/examples/wires) was written by :func:`write_campaign` with seed 0.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

#: The known laws: basis -> (W at 1 kJ [kg TNT], exponent [-]) in W = W_1kJ (E / 1 kJ)^k. Synthetic.
TRUTH = {"impulse": (80e-9, 1.15), "pressure": (60e-9, 1.30)}
#: The campaign: 4 stored energies [J] x 3 distances [m], one reflected gauge per shot.
ENERGIES_J = (500.0, 1000.0, 2000.0, 4000.0)
DISTANCES_M = (0.02, 0.035, 0.05)
#: The traces' Friedlander decay [-].
DECAY = 1.5


def truth_tnt_kg(energy_J, basis: str = "impulse"):
    """The known law W(E) [kg TNT]."""
    w1, k = TRUTH[basis]
    return w1 * (np.asarray(energy_J, dtype=float) / 1000.0) ** k


def reflected_pressure_Pa(z):
    """Appendix A: P_ro(Z) [MPa] -> Pa."""
    L = np.log(z)
    s = np.sin(L)
    return (
        (1 + 1 / (2 * np.exp(10 * z))) * np.exp(2.0304 - 1.8036 * L - 0.09293 * L**2 - 0.8779 * s - 0.3603 * s**2) * 1e6
    )


def reflected_impulse_Pa_s(w, r):
    """Appendix A: i_r = W^(1/3) i_rw(Z), i_rw [MPa ms/kg^(1/3)] -> Pa s."""
    z = r / np.cbrt(w)
    L = np.log(z)
    return np.cbrt(w) * np.exp(-0.110157 - 1.40609 * L + 0.0847358 * L**2) * 1e3


def arrival_s(w, r):
    """Appendix A: t_A = W^(1/3) t_Aw(Z), t_Aw [ms/kg^(1/3)] (Z >= 0.18) -> s."""
    L = np.log(r / np.cbrt(w))
    return np.cbrt(w) * np.exp(-0.6847 + 1.4288 * L + 0.0290 * L**2 + 0.4108 * np.sin(L)) * 1e-3


def trace(
    seed: int,
    w_impulse,
    w_pressure,
    r,
    *,
    rate_hz=20e6,
    noise=0.02,
    offset=0.05,
    ringing=0.05,
    ring_hz=2e6,
    pre_s=20e-6,
    record_to=8.0,
):
    """(t [s], p [Pa], peak [Pa], impulse [Pa s]) of a reflected gauge at ``r`` [m] from a blast whose impulse is
    that of ``w_impulse`` and whose peak that of ``w_pressure`` [kg TNT]: sampled at ``rate_hz``, white noise
    ``noise`` x P, an offset ``offset`` x P, ringing of ``ringing`` x P at ``ring_hz`` decaying over 1 us after the
    front (a gauge whose resonance lies well above the pulse's 1/t_o: 5-25 us here), ``pre_s`` of pre-trigger, the
    record running ``record_to`` positive durations past the arrival."""
    P = float(reflected_pressure_Pa(r / np.cbrt(w_pressure)))
    i = float(reflected_impulse_Pa_s(w_impulse, r))
    to = i / (P * (math.exp(-DECAY) + DECAY - 1.0) / DECAY**2)
    ta = float(arrival_s(w_impulse, r))
    rng = np.random.default_rng(seed)
    t = np.arange(-pre_s, ta + record_to * to, 1.0 / rate_hz)
    tau = t - ta
    x = np.clip(tau, 0.0, None) / to
    p = np.where(tau >= 0, P * (1 - x) * np.exp(-DECAY * x), 0.0)
    ring = np.where(
        tau >= 0, ringing * P * np.sin(2 * np.pi * ring_hz * tau) * np.exp(-np.clip(tau, 0, None) / 1e-6), 0
    )
    return t, p + ring + offset * P + noise * P * rng.standard_normal(t.size), P, i


def campaign(seed: int = 0, *, scatter: float = 0.03, bias: dict | None = None, **kw) -> list[dict]:
    """The shots of :data:`ENERGIES_J` x :data:`DISTANCES_M`: each a dict with ``energy_J``, ``distance_m``, the
    trace ``t``, ``p`` and the shot's true ``w_impulse``, ``w_pressure`` [kg TNT] (the law's times its yield).
    ``bias``: distance [m] -> factor on that distance's recorded peak and impulse (a gauge off: not self-similar)."""
    rng = np.random.default_rng(seed)
    shots = []
    for e in ENERGIES_J:
        for r in DISTANCES_M:
            eps = math.exp(scatter * rng.standard_normal())
            wi, wp = truth_tnt_kg(e) * eps, truth_tnt_kg(e, "pressure") * eps
            t, p, P, i = trace(int(rng.integers(2**31)), wi, wp, r, **kw)
            p = p * (bias or {}).get(r, 1.0)
            shots.append({"energy_J": e, "distance_m": r, "t": t, "p": p, "w_impulse": wi, "w_pressure": wp})
    return shots


def write_campaign(folder, shots: list[dict], *, header: str = "", digits: int = 6) -> Path:
    """The calibration set ``shots.toml`` and one CSV per shot (``time_us``, ``g1_kPa``, ``digits`` significant
    digits) in ``folder``."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    lines = [header] if header else []
    lines += [
        "[source]",
        'name = "synthetic exploding-wire bank (not a real source)"',
        'kind = "exploding-wire"',
        "synthetic = true",
        'blast_model = "masi2021"',
        'burst = "surface"',
        "control_min = 250.0",
        "control_max = 5000.0",
        "",
        "[source.wire]",
        'material = "aluminium"',
        "length_m = 0.04",
        "diameter_m = 0.0002",
    ]
    for k, s in enumerate(shots, 1):
        name = f"s{k:02d}.csv"
        np.savetxt(
            folder / name,
            np.column_stack([s["t"] * 1e6, s["p"] / 1e3]),
            delimiter=",",
            header="time_us,g1_kPa",
            comments="",
            fmt=f"%.{digits}g",
        )
        lines += [
            "",
            "[[shot]]",
            f'name = "s{k:02d}"',
            f"control = {s['energy_J']!r}",
            f'gauges = "{name}"',
            "[shot.gauge.g1]",
            f"distance_m = {s['distance_m']!r}",
            'kind = "reflected"',
        ]
    path = folder / "shots.toml"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path
