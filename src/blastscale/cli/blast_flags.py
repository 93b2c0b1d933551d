"""The blast-effect flags shared by ``blast``, ``design``, ``rock`` and ``critical``: the burst type,
clearing of the loaded face and the negative phase (docs/blast_physics.md), and the load model they
make. Defaults: the paper's load (a surface burst, no clearing, no negative phase)."""

from __future__ import annotations

from typing import Optional

import typer

from .._validate import BlastscaleInputError, check_choice
from ..blast.load_model import LoadModel
from ..blast.parameters import BURSTS, DEFAULT_BURST

__all__ = [
    "BURST",
    "SPECIMEN_BURST",
    "SPECIMEN_CHARGE_HEIGHT",
    "CLEARING",
    "FACE_WIDTH",
    "FACE_HEIGHT",
    "NEGATIVE_PHASE",
    "NEGATIVE_PHASE_MODEL",
    "negative_phase_model_key",
    "load_model_from_flags",
    "check_burst_flag",
]

BURST = typer.Option(
    DEFAULT_BURST,
    "--burst",
    help=f"Burst type: {' or '.join(BURSTS)} (a charge on the ground, the "
    "paper's; or away from every surface: Kingery-Bulmash spherical fits, UFC 3-340-02 Fig. 2-7).",
)
SPECIMEN_BURST = typer.Option(
    None,
    "--specimen-burst",
    help="The specimen's burst when it differs from the prototype's (a lab charge on a stand: free-air).",
)
SPECIMEN_CHARGE_HEIGHT = typer.Option(
    None,
    "--specimen-charge-height",
    help="Height of the lab charge's centre above "
    "the floor \\[m]: warns when it is neither a surface nor a free-air burst.",
)
CLEARING = typer.Option(
    False,
    "--clearing",
    help="Clear the reflected pressure on the finite loaded face (UFC 3-340-02 "
    "Sec. 2-15.3.2); the face is the block's front, or --face-width and --face-height.",
)
FACE_WIDTH = typer.Option(None, "--face-width", help="Loaded face width W \\[m] (with --clearing).")
FACE_HEIGHT = typer.Option(None, "--face-height", help="Loaded face height H above the ground \\[m] (with --clearing).")
NEGATIVE_PHASE = typer.Option(
    False,
    "--negative-phase",
    help="Add the negative phase after the positive one (UFC 3-340-02 Fig. 2-16, Granström's cubic).",
)


NEGATIVE_PHASE_MODEL = typer.Option(
    None,
    "--negative-phase-model",
    help="The negative phase's model (with "
    "--negative-phase): ufc-fig2-16-cubic (default, the chart's suction) or "
    "friedlander-continued (the positive pulse continued past its zero crossing); "
    "both bounded by the positive impulse.",
)


def negative_phase_model_key(negative_phase: bool, model: Optional[str]) -> dict:
    """``{"negative_phase_model": model}`` for a scenario's ``[blast]`` (empty when not given); one line
    when given without ``--negative-phase``."""
    if model is None:
        return {}
    if not negative_phase:
        raise BlastscaleInputError(f"--negative-phase-model = {model!r} applies only with --negative-phase")
    return {"negative_phase_model": model}


def check_burst_flag(burst: Optional[str], name: str = "--burst") -> Optional[str]:
    """``burst`` when it is None or one of the burst types; one line naming the flag otherwise."""
    if burst is not None:
        check_choice(name, burst, BURSTS)
    return burst


#: The largest loaded face a flag gives [m] (the largest structure a scenario holds).
MAX_FACE_M = 1000.0


def load_model_from_flags(
    clearing: bool,
    face_width: Optional[float],
    face_height: Optional[float],
    negative_phase: bool,
    block=None,
    negative_phase_model: Optional[str] = None,
):
    """The :class:`~blastscale.blast.load_model.LoadModel` of the flags (None for the paper's load).

    The clearing face is ``--face-width`` x ``--face-height`` or, without them, the block's front
    (depth x height). Face dimensions without ``--clearing``, or clearing without a face, are one-line
    errors."""

    negative_phase_model_key(negative_phase, negative_phase_model)
    given = face_width is not None or face_height is not None
    if given and not clearing:
        raise BlastscaleInputError(
            f"face width = {face_width}, face height = {face_height}: --face-width and "
            "--face-height apply only with --clearing"
        )
    if clearing and not given:
        if block is None:
            raise BlastscaleInputError("clearing needs the loaded face: give --face-width and --face-height (m)")
        face_width, face_height = block.depth, block.height
    if clearing and (face_width is None or face_height is None):
        raise BlastscaleInputError(
            f"face width = {face_width}, face height = {face_height}: --clearing needs both "
            "--face-width and --face-height (m)"
        )
    for flag, v in (("--face-width", face_width), ("--face-height", face_height)):
        if v is not None and not (0.0 < v <= MAX_FACE_M):  # inf and 1e308 too: numpy would overflow on them
            raise BlastscaleInputError(
                f"{flag} = {v:g} m is out of range: valid range is (0, {MAX_FACE_M:g}] m "
                "(no clearing at all: leave out --clearing)"
            )
    if not (clearing or negative_phase):
        return None
    return LoadModel(
        clearing=clearing,
        face_width_m=face_width,
        face_height_m=face_height,
        negative_phase=negative_phase,
        **({} if negative_phase_model is None else {"negative_phase_model": negative_phase_model}),
    )
