"""Pressure-impulse (P-I) overturning diagram of the paper's block for the three pulse shapes.

Not a figure of the paper, but its overturning results in one picture: the 10 m block
(alpha = 15 deg, 2000 kg/m^3, planar rocking, paper Eq. eom with Housner impacts). For a peak
reflected pressure P, the critical impulse i_c(P) just overturns the block; pulses above and
to the right of a curve overturn it. Three pulse shapes: triangular (paper Eq. 3, cut at 2 i/P),
Friedlander (paper Eq. 1, decay d = 1) and impulsive (the vertical asymptote
i = J_o theta_dot_c / (S l), reached by both curves at high pressure). The horizontal asymptote
is the uplift pressure (P S h = m g b). The blast path of the paper's scenario (charges from
10 to 500 kg at R = 2 m, ``masi2021``) is drawn over it, with the paper's 50, 79.8 and 100 kg marked.

What to look for
----------------
* At these pressures (tens of MPa, hundreds of times the uplift pressure) the curves have
  joined the impulsive asymptote: the load is impulsive (t_o p ~ 1e-3), the premise of the
  general scaling law.
* The blast path crosses the asymptote between 50 and 100 kg; the critical charges printed
  for the three shapes (critical_charge, Friedlander with the fitted decay, triangular,
  impulsive) are 79.84-79.87 kg: the paper's 79.8 kg, insensitive to the pulse shape.

Writes ``pi_diagram.png``. Run time: about 3 s (``--quick``: 8 pressures instead of 30, about 1 s).

Usage: ``python examples/pi_diagram.py [OUT] [--quick]`` (default ./results/examples).
"""

from __future__ import annotations

import math

import numpy as np
from _gallery import done, parse_args, plt, save

from blastscale.blast import blast_parameters
from blastscale.plots.rocking import plot_pi_diagram
from blastscale.rocking import RockingSystem, critical_charge, pi_diagram
from blastscale.structures import RectangularBlock

BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0), density=2000.0)
STANDOFF, MODEL = 2.0, "masi2021"


def main() -> None:
    args = parse_args(__doc__, quick_help="8 peak pressures per curve instead of 30")
    n = 8 if args.quick else 30
    system = RockingSystem.from_block(BLOCK)
    curves = {shape: pi_diagram(system, n=n, shape=shape) for shape in ("triangular", "friedlander")}
    pi = curves["triangular"]
    print(f"uplift pressure {pi.pressure_asymptote:.4g} Pa, impulsive asymptote {pi.impulse_asymptote:.4g} Pa s")
    for shape in ("friedlander", "triangular", "impulsive"):
        c = critical_charge(system, STANDOFF, pulse_shape=shape, blast_model=MODEL)
        print(f"critical charge at {STANDOFF:g} m ({shape} pulse, {MODEL}): {c.charge_kg:.3f} kg")

    fig, ax = plt.subplots(figsize=(8, 6), layout="constrained")
    plot_pi_diagram(curves["triangular"], ax=ax, label="critical, triangular pulse")
    plot_pi_diagram(curves["friedlander"], ax=ax, label="critical, Friedlander pulse (d = 1)", asymptotes=False)
    ax.lines[-1].set_linestyle("-.")
    W = np.logspace(1, math.log10(500.0), 60)
    bp = blast_parameters(W, STANDOFF, MODEL)
    ax.plot(
        bp.reflected_impulse, bp.reflected_pressure, color="C3", lw=1, label=f"blast at R = {STANDOFF:g} m, 10-500 kg"
    )
    for Wk, offset in ((50.0, (6, -12)), (79.8, (-48, 6)), (100.0, (6, -12))):  # label offsets [points]
        b = blast_parameters(Wk, STANDOFF, MODEL)
        ax.plot(b.reflected_impulse, b.reflected_pressure, "o", color="C3", ms=4)
        ax.annotate(
            f"{Wk:g} kg",
            (b.reflected_impulse, b.reflected_pressure),
            textcoords="offset points",
            xytext=offset,
            fontsize=8,
            color="C3",
        )
    ax.set_xlim(0.5 * pi.impulse_asymptote, None)
    ax.legend(fontsize="small", loc="center right")
    ax.set_title(
        "P-I overturning diagram, 10 m block (alpha = 15 deg, 2000 kg/m^3)\n"
        "impulsive pulse = vertical asymptote; curves to the right overturn"
    )
    save(fig, args.out, "pi_diagram.png")
    done(args)


if __name__ == "__main__":
    main()
