"""Blast loads: empirical air-blast models, pulse shapes and per-point parameters (SI)."""

from .base import BlastModel, ExtrapolationWarning
from .face_pulses import FacePulses
from .faces import FaceLoads, face_loads, face_loads_unchecked
from .friedlander import friedlander_decay
from .incidence import DEFAULT_INCIDENCE, INCIDENCE_MODELS, oblique_combination
from .kingery_bulmash import KingeryBulmash
from .masi_fits import Masi2021
from .parameters import (
    BLAST_MODELS,
    BlastParameters,
    blast_parameters,
    get_blast_model,
    scaled_distance,
    valid_scaled_distance_range,
)
from .pulses import PULSE_SHAPES, Friedlander, Impulsive, Pulse, Tabulated, Triangular, check_pulse_shape

__all__ = [
    "BlastModel",
    "KingeryBulmash",
    "Masi2021",
    "FaceLoads",
    "FacePulses",
    "INCIDENCE_MODELS",
    "DEFAULT_INCIDENCE",
    "face_loads",
    "face_loads_unchecked",
    "oblique_combination",
    "ExtrapolationWarning",
    "BLAST_MODELS",
    "BlastParameters",
    "blast_parameters",
    "get_blast_model",
    "scaled_distance",
    "valid_scaled_distance_range",
    "PULSE_SHAPES",
    "check_pulse_shape",
    "Pulse",
    "Friedlander",
    "Triangular",
    "Impulsive",
    "Tabulated",
    "friedlander_decay",
]
