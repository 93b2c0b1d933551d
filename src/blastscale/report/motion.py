"""The interactive 3D view of the stored motion (issue 26): plotly, its JavaScript embedded (offline, no
network), the prototype and the up-scaled specimen side by side in prototype units on one time axis (one
slider, play and pause), blocks coloured by their largest displacement, the charge marked, the ground drawn.

Size bounded: each frame carries every vertex of every system as float32 (base64 in the page); the frames are
the states of :meth:`~blastscale.sim3d.replay.Motion.frame_indices` at ``fps`` over the run, thinned to at most
:data:`FRAME_BYTES` of frame data (:func:`view_frames`), so a report's view stays under about 3 MB beside
plotly's own JavaScript (~4.7 MB).
"""

from __future__ import annotations

import base64
from dataclasses import dataclass
from html import escape

import numpy as np

from ..sim3d.replay import motion_of
from ..similitude.effects import charge_position

__all__ = [
    "FRAME_BYTES",
    "MAX_VIEW_FRAMES",
    "REPORT_FPS",
    "view_frames",
    "view_figure",
    "motion_div",
    "motion_html",
    "motion_section",
    "CAMERAS",
]

#: The most bytes of frame data in one view (vertex coordinates, float32 in base64: 16/3 bytes each).
FRAME_BYTES = 3_000_000
#: The most frames of one view, whatever the structure's size.
MAX_VIEW_FRAMES = 200
#: Frames per second of the report's view (before thinning to :data:`FRAME_BYTES`).
REPORT_FPS = 20.0
#: plotly's camera eye of each named view (as :data:`blastscale.plots.motion.VIEWS`): front from the charge (-x).
CAMERAS = {"front": (-2.2, 0.0, 0.15), "side": (0.0, -2.2, 0.15), "top": (0.0, 0.0, 2.4), "iso": (-1.6, -1.6, 0.9)}
#: The ground's colour (flat: no lighting, so the screenshots can tell it from the blocks).
GROUND = "rgb(216,210,196)"


def view_frames(motion, fps: float = 20.0, speed: float = 1.0) -> tuple[np.ndarray, int]:
    """The recorded states the view shows and the number the fps asked for: the frames of
    ``motion.frame_indices(fps, speed)``, evenly thinned to :data:`MAX_VIEW_FRAMES` and :data:`FRAME_BYTES`."""
    idx, _ = motion.frame_indices(fps, speed)
    per_frame = len(motion.labels) * int(np.isfinite(motion.vertices[..., 0]).sum()) * 3 * 16 / 3
    keep = int(min(len(idx), MAX_VIEW_FRAMES, max(2, FRAME_BYTES // max(per_frame, 1))))
    return idx[np.unique(np.round(np.linspace(0, len(idx) - 1, keep)).astype(int))], len(idx)


def _mesh(motion):
    """Concatenated triangles (i, j, k) of every body (padding dropped), the vertex mask, the body of each
    vertex."""
    ok = np.isfinite(motion.vertices[..., 0])
    offset = np.concatenate([[0], np.cumsum(ok.sum(axis=1))[:-1]])
    tri = np.concatenate([f[(f >= 0).all(axis=1)] + offset[k] for k, f in enumerate(motion.faces)])
    body = np.concatenate([np.full(int(n), k) for k, n in enumerate(ok.sum(axis=1))])
    return tri, ok, body


def _typed(v: np.ndarray) -> dict:
    """A float32 array as a plotly.js typed array (``{"dtype": "f4", "bdata": base64}``, plotly.js >= 2.28)."""
    return {"dtype": "f4", "bdata": base64.b64encode(np.ascontiguousarray(v, np.float32)).decode("ascii")}


def view_figure(motion, indices, charge=None, title: str = "", view: str = "iso", fps: float = 20.0) -> dict:
    """The plotly figure as plotly's JSON-ready dict (``data``, ``layout``, ``frames``): one 3D scene per
    system, one frame per recorded state in ``indices``, a slider and play / pause buttons (``fps`` frames per
    second of playback)."""
    from plotly.subplots import make_subplots

    meshes = _Meshes.of(motion)
    box = _Box.of(motion, charge)
    nsys = len(motion.labels)
    fig = make_subplots(
        rows=1,
        cols=nsys,
        specs=[[{"type": "scene"}] * nsys],
        subplot_titles=list(motion.labels),
        horizontal_spacing=0.02,
    )
    block_traces = [_add_system(fig, meshes, box, s, int(indices[0]), charge) for s in range(nsys)]
    fig.update_layout(**_layout(motion, indices[0], title, fps, box.scene(view), nsys))
    return _with_frames(fig.to_dict(), meshes, indices, title, block_traces)


@dataclass(frozen=True)
class _Meshes:
    """The blocks of a motion as one triangle mesh per system: the triangles, the vertex mask, the body of each
    vertex (:func:`_mesh`); each body's largest displacement [m] per system and the colour scale's top [m]."""

    motion: object
    tri: np.ndarray
    ok: np.ndarray
    body: np.ndarray
    disp: np.ndarray
    cmax: float

    @classmethod
    def of(cls, motion) -> "_Meshes":
        tri, ok, body = _mesh(motion)
        disp = motion.largest_displacement()
        return cls(motion, tri, ok, body, disp, max(float(disp.max()), 1e-12))

    def blocks(self, s: int, index: int) -> dict:
        """System ``s``'s vertices at state ``index`` [m]: plotly.js typed arrays of float32, as plotly writes
        numpy arrays."""
        v = self.motion.world(s, [index])[0][self.ok].astype(np.float32)
        return {k: _typed(v[:, a]) for a, k in enumerate("xyz")}


@dataclass(frozen=True)
class _Box:
    """The cube every scene shows [m]: the motion's bounds (and the charge) ``lo``, ``hi``, its centre ``c`` and
    half-side ``m`` (0.6 of the largest extent)."""

    lo: np.ndarray
    hi: np.ndarray
    c: np.ndarray
    m: float

    @classmethod
    def of(cls, motion, charge=None) -> "_Box":
        lo, hi = motion.bounds()
        if charge is not None:
            lo, hi = np.minimum(lo, charge), np.maximum(hi, charge)
        return cls(lo, hi, 0.5 * (lo + hi), 0.6 * float(max(hi - lo)))

    def ground(self) -> dict:
        """The ground's square (x, y, z) under the scene, float32."""
        c, m = self.c, self.m
        gx, gy = [c[0] - m, c[0] + m, c[0] + m, c[0] - m], [c[1] - m, c[1] - m, c[1] + m, c[1] + m]
        return {k: np.array(gx if k == "x" else gy if k == "y" else [0.0] * 4, np.float32) for k in "xyz"}

    def scene(self, view: str) -> dict:
        """The layout of one 3D scene seen from ``view`` (:data:`CAMERAS`)."""
        c, m, lo = self.c, self.m, self.lo
        return dict(
            aspectmode="cube",
            camera=dict(eye=dict(zip("xyz", CAMERAS[view]))),
            xaxis=dict(range=[c[0] - m, c[0] + m], title="x [m]"),
            yaxis=dict(range=[c[1] - m, c[1] + m], title="y [m]"),
            zaxis=dict(range=[min(lo[2], 0.0), min(lo[2], 0.0) + 2 * m], title="z [m]"),
        )


def _add_system(fig, meshes: _Meshes, box: _Box, s: int, first: int, charge=None) -> int:
    """Add system ``s``'s scene: the ground, its blocks at state ``first`` coloured by their largest
    displacement, the charge; returns the blocks' trace index (the trace each frame replaces)."""
    import plotly.graph_objects as go

    fig.add_trace(
        go.Mesh3d(
            **box.ground(),
            i=[0, 0],
            j=[1, 2],
            k=[2, 3],
            color=GROUND,
            flatshading=True,
            lighting=dict(ambient=1.0, diffuse=0.0, specular=0.0),
            hoverinfo="skip",
            name="ground",
            showlegend=False,
        ),
        row=1,
        col=s + 1,
    )
    index = len(fig.data)
    tri = meshes.tri
    fig.add_trace(
        go.Mesh3d(
            **meshes.blocks(s, first),
            i=tri[:, 0],
            j=tri[:, 1],
            k=tri[:, 2],
            intensity=meshes.disp[s][meshes.body].astype(np.float32),
            intensitymode="vertex",
            colorscale="Viridis",
            cmin=0.0,
            cmax=meshes.cmax,
            flatshading=True,
            showscale=s == 0,
            colorbar=dict(title=dict(text="largest<br>displacement [m]"), len=0.6),
            lighting=dict(ambient=0.55, diffuse=0.7, specular=0.05),
            name=meshes.motion.labels[s],
            hoverinfo="name",
        ),
        row=1,
        col=s + 1,
    )
    if charge is not None:
        fig.add_trace(
            go.Scatter3d(
                x=[charge[0]],
                y=[charge[1]],
                z=[charge[2]],
                mode="markers+text",
                marker=dict(size=6, color="#c0392b", symbol="diamond"),
                text=["charge"],
                textposition="top center",
                name="charge",
                showlegend=False,
            ),
            row=1,
            col=s + 1,
        )
    return index


def _layout(motion, first: int, title: str, fps: float, scene: dict, nsys: int) -> dict:
    """The figure's layout: the title at state ``first``, one ``scene`` per system, play / pause (``fps``
    frames per second) and the time slider (its steps added with the frames)."""
    play = dict(frame=dict(duration=1000.0 / fps, redraw=True), fromcurrent=True, transition=dict(duration=0))
    pause = dict(frame=dict(duration=0, redraw=False), mode="immediate", transition=dict(duration=0))
    return dict(
        title_text=f"{title}  t = {motion.time[first]:.3f} s",
        height=560,
        margin=dict(l=10, r=10, t=60, b=10),
        template="plotly_white",
        **{f"scene{'' if s == 0 else s + 1}": scene for s in range(nsys)},
        updatemenus=[
            dict(
                type="buttons",
                direction="left",
                x=0.0,
                y=0.0,
                xanchor="left",
                yanchor="top",
                pad=dict(t=40),
                buttons=[
                    dict(label="play", method="animate", args=[None, play]),
                    dict(label="pause", method="animate", args=[[None], pause]),
                ],
            )
        ],
        sliders=[
            dict(active=0, x=0.12, y=0.0, len=0.86, pad=dict(t=30), currentvalue=dict(prefix="time [s, prototype]: "))
        ],
    )


def _with_frames(out: dict, meshes: _Meshes, indices, title: str, block_traces: list[int]) -> dict:
    """``out`` (the figure's dict) with one frame per state in ``indices`` and the slider's steps.

    The one-off traces and layout were checked by plotly; the frames and the slider's steps (one per frame)
    are written as plotly writes them, without its per-item checks (0.4 s of a column report's 0.45 s view):
    only vertex coordinates change from frame to frame."""
    time = meshes.motion.time
    step = dict(mode="immediate", frame=dict(duration=0, redraw=True), transition=dict(duration=0))
    steps = [dict(args=[[str(n)], step], label=f"{time[i]:.3f}", method="animate") for n, i in enumerate(indices)]
    out["layout"]["sliders"][0] = dict(
        sorted({**out["layout"]["sliders"][0], "steps": steps}.items())
    )  # plotly's order
    nsys = len(meshes.motion.labels)
    out["frames"] = [
        dict(
            data=[dict(**meshes.blocks(s, int(i)), type="mesh3d") for s in range(nsys)],
            layout=dict(title=dict(text=f"{title}  t = {time[i]:.3f} s")),
            name=str(n),
            traces=block_traces,
        )
        for n, i in enumerate(indices)
    ]
    return out


#: Draws a view when it comes near the window (a long report opens without waiting for WebGL: the view of the
#: default report costs 2.5-5 s of software rendering on a loaded 2-core machine) and, on a page whose address
#: ends in ``#frame=N``, puts the first view at the top of the page at frame N (screenshots: docs, tests).
_DRAW = """<script>(function(){var d=document.getElementById("{id}"),drawn=null;
function draw(){if(drawn)return drawn;var f=JSON.parse(document.getElementById("{id}-data").textContent);
drawn=Plotly.newPlot(d,f.data,f.layout,{displaylogo:false,responsive:true}).then(function(){
return Plotly.addFrames(d,f.frames);});return drawn;}
var m={first}?/frame=(\\d+)/.exec(location.hash):null;
if(m){document.body.prepend(d.closest("figure")||d);window.scrollTo(0,0);draw().then(function(){
return Plotly.animate(d,[m[1]],{mode:"immediate",frame:{duration:0,redraw:true},transition:{duration:0}});});return;}
if(!("IntersectionObserver" in window)){draw();return;}
new IntersectionObserver(function(es,o){if(es.some(function(e){return e.isIntersecting;})){o.disconnect();draw();}},
{rootMargin:"300px"}).observe(d);})();</script>"""


def motion_div(
    motion,
    indices,
    charge=None,
    title: str = "",
    view: str = "iso",
    fps: float = 20.0,
    include_plotlyjs: bool = True,
    div_id: str = "motion3d",
    first: bool = True,
) -> str:
    """The view as an HTML ``<div>``, drawn when it comes near the window (plotly's JavaScript embedded before
    it when ``include_plotlyjs``; ``first``: the view a ``#frame=N`` address shows)."""
    import plotly.io as pio
    from plotly.offline import get_plotlyjs

    fig = view_figure(motion, indices, charge, title, view, fps)
    data = pio.to_json(fig, validate=False).replace("</", "<\\/")  # inert inside <script>
    lib = f'<script type="text/javascript">{get_plotlyjs()}</script>' if include_plotlyjs else ""
    return (
        f'{lib}<div id="{div_id}" style="height:{fig["layout"]["height"]}px;width:100%"></div>'
        f'<script type="application/json" id="{div_id}-data">{data}</script>'
        + _DRAW.replace("{id}", div_id).replace("{first}", "true" if first else "false")
    )


def motion_html(motion, indices, charge=None, title: str = "", view: str = "iso", fps: float = 20.0) -> str:
    """A self-contained HTML page of the view (``show --animate FILE.html``)."""

    body = motion_div(motion, indices, charge, title, view, fps)
    return (
        f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>{escape(title or "blastscale motion")}'
        f'</title></head><body style="margin:0;font-family:sans-serif">{body}</body></html>'
    )


def motion_section(result, tree=None) -> str:
    """The report's interactive 3D views of a study with a 3D run ("" without one): prototype and up-scaled
    model side by side; with an ensemble, its median and its worst member too (from ``tree``, the result's
    :meth:`~blastscale.study.StudyResult.to_datatree`, when given). Each caption states the frames
    kept (decimation) and how to use the view; plotly's JavaScript is embedded once."""

    if result.response3d is None:
        return ""
    ds = (result.to_datatree() if tree is None else tree)["sim3d"].to_dataset()
    if "body_position" not in ds:
        return ""
    sc = result.scenario
    standoff = (
        None
        if sc.blast.gravity_only
        else (result.design.prototype.standoff_m if result.design is not None else sc.blast.standoff_m)
    )
    out = ["<h3>The motion in 3D</h3>", _view(motion_of(ds), standoff, "motion3d", True, "The response in 3D")]
    ens = getattr(result.ensemble, "motion", None) if result.ensemble is not None else None
    if ens is not None:
        for case in ens["case"].values:
            one = ens.sel(case=case)
            what = {"median": "the member closest to the ensemble's median", "worst": "the ensemble's worst member"}
            out.append(
                _view(
                    motion_of(one),
                    standoff,
                    f"motion3d-{case}",
                    False,
                    f"Ensemble: {what.get(str(case), str(case))} (member {int(one['case_member'])}, largest "
                    "displacement of any point)",
                )
            )
    return "".join(out)


def _view(motion, standoff, div_id: str, include_plotlyjs: bool, lead: str) -> str:

    charge = None if standoff is None else charge_position(motion.front_x, standoff)
    indices, asked = view_frames(motion, REPORT_FPS)
    step_ms = 1e3 * motion.duration / max(len(indices) - 1, 1)
    div = motion_div(
        motion,
        indices,
        charge,
        title="",
        view="iso",
        fps=REPORT_FPS,
        include_plotlyjs=include_plotlyjs,
        div_id=div_id,
        first=include_plotlyjs,
    )
    return (
        f'<figure id="fig-{div_id}">{div}<figcaption><b>{escape(lead)}, '
        f"{escape(' and '.join(motion.labels))} side by side in prototype units on one time axis.</b> "
        f"Play, pause or drag the time slider; drag a view to turn it. Blocks coloured by their largest "
        f"displacement; the charge (red) on the ground {standoff if standoff is not None else 0:.3g} m in "
        f"front. {len(indices)} frames of the {len(motion.time)} recorded states, one every {step_ms:.3g} ms of "
        f"prototype time ({asked} asked at {REPORT_FPS:g} per second of playback; at most {MAX_VIEW_FRAMES} "
        f"and {FRAME_BYTES / 1e6:g} MB of frame data). The same view from the result folder: "
        f"<code>blastscale show RESULT_DIR --animate FILE.html</code> (or .gif, .mp4).</figcaption></figure>"
    )
