"""Angle-of-incidence models: peak pressure and impulse on an oblique face, chosen by name.

A face whose outward normal makes the angle ``a`` with the direction to the charge
(a = 0: it looks straight at the charge, a = 90 deg: grazing, a > 90 deg: turned away) sees
a peak overpressure between the side-on value P_so (a >= 90 deg) and the normally reflected
value P_r (a = 0). Two models are available (:data:`INCIDENCE_MODELS`):

``"ufc"`` (the default)
    UFC 3-340-02 (2008) Fig. 2-193, the reflection coefficient :math:`C_{r\\alpha} = P_{r\\alpha}/P_{so}`
    versus angle and incident pressure, with the Mach-reflection peak (about 40-45 deg for
    P_so = 0.1-3 MPa, moving to 60-80 deg for weak shocks). The table
    (``data/ufc_3_340_02_fig2_193.csv``) is interpolated linearly in angle along each curve and
    linearly in log P_so between curves, with the angle axis aligned on each curve's peak so
    that the peak moves continuously instead of splitting into two half-peaks. To keep the
    limits of the blast model exactly (its own P_r at 0 deg, its own P_so at 90 deg), the
    chart gives the *reflected excess* only:

    .. math:: P(a) = P_{so} + (P_r - P_{so})\\,\\frac{C_{r\\alpha}(a) - 1}{C_{r\\alpha}(0) - 1}.

    The face impulse follows Fig. 2-194 (scaled reflected impulse versus angle and incident
    pressure, ``data/ufc_3_340_02_fig2_194.csv``) in the same way,

    .. math:: i(a) = i_s + (i_r - i_s)\\,\\frac{I(a) - I(90^\\circ)}{I(0) - I(90^\\circ)},

    so the impulse falls monotonically from i_r to i_s (the figure has no Mach peak in impulse).
    Outside the charts' pressure range (Fig. 2-193: 1.38 kPa-34.5 MPa, Fig. 2-194: 4.83 kPa-41.4 MPa)
    the end curve is used.
``"closed-form"``
    Randers-Pehrson & Bannister (1997), used by CONWEP-type loaders:
    :math:`Y = Y_r\\cos^2 a + Y_s(1 + \\cos a - 2\\cos^2 a)` for pressure and impulse alike.
    It has no Mach-reflection peak: near 40-45 deg it is 27-40 % below Fig. 2-193.

Both models give the side-on values for faces turned away (cos a <= 0), never more.

References
----------
.. [1] UFC 3-340-02 (2008), *Structures to Resist the Effects of Accidental Explosions*,
       Figs. 2-193 and 2-194. Numbers from the public digitisation in the repository
       Nyobir/ufc-blast-calculator (MIT licence), resampled (see the CSV headers).
.. [2] Randers-Pehrson, G. & Bannister, K. A. (1997). *Airblast loading model for DYNA2D and
       DYNA3D*. ARL-TR-1310, Army Research Laboratory.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from importlib import resources

import numpy as np

from .._validate import check_choice, check_range

__all__ = [
    "INCIDENCE_MODELS",
    "DEFAULT_INCIDENCE",
    "check_incidence",
    "oblique_combination",
    "oblique_values",
    "ufc_reflection_coefficient",
    "ufc_impulse_fraction",
    "UFCChart",
    "ufc_chart",
    "ufc_pressure_range",
]

#: Names accepted by ``incidence=`` everywhere; the first is the default.
INCIDENCE_MODELS = ("ufc", "closed-form")
DEFAULT_INCIDENCE = INCIDENCE_MODELS[0]

_HALF_PI = 0.5 * np.pi


def check_incidence(name: str) -> str:
    """Return ``name`` if it is a known incidence model, else raise a one-line error."""
    return check_choice("incidence model", name, INCIDENCE_MODELS)


def oblique_combination(reflected, incident, cos_incidence):
    """Randers-Pehrson & Bannister (1997) blend of reflected and incident values [same unit].

    .. math::

        Y(a) = Y_r \\cos^2 a + Y_{s}\\,(1 + \\cos a - 2\\cos^2 a)\\quad(\\cos a > 0),
        \\qquad Y(a) = Y_s \\quad(\\cos a \\le 0).

    Parameters
    ----------
    reflected : array_like
        Normally reflected value Y_r (pressure [Pa] or impulse [Pa*s]).
    incident : array_like
        Incident (side-on) value Y_s, same unit.
    cos_incidence : array_like
        Cosine of the angle of incidence [-], in [-1, 1].

    Returns
    -------
    ndarray or float
        Y on the face, same unit; broadcast shape of the inputs.
    """
    yr = check_range("reflected value", reflected, 0.0)
    ys = check_range("incident value", incident, 0.0)
    # [-1, 1] up to round-off of a normalised dot product
    c = check_range("cosine of the angle of incidence", cos_incidence, -1.0 - 1e-9, 1.0 + 1e-9)
    out = _blend(yr, ys, c)
    return out if out.ndim else float(out)


def _blend(yr, ys, c):
    cp = np.clip(c, 0.0, 1.0)  # cos a <= 0 -> incident only (the formula gives Y_s at c = 0)
    return yr * cp**2 + ys * (1.0 + cp - 2.0 * cp**2)


@dataclass(frozen=True)
class UFCChart:
    """One UFC chart (a family of curves Y(angle) indexed by incident pressure), resampled on a grid.

    Each curve is mapped to a normalised angle ``u`` in [0, 2]: u = a / a_p on [0, a_p] and
    u = 1 + (a - a_p) / (90 deg - a_p) beyond, where ``a_p`` is the curve's Mach-reflection peak
    angle (its largest value beyond 38 deg; the digitised peaks lie at 40-80 deg); for a chart
    without a peak, a_p = 90 deg and u = a / 90 deg on [0, 1]. The curves
    are resampled linearly on a regular u grid once, so that evaluation is a vectorised
    bilinear interpolation in (log P_so, u) with the peak angle interpolated in log P_so.

    Attributes
    ----------
    log_pressure : ndarray, shape (ncurve,)
        ln of the curves' incident pressures [ln Pa], increasing.
    peak_angle : ndarray, shape (ncurve,)
        Peak angle of each curve [rad] (pi/2 for a chart without a peak).
    values : ndarray, shape (ncurve, nu)
        Curve values on the u grid.
    u_max : float
        2 for a peaked chart, 1 otherwise.
    """

    log_pressure: np.ndarray
    peak_angle: np.ndarray
    values: np.ndarray
    u_max: float

    @classmethod
    def from_points(cls, pressure, angle_deg, value, *, peaked: bool, n: int = 1024) -> "UFCChart":
        """Build the chart from long-format points (P_so [Pa], angle [deg], value), curve by curve."""
        pressures = np.unique(pressure)
        peaks, rows = [], []
        half = n // 2
        for p in pressures:
            sel = pressure == p
            a = np.radians(angle_deg[sel])
            v = value[sel]
            # the Mach-reflection peak: the largest value beyond 38 deg (at high pressure it is a local
            # maximum below the normal value C(0); every digitised peak lies at 40-81 deg)
            beyond = a >= np.radians(38.0)
            ap = a[beyond][np.argmax(v[beyond])] if peaked else _HALF_PI
            if peaked:
                # u grid: n/2 + 1 points on [0, a_p] and n/2 on (a_p, pi/2]; the peak is a node
                au = np.concatenate([np.linspace(0.0, ap, half + 1), np.linspace(ap, _HALF_PI, half + 1)[1:]])
            else:
                au = np.linspace(0.0, _HALF_PI, n + 1)
            peaks.append(ap)
            rows.append(np.interp(au, a, v))
        return cls(np.log(pressures), np.array(peaks), np.array(rows), 2.0 if peaked else 1.0)

    def __call__(self, angle, incident_pressure):
        """Chart value at angle [rad] in [0, pi/2] and incident pressure [Pa] (broadcast arrays)."""
        a = np.clip(np.asarray(angle, dtype=float), 0.0, _HALF_PI)
        x = np.clip(np.log(np.asarray(incident_pressure, dtype=float)), self.log_pressure[0], self.log_pressure[-1])
        a, x = np.broadcast_arrays(a, x)
        k = np.clip(np.searchsorted(self.log_pressure, x, side="right") - 1, 0, self.log_pressure.size - 2)
        w = (x - self.log_pressure[k]) / (self.log_pressure[k + 1] - self.log_pressure[k])
        ap = (1.0 - w) * self.peak_angle[k] + w * self.peak_angle[k + 1]
        if self.u_max == 2.0:
            u = np.where(a <= ap, a / ap, 1.0 + (a - ap) / np.maximum(_HALF_PI - ap, 1e-12))
        else:
            u = a / _HALF_PI
        nu = self.values.shape[1] - 1
        s = np.clip(u / self.u_max * nu, 0.0, nu)
        j = np.minimum(s.astype(int), nu - 1)
        f = s - j
        lo = self.values[k, j] * (1.0 - f) + self.values[k, j + 1] * f
        hi = self.values[k + 1, j] * (1.0 - f) + self.values[k + 1, j + 1] * f
        return (1.0 - w) * lo + w * hi


@functools.cache
def ufc_chart(figure: str) -> UFCChart:
    """The resampled UFC chart ``"2-193"`` (C_r_alpha, peaked) or ``"2-194"`` (scaled i_r_alpha)."""
    files = {"2-193": ("ufc_3_340_02_fig2_193.csv", True), "2-194": ("ufc_3_340_02_fig2_194.csv", False)}
    name, peaked = files[figure]
    path = resources.files("blastscale.blast").joinpath("data", name)
    with path.open("r", encoding="utf-8") as fh:
        lines = [ln for ln in fh if ln.strip() and not ln.startswith("#")]
    data = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])  # lines[0]: column names
    return UFCChart.from_points(data[:, 0], data[:, 1], data[:, 2], peaked=peaked)


def ufc_pressure_range(figure: str) -> tuple[float, float]:
    """The incident pressures [Pa] of the first and last curves of the UFC chart ``"2-193"`` or ``"2-194"``
    (1.38 kPa-34.5 MPa and 4.83 kPa-41.4 MPa): what the chart covers (outside it, the end curve is read)."""
    lp = ufc_chart(figure).log_pressure
    return float(np.exp(lp[0])), float(np.exp(lp[-1]))


def ufc_reflection_coefficient(angle, incident_pressure):
    """Reflection coefficient C_r_alpha = P_r_alpha / P_so [-] of UFC 3-340-02 Fig. 2-193.

    Parameters
    ----------
    angle : array_like
        Angle of incidence [rad], 0 = normal; values beyond pi/2 are treated as pi/2 (C = 1).
    incident_pressure : array_like
        Side-on peak overpressure P_so [Pa], > 0 (clamped to the chart's 1.38 kPa-34.5 MPa).

    Returns
    -------
    ndarray or float
        C_r_alpha [-], >= 1, with the Mach-reflection peak.
    """
    out = ufc_chart("2-193")(angle, incident_pressure)
    return out if out.ndim else float(out)


def ufc_impulse_fraction(angle, incident_pressure):
    """Fraction g(a) = (I(a) - I(90)) / (I(0) - I(90)) [-] of UFC 3-340-02 Fig. 2-194, in [0, 1].

    ``I`` is the chart's scaled reflected impulse at the incident pressure [Pa]; the face
    impulse of the ``"ufc"`` model is i_s + (i_r - i_s) g(a) (module docstring).
    """
    ch = ufc_chart("2-194")
    i0 = ch(0.0, incident_pressure)
    i90 = ch(_HALF_PI, incident_pressure)
    out = (ch(angle, incident_pressure) - i90) / (i0 - i90)
    return out if np.ndim(out) else float(out)


def oblique_values(
    model: str, cos_incidence, reflected_pressure, incident_pressure, reflected_impulse, incident_impulse
):
    """Peak pressure [Pa] and impulse [Pa*s] on faces at the given incidence, for model ``model``.

    Parameters
    ----------
    model : str
        ``"ufc"`` or ``"closed-form"`` (:data:`INCIDENCE_MODELS`).
    cos_incidence : ndarray
        Cosine of the angle of incidence [-] (normal vs direction to the charge), in [-1, 1].
    reflected_pressure, incident_pressure : ndarray
        Normally reflected P_r and side-on P_so peak overpressures at the face [Pa].
    reflected_impulse, incident_impulse : ndarray
        Normally reflected i_r and side-on i_s impulses at the face [Pa*s].

    Returns
    -------
    (ndarray, ndarray)
        Peak pressure [Pa] and positive-phase impulse [Pa*s] on each face: P_r and i_r at
        a = 0, P_so and i_s for a >= 90 deg.
    """
    check_incidence(model)
    c = np.clip(np.asarray(cos_incidence, dtype=float), -1.0, 1.0)
    Pr, Ps = np.asarray(reflected_pressure, dtype=float), np.asarray(incident_pressure, dtype=float)
    ir, i_s = np.asarray(reflected_impulse, dtype=float), np.asarray(incident_impulse, dtype=float)
    if model == "closed-form":
        return _blend(Pr, Ps, c), _blend(ir, i_s, c)
    a = np.arccos(np.clip(c, 0.0, 1.0))  # turned away -> pi/2 -> side-on
    ch = ufc_chart("2-193")
    cr = ch(a, Ps)
    cr0 = ch(np.zeros_like(a), Ps)
    pressure = Ps + (Pr - Ps) * (cr - 1.0) / (cr0 - 1.0)
    g = ufc_impulse_fraction(a, Ps)
    return pressure, i_s + (ir - i_s) * np.asarray(g)
