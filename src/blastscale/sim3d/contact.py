"""Contact and solver settings of the MuJoCo rigid-body model, in physical terms.

MuJoCo's contacts are soft constraints: each contact behaves like a mass-normalised
spring-damper of time constant ``tau`` and damping ratio ``zeta`` (``solref``), weighted by an
impedance ``d`` in (0, 1) that ramps from ``dmin`` to ``dmax`` over a penetration ``width``
(``solimp``). :class:`ContactSettings` states these in SI (seconds, metres) and scales them
with the geometric factor lambda so that a reduced-scale model run, up-scaled, reproduces the
prototype run (time x sqrt(lambda / lambda_g), length x lambda). The valid value of every setting is in
:mod:`.contact_ranges`.

One setting is ours and not MuJoCo's default: ``friction_time_constant``. MuJoCo gives the
frictional directions of a contact the same reference damping ``b = 2 / (dmax tau)`` as the
normal direction. With a convex (elliptic or pyramidal) friction cone the solver's optimality
conditions then tie the normal "acceleration error" to the tangential one (the Lorentz-cone
complementarity, see docs/sim3d.md), so a sliding body is pushed off the plane by roughly
``mu b |v_t| / k`` -- the spurious hop of several millimetres. Giving the frictional
directions their own, longer time constant (MuJoCo's ``solreffriction`` of an explicit contact
pair) shrinks the tangential reference term and the hop by the same ratio, while Coulomb
sliding is unchanged as long as ``b_f |v_t| >> mu g`` (below a creep speed
``v_c ~ mu g dmax tau_f / 2`` friction acts as a stiff viscous damper and brings the body to
rest within ~tau_f).

References
----------
.. [1] MuJoCo documentation, "Computation: Soft constraints" and XML reference
       (``solref``, ``solimp``, ``solreffriction``, ``impratio``, ``cone``).
.. [2] E. Todorov (2014), Convex and analytically-invertible dynamics with contacts and
       constraints, ICRA 2014.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from .._validate import BlastscaleInputError, check_choice, check_positive, check_range
from ..constants import DEFAULT_FRICTION, STANDARD_GRAVITY
from ..similitude.factors import scaling_factors
from .collision import level_stack
from .contact_ranges import CONES, JACOBIANS, SETTING_RANGES, SETTLINGS, SOLVERS, STEPS_AFTER_LOAD, check_scalar
from .solver_choice import default_jacobian

__all__ = [
    "ASSEMBLY_IMPRATIO",
    "ASSEMBLY_SETTLE_TOLERANCE",
    "LOOSE_SETTLE_ABOVE_BODIES",
    "ContactSettings",
    "default_contact",
    "mjcf_number",
    "reference_contact",
    "time_constant_for_step",
]


def mjcf_number(x) -> str:
    """A number for the MJCF text, rounded to 15 significant digits.

    Rounding makes a structure and its exactly scaled model, both brought to the engine's
    reference units (:func:`~.reference.reference_factors`), compile to the *same* MuJoCo model:
    with full ``repr`` their inputs differ by round-off (1e-16), which decides, e.g., whether two
    drums placed exactly face to face start in contact, and seeds a 1e-8 difference of the
    response that the dynamics amplify to 1e-3 of the peak over 8 s.
    """
    return format(float(x), ".15g")


@dataclass(frozen=True)
class ContactSettings:
    """Contact, integration and solver settings of a 3D rigid-body run, all SI.

    The defaults are for full-scale masonry blocks (metres, tonnes) loaded by blast pulses
    of about a millisecond; use :meth:`scaled` for a reduced-scale model.

    Parameters
    ----------
    friction : float
        Coulomb friction coefficient mu = tan(phi) [-], >= 0 (paper: phi = 35 deg, mu = 0.7).
    time_constant : float
        Time constant tau of the normal contact spring-damper [s] (MuJoCo ``solref[0]``).
        Must be >= 2 ``timestep``. 2 ms makes the static penetration of the paper's 10 m block 1.1 um
        (measured; it grows as tau^2) and the impact effectively plastic (Housner); MuJoCo's default 20 ms is far too soft.
    damping_ratio : float
        Damping ratio zeta of the normal contact [-] (``solref[1]``); 1 = critical, no bounce.
    friction_time_constant : float or None
        Time constant tau_f [s] of the reference damping ``b_f = 2/(dmax tau_f)`` of the
        frictional directions (``solreffriction``). None reproduces MuJoCo's default
        (tau_f = tau) and with it the spurious hop of a sliding block; the default 20 ms
        removes it (< 0.1 mm for a 1 m block sliding at 1.8 m/s, docs/sim3d.md).
    impedance_min, impedance_max : float
        Constraint impedance ``solimp[0:2]`` (dmin, dmax) [-], 0 < dmin <= dmax < 1.
    impedance_width : float
        Penetration [m] over which the impedance ramps from dmin to dmax (``solimp[2]``).
    timestep : float
        Integration time step dt [s] (semi-implicit Euler).
    cone : {"elliptic", "pyramidal"}
        Friction-cone model.
    impratio : float
        Ratio of frictional to normal constraint impedance (elliptic cone only) [-], >= 1
        makes friction stiffer than contact (less creep of a "sticking" pivot: the creep speed is proportional to
        1 / impratio). A structure of more than :data:`LOOSE_SETTLE_ABOVE_BODIES` bodies gets
        :data:`ASSEMBLY_IMPRATIO` by default (:func:`reference_contact`).
    solver : {"Newton", "CG", "PGS"}
        Constraint solver.
    iterations : int
        Maximum solver iterations per step.
    tolerance : float
        Solver tolerance [-] (relative cost improvement).
    settle_tolerance : float or None
        Solver tolerance [-] while the structure settles before the first arrival (None: ``tolerance``). A structure
        of more than :data:`LOOSE_SETTLE_ABOVE_BODIES` bodies settles at :data:`ASSEMBLY_SETTLE_TOLERANCE` by default
        (:func:`reference_contact`; docs/performance.md, "Walls under a blast"); ``tolerance`` gives the settling of
        before.
    noslip_iterations : int
        Iterations of MuJoCo's post-hoc no-slip solver (0 = off; it does not affect the hop).
    jacobian : {"dense", "sparse", "auto"}
        Layout of the constraint Jacobian. "dense" here; a structure's scale-consistent defaults
        (:func:`default_contact`) choose it by size and MuJoCo version
        (:func:`~.solver_choice.default_jacobian`: sparse for stacks; MuJoCo 4.0.0's
        sparse-factorisation bug, issue 3767, is not reached by our scenes). "sparse" is 2.8x faster on the square
        10-drum column and gives the dense histories to 1.4e-12 of the peak (docs/performance.md).
    settling : {"plain", "kinetic"}
        How the structure settles on its soft contacts before the first arrival
        (:func:`~.integrate.settle_time_constants`): "plain" (default) for 20 contact time constants, the velocities
        zeroed at the end; "kinetic" (kinetic damping) for 80, the velocities zeroed at every peak of the kinetic
        energy, which brings a tall stack to its static state (docs/performance.md, "What the settling leaves in a
        tall stack"). A stack on level beds of more than :data:`LOOSE_SETTLE_ABOVE_BODIES` bodies (a wall) settles
        "kinetic" by default (:func:`reference_contact`).
    step_after_load : {"double", "same"}
        The step once every pulse has passed: "double" (default) up to 2 ``timestep``, at most half of every contact
        time constant, a whole number of steps between recorded states (:func:`~.integrate.step_factor_after_load`,
        docs/performance.md); "same": ``timestep`` throughout (before issue #28).

    Notes
    -----
    Scale consistency (lambda = length factor, lambda_t = time factor = sqrt(lambda/lambda_g)):
    every time (``time_constant``, ``friction_time_constant``, ``timestep``) is multiplied by
    lambda_t and ``impedance_width`` by lambda; dimensionless settings are unchanged. The
    MuJoCo stiffness ``k = d / (dmax^2 tau^2 zeta^2)`` [1/s^2] and damping ``b = 2/(dmax tau)``
    [1/s] then scale as 1/lambda_t^2 and 1/lambda_t, exactly like gravity/length and the
    block's natural frequencies, so the dimensionless equations of motion are identical.
    """

    friction: float = DEFAULT_FRICTION
    time_constant: float = 2e-3
    damping_ratio: float = 1.0
    friction_time_constant: float | None = 20e-3
    impedance_min: float = 0.9
    impedance_max: float = 0.95
    impedance_width: float = 1e-3
    timestep: float = 2e-4
    cone: str = "elliptic"
    impratio: float = 10.0
    solver: str = "Newton"
    iterations: int = 100
    tolerance: float = 1e-10
    settle_tolerance: float | None = None
    noslip_iterations: int = 0
    jacobian: str = "dense"
    step_after_load: str = "double"
    settling: str = "plain"

    def __post_init__(self):
        for name in SETTING_RANGES:
            check_scalar(name, getattr(self, name))
        for name in ("iterations", "noslip_iterations"):
            v = getattr(self, name)
            if isinstance(v, (int, float)) and not float(v).is_integer():
                raise BlastscaleInputError(f"{name} = {v!r} is out of range: must be a whole number")
        for name, r in SETTING_RANGES.items():
            v = getattr(self, name)
            if v is None and name in ("friction_time_constant", "settle_tolerance"):  # tau_f = tau; the tolerance
                continue
            lo = self.impedance_min if name == "impedance_max" else r.lo  # dmin <= dmax
            check_range(name, v, lo, r.hi, r.unit, lo_open=r.lo_open, hi_open=r.hi_open)
        if self.time_constant < 2.0 * self.timestep * (1.0 - 1e-12):
            raise BlastscaleInputError(
                f"contact time constant = {self.time_constant:.6g} s is out of range: must be >= 2 x timestep "
                f"= {2 * self.timestep:.6g} s (MuJoCo clamps softer, stability)"
            )
        check_choice("cone", self.cone, CONES)
        check_choice("solver", self.solver, SOLVERS)
        check_choice("jacobian", self.jacobian, JACOBIANS)
        check_choice("step_after_load", self.step_after_load, STEPS_AFTER_LOAD)
        check_choice("settling", self.settling, SETTLINGS)

    # -- derived MuJoCo quantities ----------------------------------------------------
    @property
    def stiffness(self) -> float:
        """Mass-normalised normal stiffness k = dmax / (dmax^2 tau^2 zeta^2) at full impedance [1/s^2]."""
        dmax = self.impedance_max
        return dmax / (dmax**2 * self.time_constant**2 * self.damping_ratio**2)

    @property
    def damping(self) -> float:
        """Mass-normalised normal damping b = 2 / (dmax tau) [1/s]."""
        return 2.0 / (self.impedance_max * self.time_constant)

    @property
    def friction_damping(self) -> float:
        """Reference damping of the frictional directions b_f = 2 / (dmax tau_f) [1/s]."""
        tf = self.time_constant if self.friction_time_constant is None else self.friction_time_constant
        return 2.0 / (self.impedance_max * tf)

    def creep_speed(self, gravity: float) -> float:
        """Slip speed below which friction acts as a viscous damper, mu g / b_f [m/s]."""
        return self.friction * gravity / self.friction_damping

    # -- scaling -----------------------------------------------------------------------
    def scaled(self, factors) -> "ContactSettings":
        """Settings for the geometrically similar model.

        Parameters
        ----------
        factors : ScalingFactors
            Model / prototype factors (:func:`blastscale.similitude.scaling_factors`): ``length``
            lambda, ``time`` lambda_t and ``friction`` lambda_mu [-] are used.

        Returns
        -------
        ContactSettings
            Times x lambda_t, ``impedance_width`` x lambda, ``friction`` x lambda_mu (the specimen
            material's own, :mod:`blastscale.structures.materials`), the rest unchanged.
        """
        lam = float(check_positive("scale", factors.length))
        lt = float(check_positive("time factor", factors.time))
        fr = float(check_positive("friction factor", factors.friction))
        return replace(
            self,
            friction=self.friction * fr,
            time_constant=self.time_constant * lt,
            friction_time_constant=None if self.friction_time_constant is None else self.friction_time_constant * lt,
            impedance_width=self.impedance_width * lam,
            timestep=self.timestep * lt,
        )

    # -- MJCF fragments ----------------------------------------------------------------
    def mjcf_option(self, gravity: float) -> str:
        """The ``<option>`` element (time step, cone, solver, gravity)."""
        return (
            f'<option timestep="{mjcf_number(self.timestep)}" gravity="0 0 {mjcf_number(-gravity)}" cone="{self.cone}" '
            f'impratio="{mjcf_number(self.impratio)}" solver="{self.solver}" iterations="{int(self.iterations)}" '
            f'tolerance="{mjcf_number(self.tolerance)}" noslip_iterations="{int(self.noslip_iterations)}" integrator="Euler" '
            f'jacobian="{self.jacobian}"><flag multiccd="enable"/></option>'
        )

    def _mjcf_common(self, margin: float) -> str:
        return (
            f'condim="3" solref="{mjcf_number(self.time_constant)} {mjcf_number(self.damping_ratio)}" '
            f'solimp="{mjcf_number(self.impedance_min)} {mjcf_number(self.impedance_max)} '
            f'{mjcf_number(self.impedance_width)} 0.5 2" margin="{mjcf_number(margin)}" gap="0"'
        )

    def mjcf_pair_attributes(self, margin: float = 0.0) -> str:
        """Attributes of an explicit ``<pair>``: condim 3, friction, solref, solreffriction, solimp,
        ``margin`` [m] (0: engages at contact; negative: once the surfaces overlap by -margin)."""
        mu = mjcf_number(float(self.friction))
        attrs = f'{self._mjcf_common(margin)} friction="{mu} {mu} 0 0 0"'
        if self.friction_time_constant is not None:
            attrs += f' solreffriction="{mjcf_number(self.friction_time_constant)} 1"'
        return attrs

    def mjcf_geom_attributes(self, margin: float = 0.0) -> str:
        """The same settings on a ``<geom>`` colliding through MuJoCo's broad phase (equal on every geom,
        so MuJoCo's mixing of two geoms' settings returns them unchanged): sliding friction in both
        tangent directions, no solreffriction (a geom has none, :attr:`geom_expressible`)."""
        return f'{self._mjcf_common(margin)} friction="{mjcf_number(float(self.friction))} 0 0"'

    @property
    def geom_expressible(self) -> bool:
        """Whether a ``<geom>`` can carry these settings (MuJoCo geoms have no ``solreffriction``)."""
        return self.friction_time_constant is None

    def to_dict(self) -> dict:
        """Plain dict with unit-suffixed keys."""
        return {
            "friction": self.friction,
            "time_constant_s": self.time_constant,
            "damping_ratio": self.damping_ratio,
            "friction_time_constant_s": self.friction_time_constant,
            "impedance_min": self.impedance_min,
            "impedance_max": self.impedance_max,
            "impedance_width_m": self.impedance_width,
            "timestep_s": self.timestep,
            "cone": self.cone,
            "impratio": self.impratio,
            "solver": self.solver,
            "iterations": self.iterations,
            "tolerance": self.tolerance,
            "settle_tolerance": self.settle_tolerance,
            "noslip_iterations": self.noslip_iterations,
            "jacobian": self.jacobian,
            "step_after_load": self.step_after_load,
            "settling": self.settling,
        }


def length_time_factors(length: float, time: float):
    """The scaling factors of a length factor and a time factor given exactly (the gravity ratio
    they imply is length / time^2): for :meth:`ContactSettings.scaled` and structures' ``scaled``
    where a change of units, not a scaling law, fixes the two."""

    lam = float(check_positive("scale", length))
    lt = float(check_positive("time factor", time))
    return replace(scaling_factors(lam, 1.0, lam / lt**2), length=lam, time=lt)


# -- scale-consistent defaults --------------------------------------------------------------
#: Reference length [m] and gravity [m/s^2] at which the default settings below were measured
#: (the paper's 10 m block and 10 m column; docs/design.md, "Physics engine" and "Multi-drum columns").
REFERENCE_LENGTH = 10.0
REFERENCE_GRAVITY = STANDARD_GRAVITY
#: Full-scale defaults of a single body (block): contact 2 ms, friction reference 20 ms (removes
#: the sliding hop, docs/sim3d.md), dt 0.2 ms, solimp width 1 mm.
BLOCK_REFERENCE = ContactSettings()
#: Full-scale defaults of a stack of bodies (column): contact 1 ms, no separate friction time
#: constant (20 ms does not converge for columns), dt 0.25 ms, solimp width 1 mm.
STACK_REFERENCE = ContactSettings(time_constant=1e-3, friction_time_constant=None, timestep=2.5e-4)
#: Structures of more bodies than this settle at :data:`ASSEMBLY_SETTLE_TOLERANCE` and run at :data:`ASSEMBLY_IMPRATIO`
#: (walls, arches: their settled state is a knife edge that the settling tolerance picks, their joints creep; the
#: columns, 10 drums, and single blocks keep their settings).
LOOSE_SETTLE_ABOVE_BODIES = 10
#: Solver tolerance of an assembly's settling (MuJoCo's default): the 200-block wall's response over block lengths
#: 1e-6 apart keeps its mean and narrows its spread 4x, at 1.8x less cost (docs/performance.md).
ASSEMBLY_SETTLE_TOLERANCE = 1e-8
#: Friction-to-normal impedance ratio of a structure of more than :data:`LOOSE_SETTLE_ABOVE_BODIES` bodies (MuJoCo's
#: ``impratio``; 10 for the others). A sticking joint of MuJoCo's soft contact creeps at a speed proportional to
#: 1 / impratio (the frictional rows' regularisation is the normal one's over impratio): the arch R = 5 m, t/R = 0.16,
#: 20 voussoirs, friction 0.8 creeps 0.569, 0.284, 0.187, 0.125 mm in 5 s under gravity alone at 10, 20, 30, 50
#: (issue #35's limit 0.5 mm); 20 keeps the cost (the arch 6.2 vs 6.8 CPU s; the 200-block wall under its blast
#: within this machine's noise), the wall's largest displacement (+0.01 %, its spread over the geometry 0.9 %), the outcomes and the
#: 14-block wall's sparse against dense Jacobian (5.6e-13 of the peak), where 12 leaves them 4.3e-3 apart and the
#: arch at t/R = 0.14 "moving" at 1 s, and 30 the t/R = 0.16 arch "moving" at 5 s (docs/performance.md, "Assembly
#: contact defaults").
ASSEMBLY_IMPRATIO = 20.0
#: Largest time step as a fraction of the structure's gravity time sqrt(L / g).
MAX_TIMESTEP_FRACTION = 0.01
#: An explicit contact time constant above this many times max(pulse duration, scale-consistent
#: default) gets a RuntimeWarning (soft relative to the blast).
SOFT_CONTACT_FACTOR = 5.0


def structure_length(structure) -> float:
    """Characteristic length L of a structure [m]: its total height (``describe()["height_m"]``)."""
    return float(structure.describe()["height_m"])


def reference_contact(structure, friction: float = DEFAULT_FRICTION) -> ContactSettings:
    """The full-scale (10 m, 9.81 m/s^2) settings of ``structure`` with friction mu [-]:
    :data:`BLOCK_REFERENCE` for one body, :data:`STACK_REFERENCE` for several, with the Jacobian of
    :func:`~.solver_choice.default_jacobian` (by size and MuJoCo version) and, above
    :data:`LOOSE_SETTLE_ABOVE_BODIES` bodies, the settling tolerance :data:`ASSEMBLY_SETTLE_TOLERANCE`, the
    impedance ratio :data:`ASSEMBLY_IMPRATIO` and, for a stack on level beds (:func:`~.collision.level_stack`: a
    wall, a portal), the kinetic settling (``settling = "kinetic"``: a tall stack settles to its static state; an
    arch keeps the plain one, docs/performance.md)."""

    n = len(structure.bodies)
    base = BLOCK_REFERENCE if n == 1 else STACK_REFERENCE
    if n > LOOSE_SETTLE_ABOVE_BODIES:
        base = replace(base, settle_tolerance=ASSEMBLY_SETTLE_TOLERANCE, impratio=ASSEMBLY_IMPRATIO)
        if level_stack(getattr(structure, "interface_details", ())):
            base = replace(base, settling="kinetic")
    return replace(base, friction=friction, jacobian=default_jacobian(n))


#: Contact time constants per time step kept when a user coarsens the step (MuJoCo needs >= 2).
MIN_STEPS_PER_TIME_CONSTANT = 4.0


def time_constant_for_step(time_constant: float, timestep: float) -> float:
    """The contact time constant [s] to use with a user-chosen time step [s]: ``time_constant``,
    raised to :data:`MIN_STEPS_PER_TIME_CONSTANT` steps when the step is coarse (MuJoCo clamps a
    time constant below 2 steps, which would silently soften the contact)."""
    return max(float(time_constant), MIN_STEPS_PER_TIME_CONSTANT * float(timestep))


def default_contact(
    structure, friction: float = DEFAULT_FRICTION, gravity: float = REFERENCE_GRAVITY
) -> ContactSettings:
    """Scale-consistent contact settings for ``structure`` (used when ``contact=None``).

    The reference settings (:data:`BLOCK_REFERENCE` for one body, :data:`STACK_REFERENCE` for
    several) were measured on 10 m structures under g = 9.81 m/s^2. For a structure of
    height L under gravity g they are scaled as the similitude of rigid bodies requires,

    .. math:: \\lambda = L / L_{ref},\\qquad \\lambda_t = \\sqrt{\\lambda\\, g_{ref} / g},

    times (time constants, time step) x lambda_t and the solimp width x lambda, so the
    dimensionless contact (stiffness / (g/L), damping x sqrt(L/g), penetration / L) is the
    same at every size: a specimen simulated at its own size reproduces the up-scaled
    prototype, as :meth:`ContactSettings.scaled` does for a model derived from a prototype.

    Parameters
    ----------
    structure : structure
        Any structure of :mod:`blastscale.structures`.
    friction : float
        Coulomb friction mu [-].
    gravity : float
        g [m/s^2].

    Returns
    -------
    ContactSettings
    """
    L = float(check_positive("structure height", structure_length(structure), "m"))
    g = float(check_positive("gravity", gravity, "m/s^2"))
    lam = L / REFERENCE_LENGTH
    return reference_contact(structure, friction).scaled(
        length_time_factors(lam, math.sqrt(lam * REFERENCE_GRAVITY / g))
    )
