"""Benchmark of the 3D runs (MuJoCo): single block, 10-drum columns, the spurious-hop study and
the full-length acceptance figures of issue 8 (docs/sim3d.md).

Usage::

    python benchmarks/bench_sim3d.py [--json] [--quick] [--repeat N] [--hop-study] [--mode-study] [--acceptance]

Cost against the work (issue 19, :mod:`bench_scale`): ``ensemble`` (8-member circular-column ensemble,
serial vs every core: ``ensemble.members_8.speedup``), ``sweep3d`` (1 vs 2 Dask workers:
``sweep3d.workers_2.speedup``) and ``blocks`` (``blocks.wall_s_per_simulated_s`` for 1 block, stack-bonded
walls of 10, 50, 200 and running-bond walls of 11, 52, 210; ``blocks.ratio_200_over_column``).
``--quick``: one repeat, 2 s columns, shorter ensembles (the whole run in ~1 minute).

Columns (``speed.column_square`` / ``speed.column_circular``): the paper's 10-drum columns under
250 kg at 10 m (Method A), 4 s at prototype scale and their lambda = 1/100 models (``model``,
exactly scaled pulse, same number of steps), one thread, and the prototype with the opt-in sparse
constraint Jacobian (``prototype_sparse_jacobian``: speed-up and top-history agreement with dense).
``--acceptance`` re-measures the
full-length figures: drift at rest over 10 s, exact scaling over 8 s, the 1/100 column and
1/200 block specimens simulated at their own size, and the time-step halving.

Speed: simulated seconds per wall second for the paper's block (2h = 10 m, alpha = 15 deg,
50 kg TNT at 2 m, mu = 0.7, masi2021 fits) at prototype scale and at lambda = 1/200 (model
time step x sqrt(lambda), so a model second costs 1/sqrt(lambda) more steps).
``--hop-study`` re-measures every hypothesis of the hop investigation (max uplift of a 1 m
squat block pushed to 1.8 m/s) and prints them; ``--mode-study`` compares ``blast_mode="auto"``
with plain force mode, including force mode with a hard contact where it is accurate.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time
import warnings
from dataclasses import replace

import numpy as np

from blastscale.analysis.block3d_similarity import block_dataset, block_summary
from blastscale.blast.parameters import blast_parameters
from blastscale.blast.pulses import Triangular
from blastscale.sim3d import BoxShape, ContactSettings, MethodA, make_load, simulate_structure
from blastscale.sim3d.contact import default_contact
from blastscale.similitude import scaling_factors
from blastscale.structures import MultiDrumColumn
from blastscale.structures.block import RectangularBlock

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_scale  # noqa: E402  (this folder's cost-against-the-work module)

PAPER_BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
SQUAT_BLOCK = RectangularBlock(height=0.5, width=1.0, depth=1.0)


def run_block(block, pulse, duration, contact=None, **kw):
    """The block under Method A (``pulse`` on its front face at t = 0; None: no blast): the
    one-body structure run, its Response3D."""
    return simulate_structure(block, None if pulse is None else MethodA(block, pulse), duration, contact=contact, **kw)


def speed(repeat: int = 3, duration: float = 3.0) -> dict:
    """Best-of-``repeat`` wall time of a ``duration`` [s] prototype run and its 1/200 model."""
    lam = 1 / 200
    lt = math.sqrt(lam)
    c = ContactSettings(friction=0.7)
    pulse = blast_parameters(50.0, 2.0, blast_model="masi2021").pulse("friedlander")
    cases = {
        "prototype": (c, PAPER_BLOCK, pulse, duration),
        "model_1_200": (
            c.scaled(scaling_factors(lam)),
            PAPER_BLOCK.scaled(scaling_factors(lam)),
            pulse.scaled(scaling_factors(lam)),
            duration * lt,
        ),
    }
    out = {}
    for name, (cs, blk, p, T) in cases.items():
        best = math.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            run_block(blk, p, T, cs)
            best = min(best, time.perf_counter() - t0)
        steps = T / cs.timestep
        out[name] = {
            "simulated_s": T,
            "timestep_s": cs.timestep,
            "wall_s": best,
            "simulated_s_per_wall_s": T / best,
            "prototype_equivalent_s_per_wall_s": (T / (lt if name != "prototype" else 1.0)) / best,
            "steps_per_wall_s": steps / best,
        }
    return out


def column_speed(section: str, repeat: int = 1, duration: float = 4.0, lam: float = 0.01) -> dict:
    """Best-of-``repeat`` wall time of the paper's 10-drum column under 250 kg at 10 m, prototype
    and exactly scaled 1/``lam`` model (the model runs ``duration * sqrt(lam)``)."""
    col = MultiDrumColumn(section)
    lt = math.sqrt(lam)
    proto_load = make_load("A", col, blast_parameters(250.0, 10.0))
    model_col = col.scaled(scaling_factors(lam))
    model_load = MethodA(model_col, proto_load.pulse.scaled(scaling_factors(lam)), proto_load.arrival_time * lt)
    simulate_structure(col, proto_load, 0.01)  # imports and first compile outside the timing
    out = {}
    for name, (st, load, T) in {
        "prototype": (col, proto_load, duration),
        "model": (model_col, model_load, duration * lt),
    }.items():
        best = math.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            r = simulate_structure(st, load, T, record_every=20)
            best = min(best, time.perf_counter() - t0)
        dt = r.dataset.attrs["setting_timestep_s"]
        out[name] = {
            "scale": 1.0 if name == "prototype" else lam,
            "simulated_s": T,
            "timestep_s": dt,
            "wall_s": best,
            "simulated_s_per_wall_s": T / best,
            "prototype_equivalent_s_per_wall_s": (T / (1.0 if name == "prototype" else lt)) / best,
            "steps_per_wall_s": T / dt / best,
        }
    # the sparse and the dense constraint Jacobian (the default's choice: sim3d/solver_choice.py)
    sparse = replace(default_contact(col), jacobian="sparse")
    dense = replace(default_contact(col), jacobian="dense")
    t0 = time.perf_counter()
    x_dense = _top_x(simulate_structure(col, proto_load, duration, contact=dense, record_every=20))
    out["prototype_dense_jacobian"] = {
        "simulated_s": duration,
        "simulated_s_per_wall_s": duration / (time.perf_counter() - t0),
    }
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = simulate_structure(col, proto_load, duration, contact=sparse, record_every=20)
        best = min(best, time.perf_counter() - t0)
    out["prototype_sparse_jacobian"] = {
        "simulated_s": duration,
        "wall_s": best,
        "simulated_s_per_wall_s": duration / best,
        "speedup_vs_dense": duration / out["prototype_dense_jacobian"]["simulated_s_per_wall_s"] / best,
        "max_abs_top_diff_vs_dense_rel_peak": float(np.max(np.abs(_top_x(r) - x_dense)) / np.max(np.abs(x_dense))),
    }
    return out


def _top_x(resp, lam=1.0):
    return resp.dataset["point_displacement"].sel(point="P-10", component="x").values / lam


def acceptance() -> dict:
    """The full-length figures of issue 8 (docs/sim3d.md)."""
    out = {}
    for section in ("square", "circular"):
        r = simulate_structure(MultiDrumColumn(section), None, 10.0, record_every=100)
        out[f"rest_10s_{section}_top_drift_mm"] = 1e3 * float(
            np.abs(r.dataset["point_displacement"].sel(point="P-10").values).max()
        )
    col = MultiDrumColumn("square")
    lam = 0.01
    lt = math.sqrt(lam)
    load = make_load("A", col, blast_parameters(250.0, 10.0))
    proto = simulate_structure(col, load, 8.0, record_every=20)
    model = simulate_structure(
        col.scaled(scaling_factors(lam)),
        MethodA(col.scaled(scaling_factors(lam)), load.pulse.scaled(scaling_factors(lam)), load.arrival_time * lt),
        8.0 * lt,
        record_every=20,
    )
    p, m = _top_x(proto), _top_x(model, lam)
    out["exact_scaling_8s_max_diff_rel_peak"] = float(np.max(np.abs(m - p)) / np.max(np.abs(p)))
    out["square_250kg_top_first_peak_m"] = float(np.max(p))
    out["square_250kg_delivered_impulse_Ns"] = proto.summary()["delivered_impulse_Ns"]
    from blastscale.similitude import design_model

    d = design_model(250.0, 10.0, lam)
    spec_col = col.scaled(scaling_factors(lam))
    spec = simulate_structure(spec_col, make_load("A", spec_col, d.specimen), 8.0 * lt, record_every=20)
    s = _top_x(spec, lam)
    out["column_specimen_1_100_first_peak_ratio"] = float(np.max(s) / np.max(p))
    out["column_specimen_1_100_max_rotation_ratio"] = (
        spec.summary()["max_rotation_rad"] / proto.summary()["max_rotation_rad"]
    )
    out["column_specimen_1_100_8s_max_diff_rel_peak"] = float(np.max(np.abs(s - p)) / np.max(np.abs(p)))
    c = default_contact(col)
    half = ContactSettings(
        friction=c.friction, time_constant=c.time_constant, friction_time_constant=None, timestep=c.timestep / 2
    )
    ph = _top_x(simulate_structure(col, load, 1.0, contact=half, record_every=8))
    out["timestep_halving_first_peak_change"] = float(np.max(ph) / np.max(p) - 1.0)
    blk = RectangularBlock.from_slenderness(10.0, math.radians(15.0), depth=1.0, density=2000.0)
    pb = block_summary(
        run_block(
            blk, blast_parameters(50.0, 2.0, blast_model="masi2021").pulse(), 3.0, default_contact(blk), record_every=10
        )
    )
    sb = block_summary(
        run_block(
            blk.scaled(scaling_factors(1 / 200)),
            blast_parameters(2.3318e-7, 0.01, blast_model="masi2021").pulse(),
            0.2121,
            None,
            record_every=10,
        )
    )
    out["block_prototype_max_rotation_rad"] = pb["max_rotation_rad"]
    out["block_specimen_1_200_max_rotation_rad"] = sb["max_rotation_rad"]
    out["block_specimen_1_200_max_sliding_upscaled_m"] = sb["max_sliding_m"] * 200
    out["block_prototype_max_sliding_m"] = pb["max_sliding_m"]
    return out


class GridBaseBox(BoxShape):
    """A box whose contact with the ground is a 5 x 5 grid of 2 mm spheres on its base
    (25 contact points instead of box-plane's 4 corners); the spheres carry no mass."""

    n = 5

    @property
    def support_radius(self):
        """Half-extent of the base along x and y [m] (the structure geometry's, for the collapse check)."""
        return (self.half_width, self.half_depth)

    @property
    def radius(self):
        """2 mm on the 0.5 m high squat block, scaled with the block (the engine runs in reference units)."""
        return 8e-3 * self.half_height

    def _points(self):
        xs = np.linspace(-self.half_width + self.radius, self.half_width - self.radius, self.n)
        ys = np.linspace(-self.half_depth + self.radius, self.half_depth - self.radius, self.n)
        return [(x, y) for x in xs for y in ys]

    def contact_geoms(self, name):
        return [f"{name}_s{k}" for k in range(self.n * self.n)]

    def mjcf_geom(self, name):
        z = -self.half_height + self.radius
        spheres = "".join(
            f'<geom name="{name}_s{k}" type="sphere" size="{float(self.radius)!r}" pos="{float(x)!r} {float(y)!r} {float(z)!r}" density="0" '
            'contype="0" conaffinity="0"/>'
            for k, (x, y) in enumerate(self._points())
        )
        return super().mjcf_geom(name) + spheres


class GridBaseBlock(RectangularBlock):
    """The block whose engine shape is a :class:`GridBaseBox` (the structure interface hands an
    engine shape to the scene as it is; scaling keeps the class)."""

    @property
    def bodies(self):
        (body,) = super().bodies
        g = body.shape
        return (replace(body, shape=GridBaseBox(g.half_width, g.half_depth, g.half_height, self.density, g.centre_z)),)


def _hop_case(
    contact: ContactSettings, mode: str, v0: float = 1.8, initial_velocity: bool = False, block_type=RectangularBlock
) -> dict:
    blk = block_type(SQUAT_BLOCK.height, SQUAT_BLOCK.width, SQUAT_BLOCK.depth, SQUAT_BLOCK.density)
    if initial_velocity:
        resp = run_block(blk, None, 0.5, contact, blast_mode=mode, initial_velocity=(v0, 0.0, 0.0))
    else:
        i = v0 * blk.mass / blk.front_area
        resp = run_block(blk, Triangular(2 * i / 1e-3, i), 0.5, contact, blast_mode=mode)
    r, ds = block_summary(resp), block_dataset(resp)
    com_z = ds["com_z"].values[:, 0]
    expected = v0**2 / (2 * contact.friction * 9.81)
    return {
        "max_uplift_mm": 1e3 * r["max_uplift_m"],
        "com_rise_mm": 1e3 * float(com_z.max() - com_z[0]),
        "peak_velocity_x_m_s": float(ds["velocity_x"].values.max()),
        "max_rotation_rad": r["max_rotation_rad"],
        "sliding_error_pct": 100 * (r["final_sliding_m"] / expected - 1),
    }


def hop_study() -> dict:
    """Each hypothesis of the spurious hop, measured (1 m x 1 m x 0.5 m block, mu = 0.7, 1.8 m/s)."""
    raw = ContactSettings(friction=0.7, friction_time_constant=None)  # MuJoCo: friction shares solref
    cases = {
        "blast as force, MuJoCo friction reference (baseline)": (raw, "force", False),
        "  timestep 50 us": (ContactSettings(friction=0.7, friction_time_constant=None, timestep=5e-5), "force", False),
        "  contact time constant 1 ms": (
            ContactSettings(friction=0.7, friction_time_constant=None, time_constant=1e-3, timestep=1e-4),
            "force",
            False,
        ),
        "  contact time constant 4 ms": (
            ContactSettings(friction=0.7, friction_time_constant=None, time_constant=4e-3),
            "force",
            False,
        ),
        "  contact time constant 20 ms": (
            ContactSettings(friction=0.7, friction_time_constant=None, time_constant=2e-2),
            "force",
            False,
        ),
        "  impratio 1": (ContactSettings(friction=0.7, friction_time_constant=None, impratio=1.0), "force", False),
        "  impratio 100": (ContactSettings(friction=0.7, friction_time_constant=None, impratio=100.0), "force", False),
        "  pyramidal cone": (
            ContactSettings(friction=0.7, friction_time_constant=None, cone="pyramidal"),
            "force",
            False,
        ),
        "  noslip 20 iterations": (
            ContactSettings(friction=0.7, friction_time_constant=None, noslip_iterations=20),
            "force",
            False,
        ),
        "  solimp width 10 mm": (
            ContactSettings(friction=0.7, friction_time_constant=None, impedance_width=1e-2),
            "force",
            False,
        ),
        "  solimp dmax 0.99": (
            ContactSettings(friction=0.7, friction_time_constant=None, impedance_min=0.95, impedance_max=0.99),
            "force",
            False,
        ),
        "  damping ratio 0.5": (
            ContactSettings(friction=0.7, friction_time_constant=None, damping_ratio=0.5),
            "force",
            False,
        ),
        "  friction time constant 20 ms": (ContactSettings(friction=0.7), "force", False),
        "  25-point base (5 x 5 spheres)": (raw, "force", False, GridBaseBlock),
        "blast as momentum kick, MuJoCo friction reference": (raw, "kick", False),
        "blast as momentum kick, friction time constant 20 ms": (ContactSettings(friction=0.7), "kick", False),
        "default: auto (force if sticking, kick if sliding), 20 ms": (ContactSettings(friction=0.7), "auto", False),
        "initial velocity, no blast, MuJoCo friction reference": (raw, "auto", True),
        "initial velocity, no blast, friction time constant 20 ms": (ContactSettings(friction=0.7), "auto", True),
    }
    return {name: _hop_case(c, mode, 1.8, *v) for name, (c, mode, *v) in cases.items()}


#: Plain force mode is accurate with a normal contact much harder than the pulse (tau << t_o)
#: and a fine step; friction keeps its default 20 ms reference (docs/sim3d.md).
HARD = dict(time_constant=2e-5, timestep=2e-6)


def _after_pulse(block, pulse, contact: ContactSettings, mode: str) -> dict:
    """COM velocity x and angular velocity at the first recorded time after the load steps."""
    t_end = pulse.duration + contact.timestep
    resp = run_block(block, pulse, t_end + 2 * contact.timestep, contact, blast_mode=mode)
    r = block_dataset(resp)
    t, vx, om = r["time"].values, r["velocity_x"].values[:, 0], r["angular_velocity_y"].values[:, 0]
    k = int(np.searchsorted(t, t_end))
    exact = pulse.impulse * block.front_area / block.mass - contact.friction * 9.81 * t[k]
    return {
        "velocity_x_m_s": float(vx[k]),
        "velocity_error_pct": 100 * (vx[k] / exact - 1),
        "angular_velocity_rad_s": float(om[k]),
        "kick_steps": int(resp.dataset.attrs["setting_kick_steps"]),
    }


def mode_study(mus=(0.7, 0.9, 1.2, 1.4, 1.5, 1.58, 1.62, 1.65, 1.7, 2.0)) -> dict:
    """blast_mode "auto" (default contact, dt = 0.2 ms) against plain "force" (default contact,
    dt = 0.2 ms and 10 us) and "force" with a hard contact (tau = 20 us, dt = 2 us).

    ``after_pulse``: the 1 m squat block (1.8 m/s) and the paper's block (50 kg at 2 m), mu = 0.7,
    velocity right after the pulse vs the rigid-body I S / m - mu g t (pure slip).
    ``peak_rotation``: the paper's block, 50 kg at 2 m, 1.5 s, for mu around mu* = 1.60.
    """
    i = 1.8 * SQUAT_BLOCK.mass / SQUAT_BLOCK.front_area
    paper = blast_parameters(50.0, 2.0, blast_model="masi2021").pulse("friedlander")
    variants = {
        "auto, default contact, dt 0.2 ms": ({}, "auto"),
        "force, default contact, dt 0.2 ms": ({}, "force"),
        "force, default contact, dt 10 us": ({"timestep": 1e-5}, "force"),
        "force, hard contact (tau 20 us), dt 2 us": (HARD, "force"),
    }
    after = {
        case: {
            name: _after_pulse(blk, p, ContactSettings(friction=0.7, **kw), mode)
            for name, (kw, mode) in variants.items()
        }
        for case, blk, p in (
            ("squat 1.8 m/s", SQUAT_BLOCK, Triangular(2 * i / 1e-3, i)),
            ("paper block 50 kg at 2 m", PAPER_BLOCK, paper),
        )
    }
    peak = {}
    for mu in mus:
        with warnings.catch_warnings():  # the near-mu* warning is what this study measures
            warnings.simplefilter("ignore", RuntimeWarning)
            ra = run_block(PAPER_BLOCK, paper, 1.5, ContactSettings(friction=mu), blast_mode="auto")
        h = block_summary(
            run_block(
                PAPER_BLOCK, paper, 1.5, ContactSettings(friction=mu, **HARD), blast_mode="force", record_every=50
            )
        )
        a = block_summary(ra)
        peak[f"mu={mu:g}"] = {
            "auto_rad": a["max_rotation_rad"],
            "hard_force_rad": h["max_rotation_rad"],
            "difference_pct": 100 * (a["max_rotation_rad"] / h["max_rotation_rad"] - 1),
            "auto_kick_steps": int(ra.dataset.attrs["setting_kick_steps"]),
        }
    return {"after_pulse": after, "peak_rotation": peak}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="one repeat, shorter runs (~1 minute in all)")
    ap.add_argument("--hop-study", action="store_true", help="also run the spurious-hop study")
    ap.add_argument("--mode-study", action="store_true", help="also compare blast modes (auto vs force)")
    ap.add_argument("--acceptance", action="store_true", help="also measure the full-length figures of issue 8")
    a = ap.parse_args()
    out = {"machine": platform.processor() or platform.machine(), "python": platform.python_version()}
    import mujoco

    out["mujoco"] = mujoco.__version__
    out["load_average"] = os.getloadavg()[0]
    out["speed"] = speed(1 if a.quick else a.repeat)
    for section in ("square", "circular"):
        out["speed"][f"column_{section}"] = column_speed(section, max(1, a.repeat // 3), 2.0 if a.quick else 4.0)
    out.update(
        {
            k: f(a.quick)
            for k, f in (
                ("ensemble", bench_scale.ensemble),
                ("sweep3d", bench_scale.sweep3d),
                ("blocks", bench_scale.blocks),
            )
        }
    )
    if a.acceptance:
        out["acceptance"] = acceptance()
    if a.hop_study:
        out["hop_study"] = hop_study()
    if a.mode_study:
        out["mode_study"] = mode_study()
    if a.json:
        print(json.dumps(out, indent=2))
        return
    for k, v in out["speed"].items():
        if k.startswith("column_"):
            for kind, w in v.items():
                if "timestep_s" not in w:  # the sparse- and dense-Jacobian runs: speed-up, agreement
                    extra = (
                        (
                            f", x{w['speedup_vs_dense']:.2f} vs dense, top history within "
                            f"{w['max_abs_top_diff_vs_dense_rel_peak']:.1e} of the peak"
                        )
                        if "speedup_vs_dense" in w
                        else ""
                    )
                    print(f"{k} {kind}: {w['simulated_s_per_wall_s']:.2f} simulated s / wall s{extra}")
                    continue
                print(
                    f"{k} {kind:9s} dt = {w['timestep_s']:.3g} s: {w['simulated_s_per_wall_s']:8.2f} simulated s / wall s "
                    f"({w['prototype_equivalent_s_per_wall_s']:.2f} prototype s / wall s)"
                )
            continue
        print(
            f"{k:12s} dt = {v['timestep_s']:.3g} s: {v['simulated_s_per_wall_s']:8.2f} simulated s / wall s "
            f"({v['prototype_equivalent_s_per_wall_s']:.2f} prototype s / wall s, {v['steps_per_wall_s']:.0f} steps/s)"
        )
    for k in ("ensemble", "sweep3d", "blocks"):
        print(k, json.dumps(out[k]))
    for k, v in out.get("hop_study", {}).items():
        print(
            f"{k:60s} uplift {v['max_uplift_mm']:7.3f} mm  v_x peak {v['peak_velocity_x_m_s']:.4f} m/s  "
            f"rot {v['max_rotation_rad']:.1e} rad  sliding err {v['sliding_error_pct']:+.2f}%"
        )
    for k, v in out.get("acceptance", {}).items():
        print(f"{k:48s} {v}")
    ms = out.get("mode_study")
    if ms:
        for case, rows in ms["after_pulse"].items():
            for name, v in rows.items():
                print(
                    f"{case:26s} {name:42s} v_x {v['velocity_x_m_s']:.4f} m/s ({v['velocity_error_pct']:+.2f}% vs "
                    f"I S/m - mu g t)  omega {v['angular_velocity_rad_s']:+.4f} rad/s  kicks {v['kick_steps']}"
                )
        for mu, v in ms["peak_rotation"].items():
            print(
                f"paper block 50 kg, {mu:8s} peak rotation auto {v['auto_rad']:.5f}  hard force {v['hard_force_rad']:.5f} "
                f"rad ({v['difference_pct']:+.2f}%)  kicks {v['auto_kick_steps']}"
            )


if __name__ == "__main__":
    main()
