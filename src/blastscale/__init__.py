"""blastscale: design reduced-scale blast experiments on masonry structures.

Implements the scaling laws of Masi, Stefanou & Maffi-Berthier, *Scaling laws for the
rigid-body response of masonry structures under blast loads*, with blast loads
(Kingery-Bulmash / Swisdak 1994 and the paper's Appendix A fits), similitude design,
planar rocking and 3D rigid-body response (MuJoCo).

All quantities inside the library are SI: m, kg, s, Pa, Pa*s, rad.
"""

__version__ = "0.1.0"
