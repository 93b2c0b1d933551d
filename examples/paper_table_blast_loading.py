"""Paper Table "Blast loading characteristics": model charges and scaled distances.

Reproduces the table of Masi, Stefanou & Maffi-Berthier (Sec. "Equations of motion", similar
materials): the 10 m block (alpha = 15 deg, 2000 kg/m^3) at R = 2 m for W = 50, 100 and 79.8 kg,
and its two models, lambda = 1/20 (model 1) and 1/200 (model 2), gamma = 1, designed with the
general law (paper Eq. 8). Both blast models are computed: ``masi2021`` (the paper's Appendix A
fits, which the table uses) and ``kingery-bulmash`` (Swisdak 1994, blastscale's default).

What to look for
----------------
* The mantissas of the paper's table (1.0, 2.06, 1.635 and 0.233, 0.492, 0.386) come out of the
  ``masi2021`` rows, but in **g** for model 1 and **mg** for model 2: the paper prints mg and
  ug (a factor 1000 slip, docs/paper_slips.md #4). The paper truncates the scaled distances
  (0.9985 -> 0.99).
* The non-slender case of the FE section, 2500 kg at 3 m, lambda = 1/200: 14.27 mg (paper 14.26 mg).
* Kingery-Bulmash gives model charges 2-4 % (lambda = 1/20) and 6-8 % (1/200) below the paper's fits.

Writes ``table_blast_loading.png`` (the table drawn) and ``table_blast_loading.csv``.
Run time: about 1 s.

Usage: ``python examples/paper_table_blast_loading.py [OUT]`` (default ./results/examples).
"""

from __future__ import annotations

import csv

from _gallery import done, parse_args, plt, save

from blastscale.similitude import design_model

CHARGES = (50.0, 100.0, 79.8)  # paper cases (a), (b), (c) [kg]
STANDOFF = 2.0  # [m]
SCALES = ((1 / 20, "g", 1e3), (1 / 200, "mg", 1e6))  # (lambda, unit of the model charge, kg -> unit)
MODELS = ("masi2021", "kingery-bulmash")


def rows(model: str) -> list[list]:
    """One row per prototype charge: W, Z_p, then (W_m, Z_m) for each model scale."""
    out = []
    for W in CHARGES:
        row = [model, W, None]
        for lam, _, k in SCALES:
            d = design_model(W, STANDOFF, lam, 1.0, blast_model=model)
            row[2] = d.prototype.scaled_distance
            row += [d.specimen_charge_kg * k, d.specimen.scaled_distance]
        out.append(row)
    return out


def main() -> None:
    args = parse_args(__doc__)
    header = [
        "blast model",
        "W_p [kg]",
        "Z_p [m/kg^1/3]",
        "W_m1 [g] (1/20)",
        "Z_m1 [m/kg^1/3]",
        "W_m2 [mg] (1/200)",
        "Z_m2 [m/kg^1/3]",
    ]
    table = [r for m in MODELS for r in rows(m)]
    print("Blast loading characteristics (R = 2 m, gamma = 1, general law)")
    print("paper prints model 1 in mg and model 2 in ug: the correct units are g and mg")
    print(" | ".join(header))
    for r in table:
        print(f"{r[0]:>15} | {r[1]:6.1f} | {r[2]:.4f} | {r[3]:7.4f} g | {r[4]:.4f} | {r[5]:7.4f} mg | {r[6]:.4f}")
    ns = design_model(2500.0, 3.0, 1 / 200, 1.0, blast_model="masi2021")
    print(
        f"non-slender block, 2500 kg at 3 m, lambda = 1/200 (masi2021): model charge "
        f"{ns.specimen_charge_kg * 1e6:.4f} mg (paper 14.26 mg, truncated), Z_m = {ns.specimen.scaled_distance:.4f}"
    )

    with open(args.out / "table_blast_loading.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(table)
    print(f"wrote {args.out / 'table_blast_loading.csv'}")

    fig, ax = plt.subplots(figsize=(11, 3.2), layout="constrained")
    ax.axis("off")
    cells = [
        [r[0], f"{r[1]:g}", f"{r[2]:.3f}", f"{r[3]:.4g}", f"{r[4]:.3f}", f"{r[5]:.4g}", f"{r[6]:.3f}"] for r in table
    ]
    cells.append(
        [
            "masi2021",
            "2500 (R = 3 m)",
            f"{ns.prototype.scaled_distance:.3f}",
            "-",
            "-",
            f"{ns.specimen_charge_kg * 1e6:.4g}",
            f"{ns.specimen.scaled_distance:.3f}",
        ]
    )
    t = ax.table(cellText=cells, colLabels=header, loc="center", cellLoc="center")
    t.auto_set_font_size(False)
    t.set_fontsize(9)
    t.scale(1.0, 1.4)
    ax.set_title(
        "Blast loading characteristics, prototype R = 2 m, gamma = 1 (model charges in g and mg: "
        "the paper's mg and ug are a 1000x slip)",
        fontsize=10,
    )
    save(fig, args.out, "table_blast_loading.png")
    done(args)


if __name__ == "__main__":
    main()
