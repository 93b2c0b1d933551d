"""Blast parameters for a charge W at stand-off R: the model registry and one result type.

``blast_parameters(W, R, blast_model=...)`` evaluates an empirical model at Z = R / W^(1/3)
and returns a :class:`BlastParameters` with every effective (not scaled) quantity in SI
and the Friedlander decay fitted to the reflected impulse (paper Eq. 2).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_positive
from .base import BlastModel
from .friedlander import friedlander_decay
from .kingery_bulmash import KingeryBulmash
from .kingery_bulmash_free_air import KingeryBulmashFreeAir
from .masi_fits import Masi2021
from .pulses import Friedlander, Impulsive, Pulse, Triangular, check_pulse_shape

__all__ = [
    "BLAST_MODELS",
    "get_blast_model",
    "blast_parameters",
    "blast_parameters_unchecked",
    "BlastParameters",
    "scaled_distance",
    "valid_scaled_distance_range",
    "BURSTS",
    "DEFAULT_BURST",
    "check_burst",
    "burst_of",
    "model_for_burst",
]


def _kingery_bulmash() -> BlastModel:

    return KingeryBulmash()


def _masi2021() -> BlastModel:

    return Masi2021()


def _kingery_bulmash_free_air() -> BlastModel:

    return KingeryBulmashFreeAir()


#: Names accepted by ``blast_model=`` everywhere; the first is the default.
BLAST_MODELS = {"kingery-bulmash": _kingery_bulmash, "masi2021": _masi2021}
DEFAULT_BLAST_MODEL = "kingery-bulmash"
#: Fits chosen by a burst type rather than by name (:func:`blastscale.blast.parameters.model_for_burst`);
#: their names are resolved too, so that a result's ``blast_model`` names the fit it came from.
BURST_VARIANTS = {"kingery-bulmash-free-air": _kingery_bulmash_free_air}
_CACHE: dict[str, BlastModel] = {}


def get_blast_model(blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL) -> BlastModel:
    """Return the blast model named ``blast_model`` (``"kingery-bulmash"`` or ``"masi2021"``),
    or ``blast_model`` itself when it already is a :class:`BlastModel` (user-supplied fits)."""
    if isinstance(blast_model, BlastModel):
        return blast_model
    if blast_model not in BURST_VARIANTS:  # resolved too, but not offered: a burst type chooses them
        check_choice("blast model", blast_model, BLAST_MODELS)
    if blast_model not in _CACHE:
        _CACHE[blast_model] = {**BLAST_MODELS, **BURST_VARIANTS}[blast_model]()
    return _CACHE[blast_model]


#: Burst types (:mod:`.bursts`), the first the default (the paper's).
BURSTS = ("surface", "free-air")
DEFAULT_BURST = "surface"


def check_burst(burst: str) -> str:
    """``burst`` itself when it is one of :data:`BURSTS`; one line otherwise."""
    return check_choice("burst", burst, BURSTS)


def burst_of(blast_model) -> str:
    """The burst type of a blast model (name or :class:`BlastModel`): its ``burst`` attribute."""
    return getattr(get_blast_model(blast_model), "burst", DEFAULT_BURST)


def model_for_burst(blast_model, burst: str = DEFAULT_BURST) -> BlastModel:
    """The fit of ``blast_model``'s family for ``burst``.

    ``"kingery-bulmash"`` gives the Swisdak (1994) surface fit or the Kingery-Bulmash (1984)
    spherical free-air fit; ``"masi2021"`` (the paper's Appendix A) has only a surface form, and a
    user's :class:`BlastModel` is taken as it is when its ``burst`` attribute matches.

    Raises
    ------
    BlastscaleInputError
        An unknown burst, or a model without a fit for it (one line naming both).
    """
    check_burst(burst)
    m = get_blast_model(blast_model)
    if getattr(m, "burst", DEFAULT_BURST) == burst:
        return m
    family = getattr(m, "family", m.name)
    if family == "kingery-bulmash":
        return get_blast_model("kingery-bulmash-free-air" if burst == "free-air" else "kingery-bulmash")
    raise BlastscaleInputError(
        f"burst = {burst!r} is not available for blast model {m.name!r} (its fits are for a "
        f"{getattr(m, 'burst', DEFAULT_BURST)} burst only): use blast model kingery-bulmash"
    )


#: Quantities :func:`blast_parameters` evaluates (the last three only where the model provides them).
_USED = (
    "reflected_pressure",
    "scaled_reflected_impulse",
    "scaled_arrival_time",
    "scaled_positive_duration",
    "incident_pressure",
    "scaled_incident_impulse",
    "shock_front_velocity",
)


def valid_scaled_distance_range(blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL) -> tuple[float, float]:
    """Range of Z [m/kg^(1/3)] over which :func:`blast_parameters` evaluates every fit it uses
    without extrapolating: the intersection of the quantities' ranges (kingery-bulmash [0.2, 40],
    masi2021 [0.2, 6.5], limited by the duration fits; Swisdak 1994 and paper Appendix A)."""
    m = get_blast_model(blast_model)
    ranges = [m.valid_range(q) for q in _USED if m.provides(q)]
    return max(r[0] for r in ranges), min(r[1] for r in ranges)


def scaled_distance(charge, standoff):
    """Hopkinson-Cranz scaled distance :math:`Z = R / W^{1/3}` [m/kg^(1/3)].

    ``charge`` W is the TNT-equivalent mass [kg], ``standoff`` R the distance [m]; both finite
    and > 0, scalars or arrays (broadcast). Reference: Baker et al. (1983), *Explosion Hazards
    and Evaluation*, ch. 2 (cube-root scaling); paper Sec. "Blast loading".
    """
    W = check_positive("charge", charge, "kg")
    R = check_positive("standoff", standoff, "m")
    z = R / np.cbrt(W)
    return z if z.ndim else float(z)


@dataclass(frozen=True)
class BlastParameters:
    """Blast parameters at one point (of a surface or a free-air burst), all SI.

    Every numeric field is a float for one charge and stand-off, or an array of their broadcast
    shape when :func:`blast_parameters` was given arrays.

    Attributes
    ----------
    blast_model : str
        Name of the empirical blast model used.
    charge_kg, standoff_m : float
        TNT-equivalent charge W [kg] and stand-off R [m].
    scaled_distance : float
        Z = R / W^(1/3) [m/kg^(1/3)].
    reflected_pressure : float
        Peak normally reflected overpressure P_ro [Pa].
    reflected_impulse : float
        Positive-phase reflected impulse i_ro [Pa*s].
    arrival_time : float
        Shock arrival time t_A [s].
    positive_duration : float
        Positive-phase duration t_o [s].
    incident_pressure, incident_impulse : float or None
        Side-on overpressure [Pa] and impulse [Pa*s]; None where the model has no fit.
    shock_front_velocity : float or None
        Shock-front velocity [m/s]; None where the model has no fit.
    friedlander_decay : float
        Decay coefficient d fitted so that the Friedlander pulse carries i_ro (Eq. 2).
    burst : str
        ``"surface"`` (hemispherical surface burst, the paper's) or ``"free-air"`` (spherical).
    """

    blast_model: str
    charge_kg: float
    standoff_m: float
    scaled_distance: float
    reflected_pressure: float
    reflected_impulse: float
    arrival_time: float
    positive_duration: float
    incident_pressure: float | None
    incident_impulse: float | None
    shock_front_velocity: float | None
    friedlander_decay: float
    burst: str = "surface"

    def pulse(self, shape: str = "friedlander") -> Pulse:
        """The reflected pulse on a face normal to the blast: ``"friedlander"`` (Eq. 1),
        ``"triangular"`` (Eq. 3, cut at 2 i/P) or ``"impulsive"`` (Dirac of area i_ro)."""
        if np.ndim(self.reflected_pressure) != 0:
            raise BlastscaleInputError(
                f"pulse of blast parameters with shape {np.shape(self.reflected_pressure)}: a pulse needs one "
                "charge and one stand-off (index the arrays first)"
            )
        check_pulse_shape(shape)
        if shape == "friedlander":
            return Friedlander(self.reflected_pressure, self.positive_duration, self.friedlander_decay)
        if shape == "triangular":
            return Triangular(self.reflected_pressure, self.reflected_impulse)
        return Impulsive(self.reflected_impulse)

    def select(self, index) -> "BlastParameters":
        """The parameters of some of the points of an array of them (``index``: a boolean mask or
        indices into the arrays)."""
        if np.ndim(self.charge_kg) == 0:
            raise BlastscaleInputError("select needs blast parameters of arrays (these are of one point)")
        return BlastParameters(
            **{k: (v if isinstance(v, str) or v is None else np.asarray(v)[index]) for k, v in asdict(self).items()}
        )

    def to_dict(self) -> dict:
        """Plain dict with unit-suffixed keys (as written by the CLI's ``--json``, which adds the
        deprecated alias ``model`` of ``blast_model``: :func:`blastscale.io.results.with_legacy_keys`)."""
        d = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in asdict(self).items()}
        return {
            "blast_model": d["blast_model"],
            "charge_kg": d["charge_kg"],
            "standoff_m": d["standoff_m"],
            "scaled_distance_m_per_kg13": d["scaled_distance"],
            "reflected_pressure_Pa": d["reflected_pressure"],
            "reflected_impulse_Pa_s": d["reflected_impulse"],
            "arrival_time_s": d["arrival_time"],
            "positive_duration_s": d["positive_duration"],
            "incident_pressure_Pa": d["incident_pressure"],
            "incident_impulse_Pa_s": d["incident_impulse"],
            "shock_front_velocity_m_s": d["shock_front_velocity"],
            "friedlander_decay": d["friedlander_decay"],
            "burst": d["burst"],
        }


def blast_parameters(
    charge,
    standoff,
    blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    *,
    extrapolate: bool = False,
    burst: str | None = None,
) -> BlastParameters:
    """Blast parameters of a burst of ``charge`` [kg TNT] at ``standoff`` [m] (a hemispherical surface
    burst unless ``burst="free-air"``).

    Evaluates the chosen empirical model at :math:`Z = R/W^{1/3}` and scales time and impulse
    by :math:`W^{1/3}` (Hopkinson-Cranz cube-root scaling, Baker et al. 1983):

    .. math:: P_{ro} = \\hat P(Z),\\quad i_{ro} = W^{1/3}\\,\\hat i(Z),\\quad
              t_A = W^{1/3}\\,\\hat t_A(Z),\\quad t_o = W^{1/3}\\,\\hat t_o(Z),

    and fits the Friedlander decay d to the reflected impulse (paper Eq. 2).

    Parameters
    ----------
    charge : float or array_like
        TNT-equivalent charge W [kg], > 0.
    standoff : float or array_like
        Stand-off distance R [m], > 0; broadcast against ``charge``.
    blast_model : str or BlastModel
        ``"kingery-bulmash"`` (Swisdak 1994, default) or ``"masi2021"`` (paper Appendix A).
    extrapolate : bool
        Evaluate the fits outside their validity ranges (with an ``ExtrapolationWarning``).
    burst : {"surface", "free-air"}, optional
        Burst type (:mod:`.bursts`): the fit of ``blast_model``'s family for it (kingery-bulmash:
        Swisdak's surface fit or Kingery-Bulmash's spherical free-air fit, UFC 3-340-02 Fig. 2-7).
        None: ``blast_model`` as it is (a surface burst for the named models).

    Returns
    -------
    BlastParameters
        Floats for scalar input, arrays of the broadcast shape otherwise (SI units, see the class).

    Raises
    ------
    BlastscaleInputError
        For a charge or stand-off that is not finite and > 0, or shapes that do not broadcast.
    OutOfRangeError
        When Z is outside a fit's validity range (unless ``extrapolate=True``); each quantity has
        its own range (``get_blast_model(blast_model).valid_range(quantity)``).
    """
    m = get_blast_model(blast_model) if burst is None else model_for_burst(blast_model, burst)
    W = check_positive("charge", charge, "kg")
    R = check_positive("standoff", standoff, "m")
    try:
        W, R = np.broadcast_arrays(W, R)
    except ValueError:
        raise BlastscaleInputError(
            f"charge and standoff have shapes {W.shape} and {R.shape}, which do not broadcast together"
        ) from None
    return blast_parameters_unchecked(W, R, m, extrapolate=extrapolate)


def blast_parameters_unchecked(W, R, blast_model: "str | BlastModel", *, extrapolate: bool = False) -> BlastParameters:
    """:func:`blast_parameters` of inputs the caller has already checked: ``W`` [kg] and ``R`` [m]
    finite, > 0 and of one shape (numpy arrays or floats). For the inner loops of the capacity
    searches, which check their inputs once and evaluate the fits many times; anything else should
    call :func:`blast_parameters`."""
    m = get_blast_model(blast_model)
    W, R = np.broadcast_arrays(np.asarray(W, dtype=float), np.asarray(R, dtype=float))
    scalar = W.ndim == 0

    def out(x):
        return float(x) if scalar else np.asarray(x, dtype=float)

    w13 = np.cbrt(W)
    z = R / w13
    P = m.reflected_pressure(z, extrapolate=extrapolate)
    i = m.scaled_reflected_impulse(z, extrapolate=extrapolate) * w13
    ta = m.scaled_arrival_time(z, extrapolate=extrapolate) * w13
    to = m.scaled_positive_duration(z, extrapolate=extrapolate) * w13

    def opt(q: str, scale=1.0):
        return out(getattr(m, q)(z, extrapolate=extrapolate) * scale) if m.provides(q) else None

    return BlastParameters(
        blast_model=m.name,
        charge_kg=out(W),
        standoff_m=out(R),
        scaled_distance=out(z),
        reflected_pressure=out(P),
        reflected_impulse=out(i),
        arrival_time=out(ta),
        positive_duration=out(to),
        incident_pressure=opt("incident_pressure"),
        incident_impulse=opt("scaled_incident_impulse", w13),
        shock_front_velocity=opt("shock_front_velocity"),
        friedlander_decay=out(friedlander_decay(P, to, i)),
        burst=getattr(m, "burst", "surface"),
    )
