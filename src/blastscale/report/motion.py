"""The interactive 3D view of the stored motion (issues 26, 39, 41): the prototype and the up-scaled specimen side
by side in prototype units on one time axis (one slider, play and pause), at one displacement magnification
(an automatic default stated on the page, :func:`blastscale.plots.motion.auto_magnification`, and a box to
change it), blocks coloured by their displacement at the frame shown, the charge marked, the ground drawn.

Small and quick to open: no plotting library. The page carries each body's surface once (its vertices in its
own frame and its triangles) and, per frame, only each body's pose (position and unit quaternion, float32 in
base64: 28 bytes per body); about 200 lines of JavaScript embedded once per page (:data:`VIEW_JS`) put the
vertices in the world, magnify the motion (the rule of :func:`blastscale.plots.motion.magnified_world`) and draw
the triangles on a 2D canvas, far ones first (no WebGL: headless and software browsers draw it at once). The
frames are the states of :meth:`~blastscale.sim3d.replay.Motion.frame_indices` at ``fps`` over the run, thinned
to at most :data:`MAX_VIEW_FRAMES` and :data:`FRAME_BYTES` of pose data (:func:`view_frames`).
"""

from __future__ import annotations

import base64
import json
from html import escape

import numpy as np

from ..plots.motion import VIEWS, VISIBLE_FRACTION, auto_magnification, peak_motion, record_height
from ..sim3d.replay import motion_of
from ..similitude.effects import charge_position

__all__ = [
    "FRAME_BYTES",
    "MAX_VIEW_FRAMES",
    "REPORT_FPS",
    "GROUND",
    "VIEW_JS",
    "view_frames",
    "view_data",
    "motion_div",
    "motion_html",
    "motion_section",
]

#: The most bytes of pose data in one view (position and quaternion of every body of every system per frame,
#: float32 in base64: 28 x 4/3 bytes per body and frame).
FRAME_BYTES = 1_000_000
#: The most frames of one view, whatever the structure's size.
MAX_VIEW_FRAMES = 200
#: Frames per second of the report's view (before thinning to :data:`FRAME_BYTES`).
REPORT_FPS = 20.0
#: The ground's colour (flat, unlit: the screenshots can tell it from the blocks).
GROUND = "rgb(216,210,196)"
#: Bytes of one body's pose in one frame of the page (7 float32 in base64).
_POSE_BYTES = 7 * 4 * 4 / 3


def view_frames(motion, fps: float = 20.0, speed: float = 1.0) -> tuple[np.ndarray, int]:
    """The recorded states the view shows and the number the fps asked for: the frames of
    ``motion.frame_indices(fps, speed)``, evenly thinned to :data:`MAX_VIEW_FRAMES` and :data:`FRAME_BYTES`."""
    idx, _ = motion.frame_indices(fps, speed)
    per_frame = len(motion.labels) * len(motion.bodies) * _POSE_BYTES
    keep = int(min(len(idx), MAX_VIEW_FRAMES, max(2, FRAME_BYTES // max(per_frame, 1))))
    return idx[np.unique(np.round(np.linspace(0, len(idx) - 1, keep)).astype(int))], len(idx)


def _b64(v: np.ndarray, dtype) -> str:
    return base64.b64encode(np.ascontiguousarray(v, dtype=dtype).tobytes()).decode("ascii")


def view_data(motion, indices, charge=None, view: str = "iso", fps: float = 20.0, magnification=None) -> dict:
    """What the page's script draws, JSON-ready: the surfaces once, one pose per body, system and frame.

    Keys: ``labels``, ``times`` [s] (one per frame), ``counts`` (vertices of each body), ``vertices`` (float32,
    each body's in its own frame [m], concatenated), ``triangles`` (int32, indices into ``vertices``),
    ``position`` (float32, (system, frame, body, 3) [m]), ``quaternion`` (float32, (system, frame, body, 4),
    w x y z), ``charge`` [m] or None, ``view`` (elevation, azimuth [deg] of :data:`VIEWS`), ``fps``,
    ``magnification`` (``magnification`` or the automatic default), ``auto_magnification``, ``peak_m`` (the
    largest motion of any vertex, true), ``height_m``, ``visible_fraction``, ``colour_max_m`` (the largest
    displacement of a centre of mass over the frames: the colour scale's top, the same for every frame).
    """
    idx = np.asarray(indices, dtype=int)
    ok = np.isfinite(motion.vertices[..., 0])
    counts = ok.sum(axis=1)
    offset = np.concatenate([[0], np.cumsum(counts)[:-1]])
    tri = np.concatenate([f[(f >= 0).all(axis=1)] + offset[k] for k, f in enumerate(motion.faces)])
    q = motion.quaternion[:, idx]
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    pos = motion.position[:, idx]
    auto = auto_magnification(motion, idx)
    return {
        "labels": list(motion.labels),
        "times": [round(float(t), 6) for t in motion.time[idx]],
        "counts": [int(c) for c in counts],
        "vertices": _b64(motion.vertices[ok], np.float32),
        "triangles": _b64(tri, np.int32),
        "position": _b64(pos, np.float32),
        "quaternion": _b64(q, np.float32),
        "charge": None if charge is None else [float(c) for c in charge],
        "view": list(VIEWS[view]),
        "fps": float(fps),
        "magnification": float(auto if magnification is None else magnification),
        "auto_magnification": auto,
        "peak_m": peak_motion(motion, idx),
        "height_m": record_height(motion),
        "visible_fraction": VISIBLE_FRACTION,
        "colour_max_m": max(float(np.linalg.norm(pos - pos[:, :1], axis=-1).max()), 1e-12),
    }


def _magnification_words(data: dict) -> str:
    """The magnification as the page states it (HTML)."""
    m, auto = data["magnification"], data["auto_magnification"]
    why = (
        f"the automatic default draws the largest motion of any point, {data['peak_m']:.3g} m, as at most "
        f"{100 * data['visible_fraction']:g} % of the structure's height, {data['height_m']:.3g} m"
        if auto > 1.0
        else f"the largest motion, {data['peak_m']:.3g} m, is at least {100 * data['visible_fraction']:g} % of "
        f"the structure's height ({data['height_m']:.3g} m): drawn as it is"
    )
    chosen = "" if m == auto else f" (chosen; the automatic default is x {auto:g})"
    return f"Displacements drawn x {m:g}{chosen}: {why}. Colours and the colour bar are the true displacements."


#: The view's script, embedded once per page: ``blastscaleView(id, first)`` draws the view of the ``<div id>``
#: from the JSON in ``<script id="{id}-data">`` (:func:`view_data`); the first view of a page whose address ends
#: in ``#frame=N`` (optionally ``&mag=M``) is put at the top of the page at frame N (screenshots: docs, tests).
VIEW_JS = r"""
(function(){
var VIR=[[68,1,84],[72,36,117],[65,68,135],[53,95,141],[42,120,142],[33,145,140],[34,168,132],[68,191,112],
[122,209,81],[189,223,38],[253,231,37]];
function vir(t){t=Math.max(0,Math.min(1,t))*(VIR.length-1);var i=Math.min(Math.floor(t),VIR.length-2),f=t-i,
a=VIR[i],b=VIR[i+1];return [a[0]+f*(b[0]-a[0]),a[1]+f*(b[1]-a[1]),a[2]+f*(b[2]-a[2])];}
function dec(s,T){var b=atob(s),u=new Uint8Array(b.length);for(var i=0;i<b.length;i++)u[i]=b.charCodeAt(i);
return new T(u.buffer);}
function qmul(a,b){return [a[0]*b[0]-a[1]*b[1]-a[2]*b[2]-a[3]*b[3],a[0]*b[1]+a[1]*b[0]+a[2]*b[3]-a[3]*b[2],
a[0]*b[2]-a[1]*b[3]+a[2]*b[0]+a[3]*b[1],a[0]*b[3]+a[1]*b[2]-a[2]*b[1]+a[3]*b[0]];}
function qmat(q){var w=q[0],x=q[1],y=q[2],z=q[3];return [1-2*(y*y+z*z),2*(x*y-w*z),2*(x*z+w*y),
2*(x*y+w*z),1-2*(x*x+z*z),2*(y*z-w*x),2*(x*z-w*y),2*(y*z+w*x),1-2*(x*x+y*y)];}
function nice(span,n){var r=span/Math.max(n,1),e=Math.pow(10,Math.floor(Math.log10(r))),m=r/e;
return (m<=1?1:m<=2?2:m<=5?5:10)*e;}
function fmt(v,st){var d=Math.max(0,-Math.floor(Math.log10(st)+1e-9));return (Math.abs(v)<st/2?0:v).toFixed(d);}
var LIGHT=(function(){var l=[-0.5,-0.4,0.77],n=Math.hypot(l[0],l[1],l[2]);return [l[0]/n,l[1]/n,l[2]/n];})();
window.blastscaleView=function(id,first){
var root=document.getElementById(id),D=JSON.parse(document.getElementById(id+"-data").textContent);
var V=dec(D.vertices,Float32Array),T=dec(D.triangles,Int32Array),P=dec(D.position,Float32Array),
Q=dec(D.quaternion,Float32Array),NS=D.labels.length,NF=D.times.length,NB=D.counts.length,NV=V.length/3,
NT=T.length/3,VB=new Int32Array(NV);
for(var b=0,k=0;b<NB;b++)for(var j=0;j<D.counts[b];j++)VB[k++]=b;
var cv=root.querySelector("canvas"),sl=root.querySelector("input[type=range]"),
mg=root.querySelector("input[type=number]"),bt=root.querySelector("button"),tl=root.querySelector(".bs-time");
var st={f:0,m:D.magnification,el:D.view[0],az:D.view[1],play:null,box:null};
function pose(s,f,b){var o=((s*NF+f)*NB+b),p=[P[3*o],P[3*o+1],P[3*o+2]],q=[Q[4*o],Q[4*o+1],Q[4*o+2],Q[4*o+3]],
o0=s*NF*NB+b,p0=[P[3*o0],P[3*o0+1],P[3*o0+2]],q0=[Q[4*o0],Q[4*o0+1],Q[4*o0+2],Q[4*o0+3]],m=st.m;
var d=Math.hypot(p[0]-p0[0],p[1]-p0[1],p[2]-p0[2]);if(m===1)return {p:p,R:qmat(q),d:d};
var r=qmul(q,[q0[0],-q0[1],-q0[2],-q0[3]]);if(r[0]<0)r=[-r[0],-r[1],-r[2],-r[3]];
var sn=Math.hypot(r[1],r[2],r[3]),h=Math.atan2(sn,r[0]),a=sn>0?[r[1]/sn,r[2]/sn,r[3]/sn]:[0,0,0],
sm=Math.sin(m*h),qm=qmul([Math.cos(m*h),a[0]*sm,a[1]*sm,a[2]*sm],q0);
return {p:[p0[0]+m*(p[0]-p0[0]),p0[1]+m*(p[1]-p0[1]),p0[2]+m*(p[2]-p0[2])],R:qmat(qm),d:d};}
function world(s,f){var W=new Float32Array(3*NV),ps=[];for(var b=0;b<NB;b++)ps.push(pose(s,f,b));
for(var i=0;i<NV;i++){var o=ps[VB[i]],R=o.R,x=V[3*i],y=V[3*i+1],z=V[3*i+2];
W[3*i]=o.p[0]+R[0]*x+R[1]*y+R[2]*z;W[3*i+1]=o.p[1]+R[3]*x+R[4]*y+R[5]*z;W[3*i+2]=o.p[2]+R[6]*x+R[7]*y+R[8]*z;}
return {W:W,d:ps.map(function(o){return o.d;})};}
function bounds(){var lo=[Infinity,Infinity,0],hi=[-Infinity,-Infinity,-Infinity],fs=[],
step=Math.max(1,Math.floor(NF/50));for(var f=0;f<NF;f+=step)fs.push(f);fs.push(NF-1);
for(var s=0;s<NS;s++)fs.forEach(function(f){var W=world(s,f).W;
for(var i=0;i<W.length;i++){var a=i%3;if(W[i]<lo[a])lo[a]=W[i];if(W[i]>hi[a])hi[a]=W[i];}});
if(D.charge)for(var a=0;a<3;a++){lo[a]=Math.min(lo[a],D.charge[a]);hi[a]=Math.max(hi[a],D.charge[a]);}
var pad=0.08*Math.max(hi[0]-lo[0],hi[1]-lo[1],hi[2]-lo[2]);
return {lo:[lo[0]-pad,lo[1]-pad,lo[2]],hi:[hi[0]+pad,hi[1]+pad,hi[2]]};}
function cam(){var e=st.el*Math.PI/180,a=st.az*Math.PI/180;
return {e:[Math.cos(e)*Math.cos(a),Math.cos(e)*Math.sin(a),Math.sin(e)],r:[-Math.sin(a),Math.cos(a),0],
u:[-Math.sin(e)*Math.cos(a),-Math.sin(e)*Math.sin(a),Math.cos(e)]};}
function draw(){
var dpr=window.devicePixelRatio||1,cw=cv.clientWidth,ch=cv.clientHeight;cv.width=cw*dpr;cv.height=ch*dpr;
var g=cv.getContext("2d");g.setTransform(dpr,0,0,dpr,0,0);g.fillStyle="#fff";g.fillRect(0,0,cw,ch);
if(!st.box)st.box=bounds();var B=st.box,C=cam(),bar=78,top=34,pw=(cw-bar)/NS,ph=ch-top-8;
var cx=[0,1],cy=[0,1],cz=[0,1],sx=[],sy=[];
cx.forEach(function(i){cy.forEach(function(j){cz.forEach(function(k){var p=[i?B.hi[0]:B.lo[0],j?B.hi[1]:B.lo[1],
k?B.hi[2]:B.lo[2]];sx.push(p[0]*C.r[0]+p[1]*C.r[1]+p[2]*C.r[2]);sy.push(p[0]*C.u[0]+p[1]*C.u[1]+p[2]*C.u[2]);});});});
var x0=Math.min.apply(null,sx),x1=Math.max.apply(null,sx),y0=Math.min.apply(null,sy),y1=Math.max.apply(null,sy),
sc=Math.min((pw-90)/Math.max(x1-x0,1e-9),(ph-50)/Math.max(y1-y0,1e-9));
for(var s=0;s<NS;s++){var ox=s*pw+pw/2-sc*(x0+x1)/2,oy=top+ph/2+sc*(y0+y1)/2;
var pr=function(p){return [ox+sc*(p[0]*C.r[0]+p[1]*C.r[1]+p[2]*C.r[2]),oy-sc*(p[0]*C.u[0]+p[1]*C.u[1]+p[2]*C.u[2])];};
g.save();g.beginPath();g.rect(s*pw,top,pw,ph);g.clip();
var gr=[[B.lo[0],B.lo[1],0],[B.hi[0],B.lo[1],0],[B.hi[0],B.hi[1],0],[B.lo[0],B.hi[1],0]].map(pr);
g.fillStyle="rgb(216,210,196)";g.beginPath();gr.forEach(function(p,i){i?g.lineTo(p[0],p[1]):g.moveTo(p[0],p[1]);});
g.closePath();g.fill();axes(g,pr,B,C);
var w=world(s,st.f),W=w.W,order=[],dep=new Float32Array(NT),sh=new Float32Array(NT);
for(var t=0;t<NT;t++){var a=T[3*t],b=T[3*t+1],c=T[3*t+2],
ux=W[3*b]-W[3*a],uy=W[3*b+1]-W[3*a+1],uz=W[3*b+2]-W[3*a+2],vx=W[3*c]-W[3*a],vy=W[3*c+1]-W[3*a+1],vz=W[3*c+2]-W[3*a+2],
nx=uy*vz-uz*vy,ny=uz*vx-ux*vz,nz=ux*vy-uy*vx,nn=Math.hypot(nx,ny,nz)||1;nx/=nn;ny/=nn;nz/=nn;
if(nx*C.e[0]+ny*C.e[1]+nz*C.e[2]<=1e-9)continue;
dep[t]=(W[3*a]+W[3*b]+W[3*c])*C.e[0]+(W[3*a+1]+W[3*b+1]+W[3*c+1])*C.e[1]+(W[3*a+2]+W[3*b+2]+W[3*c+2])*C.e[2];
sh[t]=0.55+0.45*Math.max(0,nx*LIGHT[0]+ny*LIGHT[1]+nz*LIGHT[2]);order.push(t);}
order.sort(function(i,j){return dep[i]-dep[j];});g.lineWidth=0.6;g.lineJoin="round";
order.forEach(function(t){var col=vir(w.d[VB[T[3*t]]]/D.colour_max_m),k=sh[t],
css="rgb("+Math.round(col[0]*k)+","+Math.round(col[1]*k)+","+Math.round(col[2]*k)+")";g.fillStyle=css;
g.strokeStyle=css;g.beginPath();for(var n=0;n<3;n++){var v=T[3*t+n],q=pr([W[3*v],W[3*v+1],W[3*v+2]]);
n?g.lineTo(q[0],q[1]):g.moveTo(q[0],q[1]);}g.closePath();g.fill();g.stroke();});
if(D.charge){var c=pr(D.charge);g.fillStyle="#c0392b";g.beginPath();g.moveTo(c[0],c[1]-7);g.lineTo(c[0]+6,c[1]);
g.lineTo(c[0],c[1]+7);g.lineTo(c[0]-6,c[1]);g.closePath();g.fill();g.font="12px sans-serif";g.textAlign="center";
g.fillText("charge",c[0],c[1]-11);}
g.restore();g.fillStyle="#222";g.font="bold 13px sans-serif";g.textAlign="center";g.textBaseline="alphabetic";
g.fillText(D.labels[s],s*pw+pw/2,16);g.font="12px sans-serif";g.fillText("motion x "+st.m,s*pw+pw/2,30);}
colourbar(g,cw-bar+14,top+20,14,ph-70);tl.textContent="t = "+D.times[st.f].toFixed(3)+" s (prototype time)";
root.setAttribute("data-frame",st.f);}
function axes(g,pr,B,C){var c0=[(B.lo[0]+B.hi[0])/2,(B.lo[1]+B.hi[1])/2,0],pc=pr(c0);
var yn=(C.e[1]<0)?B.lo[1]:B.hi[1],yf=(C.e[1]<0)?B.hi[1]:B.lo[1],xn=(C.e[0]<0)?B.lo[0]:B.hi[0],
xf=(C.e[0]<0)?B.hi[0]:B.lo[0],zx=pr([xn,yf,0])[0]<pr([xf,yn,0])[0]?[xn,yf]:[xf,yn];
var ax=[["x [m]",[B.lo[0],yn,0],[B.hi[0],yn,0],0],["y [m]",[xn,B.lo[1],0],[xn,B.hi[1],0],1],
["z [m]",[zx[0],zx[1],B.lo[2]],[zx[0],zx[1],B.hi[2]],2]];
g.strokeStyle="#555";g.fillStyle="#333";g.lineWidth=1;g.font="11px sans-serif";g.textAlign="center";
g.textBaseline="middle";ax.forEach(function(A){var p=pr(A[1]),q=pr(A[2]),L=Math.hypot(q[0]-p[0],q[1]-p[1]);
if(L<40)return;var i=A[3],lo=A[1][i],hi=A[2][i],stp=nice(hi-lo,Math.max(2,Math.floor(L/70)));
g.beginPath();g.moveTo(p[0],p[1]);g.lineTo(q[0],q[1]);g.stroke();
var m=[(p[0]+q[0])/2-pc[0],(p[1]+q[1])/2-pc[1]];if(i===2)m=[p[0]<pc[0]?-1:1,0];
var mn=Math.hypot(m[0],m[1])||1;m=[m[0]/mn,m[1]/mn];
for(var v=Math.ceil(lo/stp)*stp;v<=hi+1e-9*stp;v+=stp){var pt=A[1].slice();pt[i]=v;var s2=pr(pt);
g.beginPath();g.moveTo(s2[0],s2[1]);g.lineTo(s2[0]+4*m[0],s2[1]+4*m[1]);g.stroke();
g.fillText(fmt(v,stp),s2[0]+16*m[0],s2[1]+14*m[1]);}
var c=(lo+hi)/2,a=Math.floor(c/stp)*stp,tp=A[1].slice();tp[i]=Math.max(lo,Math.min(hi,a+stp/2));tp=pr(tp);
g.font="italic 11px sans-serif";
g.fillText(A[0],i===2?q[0]:tp[0]+30*m[0],i===2?q[1]-12:tp[1]+28*m[1]);g.font="11px sans-serif";});}
function colourbar(g,x,y,w,h){for(var i=0;i<h;i++){var c=vir(1-i/h);g.fillStyle="rgb("+(c[0]|0)+","+(c[1]|0)+
","+(c[2]|0)+")";g.fillRect(x,y+i,w,1);}g.fillStyle="#222";g.font="11px sans-serif";g.textAlign="left";
g.textBaseline="middle";var top=D.colour_max_m,stp=nice(top,4);
for(var v=0;v<=top+1e-9*stp;v+=stp)g.fillText(fmt(v,stp),x+w+3,y+h-h*v/top);
g.save();g.translate(x-5,y+h/2);g.rotate(-Math.PI/2);g.textAlign="center";
g.fillText("displacement now [m], true",0,0);g.restore();}
function set(f){st.f=Math.max(0,Math.min(NF-1,f|0));sl.value=st.f;draw();}
sl.max=NF-1;sl.addEventListener("input",function(){set(+sl.value);});
mg.value=st.m;mg.addEventListener("change",function(){var v=+mg.value;if(v>0&&isFinite(v)){st.m=v;st.box=null;
draw();}else mg.value=st.m;});
bt.addEventListener("click",function(){if(st.play){clearInterval(st.play);st.play=null;bt.textContent="play";return;}
bt.textContent="pause";st.play=setInterval(function(){set((st.f+1)%NF);},1000/D.fps);});
var drag=null;cv.addEventListener("pointerdown",function(e){drag=[e.clientX,e.clientY,st.az,st.el];
cv.setPointerCapture(e.pointerId);});cv.addEventListener("pointerup",function(){drag=null;});
cv.addEventListener("pointermove",function(e){if(!drag)return;st.az=drag[2]-(e.clientX-drag[0])*0.5;
st.el=Math.max(-5,Math.min(90,drag[3]+(e.clientY-drag[1])*0.5));draw();});
var h=first?/frame=(\d+)(?:&mag=([0-9.eE+-]+))?/.exec(location.hash):null;
if(h){document.body.prepend(root.closest("figure")||root);window.scrollTo(0,0);if(h[2]&&+h[2]>0){st.m=+h[2];
mg.value=st.m;}set(+h[1]);}else set(0);
window.addEventListener("resize",draw);};
})();
"""


def motion_div(
    motion,
    indices,
    charge=None,
    view: str = "iso",
    fps: float = 20.0,
    include_js: bool = True,
    div_id: str = "motion3d",
    first: bool = True,
    magnification=None,
    height_px: int = 520,
) -> str:
    """The view as an HTML ``<div>`` (its script, :data:`VIEW_JS`, before it when ``include_js``; ``first``:
    the view a ``#frame=N`` address shows): the canvas, the stated magnification with a box to change it, the
    time slider, play and pause. ``magnification`` None: the automatic default."""
    data = view_data(motion, indices, charge, view, fps, magnification)
    text = json.dumps(data, separators=(",", ":")).replace("</", "<\\/")  # inert inside <script>
    lib = f"<script>{VIEW_JS}</script>" if include_js else ""
    return (
        f'{lib}<div id="{div_id}" class="bs-view" style="width:100%;font-family:sans-serif;font-size:13px">'
        f'<p class="bs-magnification" style="margin:4px 0">{escape(_magnification_words(data))} '
        f'<label>Magnification x <input type="number" min="1" step="any" value="{data["magnification"]:g}" '
        f'style="width:6em"></label></p>'
        f'<canvas style="width:100%;height:{height_px}px;display:block;touch-action:none;cursor:grab"></canvas>'
        f'<div style="display:flex;gap:8px;align-items:center"><button type="button">play</button>'
        f'<input type="range" min="0" value="0" step="1" style="flex:1"><span class="bs-time"></span></div></div>'
        f'<script type="application/json" id="{div_id}-data">{text}</script>'
        f'<script>blastscaleView("{div_id}",{"true" if first else "false"});</script>'
    )


def motion_html(
    motion, indices, charge=None, title: str = "", view: str = "iso", fps: float = 20.0, magnification=None
) -> str:
    """A self-contained HTML page of the view (``show --animate FILE.html``)."""

    body = motion_div(motion, indices, charge, view, fps, magnification=magnification)
    return (
        f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>{escape(title or "blastscale motion")}'
        f'</title></head><body style="margin:0 8px;font-family:sans-serif"><h3>{escape(title)}</h3>{body}</body></html>'
    )


def motion_section(result, tree=None) -> str:
    """The report's interactive 3D views of a study with a 3D run ("" without one): prototype and up-scaled
    model side by side; with an ensemble, its median and its worst member too (from ``tree``, the result's
    :meth:`~blastscale.study.StudyResult.to_datatree`, when given). Each caption states the frames
    kept (decimation) and how to use the view; the view's script is embedded once."""

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


def _view(motion, standoff, div_id: str, include_js: bool, lead: str) -> str:

    charge = None if standoff is None else charge_position(motion.front_x, standoff)
    indices, asked = view_frames(motion, REPORT_FPS)
    step_ms = 1e3 * motion.duration / max(len(indices) - 1, 1)
    div = motion_div(motion, indices, charge, "iso", REPORT_FPS, include_js, div_id, first=include_js)
    return (
        f'<figure id="fig-{div_id}" style="margin:0">{div}<figcaption><b>{escape(lead)}, '
        f"{escape(' and '.join(motion.labels))} side by side in prototype units on one time axis, at one "
        f"magnification.</b> Play, pause or drag the time slider; drag the view to turn it; type another "
        f"magnification. Blocks coloured by their displacement at the time shown (true, one scale for the run); "
        f"the charge (red) on the ground {standoff if standoff is not None else 0:.3g} m in front. "
        f"{len(indices)} frames of the {len(motion.time)} recorded states, one every {step_ms:.3g} ms of "
        f"prototype time ({asked} asked at {REPORT_FPS:g} per second of playback; at most {MAX_VIEW_FRAMES} "
        f"and {FRAME_BYTES / 1e6:g} MB of poses). The same view from the result folder: "
        f"<code>blastscale show RESULT_DIR --animate FILE.html</code> (or .gif, .mp4).</figcaption></figure>"
    )
