"""Blast sources: a chemical explosive (:mod:`.explosives`) or a calibrated source, whose TNT equivalence is a power
law in its control variable (an exploding-wire bank: its stored energy [J]).

A calibrated source (:class:`CalibratedSource`) is what a lab measured of its own source
(:mod:`blastscale.fired.source_calibration` fits it from the lab's shots; ``blastscale source calibrate``): for
each basis b (``impulse``, ``pressure``), the TNT mass that gives the same impulse (or peak) under the blast model
it was calibrated with is a power law in the control value x,

.. math:: W_b(x) = W_{b,ref}\\,(x / x_{ref})^{k_b},\\qquad
          \\ln W_b = \\alpha_b + k_b\\,u,\\quad u = \\ln(x / x_{ref}),\\ \\alpha_b = \\ln W_{b,ref},

(:class:`PowerLaw`), fitted by least squares in log-log to the shots' effective charges, with the fit's
parameter covariance C_b of (alpha_b, k_b) and its degrees of freedom n - 2 (n shots). Its uncertainty at x:

.. math:: \\sigma_{fit}(x)^2 = g^T C_b\\, g,\\quad g = [1, u];\\qquad
          W_b(x)\\,\\exp\\left(\\pm \\sqrt{2 F_{0.95}(2, n-2)}\\,\\sigma_{fit}(x)\\right),

the 95 % Working-Hotelling band of the law: it holds the true law at every control value at once, with 95 %
confidence (Working & Hotelling 1929; Draper & Smith 1998, *Applied Regression Analysis*, 3rd ed.: the confidence band of a straight-line fit),
what "the equivalence within its interval at every energy" asks of it (a pointwise Student's t interval, narrower
by t_{0.975, n-2} / sqrt(2 F), covers each control value alone: 82 % of 40 synthetic campaigns held the truth at all
four energies with it);

its **repeatability** s_b is the shot-to-shot scatter, the standard deviation of ln W of one shot about the law
(the residuals' standard deviation, n - 2 degrees of freedom), so one shot at x has

.. math:: \\sigma_{shot}(x) = \\sqrt{s_b^2 + \\sigma_{fit}(x)^2}

(the log-normal standard deviation the planner's Monte Carlo draws the shot's charge with, in place of the
weighed charge's ``[lab] charge_tolerance``: the calibration's scatter holds the bank's charging precision).
The control value that gives a TNT mass W on basis b is ``x = x_ref (W / W_b,ref)^(1/k_b)`` (the planner plans in
it on the impulse basis, which the general scaling law matches; the pressure basis sets the safety distances as
a chemical charge's does). The source's limits (``control_min``, ``control_max``: the lab's bank, e.g. its
capacitor's rated voltage) bound the control values the planner may ask for; the calibration's own range of
control values and of scaled distances (its self-similarity) is kept to warn of an extrapolation.

No number of any real source is built in: the lab's calibration is the input (a synthetic set, marked as such,
ships as the example: ``blastscale source calibrate example_source``). The energy fraction
``eta = W q_TNT / x`` of an energy-controlled source is reported with q_TNT = 4.184 MJ/kg, the TNT energy
convention (1 ton of TNT = 4.184e9 J, NIST SP 811 (2008) App. B.8).

References
----------
.. [1] Morsel, A., Masi, F., Marche, E., Racineux, G., Kotronis, P. & Stefanou, I. (2024). miniBLAST, a
       laboratory source of blasts from exploding wires driven by a capacitor bank. arXiv:2408.01586.
.. [2] Measurement, self-similarity, and TNT equivalence of blasts from exploding wires. arXiv:2410.07221.
.. [3] Hopkinson-Cranz scaling: Baker, W. E. et al. (1983), *Explosion Hazards and Evaluation*, ch. 2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import BlastscaleInputError, check_positive_scalar

__all__ = [
    "SOURCE_BASES",
    "SOURCE_KINDS",
    "TNT_ENERGY_J_PER_KG",
    "PowerLaw",
    "CalibratedSource",
    "SourceShot",
    "source_from_dict",
    "source_to_dict",
]

#: The two bases of a TNT equivalence: the impulse (the specimen's charge) and the peak pressure (safety).
SOURCE_BASES = ("impulse", "pressure")
#: Source kind -> (its control variable, the control's unit). Only the exploding-wire bank has a kind of its own;
#: ``"other"`` names its control in the calibration set.
SOURCE_KINDS = {"exploding-wire": ("stored_energy", "J"), "other": (None, None)}
#: TNT's energy convention [J/kg]: 1 ton of TNT = 4.184e9 J (NIST SP 811 (2008) App. B.8).
TNT_ENERGY_J_PER_KG = 4.184e6


@dataclass(frozen=True)
class PowerLaw:
    """``W(x) = tnt_kg_at_reference (x / reference)^exponent`` [kg TNT] and its uncertainty (module docstring).

    Attributes
    ----------
    reference : float
        x_ref, the control value the law is referred to [control unit] (the calibration's geometric mean: the
        two parameters nearly uncorrelated).
    tnt_kg_at_reference : float
        W_ref [kg TNT].
    exponent : float
        k [-].
    covariance : tuple of tuple
        C, the 2 x 2 covariance of (ln W_ref, k) [-].
    dof : int
        The fit's degrees of freedom, n - 2 (n shots).
    repeatability : float
        s, one shot's standard deviation of ln W about the law [-].

    Examples
    --------
    >>> law = PowerLaw(1000.0, 1e-7, 1.2, ((4e-4, 0.0), (0.0, 9e-4)), 8, 0.03)
    >>> round(float(law.control_for(law.tnt_kg(1850.0))), 9), round(float(law.sigma_shot(1000.0)), 4)
    (1850.0, 0.0361)
    """

    reference: float
    tnt_kg_at_reference: float
    exponent: float
    covariance: tuple
    dof: int
    repeatability: float

    def _u(self, x):
        return np.log(np.asarray(x, dtype=float) / self.reference)

    def tnt_kg(self, x):
        """W(x) [kg TNT] at control values ``x``."""
        return self.tnt_kg_at_reference * np.exp(self.exponent * self._u(x))

    def control_for(self, tnt_kg):
        """The control value x with W(x) = ``tnt_kg`` [kg TNT]."""
        return self.reference * np.exp(
            np.log(np.asarray(tnt_kg, dtype=float) / self.tnt_kg_at_reference) / self.exponent
        )

    def sigma_fit(self, x):
        """The fit's standard deviation of ln W(x) [-]: ``sqrt(g^T C g)``, g = [1, ln(x / x_ref)]."""
        u = self._u(x)
        c = np.asarray(self.covariance, dtype=float)
        return np.sqrt(np.maximum(c[0, 0] + 2.0 * c[0, 1] * u + c[1, 1] * u * u, 0.0))

    def sigma_shot(self, x):
        """One shot's standard deviation of ln W at x [-]: the repeatability and the fit's, in quadrature."""
        return np.hypot(self.repeatability, self.sigma_fit(x))

    def quantile(self, level: float = 0.95) -> float:
        """The Working-Hotelling band's multiplier ``sqrt(2 F_level(2, dof))`` of the fit's sigma (module docstring)."""
        from scipy.stats import f as f_dist  # noqa: PLC0415 -- start-up: scipy.stats at module top is slow

        return math.sqrt(2.0 * float(f_dist.ppf(level, 2, max(self.dof, 1))))

    def interval(self, x, level: float = 0.95) -> tuple:
        """(low, high) [kg TNT]: the ``level`` confidence band of the law W(x), simultaneous over every control
        value (Working-Hotelling; not of one shot)."""
        w, h = self.tnt_kg(x), self.quantile(level) * self.sigma_fit(x)
        return w * np.exp(-h), w * np.exp(h)


@dataclass(frozen=True)
class SourceShot:
    """One shot of a calibrated source for a TNT charge (impulse basis) [SI]: what to set and what it gives.

    Attributes
    ----------
    source : CalibratedSource
    control_value : float
        The control value to set [control unit] (the bank's stored energy, J).
    tnt_equivalent_impulse_kg, tnt_equivalent_pressure_kg : float
        The law's TNT equivalents at that control value [kg] (impulse: the design's charge; pressure: safety).
    sigma_ln_impulse : float
        One shot's standard deviation of ln W by impulse (repeatability and fit) [-].
    ci95_impulse_kg : tuple
        The 95 % interval of the law by impulse at that control value [kg].
    violations : tuple
        ``(key, value, limit, sentence)`` for a control value outside the source's limits.
    warnings : tuple of str
        An extrapolation beyond the calibrated control values.
    """

    source: "CalibratedSource"
    control_value: float
    tnt_equivalent_impulse_kg: float
    tnt_equivalent_pressure_kg: float
    sigma_ln_impulse: float
    ci95_impulse_kg: tuple
    violations: tuple = ()
    warnings: tuple = ()
    #: No initiator: the calibration's effective charges hold everything the source's shot delivers.
    initiator_tnt_kg: float = 0.0
    initiator_fraction: float = 0.0

    @property
    def tnt_equivalent_safety_kg(self) -> float:
        """The shot's TNT equivalent on the stricter basis [kg]: the larger of the pressure and impulse
        equivalents (the safety distances, the licence limit ``tnt_max_kg``), as for a chemical charge."""
        return max(self.tnt_equivalent_pressure_kg, self.tnt_equivalent_impulse_kg)

    @property
    def setting(self) -> str:
        """The line the lab reads: ``"charge the bank to 1.85 kJ"`` (``"set stored_energy to ..."`` for another
        kind)."""
        return self.source.setting_text(self.control_value)

    def to_dict(self) -> dict:
        s = self.source
        return {
            "name": s.name,
            "kind": s.kind,
            "control": s.control,
            "control_unit": s.control_unit,
            "control_value": self.control_value,
            "control_min": s.control_min,
            "control_max": s.control_max,
            "setting": self.setting,
            "tnt_equivalent_impulse_kg": self.tnt_equivalent_impulse_kg,
            "tnt_equivalent_pressure_kg": self.tnt_equivalent_pressure_kg,
            "ci95_tnt_equivalent_impulse_kg": list(self.ci95_impulse_kg),
            "sigma_ln_impulse": self.sigma_ln_impulse,
            "repeatability_impulse": s.impulse.repeatability,
            "blast_model": s.blast_model,
            "burst": s.burst,
            "synthetic": s.synthetic,
            "warnings": list(self.warnings),
        }


@dataclass(frozen=True)
class CalibratedSource:
    """A blast source calibrated from its own shots (module docstring).

    Attributes
    ----------
    name, kind : str
        The source's name and its kind (:data:`SOURCE_KINDS`).
    control, control_unit : str
        The control variable's name (``"stored_energy"``) and unit (``"J"``).
    control_min, control_max : float
        The control values the lab may set [control unit].
    impulse, pressure : PowerLaw
        The TNT equivalence by impulse and by peak pressure.
    blast_model, burst : str
        The blast model and burst the effective charges were inverted with (the equivalence is relative to them).
    calibrated_control : tuple
        (least, largest) control value of the shots [control unit].
    calibrated_scaled_distance : tuple
        (least, largest) scaled distance of the records, impulse basis [m/kg^(1/3)].
    shots : int
    synthetic : bool
        True for a made-up calibration (the shipped example): never a real source.
    self_similar : bool
        False when the records did not collapse on scaled distance (``self_similarity`` says why).
    self_similarity : str
    details : dict
        What else the lab recorded (for an exploding wire: ``wire_material``, ``wire_length_m``, ...).
    """

    name: str
    kind: str
    control: str
    control_unit: str
    control_min: float
    control_max: float
    impulse: PowerLaw
    pressure: PowerLaw
    blast_model: str
    burst: str
    calibrated_control: tuple
    calibrated_scaled_distance: tuple
    shots: int
    synthetic: bool
    self_similar: bool = True
    self_similarity: str = ""
    details: dict = field(default_factory=dict)

    def law(self, basis: str) -> PowerLaw:
        if basis not in SOURCE_BASES:
            raise BlastscaleInputError(f"basis = {basis!r} is not known: valid values are {', '.join(SOURCE_BASES)}")
        return self.impulse if basis == "impulse" else self.pressure

    def energy_fraction(self, x, basis: str = "impulse"):
        """``W q_TNT / x`` [-]: the share of the stored energy that the TNT equivalent carries (an energy control)."""
        return self.law(basis).tnt_kg(x) * TNT_ENERGY_J_PER_KG / np.asarray(x, dtype=float)

    def setting_text(self, x: float) -> str:
        """``"charge the bank to 1.85 kJ"`` (exploding wire, J), else ``"set CONTROL to X UNIT"``."""
        if self.kind == "exploding-wire" and self.control_unit == "J":
            v = float(x)
            text = f"{v / 1e3:.3g} kJ" if v >= 1e3 else f"{v:.3g} J"
            return f"charge the bank to {text}"
        return f"set {self.control} to {float(x):.4g} {self.control_unit}"

    def shot(self, tnt_kg: float, blast_model: str | None = None, scaled_distance: float | None = None) -> SourceShot:
        """The shot that gives ``tnt_kg`` [kg TNT, impulse basis]: its control value, both equivalents, one shot's
        uncertainty, and the source's limits checked (:class:`SourceShot`). A warning when the design's
        ``blast_model`` (a name) is not the one the source was calibrated against, or its ``scaled_distance``
        [m/kg^(1/3)] lies outside the calibrated records' (self-similarity extrapolated)."""
        W = check_positive_scalar("charge (TNT, impulse basis)", tnt_kg, "kg")
        x = float(self.impulse.control_for(W))
        bad, notes = [], []
        u = self.control_unit
        if x < self.control_min:
            bad.append(
                (
                    "source control_min",
                    x,
                    self.control_min,
                    f"{self.control} {x:.4g} {u} < the source's control_min = {self.control_min:g} {u}",
                )
            )
        if x > self.control_max:
            bad.append(
                (
                    "source control_max",
                    x,
                    self.control_max,
                    f"{self.control} {x:.4g} {u} > the source's control_max = {self.control_max:g} {u}",
                )
            )
        lo, hi = self.calibrated_control
        if not lo <= x <= hi:
            notes.append(
                f"{self.control} {x:.4g} {u} is outside the calibrated {lo:.4g}-{hi:.4g} {u}: the power law is "
                "extrapolated"
            )
        if blast_model is not None and blast_model != self.blast_model:
            notes.append(
                f"the design's blast model {blast_model!r} is not the source's ({self.blast_model!r}, its "
                "equivalence is read against it): calibrate the source against the design's model"
            )
        zlo, zhi = self.calibrated_scaled_distance
        if scaled_distance is not None and not zlo <= scaled_distance <= zhi:
            notes.append(
                f"scaled distance {scaled_distance:.3g} m/kg^(1/3) is outside the calibrated {zlo:.3g}-{zhi:.3g}: "
                "the source's self-similarity is extrapolated"
            )
        if self.synthetic:
            notes.append(f"source {self.name!r} is a synthetic calibration: not a real source")
        ci = self.impulse.interval(x)
        return SourceShot(
            self,
            x,
            float(W),
            float(self.pressure.tnt_kg(x)),
            float(self.impulse.sigma_shot(x)),
            (float(ci[0]), float(ci[1])),
            tuple(bad),
            tuple(notes),
        )


def _law_to_dict(p: PowerLaw) -> dict:
    return {
        "reference": p.reference,
        "tnt_kg_at_reference": p.tnt_kg_at_reference,
        "exponent": p.exponent,
        "covariance": [list(map(float, row)) for row in p.covariance],
        "degrees_of_freedom": int(p.dof),
        "repeatability": p.repeatability,
    }


def source_to_dict(s: CalibratedSource) -> dict:
    """The source as the nested tables of a source file (docs/planning.md, "Sources"); units in ``[units]``."""
    return {
        "source": {
            "name": s.name,
            "kind": s.kind,
            "control": s.control,
            "control_unit": s.control_unit,
            "control_min": s.control_min,
            "control_max": s.control_max,
            "synthetic": s.synthetic,
            "blast_model": s.blast_model,
            "burst": s.burst,
            "shots": int(s.shots),
            "calibrated_control": list(s.calibrated_control),
            "calibrated_scaled_distance": list(s.calibrated_scaled_distance),
            "self_similar": s.self_similar,
            "self_similarity": s.self_similarity,
            "details": dict(s.details),
        },
        "equivalence": {"impulse": _law_to_dict(s.impulse), "pressure": _law_to_dict(s.pressure)},
        "units": {
            "reference": s.control_unit,
            "control_min": s.control_unit,
            "control_max": s.control_unit,
            "calibrated_control": s.control_unit,
            "tnt_kg_at_reference": "kg TNT",
            "exponent": "-",
            "covariance": "of (ln tnt_kg_at_reference, exponent), -",
            "repeatability": "one shot's standard deviation of ln W, -",
            "calibrated_scaled_distance": "m/kg^(1/3)",
        },
        "law": "W = tnt_kg_at_reference * (control / reference)^exponent, per basis (impulse, pressure)",
    }


def _need(table: dict, key: str, where: str):
    if key not in table:
        raise BlastscaleInputError(f"{where}.{key} is missing: a source file holds it (docs/planning.md, 'Sources')")
    return table[key]


def _number(table: dict, key: str, where: str, lo: float = -math.inf, positive: bool = False) -> float:
    v = _need(table, key, where)
    ok = (
        isinstance(v, (int, float))
        and not isinstance(v, bool)
        and math.isfinite(v)
        and (v > 0 if positive else v >= lo)
    )
    if not ok:
        rng = "> 0" if positive else f">= {lo:g}"
        raise BlastscaleInputError(f"{where}.{key} = {v!r} is out of range: valid range is {rng}")
    return float(v)


def _law_from_dict(t: dict, where: str) -> PowerLaw:
    if not isinstance(t, dict):
        raise BlastscaleInputError(f"{where} is missing: a source file has [equivalence.impulse] and [.pressure]")
    cov = _need(t, "covariance", where)
    try:
        c = np.asarray(cov, dtype=float)
    except (TypeError, ValueError):
        c = np.zeros(0)
    if c.shape != (2, 2) or not np.all(np.isfinite(c)) or c[0, 0] < 0 or c[1, 1] < 0:
        raise BlastscaleInputError(
            f"{where}.covariance = {cov!r} is not a covariance: give [[var(ln W_ref), cov], [cov, var(k)]]"
        )
    dof = _need(t, "degrees_of_freedom", where)
    if not isinstance(dof, int) or isinstance(dof, bool) or dof < 1:
        raise BlastscaleInputError(f"{where}.degrees_of_freedom = {dof!r} is out of range: valid range is >= 1")
    return PowerLaw(
        _number(t, "reference", where, positive=True),
        _number(t, "tnt_kg_at_reference", where, positive=True),
        _number(t, "exponent", where, positive=True),
        tuple(tuple(float(v) for v in row) for row in c),
        dof,
        _number(t, "repeatability", where, 0.0),
    )


def source_from_dict(data: dict, where: str = "source file") -> CalibratedSource:
    """The :class:`CalibratedSource` of a source file's tables (:func:`source_to_dict`); a missing or bad key is one
    :class:`~blastscale._validate.BlastscaleInputError` line naming it (prefixed ``where``), its value and range."""
    s = data.get("source") if isinstance(data, dict) else None
    if not isinstance(s, dict):
        raise BlastscaleInputError(f"{where}: no [source] table: give a file written by `blastscale source calibrate`")
    eq = data.get("equivalence") or {}
    w = f"{where}: source"
    kind = _need(s, "kind", w)
    if kind not in SOURCE_KINDS:
        raise BlastscaleInputError(f"{w}.kind = {kind!r} is not known: valid values are {', '.join(SOURCE_KINDS)}")
    lo, hi = _number(s, "control_min", w, positive=True), _number(s, "control_max", w, positive=True)
    if lo > hi:
        raise BlastscaleInputError(f"{w}.control_min = {lo:g} is above control_max = {hi:g}: give min <= max")
    cc = _need(s, "calibrated_control", w)
    cz = _need(s, "calibrated_scaled_distance", w)
    return CalibratedSource(
        name=str(_need(s, "name", w)),
        kind=kind,
        control=str(_need(s, "control", w)),
        control_unit=str(_need(s, "control_unit", w)),
        control_min=lo,
        control_max=hi,
        impulse=_law_from_dict(eq.get("impulse"), f"{where}: equivalence.impulse"),
        pressure=_law_from_dict(eq.get("pressure"), f"{where}: equivalence.pressure"),
        blast_model=str(_need(s, "blast_model", w)),
        burst=str(_need(s, "burst", w)),
        calibrated_control=(float(cc[0]), float(cc[1])),
        calibrated_scaled_distance=(float(cz[0]), float(cz[1])),
        shots=int(_need(s, "shots", w)),
        synthetic=bool(_need(s, "synthetic", w)),
        self_similar=bool(s.get("self_similar", True)),
        self_similarity=str(s.get("self_similarity", "")),
        details=dict(s.get("details") or {}),
    )
