"""The rocking system: a rigid body on a rigid base, loaded on its front face (planar).

Paper Eq. (eq:eom) (Masi, Stefanou & Maffi-Berthier, Sec. "Equations of motion"), written for
a general body:

.. math::

    J_o \\ddot\\theta + m g r \\sin(\\alpha\\,\\mathrm{sgn}\\theta - \\theta)
    = S\\,\\ell\\,P(t)\\,\\frac{\\cos(\\alpha\\,\\mathrm{sgn}\\theta - \\theta)}{\\cos\\alpha},

with m the mass [kg], J_o the moment of inertia about the pivot edge [kg m^2], r the
pivot-to-centre-of-mass distance [m], alpha the slenderness angle [rad], S the loaded area
[m^2] and l the lever arm [m] of the load resultant about the pivot with the body upright.
The load's arm follows the centre of mass as the body tilts (the paper applies the blast
resultant through the centre of mass); for a rectangular block l = h = r cos(alpha) and the
equation is exactly the paper's, ``S r P cos(alpha sgn(theta) - theta)``.

Impacts (theta = 0) follow Housner (1963): the angular velocity is multiplied by the
coefficient of restitution ``e`` (default ``1 - 1.5 sin^2 alpha``, exact for a rectangular
block whose impact conserves angular momentum about the new pivot).

References
----------
.. [1] Housner, G. W. (1963). The behavior of inverted pendulum structures during earthquakes.
       Bull. Seismol. Soc. Am. 53(2), 403-417.
.. [2] Masi, F., Stefanou, I., Vannucci, P., Maffi-Berthier, V. (2019). Rocking response of
       inverted pendulum structures under blast loading. Int. J. Mech. Sci. 157, 833-848.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from .._validate import BlastscaleInputError, check_positive, check_range
from ..constants import STANDARD_GRAVITY
from ..structures.block import RectangularBlock

__all__ = ["RockingSystem", "housner_restitution", "as_rocking_system"]


def housner_restitution(alpha: float) -> float:
    """Housner's coefficient of restitution on the angular velocity of a rectangular block.

    .. math:: e = 1 - \\tfrac{3}{2} \\sin^2\\alpha

    Parameters
    ----------
    alpha : float
        Slenderness angle [rad], 0 < alpha < pi/2.

    Returns
    -------
    e : float
        Ratio of the angular velocities after / before an impact [-]. Valid (>= 0) for
        alpha <= 54.7 deg; for stockier blocks the formula gives a negative value and 0
        (the block stops at the impact) is returned.

    References: Housner (1963), Eq. (8); paper Sec. "Equations of motion".
    """
    a = float(check_range("slenderness angle alpha", alpha, 0.0, math.pi / 2, "rad", lo_open=True, hi_open=True))
    return max(0.0, 1.0 - 1.5 * math.sin(a) ** 2)


@dataclass(frozen=True)
class RockingSystem:
    """A rigid body rocking on a rigid base about two pivot edges, in SI.

    Parameters
    ----------
    mass : float
        Mass m [kg], > 0.
    inertia_pivot : float
        Moment of inertia J_o about the pivot edge [kg m^2], > 0 (4/3 m r^2 for a rectangle).
    radius : float
        Pivot-to-centre-of-mass distance r [m], > 0.
    alpha : float
        Slenderness angle [rad], 0 < alpha < pi/2 (angle between the vertical through the pivot
        and the line pivot-centre of mass, with the body upright).
    loaded_area : float
        Area S of the face loaded by the blast [m^2], > 0.
    lever_arm : float
        Height l of the load resultant above the base with the body upright [m], > 0
        (h for a rectangular block of height 2h).
    gravity : float
        Gravitational acceleration g [m/s^2], > 0; default 9.81.
    restitution : float or None
        Coefficient of restitution e on the angular velocity at each impact [-], in [0, 1];
        None (default) means Housner's value ``1 - 1.5 sin^2 alpha``.
    """

    mass: float
    inertia_pivot: float
    radius: float
    alpha: float
    loaded_area: float
    lever_arm: float
    gravity: float = STANDARD_GRAVITY
    restitution: float | None = None

    def __post_init__(self):
        check_positive("mass", self.mass, "kg")
        check_positive("moment of inertia J_o", self.inertia_pivot, "kg m^2")
        check_positive("radius r", self.radius, "m")
        check_range("slenderness angle alpha", self.alpha, 0.0, math.pi / 2, "rad", lo_open=True, hi_open=True)
        check_positive("loaded area S", self.loaded_area, "m^2")
        check_positive("lever arm", self.lever_arm, "m")
        check_positive("gravity", self.gravity, "m/s^2")
        if self.restitution is not None:
            check_range("restitution", self.restitution, 0.0, 1.0)
        if self.inertia_pivot < self.mass * self.radius**2 * (1.0 - 1e-12):
            raise BlastscaleInputError(
                f"moment of inertia J_o = {self.inertia_pivot:.6g} kg m^2 is out of range: must be >= m r^2 "
                f"= {self.mass * self.radius**2:.6g} kg m^2 (parallel-axis theorem)"
            )

    @classmethod
    def from_block(
        cls, block: RectangularBlock, gravity: float = STANDARD_GRAVITY, restitution: float | None = None
    ) -> "RockingSystem":
        """The rocking system of a :class:`~blastscale.structures.RectangularBlock` loaded on
        its front face (S = 2h x 2w, l = h, J_o = 4/3 m r^2)."""
        if not isinstance(block, RectangularBlock):
            raise BlastscaleInputError(f"block must be a RectangularBlock, got {type(block).__name__}")
        return cls(
            mass=block.mass,
            inertia_pivot=block.inertia_pivot,
            radius=block.r,
            alpha=block.alpha,
            loaded_area=block.front_area,
            lever_arm=block.h,
            gravity=gravity,
            restitution=restitution,
        )

    def scaled(self, factors) -> RockingSystem:
        """The similar system of the reduced-scale model (the specimen): mass x gamma lambda^3, J_o x gamma
        lambda^5, r and l x lambda, S x lambda^2, gravity x varsigma; alpha and the restitution unchanged
        (``factors``: a :class:`~blastscale.similitude.ScalingFactors`; ``length`` lambda, ``density`` gamma,
        ``gravity`` varsigma [-]). Paper Tables 1-2. Called by
        :func:`blastscale.similitude.specimen.specimen_system`, the one place a specimen is scaled."""

        lam = float(check_positive("scale", factors.length))
        gam = float(check_positive("density ratio", factors.density))
        sig = float(check_positive("gravity ratio", factors.gravity))
        return replace(
            self,
            mass=self.mass * gam * lam**3,
            inertia_pivot=self.inertia_pivot * gam * lam**5,
            radius=self.radius * lam,
            loaded_area=self.loaded_area * lam**2,
            lever_arm=self.lever_arm * lam,
            gravity=self.gravity * sig,
        )

    # derived quantities ----------------------------------------------------
    @property
    def frequency_parameter(self) -> float:
        """p = sqrt(m g r / J_o) [rad/s]; sqrt(3 g / (4 r)) for a rectangular block (Housner 1963)."""
        return math.sqrt(self.mass * self.gravity * self.radius / self.inertia_pivot)

    @property
    def coefficient_of_restitution(self) -> float:
        """The restitution e in use [-] (the user's value, or Housner's)."""
        return housner_restitution(self.alpha) if self.restitution is None else float(self.restitution)

    @property
    def load_ratio_per_pascal(self) -> float:
        """Load-to-weight ratio per pascal, ``S l / (m g r cos alpha)`` [1/Pa]
        (``S / (m g)`` for a rectangular block)."""
        return self.loaded_area * self.lever_arm / (self.mass * self.gravity * self.radius * math.cos(self.alpha))

    @property
    def uplift_pressure(self) -> float:
        """Least pressure that lifts the body off its base at rest [Pa]:
        ``S l P > m g r sin alpha`` (``P S h > m g b`` for a rectangle)."""
        return math.tan(self.alpha) / self.load_ratio_per_pascal

    @property
    def critical_angular_velocity(self) -> float:
        """Least initial angular velocity [rad/s] that overturns the body from rest, without
        load: ``p sqrt(2 (1 - cos alpha))`` (energy balance, Housner 1963)."""
        return self.frequency_parameter * math.sqrt(2.0 * (1.0 - math.cos(self.alpha)))

    @property
    def critical_impulse(self) -> float:
        """Impulsive-limit overturning impulse per unit area [Pa*s]: ``J_o theta_dot_c / (S l)``
        (impulse-momentum, paper Sec. "Equations of motion")."""
        return self.inertia_pivot * self.critical_angular_velocity / (self.loaded_area * self.lever_arm)

    def impulse_velocity(self, impulse: float) -> float:
        """Angular velocity [rad/s] given to the body at rest by an impulsive load of
        ``impulse`` per area [Pa*s]: ``theta_dot_0 = i S l / J_o``."""
        return float(impulse) * self.loaded_area * self.lever_arm / self.inertia_pivot


def as_rocking_system(
    body: "RockingSystem | RectangularBlock", gravity: float | None = None, restitution: float | None = None
) -> RockingSystem:
    """Return ``body`` as a :class:`RockingSystem` (a block is converted with ``gravity``
    [m/s^2] (default 9.81) and ``restitution``; a system is returned as is unless
    ``gravity`` / ``restitution`` are given, which then replace its own)."""
    if isinstance(body, RockingSystem):
        changes = {}
        if gravity is not None:
            changes["gravity"] = gravity
        if restitution is not None:
            changes["restitution"] = restitution
        return replace(body, **changes) if changes else body
    if isinstance(body, RectangularBlock):
        return RockingSystem.from_block(body, STANDARD_GRAVITY if gravity is None else gravity, restitution)
    raise BlastscaleInputError(f"body must be a RockingSystem or a RectangularBlock, got {type(body).__name__}")
