"""``blastscale show RESULT_DIR --animate FILE.gif|FILE.mp4|FILE.html``: the stored motion of a result folder
(:func:`blastscale.io.motion.read_motion`) animated, prototype and up-scaled specimen side by side in
prototype units (:mod:`blastscale.plots.motion`; the HTML view is :mod:`blastscale.report.motion`).

Every option is checked before any work; the file is written through the one output mechanism
(:func:`blastscale.io.output.write_file`: atomic, one line on a fault). GIF through Pillow; MP4 through
ffmpeg where it is installed (one line otherwise); HTML self-contained (plotly's JavaScript embedded).
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
from ..plots.motion import VIEWS
from ..sim3d.replay import frame_count
from ..similitude.effects import charge_position
from ._output import one_line_warnings, print_json, print_written

__all__ = ["ANIMATION_SUFFIXES", "MAX_FRAMES", "check_animation", "write_animation"]

ANIMATION_SUFFIXES = (".gif", ".mp4", ".html")
#: The most frames an animation may have (a GIF's frames are held in memory, ~0.3 MB each at 800 x 360 pixels).
MAX_FRAMES = 1000
FPS_RANGE = (1.0, 120.0)


def check_animation(out: str, view: str, fps: float, speed: float) -> Path:
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
    if p.suffix.lower() == ".mp4" and shutil.which("ffmpeg") is None:
        raise BlastscaleInputError(
            f"animate = {out!r}: no MP4 encoder is installed (ffmpeg not found): write .gif or .html, or install ffmpeg"
        )
    return check_target(p, Kind("an animation", lambda q: True, folder=False), name="animate")


def _gif(frames, fps: float) -> bytes:
    from PIL import Image

    images = [Image.fromarray(f).quantize(colors=128, method=Image.Quantize.MEDIANCUT) for f in frames]
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


def write_animation(source: str, out: str, view: str = "iso", fps: float = 20.0, speed: float = 1.0) -> dict:
    """Animate the result folder ``source`` into ``out`` (.gif, .mp4 or .html); returns ``frames``,
    ``duration_s`` (simulated, prototype time), ``fps``, ``speed``, ``view``."""

    target = check_animation(out, view, fps, speed)
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

        data = motion_html(motion, indices, charge=charge, title=info["title"], view=view, fps=fps)
    else:
        from ..plots.motion import render_frames

        frames = render_frames(motion, indices, view, charge)
        data = _gif(frames, fps) if kind == ".gif" else _mp4(frames, fps)
    write_file(target, data, what="animate")
    return {"frames": int(len(indices)), "duration_s": motion.duration, "fps": fps, "speed": speed, "view": view}


def show_animation(source: str, out: str, view: str, fps: float, speed: float, as_json: bool = False) -> None:
    """``show RESULT_DIR --animate FILE``: write the animation, then one line (or the JSON of
    :func:`write_animation`)."""

    with one_line_warnings():
        info = write_animation(source, out, view, fps, speed)
    if as_json:
        print_json(info)
    print_written(
        out, f"{info['frames']} frames, {info['duration_s']:.3g} s at {info['fps']:g} fps x {info['speed']:g}"
    )
