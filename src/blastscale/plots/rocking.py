"""Plots of planar rocking: theta(t), theta_dot(t), phase portrait, prototype vs up-scaled
model (paper Figs. 6-9) and the pressure-impulse (P-I) overturning diagram.

Every function takes ``ax=`` (a new figure's axes when None) and returns it; matplotlib is
imported only when a plot is drawn. Inputs are :class:`~blastscale.rocking.RockingResult`,
:class:`~blastscale.analysis.rocking_similarity.RockingSimilarity` and
:class:`~blastscale.rocking.PIDiagram` objects (SI; angles shown in rad, times in s).
"""

from __future__ import annotations

import numpy as np

from .._validate import check_choice
from .sim3d import axes_or_new

__all__ = [
    "plot_angle",
    "plot_planar_angular_velocity",
    "plot_phase_portrait",
    "plot_similarity",
    "plot_pi_diagram",
    "rocking_figure",
]


def _runs(results, labels):
    if isinstance(results, dict):
        return list(results.items())
    if not isinstance(results, (list, tuple)):
        results = [results]
    labels = labels or [None] * len(results)
    return list(zip(labels, results))


_STYLES = ("-", "--", ":", "-.")
_LABELS = {
    "t": "time after arrival t [s]",
    "theta": "rocking angle theta [rad]",
    "theta_dot": "angular velocity theta_dot [rad/s]",
}


def _mark_events(ax, res, quantity):
    if quantity == "theta" and res.impact_times.size:
        ax.plot(res.impact_times, np.zeros(res.impact_times.size), "|", ms=8, color="0.4", label=None)
    if res.collapse_time is not None:
        ax.axvline(res.collapse_time, color="C3", lw=0.8, ls=":", label=None)


def _draw_runs(ax, results, labels, x: str, y: str):
    """Plot ``res.<y>`` against ``res.<x>`` ("t", "theta", "theta_dot") for every run, one
    line style per run; events are marked on time plots. Returns the runs."""
    ax = axes_or_new(ax)
    runs = _runs(results, labels)
    for k, (lab, res) in enumerate(runs):
        ax.plot(getattr(res, x), getattr(res, y), ls=_STYLES[k % len(_STYLES)], label=lab)
        if x == "t":
            _mark_events(ax, res, y)
    ax.set_xlabel(_LABELS[x])
    ax.set_ylabel(_LABELS[y])
    if any(lab for lab, _ in runs):
        ax.legend()
    return ax, runs


def plot_angle(results, ax=None, labels=None, alpha_line: bool = True):
    """Rocking angle theta(t) [rad] vs time [s] of one or several runs.

    ``results``: a RockingResult, a sequence of them or a dict label -> result. Impacts are
    ticked on the axis, the overturn time (if any) is a dotted line and, with ``alpha_line``,
    +-alpha (the tipping angles) are drawn dashed.
    """
    ax, runs = _draw_runs(ax, results, labels, "t", "theta")
    if alpha_line and runs and runs[0][1].system is not None:
        a = runs[0][1].system.alpha
        for v in (a, -a):
            ax.axhline(v, color="0.5", lw=0.6, ls="--")
    return ax


def plot_planar_angular_velocity(results, ax=None, labels=None):
    """Planar angular velocity theta_dot(t) [rad/s] vs time [s] of RockingResults (jumps at impacts:
    restitution); a 3D block run's is :func:`blastscale.plots.sim3d.plot_block_angular_velocity`."""
    return _draw_runs(ax, results, labels, "t", "theta_dot")[0]


def plot_phase_portrait(results, ax=None, labels=None):
    """Phase portrait theta_dot [rad/s] vs theta [rad] (paper Fig. 8, last panel)."""
    return _draw_runs(ax, results, labels, "theta", "theta_dot")[0]


def plot_similarity(sim, quantity: str = "theta", ax=None):
    """Prototype vs up-scaled model overlay (paper Figs. 8-9) from a RockingSimilarity.

    ``quantity``: ``"theta"`` (angle [rad] vs t [s]), ``"theta_dot"`` (angular velocity
    [rad/s] vs t [s]) or ``"phase"`` (theta_dot vs theta). Model values are already in
    prototype units (t / f.time, theta_dot / f.angular_velocity).
    """
    check_choice("quantity", quantity, ("theta", "theta_dot", "phase"))
    ax = axes_or_new(ax)
    lam = sim.design.scale
    lab_m = f"model lambda = 1/{1 / lam:.4g}, up-scaled" if lam < 1 else f"model lambda = {lam:.4g}, up-scaled"
    if quantity == "theta":
        ax.plot(sim.t, sim.theta_prototype, "-", label="prototype")
        ax.plot(sim.t, sim.theta_model, "--", label=lab_m)
        ax.set_xlabel("time after arrival t [s]")
        ax.set_ylabel("rocking angle theta [rad]")
    elif quantity == "theta_dot":
        ax.plot(sim.t, sim.theta_dot_prototype, "-", label="prototype")
        ax.plot(sim.t, sim.theta_dot_model, "--", label=lab_m)
        ax.set_xlabel("time after arrival t [s]")
        ax.set_ylabel("angular velocity theta_dot [rad/s]")
    else:  # "phase"
        ax.plot(sim.theta_prototype, sim.theta_dot_prototype, "-", label="prototype")
        ax.plot(sim.theta_model, sim.theta_dot_model, "--", label=lab_m)
        ax.set_xlabel("rocking angle theta [rad]")
        ax.set_ylabel("angular velocity theta_dot [rad/s]")
    title = f"max |delta theta| = {sim.max_abs_rotation_diff:.2e} rad"
    if sim.collapse_time_diff is not None:  # both overturn: the figures that measure similarity
        fall = "-" if sim.max_fall_phase_diff is None else f"{sim.max_fall_phase_diff:.2e}"
        title = (
            f"to tipping {sim.max_abs_rotation_diff_to_tipping:.2e} rad, fall (equal angle) {fall}\n"
            f"whole run {sim.max_abs_rotation_diff:.2e} rad (tipping shift {sim.collapse_time_diff * 1e3:+.2f} ms)"
        )
    ax.set_title(title, fontsize=9)
    ax.legend()
    return ax


def _log_ticks(axis, lo: float, hi: float) -> None:
    """Readable log-axis labels: no minor-tick labels (matplotlib labels them on short spans,
    where '3x10^4' and '4x10^4' collide), and majors at 1, 2, 5 x 10^k when the data span
    less than 1.5 decades (so that at least two ticks are labelled)."""
    from matplotlib.ticker import LogFormatterSciNotation, LogLocator, NullFormatter

    axis.set_minor_formatter(NullFormatter())
    if hi > lo > 0 and np.log10(hi / lo) < 1.5:
        axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(LogFormatterSciNotation(labelOnlyBase=False, minor_thresholds=(np.inf, np.inf)))


def plot_pi_diagram(pi, ax=None, label: str | None = None, asymptotes: bool = True):
    """Pressure-impulse overturning diagram: peak pressure [Pa] vs impulse [Pa s], log-log.

    Pulses above and to the right of the curve overturn the body. With ``asymptotes`` the
    impulsive (vertical) and quasi-static (horizontal) limits are drawn dashed. Minor ticks
    are not labelled (see ``_log_ticks``).
    """
    ax = axes_or_new(ax)
    ax.loglog(pi.critical_impulse, pi.peak_pressure, "-", label=label or f"critical ({pi.shape} pulse)")
    if asymptotes:
        ax.axvline(pi.impulse_asymptote, color="0.4", ls="--", lw=0.8, label="impulsive limit")
        ax.axhline(pi.pressure_asymptote, color="0.4", ls=":", lw=0.8, label="quasi-static limit (uplift)")
    i_all = np.append(pi.critical_impulse, pi.impulse_asymptote)
    p_all = np.append(pi.peak_pressure, pi.pressure_asymptote)
    _log_ticks(ax.xaxis, float(i_all.min()), float(i_all.max()))
    _log_ticks(ax.yaxis, float(p_all.min()), float(p_all.max()))
    ax.set_xlabel("reflected impulse i [Pa s]")
    ax.set_ylabel("peak reflected pressure P [Pa]")
    ax.legend()
    return ax


def rocking_figure(result, similarity=None):
    """A 3-panel figure (theta, theta_dot, phase portrait) of a run, or of a prototype vs
    up-scaled model comparison when ``similarity`` is given. Returns the figure."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(14, 4), layout="constrained")
    if similarity is None:
        plot_angle(result, ax=axes[0])
        plot_planar_angular_velocity(result, ax=axes[1])
        plot_phase_portrait(result, ax=axes[2])
    else:
        for ax, q in zip(axes, ("theta", "theta_dot", "phase")):
            plot_similarity(similarity, q, ax=ax)
    return fig
