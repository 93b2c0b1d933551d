"""``blastscale show RESULT_DIR --animate FILE.gif|FILE.mp4|FILE.html``: the stored motion of a result folder
(:func:`blastscale.io.motion.read_motion`) animated, prototype and up-scaled specimen side by side in
prototype units (:mod:`blastscale.plots.motion`; the HTML view is :mod:`blastscale.report.motion`).

Every option is checked before any work; the file is written through the one output mechanism
(:func:`blastscale.io.output.write_file`: atomic, one line on a fault). GIF through Pillow; MP4 through
ffmpeg where it is installed (one line otherwise); HTML self-contained (the report's view, its script embedded).
Frames: ``fps`` per second of playback at ``speed`` x real (prototype) time: round(fps x duration / speed).
A GIF stores each frame's delay in hundredths of a second: 1/fps is rounded to 10 ms (exact for fps = 10, 20,
25, 50; browsers show delays under 20 ms as 100 ms, so a GIF plays right up to 50 fps).
"""

from __future__ import annotations

import io
import math
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from .._validate import BlastscaleInputError
from ..io.motion import read_motion
from ..io.output import write_file
from ..io.targets import Kind, check_target
from ..plots.motion import VIEWS, auto_magnification
from ..sim3d.replay import frame_count
from ..similitude.effects import charge_position
from ._output import one_line_warnings, print_json, print_written

__all__ = ["ANIMATION_SUFFIXES", "MAX_FRAMES", "check_animation", "write_animation"]

ANIMATION_SUFFIXES = (".gif", ".mp4", ".html")
#: The most frames an animation may have (a GIF's frames are held in memory, ~0.3 MB each at 800 x 360 pixels).
MAX_FRAMES = 1000
FPS_RANGE = (1.0, 120.0)
#: The displacement magnifications an animation may ask for (1: the motion as it is).
MAGNIFICATION_RANGE = (1.0, 1e4)


def check_animation(out: str, view: str, fps: float, speed: float, magnification: float | None = None) -> Path:
    """Check the animation's options before any work; returns the target path. One line per fault."""

    p = Path(out).expanduser()
    if p.suffix.lower() not in ANIMATION_SUFFIXES:
        raise BlastscaleInputError(
            f"animate = {out!r} has no animation extension: valid extensions are {', '.join(ANIMATION_SUFFIXES)}"
        )
    if view not in VIEWS:
        raise BlastscaleInputError(f"view = {view!r} is not known: valid views are {', '.join(VIEWS)}")
    if not (math.isfinite(fps) and FPS_RANGE[0] <= fps <= FPS_RANGE[1]):
        raise BlastscaleInputError(
            f"fps = {fps!r} is out of range: valid range is [{FPS_RANGE[0]:g}, {FPS_RANGE[1]:g}] frames per second"
        )
    if not (math.isfinite(speed) and 0.0 < speed <= 1e6):
        raise BlastscaleInputError(f"speed = {speed!r} is out of range: valid range is (0, 1e6] x real time")
    lo, hi = MAGNIFICATION_RANGE
    if magnification is not None and not (math.isfinite(magnification) and lo <= magnification <= hi):
        raise BlastscaleInputError(
            f"magnification = {magnification!r} is out of range: valid range is [{lo:g}, {hi:g}] (omit it for the "
            "automatic default)"
        )
    if p.suffix.lower() == ".mp4" and shutil.which("ffmpeg") is None:
        raise BlastscaleInputError(
            f"animate = {out!r}: no MP4 encoder is installed (ffmpeg not found): write .gif or .html, or install ffmpeg"
        )
    return check_target(p, Kind("an animation", lambda q: True, folder=False), name="animate")


#: Frames that share one GIF palette (each group's palette from :data:`PALETTE_SAMPLES` of its frames).
PALETTE_FRAMES = 40
PALETTE_SAMPLES = 4


def _paletted(frames):
    """Each RGB frame as a palette image ("P"), without dithering: every :data:`PALETTE_FRAMES` frames share a
    256-colour median-cut palette made from :data:`PALETTE_SAMPLES` of them (first to last), and each pixel is
    its nearest palette colour (``Dither.NONE``: one colour in, one colour out, no dither noise on the shaded
    drums). One median cut per group, not per frame: 0.14 s each for 800 x 360 pixels."""
    from PIL import Image

    def group(chunk):
        pick = [chunk[int(k)] for k in np.unique(np.linspace(0, len(chunk) - 1, PALETTE_SAMPLES).round())]
        palette = Image.fromarray(np.concatenate(pick, axis=0)).quantize(256, method=Image.Quantize.MEDIANCUT)
        return [Image.fromarray(f).quantize(palette=palette, dither=Image.Dither.NONE) for f in chunk]

    chunk = []
    for f in frames:
        chunk.append(f)
        if len(chunk) == PALETTE_FRAMES:
            yield from group(chunk)
            chunk = []
    if chunk:
        yield from group(chunk)


def _gif(frames, fps: float) -> bytes:
    images = list(_paletted(frames))
    buf = io.BytesIO()
    images[0].save(
        buf,
        format="GIF",
        save_all=True,
        append_images=images[1:],
        duration=round(1000.0 / fps),
        loop=0,
        optimize=False,
        disposal=1,
    )
    return buf.getvalue()


def _mp4(frames, fps: float) -> bytes:
    """H.264 through ffmpeg, the frames streamed to its input (never all in memory)."""

    with tempfile.TemporaryDirectory(prefix="blastscale-animate-") as tmp:
        out, proc = Path(tmp) / "a.mp4", None
        try:
            for f in frames:
                if proc is None:
                    h, w = f.shape[:2]
                    proc = subprocess.Popen(
                        [
                            "ffmpeg",
                            "-loglevel",
                            "error",
                            "-y",
                            "-f",
                            "rawvideo",
                            "-pix_fmt",
                            "rgb24",
                            "-s",
                            f"{w}x{h}",
                            "-r",
                            f"{fps:g}",
                            "-i",
                            "-",
                            "-vf",
                            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                            "-pix_fmt",
                            "yuv420p",
                            "-vcodec",
                            "libx264",
                            str(out),
                        ],
                        stdin=subprocess.PIPE,
                        stderr=subprocess.PIPE,
                    )
                proc.stdin.write(np.ascontiguousarray(f, dtype=np.uint8).tobytes())
            proc.stdin.close()
            err = proc.stderr.read().decode(errors="replace").strip()
            if proc.wait() != 0:
                raise BlastscaleInputError(f"animate: ffmpeg failed: {err[-200:]}")
        except BrokenPipeError:
            err = proc.stderr.read().decode(errors="replace").strip()
            proc.wait()
            raise BlastscaleInputError(f"animate: ffmpeg failed: {err[-200:]}") from None
        finally:
            if proc is not None and proc.poll() is None:
                proc.kill()
                proc.wait()
        return out.read_bytes()


def write_animation(
    source: str, out: str, view: str = "iso", fps: float = 20.0, speed: float = 1.0, magnification=None
) -> dict:
    """Animate the result folder ``source`` into ``out`` (.gif, .mp4 or .html); returns ``frames``,
    ``duration_s`` (simulated, prototype time), ``fps``, ``speed``, ``view``, ``magnification`` (the one drawn:
    ``magnification``, or the automatic default of :func:`blastscale.plots.motion.auto_magnification`)."""

    target = check_animation(out, view, fps, speed, magnification)
    motion, info = read_motion(source)
    n = frame_count(motion.duration, fps, speed)
    if n > MAX_FRAMES:
        raise BlastscaleInputError(
            f"fps = {fps:g} with speed = {speed:g} over {motion.duration:.3g} s gives {n} "
            f"frames: at most {MAX_FRAMES} (lower --fps or raise --speed)"
        )
    charge = None if info["standoff_m"] is None else charge_position(motion.front_x, info["standoff_m"])
    indices, _ = motion.frame_indices(fps, speed)
    kind = target.suffix.lower()
    if kind == ".html":
        from ..report.motion import motion_html, view_frames

        indices, _ = view_frames(motion, fps, speed)
    mag = auto_magnification(motion, indices) if magnification is None else float(magnification)
    if kind == ".html":
        data = motion_html(motion, indices, charge, info["title"], view, fps, mag)
    else:
        from ..plots.motion import render_frames

        frames = render_frames(motion, indices, view, charge, magnification=mag)
        data = _gif(frames, fps) if kind == ".gif" else _mp4(frames, fps)
    write_file(target, data, what="animate")
    return {
        "frames": int(len(indices)),
        "duration_s": motion.duration,
        "fps": fps,
        "speed": speed,
        "view": view,
        "magnification": mag,
    }


def show_animation(
    source: str, out: str, view: str, fps: float, speed: float, as_json: bool = False, magnification=None
) -> None:
    """``show RESULT_DIR --animate FILE``: write the animation, then one line (or the JSON of
    :func:`write_animation`)."""

    with one_line_warnings():
        info = write_animation(source, out, view, fps, speed, magnification)
    if as_json:
        print_json(info)
    print_written(
        out,
        f"{info['frames']} frames, {info['duration_s']:.3g} s at {info['fps']:g} fps x {info['speed']:g}, "
        f"motion x {info['magnification']:g}",
    )
