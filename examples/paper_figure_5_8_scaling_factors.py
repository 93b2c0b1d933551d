"""Paper Figures 5 and 8: blast scaling factors vs the geometric scale and the density ratio.

Figure 5 ("Scaling factors of overpressure (a), scaled distance (b), and impulse (c), in
function of the geometric scaling factor"): prototype 50 kg TNT at 2 m, same material
(gamma = 1), lambda from 1/1000 to 1. Figure 8: the same factors vs the density ratio gamma,
for lambda = 1/20 and 1/200 and W = 50 kg. General law (paper Eq. 8) solid, Hopkinson-Cranz
dashed, as in the paper; the paper's own fits (``masi2021``, Appendix A).

What to look for
----------------
* Fig. 5: under the general law the model's scaled distance grows as lambda shrinks
  (lambda_Z = 2.99 at 1/200), so the model sees a *lower* overpressure (5.8 % of the
  prototype's at 1/200) and an impulse of lambda^1.5 (0.035 %); Hopkinson-Cranz keeps the
  pressure (100 %) and gives an impulse of lambda (0.5 %). (The paper's text says 0.3 % and
  5 %: 10x its own law, docs/paper_slips.md #5.)
* Fig. 8: a lighter model material (gamma < 1) lowers pressure and impulse further: at
  lambda = 1/200, gamma = 0.05 gives 0.19 % of the prototype pressure (paper: 0.18 %).
  Hopkinson-Cranz does not depend on gamma (it imposes gamma = 1/sqrt(lambda)): flat dashed lines.
* The gamma curves stop where the model's scaled distance would leave the range where every
  fit holds (masi2021: Z <= 6.5 m/kg^(1/3), the duration fit): those points are NaN
  (``ScalingCurves.valid`` is False), not extrapolated. The script prints where.

Writes ``figure_5_scaling_factors_vs_lambda.png`` and ``figure_8_scaling_factors_vs_gamma.png``.
Run time: about 1 s.

Usage: ``python examples/paper_figure_5_8_scaling_factors.py [OUT]`` (default ./results/examples).
"""

from __future__ import annotations

import numpy as np
from _gallery import done, parse_args, save

from blastscale.plots.similitude import scaling_factors_figure
from blastscale.similitude.curves import scaling_curves

W, R, MODEL = 50.0, 2.0, "masi2021"


def main() -> None:
    args = parse_args(__doc__)

    # Figure 5: vs lambda, gamma = 1
    lam = np.logspace(-3, 0, 121)
    c5 = scaling_curves(W, R, lam, 1.0, blast_model=MODEL)
    fig = scaling_factors_figure(c5, x="scale", labels=["gamma = 1"])
    fig.suptitle(f"Fig. 5: scaling factors vs lambda, prototype {W:g} kg at {R:g} m ({MODEL})")
    save(fig, args.out, "figure_5_scaling_factors_vs_lambda.png")
    for lam_k in (1 / 20, 1 / 200):
        p = scaling_curves(W, R, lam_k, 1.0, blast_model=MODEL)
        print(
            f"lambda = 1/{1 / lam_k:.0f}, gamma = 1: lambda_Z = {float(p.scaled_distance_factor):.4f}, "
            f"pressure {100 * float(p.pressure_ratio):.3f} %, impulse {100 * float(p.impulse_ratio):.4f} %, "
            f"duration {100 * float(p.duration_ratio):.3f} % | Hopkinson-Cranz: pressure 100 %, "
            f"impulse {100 * float(p.hc_impulse_ratio):.3f} %"
        )

    # Figure 8: vs gamma, lambda = 1/20 and 1/200
    gam = np.logspace(-2, 0, 121)
    runs = [scaling_curves(W, R, lam_k, gam, blast_model=MODEL) for lam_k in (1 / 20, 1 / 200)]
    fig = scaling_factors_figure(runs, x="density_ratio", labels=["lambda = 1/20", "lambda = 1/200"])
    fig.suptitle(
        f"Fig. 8: scaling factors vs gamma, prototype {W:g} kg at {R:g} m ({MODEL}); "
        "curves end where the model Z leaves the fits"
    )
    save(fig, args.out, "figure_8_scaling_factors_vs_gamma.png")
    for c in runs:
        lam_k = float(c.scale[0])
        g_min = float(c.density_ratio[c.valid].min())
        print(
            f"lambda = 1/{1 / lam_k:.0f}: general law solvable inside the fits for gamma >= {g_min:.3g} "
            f"(model Z <= {c.z_range[1]:g} m/kg^(1/3)); {int((~c.valid).sum())} of {c.valid.size} points NaN"
        )
    p = scaling_curves(W, R, 1 / 200, [1.0, 0.07, 0.05], blast_model=MODEL)
    print(
        "lambda = 1/200: pressure ratio "
        + ", ".join(f"gamma = {g:g}: {100 * x:.3f} %" for g, x in zip(p.density_ratio, p.pressure_ratio))
    )
    done(args)


if __name__ == "__main__":
    main()
