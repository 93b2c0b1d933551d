"""Mass properties of a linearly tapered prism (frustum): the solid of a tapered drum.

A prism of height H whose cross-section is a fixed shape scaled by ``s(z) = s0 + (s1 - s0) z / H``
(side of a square, circumradius of a regular polygon): with section area ``A(z) = a s^2`` and section
second moment about an in-plane centroidal axis ``I(z) = k s^4``,

.. math:: m = \\rho \\int_0^H A\\,dz,\\quad z_c = \\frac{\\int A z\\,dz}{\\int A\\,dz},\\quad
          I_{xx} = I_{yy} = \\rho\\int_0^H [I + A (z - z_c)^2]\\,dz,\\quad I_{zz} = 2\\rho\\int_0^H I\\,dz .

The integrands are polynomials of degree <= 4 in z, so 3-point Gauss-Legendre quadrature is
exact. Square of side s: a = 1, k = 1/12. Regular n-gon of circumradius R:
``a = (n/2) sin(2 pi/n)``, ``k = (n/24) sin(2 pi/n) (2 + cos(2 pi/n))`` (polar moment
``J = (n R^4/12) sin(2 pi/n)(2 + cos(2 pi/n))``, which tends to pi R^4/2 for a circle).

The faces of such a prism (trapezoids in the body frame) are :func:`~.base.tapered_face`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["FrustumMassProperties", "frustum_mass_properties", "polygon_section_constants"]


@dataclass(frozen=True)
class FrustumMassProperties:
    """Mass properties of a linearly tapered prism (module docstring).

    Attributes
    ----------
    mass : float
        [kg].
    volume : float
        [m^3].
    z_com : float
        Height of the centre of mass above the base [m].
    inertia : tuple of float
        (I_xx, I_yy, I_zz) about the centre of mass [kg m^2].
    """

    mass: float
    volume: float
    z_com: float
    inertia: tuple


def polygon_section_constants(sides: int) -> tuple:
    """(a, k) of a regular polygon of circumradius R: area a R^2, centroidal in-plane second
    moment k R^4 [-] (module docstring)."""
    n = int(sides)
    s2 = math.sin(2.0 * math.pi / n)
    return 0.5 * n * s2, n * s2 * (2.0 + math.cos(2.0 * math.pi / n)) / 24.0


def frustum_mass_properties(
    s0: float, s1: float, height: float, density: float, a: float = 1.0, k: float = 1.0 / 12.0
) -> FrustumMassProperties:
    """Exact mass properties of a frustum whose section size tapers linearly from s0 to s1.

    Parameters
    ----------
    s0, s1 : float
        Section size at the base and at the top [m] (side of a square, circumradius of a polygon).
    height : float
        Height H [m].
    density : float
        rho [kg/m^3].
    a, k : float
        Section constants: area a s^2 [m^2], in-plane centroidal second moment k s^4 [m^4]
        (square: 1, 1/12; polygon: :func:`polygon_section_constants`).

    Returns
    -------
    FrustumMassProperties
    """
    x, w = np.polynomial.legendre.leggauss(3)  # exact for degree <= 5
    z = 0.5 * height * (x + 1.0)
    w = 0.5 * height * w
    s = s0 + (s1 - s0) * z / height
    A = a * s**2
    vol = float(w @ A)
    zc = float(w @ (A * z)) / vol
    sec = k * s**4
    ixx = density * float(w @ (sec + A * (z - zc) ** 2))
    izz = density * 2.0 * float(w @ sec)
    return FrustumMassProperties(density * vol, vol, zc, (ixx, ixx, izz))
