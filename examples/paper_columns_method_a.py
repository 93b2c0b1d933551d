"""Paper Sec. 6 (Figs. of the multi-drum columns, Method A): prototype vs 1/100 model on MuJoCo.

The paper's columns (10 m, ten 1 m drums, 1.65 -> 1.28 m, marble 2700 kg/m^3, friction 0.7),
loaded by Method A (the reflected pulse, uniform and simultaneous on every drum's front face;
Kingery-Bulmash, Friedlander pulse), and their lambda = 1/100 models (gamma = 1) designed by the
general law, run at their own size and up-scaled: each case a scenario run by the Study (the
collapse thresholds through prototype-only scenarios of the prototype and of the specimen):

* square section, 250 kg and 500 kg at 10 m; circular section (32-gon drums), 200 kg and 400 kg
  at 10 m; 8 s of prototype time. Per case: outcome, first peak and similarity at every
  monitoring point (P-1 base drum ... P-10 top drum), and a figure of the horizontal
  displacement and velocity of P-1, P-3, P-5, P-7, P-10 (prototype solid, model dashed) with
  pose snapshots (``figure_column_<section>_<W>kg.png``);
* the collapse thresholds of the prototype and of the model (bisection on the prototype charge,
  +-10 kg);
* ensembles (8 runs each, load x (1 + 1e-6 u), u in [-1, 1]) of the circular cases and of the
  square 250 kg case: first peak mean and spread, envelopes, collapse probability, noise floor
  and horizon (``figure_column_ensemble_<section>_<W>kg.png``).

All numbers go to ``paper_columns_method_a.json`` in the output folder; docs/columns.md gives them.

What to look for
----------------
* Square columns: the up-scaled model lies on the prototype: top first peak 0.2796 / 0.2808 m at
  250 kg (ratio 1.0043; 1.065 / 1.069 m at 500 kg), within 2.7 % (250 kg) and 8.8 % (500 kg) of
  the peak over 8 s, the lower drums differing most, as the paper says; 8-member ensembles show
  a noise floor of 1.7 % of the peak (not chaotic).
* Circular columns: the first peak is reproduced (top 0.3381 / 0.3429 m at 200 kg), then the
  histories part; the prototype's own ensemble parts by > 5 % of the peak after 2.9 s and by
  94 % within 8 s, so from there on only envelopes and collapse probabilities can be compared.
  400 kg collapses in every member of both ensembles (the model 0.25 s early).
* Collapse thresholds (prototype and model alike): square 544-562 kg, circular 388-400 kg.

Run time: about 15-18 min on the shared 2-core machine (measured 883 s and 1063 s;
``--quick``: a 3-drum column for 0.5 s, about 5 s).

Usage: ``python examples/paper_columns_method_a.py [OUT] [--quick]`` (default ./results/examples).
"""

from __future__ import annotations

import json

from _gallery import done, parse_args, plt, save

from blastscale.plots.column import plot_column_comparison, plot_ensemble_envelope
from blastscale.scenario import Scenario
from blastscale.study import Study

SCALE, GAMMA, STANDOFF, MODEL = 1 / 100, 1.0, 10.0, "kingery-bulmash"
CASES = (("square", 250.0), ("square", 500.0), ("circular", 200.0), ("circular", 400.0))
#: bisection brackets [kg] (collapse expected inside; widened if not)
BRACKETS = {"square": (300.0, 900.0), "circular": (200.0, 600.0)}
SHOWN_POINTS = ("P-1", "P-3", "P-5", "P-7", "P-10")
#: the paper's column (the scenario's defaults: 10 drums, 10 m, 1.65 -> 1.28 m, marble, friction 0.7)
PAPER = {"kind": "column"}
#: --quick: a 3-drum column (the paper's taper over 3 m), 16-gon circular drums
SHORT = {"kind": "column", "drums": 3, "height_m": 3.0, "base_width_m": 1.65, "top_width_m": 1.54, "sides": 16}


def scenario(
    column: dict,
    section: str,
    charge: float,
    duration: float,
    record_every: int,
    scale=SCALE,
    ensemble_members: int = 0,
) -> Scenario:
    """The case as a scenario: the column, ``charge`` [kg] at 10 m (Kingery-Bulmash, Friedlander,
    Method A), the 1/100 specimen (gamma = 1; ``scale`` None: the prototype alone), the 3D engine."""
    data = {
        "title": f"{section} column, {charge:g} kg at {STANDOFF:g} m",
        "structure": {**column, "section": section},
        "blast": {"charge_kg": charge, "standoff_m": STANDOFF, "model": MODEL},
        "simulation": {
            "engine": "3d",
            "duration_s": duration,
            "record_every": record_every,
            "ensemble_members": ensemble_members,
            "critical_charge": False,
        },
    }
    if scale is not None:
        data["scale"] = {"length": scale, "density_ratio": GAMMA}
    return Scenario.from_dict(data)


def specimen_scenario(column: dict, section: str, charge: float, duration: float, record_every: int) -> Scenario:
    """The specimen of the case alone, at its own size: a prototype-only scenario of the scaled
    column (lengths x lambda, density x gamma) under the model charge and stand-off that the case's
    design gives (the general law), for the specimen's duration (x lambda_t)."""
    sc = scenario(column, section, charge, duration, record_every)
    study = Study(sc)
    d, col = study.design(), study.structure().scaled(study.design().factors)
    spec = {
        "kind": "column",
        "section": section,
        "drums": col.drums,
        "height_m": col.height,
        "base_width_m": col.base_width,
        "top_width_m": col.top_width,
        "sides": col.sides,
        "density_kg_m3": col.density,
    }
    return Scenario.from_dict(
        {
            "title": f"{sc.title}: the 1/100 specimen alone",
            "structure": {k: v for k, v in spec.items() if v is not None},
            "blast": {"charge_kg": d.specimen_charge_kg, "standoff_m": d.specimen_standoff_m, "model": MODEL},
            "simulation": {
                "engine": "3d",
                "duration_s": duration * d.factors.time,
                "record_every": record_every,
                "critical_charge": False,
            },
        }
    )


def collapses(column, section, charge, duration, record_every, system):
    """Outcome of the prototype ("prototype") or of the specimen ("model") at a prototype charge:
    one prototype-only study of that system alone."""
    sc = (
        scenario(column, section, charge, duration, record_every, scale=None)
        if system == "prototype"
        else specimen_scenario(column, section, charge, duration, record_every)
    )
    return bool(Study(sc).run().summary()["3d"]["prototype"]["collapsed"])


def threshold(column, section, lo, hi, duration, record_every, system, tol=10.0):
    """Bisection on the prototype charge: (largest charge seen standing, smallest seen collapsing)."""
    args = (column, section)
    while collapses(*args, lo, duration, record_every, system) and lo > 10.0:
        lo, hi = lo / 2.0, lo
    while not collapses(*args, hi, duration, record_every, system) and hi < 1e4:
        lo, hi = hi, hi * 2.0
    while hi - lo > 2.0 * tol:
        mid = 0.5 * (lo + hi)
        if collapses(*args, mid, duration, record_every, system):
            hi = mid
        else:
            lo = mid
    return lo, hi


def main() -> None:
    args = parse_args(__doc__, quick_help="a 3-drum column for 0.5 s, 2-member ensembles, no thresholds")
    if args.quick:
        column, duration, n_members, cases = SHORT, 0.5, 2, (("square", 250.0), ("circular", 200.0))
        ens_cases = cases
    else:
        column, duration, n_members, cases = PAPER, 8.0, 8, CASES
        ens_cases = (("square", 250.0), ("circular", 200.0), ("circular", 400.0))
    record_every = 8
    results: dict = {
        "settings": {
            "scale": SCALE,
            "density_ratio": GAMMA,
            "standoff_m": STANDOFF,
            "blast_model": MODEL,
            "pulse": "friedlander",
            "load": "A",
            "duration_s": duration,
        },
        "cases": {},
    }
    ensembles = {}
    for section, W in cases:
        members = n_members if (section, W) in ens_cases else 0  # the ensembles run in the same study
        r = Study(scenario(column, section, W, duration, record_every, ensemble_members=members)).run()
        s = r.summary()["3d"]
        key = f"{section}_{W:g}kg"
        results["cases"][key] = s
        if r.ensemble is not None:
            ensembles[(section, W)] = r
        sim = s["similarity"]
        print(
            f"{section} {W:g} kg: prototype collapsed {s['prototype']['collapsed']}, model collapsed "
            f"{s['model']['collapsed']}, top first peak ratio {sim['top_first_peak_ratio']:.4f}, "
            f"max |top diff| {sim['max_abs_top_displacement_diff_m']:.4g} m "
            f"({100 * sim['max_abs_top_displacement_diff_rel_peak']:.2f} % of the peak)"
        )
        for name, p in sim["points"].items():
            print(
                f"  {name}: first peak {p['first_peak_prototype_m']:.4g} m (model {p['first_peak_model_m']:.4g} m, "
                f"ratio {p['first_peak_ratio']:.4f}), max |diff| {100 * p['max_abs_displacement_diff_rel_peak']:.2f} % "
                "of the peak"
            )
        pts = [p for p in SHOWN_POINTS if p in sim["points"]] or None
        cmp = r.response3d
        fig = plot_column_comparison(r.structure, cmp.prototype_dataset, cmp.upscaled_dataset, points=pts)
        fig.suptitle(
            f"{section} column, {W:g} kg at {STANDOFF:g} m, Method A: prototype (solid) vs "
            f"lambda = 1/100 model up-scaled (dashed)"
        )
        save(fig, args.out, f"figure_column_{key}.png")

    if not args.quick:
        results["thresholds_kg"] = {}
        for section, (lo, hi) in BRACKETS.items():
            for system in ("prototype", "model"):
                a, b = threshold(column, section, lo, hi, duration, record_every, system)
                results["thresholds_kg"][f"{section}_{system}"] = [a, b]
                print(f"collapse threshold, {section}, {system}: between {a:.0f} and {b:.0f} kg (prototype charge)")

    results["ensembles"] = {}
    for (section, W), r in ensembles.items():
        ens, key = r.ensemble, f"{section}_{W:g}kg"
        es = r.summary()["ensemble"]
        results["ensembles"][key] = es
        top = es["points"][ens.points[-1]]
        print(
            f"ensemble {section} {W:g} kg ({n_members} runs, 1e-6): top first peak prototype "
            f"{top['first_peak_prototype_mean_m']:.4g} +- {top['first_peak_prototype_spread_m']:.2g} m, model "
            f"{top['first_peak_model_mean_m']:.4g} +- {top['first_peak_model_spread_m']:.2g} m; noise floor "
            f"{100 * top['noise_floor_rel_peak']:.1f} % of the peak, horizon {top['horizon_prototype_s']:.3g} s; "
            f"collapse probability prototype {es['collapse_probability_prototype']:.2f}, model "
            f"{es['collapse_probability_model']:.2f}"
        )
        fig, ax = plt.subplots(figsize=(9, 5), layout="constrained")
        plot_ensemble_envelope(ens, ax=ax)
        ax.set_title(f"{section} column, {W:g} kg at {STANDOFF:g} m: ensembles of {n_members} (load x (1 +- 1e-6))")
        save(fig, args.out, f"figure_column_ensemble_{key}.png")

    path = args.out / "paper_columns_method_a.json"
    path.write_text(json.dumps(results, indent=1, default=float))
    print(f"wrote {path}")
    done(args)


if __name__ == "__main__":
    main()
