"""Does the scenario's load method, or its clearing choice, change the answer more than the verdict
tolerates? A cheap check before (or beside) the 3D run (issue #39, deliverable 3; docs/face_loads.md,
"Which load method").

The similarity verdict judges the up-scaled specimen against the prototype *under one load model*; the
load model itself can move the prototype's answer much further. On the paper's 10.4 m circular column under
500 kg at 20 m, Method A (the reflected pulse, uniform and simultaneous, on every drum's projected front)
gives a 151 mm top displacement where Method C (every exposed face with its own distance, arrival and
incidence: the paper's "most realistic", its Appendix II) gives 22 mm: a factor 7, where the verdict's
tolerance on first peaks is 5 %.

The check (:func:`load_choice`) builds the prototype's loads under each method (no simulation: the load
strategies' :meth:`delivered_impulse` at the rest pose, milliseconds for a column) and compares the
**overturning impulse** about the ground line,

.. math:: H = \\sum_b J_{x,b}\\, z_b \\quad [\\mathrm{N\\,s\\,m}],

with :math:`J_{x,b}` the impulse along the blast delivered to body b and :math:`z_b` its centre of mass's
height. Why this measure: under an impulsive load (the design's :math:`t_o p` check) a rocking body starts
with the angular velocity :math:`\\omega_0 = H / I_O` and keeps no memory of the pulse's shape (Housner
1963); its kinetic energy :math:`I_O \\omega_0^2 / 2` is spent lifting it, and for small rotations the lift
grows linearly with the rotation (:math:`m g R \\sin\\alpha\\, \\theta`), so the first peak grows about as
:math:`H^2`. The factor between methods in H is therefore a floor of the factor in the first peak, and its
square an estimate: 2.65 in H and 2.65^2 = 7.0 in the peak on the column above (the 3D runs: 151 / 22 =
6.9). A full second 3D run would measure it exactly at the cost of the run itself (minutes on a column);
the impulse needs none.

The reference is Method C. It is built for structures of at most :data:`C_MAX_BODIES` bodies (its ray
casts for shadowing cost ~2 s for 210 bodies and grow with their square); above, the scenario's method is
compared with Method B and the note says so (and the specimen's clearing is not checked: its front's interfaces
cost 35 s of CPU for 3000 blocks). Clearing (UFC 3-340-02 Sec. 2-15.3.2; Hudson 1955; Rigby et al.
2014: a small target's reflected pressure relieves to the stagnation pressure within a few transit times
of its edges) is compared the same way: the scenario's method with and without it.

References
----------
.. [1] Masi, F., Stefanou, I., Maffi-Berthier, V. & Vannucci, P. (2021). Scaling laws for rigid-body
       response of masonry structures under blast loads. Methods A, B and C (Sec. 5, Appendix II).
.. [2] Housner, G. W. (1963). The behavior of inverted pendulum structures during earthquakes. *BSSA* 53(2).
.. [3] UFC 3-340-02 (2008). *Structures to Resist the Effects of Accidental Explosions*, Sec. 2-15.3.2
       (clearing of a front wall) and Sec. 2-16 (drag loading: drag coefficients by shape, a cylinder's
       among them).
.. [4] Glasstone, S. & Dolan, P. J. (1977). *The Effects of Nuclear Weapons*, 3rd ed., ch. IV, Air Blast
       Loading (diffraction and drag loading: a structure small beside the wave is engulfed, its reflected
       pressure lasting only while the front passes around it).
.. [5] Hudson, C. C. (1955). Sound pulse approximations to blast loading (with comments on transient drag).
       Sandia Corporation, SC-TM-191-55-51.
.. [6] Rigby, S. E., Tyas, A., Bennett, T., Fay, S. D., Clarke, S. D. & Warren, J. A. (2014). A numerical
       investigation of blast loading and clearing on small targets. *Int. J. Protective Structures* 5(3),
       253-274; Rigby, S. E., Tyas, A. & Bennett, T. (2014). Elastic-plastic response of plates subjected to
       cleared blast loads. *Int. J. Impact Eng.* 66, 37-47.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._validate import BlastscaleInputError
from ..scenario.scenario import Scenario
from ..sim3d.load_methods import make_load
from .engines import load_model_of

__all__ = ["C_MAX_BODIES", "LoadChoice", "load_choice", "overturning_impulse"]

#: Largest structure [bodies] for which the check builds Method C (its shadowing ray casts: ~2 s at 210 bodies).
C_MAX_BODIES = 120


def overturning_impulse(load, structure) -> float:
    """The overturning impulse H = sum_b J_x,b z_b [N s m] of a built load strategy about the ground line
    (module docstring): each body's impulse along the blast (``load.delivered_impulse()``, at the rest pose)
    times its centre of mass's height."""
    J = np.asarray(load.delivered_impulse(), dtype=float)
    z = np.array([float(b.com[2]) for b in structure.bodies])
    return float(J[:, 0] @ z)


@dataclass(frozen=True)
class LoadChoice:
    """What the scenario's load choices do to the prototype's load (:func:`load_choice`).

    Attributes
    ----------
    method : str
        The scenario's load method.
    reference : str
        The method compared against ("C", or "B" above :data:`C_MAX_BODIES` bodies).
    overturning_impulse_N_s_m : dict
        H [N s m] of each method built.
    method_factor : float
        H of the scenario's method over the reference's [-] (1: the same load).
    clearing : bool
        The scenario's ``blast.clearing``.
    clearing_factor, specimen_clearing_factor : float or None
        H with clearing over H without, for the scenario's method [-], on the prototype and on the specimen
        (None: not computed, clearing on already, or not applicable).
    tolerance : float
        The verdict's tolerance on first peaks, ``[verdict] peak`` [-].
    notes : tuple of str
        The warnings, in words (empty: the choices move the load less than the tolerance).
    """

    method: str
    reference: str
    overturning_impulse_N_s_m: dict
    method_factor: float
    clearing: bool
    clearing_factor: float | None
    specimen_clearing_factor: float | None
    tolerance: float
    notes: tuple = field(default_factory=tuple)

    def to_dict(self) -> dict:
        """The summary's ``load_choice`` block (SI keys)."""
        return {
            "method": self.method,
            "reference": self.reference,
            "overturning_impulse_N_s_m": dict(self.overturning_impulse_N_s_m),
            "method_factor": self.method_factor,
            "first_peak_factor_estimate": self.method_factor**2,
            "clearing": self.clearing,
            "clearing_factor": self.clearing_factor,
            "specimen_clearing_factor": self.specimen_clearing_factor,
            "tolerance": self.tolerance,
            "notes": list(self.notes),
        }


def _build(method: str, structure, blast, scenario: Scenario, load_model=None):
    bl = scenario.blast
    return make_load(
        method,
        structure,
        blast,
        pulse_shape=bl.pulse_shape,
        incidence=bl.incidence,
        extrapolate=bl.extrapolate,
        load_model=load_model,
    )


def load_choice(scenario: Scenario, structure, blast, design=None) -> LoadChoice | None:
    """Compare the scenario's load method with Method C (B for a large structure) and, where clearing is off,
    with clearing on, on the prototype's overturning impulse (module docstring). None where no 3D load
    applies (planar engine only, gravity alone, or no blast parameters).

    Parameters
    ----------
    scenario : Scenario
        Its ``blast.load``, ``blast.clearing``, ``blast.negative_phase`` and ``[verdict] peak``.
    structure : structure
        The prototype structure (any kind of :mod:`blastscale.structures`).
    blast : BlastParameters
        The prototype's blast parameters (the design's ``prototype``, never recomputed).
    design : ModelDesign, optional
        The design: clearing is then checked on its specimen too (its structure and blast parameters), where
        it matters most (a small front clears in a shorter time, its pulse is shorter too but not in step).

    Returns
    -------
    LoadChoice or None
    """
    bl = scenario.blast
    if blast is None or bl.gravity_only or scenario.simulation.engine not in ("3d", "both"):
        return None
    tol = float(scenario.verdict.peak)
    lm = load_model_of(scenario, structure)
    ref = "C" if len(structure.bodies) <= C_MAX_BODIES else "B"
    H = {m: overturning_impulse(_build(m, structure, blast, scenario, lm), structure) for m in sorted({bl.load, ref})}
    factor = H[bl.load] / H[ref] if H[ref] else float("inf")
    notes = []
    if bl.load != ref and abs(factor - 1.0) > tol:
        notes.append(_method_note(bl.load, ref, factor, tol, structure))
    clear = specimen_clear = None
    if not bl.clearing:
        clear = _clearing_factor(scenario, structure, blast, H[bl.load])
        # the specimen's front needs its interfaces (35 s of CPU for 3000 blocks when not yet found): small ones
        if design is not None and clear is not None and len(structure.bodies) <= C_MAX_BODIES:
            specimen_clear = _clearing_factor(scenario, design.specimen_structure, design.specimen)
        worst = max((abs(f - 1.0) for f in (clear, specimen_clear) if f is not None), default=0.0)
        if worst > tol:
            notes.append(_clearing_note(bl.load, clear, specimen_clear, tol))
    return LoadChoice(bl.load, ref, H, float(factor), bool(bl.clearing), clear, specimen_clear, tol, tuple(notes))


def _clearing_factor(scenario: Scenario, structure, blast, uncleared: float | None = None) -> float | None:
    """H with clearing over H without under the scenario's method (None: clearing does not apply, e.g. an
    arch's open front)."""
    try:
        cleared = load_model_of(scenario, structure, clearing=True)
        hc = overturning_impulse(_build(scenario.blast.load, structure, blast, scenario, cleared), structure)
        if uncleared is None:
            lm = load_model_of(scenario, structure)
            uncleared = overturning_impulse(_build(scenario.blast.load, structure, blast, scenario, lm), structure)
    except BlastscaleInputError:
        return None
    return hc / uncleared if uncleared else None


def _clearing_note(method: str, prototype: float | None, specimen: float | None, tol: float) -> str:
    """The warning that clearing changes the load more than the verdict's tolerance."""
    where = f"x{prototype:.3g} on the prototype" + ("" if specimen is None else f", x{specimen:.3g} on the specimen")
    return (
        f"clearing: the reflected pressure on this front relieves soon enough to change the overturning impulse "
        f"({where}, Method {method}) by more than the verdict's {tol:.3g} tolerance on first peaks; a small target "
        "clears within a few transit times of its edges: set blast.clearing = true (UFC 3-340-02 Sec. 2-15.3.2; "
        "Hudson 1955; Rigby et al. 2014; docs/face_loads.md, 'Which load method')"
    )


def _method_note(method: str, ref: str, ratio: float, tol: float, structure) -> str:
    """The warning that the load method matters more than the verdict's tolerance."""
    why = {
        "C": "every exposed face with its own distance, arrival and incidence, rear and top included: the "
        "paper's most realistic, its Appendix II",
        "B": "each body's front with its own distance, arrival and incidence (Method C not built for "
        f"more than {C_MAX_BODIES} bodies)",
    }[ref]
    note = (
        f"load method {method} gives this structure x{ratio:.3g} the overturning impulse of Method {ref} ({why}); "
        f"a rocking first peak grows about as its square (x{ratio**2:.3g}), far beyond the verdict's {tol:.3g} "
        "tolerance on first peaks: the method changes the answer more than the scaling does"
    )
    if getattr(structure, "section", "") == "circular":
        note += (
            f"; a cylinder is engulfed by the wave: Method {method} loads its projected front with the full "
            "reflected pressure, where diffraction and drag load it far less (UFC 3-340-02 Sec. 2-16; Glasstone "
            '& Dolan 1977): use blast.load = "C"'
        )
    return note + " (docs/face_loads.md, 'Which load method')"
