"""Gravity alone: run until the stability rule decides, up to a stated cap.

Under gravity alone the 3D summary says whether the structure **stands**, **settles**, **collapses**
or is still **moving** (:func:`blastscale.sim3d.results.stability_of`, docs/assemblies.md). "Moving"
only means that the run ended before the rule could decide: a clearly stable arch (R = 5 m, t/R =
0.16, 20 voussoirs, friction 0.8) is still settling onto its soft contacts after 2 s (final speed
2.1e-4 sqrt(g H), above the 1e-4 of "at rest"; 0.23 mm drift) and stands at 4 s (1.6e-5 sqrt(g H)).
A run that ends moving is therefore repeated with its duration doubled, from the start (the engine is
deterministic: the first part is the same run), until the rule decides or the duration reaches
:data:`STABILITY_EXTENSION_CAP` times the one asked for; only then is "moving" the answer. The
duration actually simulated is recorded (``duration_s``, beside ``duration_asked_s``).
"""

from __future__ import annotations

from typing import Callable

__all__ = ["STABILITY_EXTENSION_CAP", "until_decided", "extended_keys"]

#: The longest gravity-alone run, as a multiple of the duration asked for [-] (two doublings).
STABILITY_EXTENSION_CAP = 4.0


def until_decided(
    run: Callable[[float], object], duration: float, decide: bool = True, cap: float = STABILITY_EXTENSION_CAP
) -> tuple:
    """``run(duration)`` [s], repeated (when ``decide``: under gravity alone) with the duration doubled
    while its response's stability is "moving" and the doubled duration stays within ``cap`` x
    ``duration``.

    Parameters
    ----------
    run : callable
        ``run(T)`` returns an object with ``response.summary()`` (a system run of
        :mod:`blastscale.analysis.structure3d`), T the simulated time [s].
    duration : float
        The duration asked for [s].
    cap : float
        Largest duration as a multiple of ``duration`` [-].

    Returns
    -------
    (run result, duration simulated [s])
    """
    T = float(duration)
    r = run(T)
    while (
        decide
        and r.response.summary().get("stability") == "moving"
        and 2.0 * T <= cap * float(duration) * (1.0 + 1e-12)
    ):
        T *= 2.0
        r = run(T)
    return r, T


def extended_keys(settings: dict) -> dict:
    """The summary's record of an extended run: ``duration_simulated_s`` and ``duration_asked_s`` [s]
    (nothing when the run was not extended)."""
    if "duration_asked_s" not in settings:
        return {}
    return {
        "duration_simulated_s": float(settings["duration_s"]),
        "duration_asked_s": float(settings["duration_asked_s"]),
        "stability_extension_cap": STABILITY_EXTENSION_CAP,
    }
