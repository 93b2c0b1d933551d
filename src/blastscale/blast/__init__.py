"""Blast loads: empirical air-blast models, pulse shapes and per-point parameters (SI)."""

from .base import BlastModel, ExtrapolationWarning
from .parameters import BLAST_MODELS, BlastParameters, blast_parameters, get_blast_model, scaled_distance
from .pulses import Friedlander, Impulsive, Pulse, Tabulated, Triangular, friedlander_decay

__all__ = [
    "BlastModel",
    "ExtrapolationWarning",
    "BLAST_MODELS",
    "BlastParameters",
    "blast_parameters",
    "get_blast_model",
    "scaled_distance",
    "Pulse",
    "Friedlander",
    "Triangular",
    "Impulsive",
    "Tabulated",
    "friedlander_decay",
]
