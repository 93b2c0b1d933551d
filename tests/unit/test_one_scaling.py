"""One scaling rule (issue #34, Deliver 1): a prototype quantity becomes a specimen quantity through
:func:`blastscale.similitude.factors.to_specimen`, a specimen quantity a prototype one through
:func:`blastscale.analysis.upscale.upscale`, an object through its ``scaled(factors)``; no module
multiplies or divides by lambda or a scaling factor by hand.

The scan (:func:`hand_scalings`) reads every module of ``src/blastscale`` with :mod:`ast` and reports
each ``*``, ``/`` or ``**`` one of whose operands is a scaling factor: an attribute ``<x>.factors.<field>``
or ``factors.<field>`` (a :class:`~blastscale.similitude.ScalingFactors` field), ``float()`` of one, a
name of lambda (``lam``, ``lambda_*``), or a local name assigned from one of these in the same function
(``tf = float(d.factors.time)``; ``lam = float(design.factors.length)``). The laws that define the factors
(:data:`LAW_MODULES`), the two conversion functions and the objects' own ``scaled`` methods are where
the factors are allowed (:data:`ALLOWED_FUNCTIONS`, each with its reason).

The round trip checks ``to_specimen`` and ``upscale`` against the paper's Table 1 (Masi, Stefanou,
Maffi-Berthier), generalised to a gravity ratio varsigma, for every dimension.
"""

from __future__ import annotations

import ast
import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.upscale import upscale
from blastscale.similitude.factors import DIMENSIONLESS, ScalingFactors, scaling_factors, to_specimen

SRC = Path(__file__).resolve().parents[2] / "src" / "blastscale"

FIELDS = frozenset(f.name for f in dataclasses.fields(ScalingFactors))

#: Modules that define the scaling laws and the factors (paper Tables 1-2, Eq. 8): they compute with
#: lambda, gamma and varsigma by construction.
LAW_MODULES = frozenset(
    {
        "similitude/factors.py",  # the factors and to_specimen
        "similitude/laws.py",  # the general law's lambda_Z (Eq. 8)
        "similitude/curves.py",  # the law's curves over (lambda, gamma), vectorised
        "similitude/design.py",  # design_model: the specimen's charge W x lambda_W at R x lambda
        "analysis/upscale.py",  # upscale, upscale_summary
    }
)

#: (module, function): why it may use a factor (or a name the scan takes for lambda) by hand.
ALLOWED_FUNCTIONS = {
    ("analysis/compare.py", "upscale_dataset"): "the histories' up-scaling (dimension_factor per variable)",
    ("rocking/system.py", "scaled"): "RockingSystem.scaled(factors): the object's own scaling",
    ("sim3d/contact.py", "scaled"): "ContactSettings.scaled(factors): the object's own scaling",
    ("sim3d/contact.py", "length_time_factors"): "builds the factors of a length and a time scale",
    ("sim3d/contact.py", "default_contact"): "the factors of a structure's size against the reference",
    ("structures/block.py", "scaled"): "RectangularBlock.scaled(factors): the object's own scaling",
    ("structures/column.py", "scaled"): "Column.scaled(factors): the object's own scaling",
    ("structures/assembly.py", "scaled"): "Assembly.scaled(factors): the object's own scaling",
    ("blast/load_model.py", "scaled"): "LoadModel.scaled(factors): the object's own scaling",
    ("blast/pulses.py", "scaled"): "Pulse.scaled(factors): the object's own scaling",
    ("rocking/_free.py", "carlson_rf"): "lam is Carlson's elliptic-integral variable, not lambda",
    ("blast/pulses.py", "_rescaled"): "the pulses' scaled(factors): pressure x factors.pressure, time x factors.time",
    ("blast/load_model.py", "_rescaled"): "LoadModel.scaled's negative phase: pressure and time factors",
    ("structures/assembly.py", "dens"): "Assembly.scaled(factors): its densities x gamma",
    ("structures/assembly.py", "_remade"): "Assembly.scaled(factors): its coordinates x lambda",
    ("blast/faces.py", "q"): "a unit scale of a blast fit's output, not lambda",
    ("blast/parameters.py", "opt"): "a unit scale of a blast fit's output, not lambda",
    ("blast/safety.py", "quantity_distance"): "the DoD K factor in ft/lb^(1/3) to m/kg^(1/3), not a scaling factor",
    ("fired/records.py", "read_tracks"): "a camera's px per mm and a length unit, not lambda",
    ("study/memory.py", "estimate_seconds"): "a run-time estimate's factor, not a scaling factor",
    ("planning/candidates.py", "scale_label"): "a label, '1/20', not a quantity",
    ("report/html.py", "_experiment"): "a label, '1/20', not a quantity",
    ("plots/rocking.py", "plot_similarity"): "a label, 'lambda = 1/20', not a quantity",
    ("plots/similitude.py", "_default_label"): "a label, 'lambda = 1/200', not a quantity",
}

_LAMBDA = frozenset({"lam", "scale", "factor"})


def _is_factors(node) -> bool:
    """A :class:`ScalingFactors` object: ``factors``, ``<x>.factors`` or ``scaling_factors(...)``."""
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        return node.func.id == "scaling_factors"
    return (isinstance(node, ast.Name) and node.id == "factors") or (
        isinstance(node, ast.Attribute) and node.attr == "factors"
    )


class _Scan(ast.NodeVisitor):
    """Hand scalings of one module: ``self.found``."""

    def __init__(self, rel: str):
        self.rel, self.stack, self.found = rel, [], []
        self.bound: list[tuple[set, set]] = [(set(), set())]

    def is_factor(self, node) -> bool:
        """A factor (module docstring): a field of a factors object, ``float()`` of one, a name of lambda
        (``lam``, ``lambda_*``, ``scale``, ``factor``, ``*_factor``) or a local name bound to one."""
        names, objects = self.bound[-1]
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "float" and node.args:
            return self.is_factor(node.args[0])
        if isinstance(node, ast.Attribute):
            if node.attr in FIELDS and (
                _is_factors(node.value) or (isinstance(node.value, ast.Name) and node.value.id in objects)
            ):
                return True
            return node.attr in ("scale", "density_ratio", "gravity_ratio")  # design.scale: lambda; gamma; varsigma
        if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Constant):
            return node.slice.value == "scale"  # inputs["scale"]
        return isinstance(node, ast.Name) and (
            node.id in _LAMBDA or node.id.startswith("lambda_") or node.id.endswith("_factor") or node.id in names
        )

    def _function(self, node):
        self.stack.append(node.name)
        self.bound.append((set(), set()))
        names, objects = self.bound[-1]
        for sub in ast.walk(node):  # names bound to a factor or to the factors: tf = float(d.factors.time)
            if not isinstance(sub, ast.Assign):
                continue
            for target in sub.targets:
                pairs = [(target, sub.value)]
                if isinstance(target, ast.Tuple) and isinstance(sub.value, ast.Tuple):
                    pairs = list(zip(target.elts, sub.value.elts))
                for t, v in pairs:
                    if isinstance(t, ast.Name) and self.is_factor(v):
                        names.add(t.id)
                    elif isinstance(t, ast.Name) and _is_factors(v):
                        objects.add(t.id)
        self.generic_visit(node)
        self.bound.pop()
        self.stack.pop()

    visit_FunctionDef = visit_AsyncFunctionDef = _function

    def visit_BinOp(self, node):
        ops = (ast.Mult, ast.Div, ast.Pow)
        if isinstance(node.op, ops) and (self.is_factor(node.left) or self.is_factor(node.right)):
            fn = self.stack[-1] if self.stack else "<module>"
            if (self.rel, fn) not in ALLOWED_FUNCTIONS:
                self.found.append(f"{self.rel}:{node.lineno} ({fn}): {ast.unparse(node)}")
        self.generic_visit(node)


def hand_scalings(root: Path = SRC) -> list[str]:
    """``module:line (function): expression`` of each hand scaling under ``root`` (module docstring)."""
    found = []
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).as_posix()
        if rel in LAW_MODULES:
            continue
        scan = _Scan(rel)
        scan.visit(ast.parse(path.read_text(encoding="utf-8")))
        found += scan.found
    return found


def test_no_hand_scaling_outside_the_laws():
    """Every prototype -> specimen conversion goes through to_specimen, every specimen -> prototype one
    through upscale, every object through its scaled(factors) (before: 36 hand scalings in 15 modules,
    changes/scaling.md)."""
    assert hand_scalings() == []


def test_the_scan_finds_a_hand_scaling(tmp_path):
    """The scan sees the forms it is meant to catch (so that an empty list means something)."""
    (tmp_path / "m.py").write_text(
        "def f(d, x, t):\n"
        "    tf = float(d.factors.time)\n"
        "    lam = d.scale\n"
        "    return x * d.factors.length, t * tf, x / factors.impulse, lam * x, x * float(d.factors.mass)\n"
        "def g(d, b, inputs, x):\n"
        "    f = d.factors\n"
        "    ft, n = float(d.factors.time), 2\n"
        "    return b.height * inputs['scale'], x / f.velocity, x * ft, x * n, x * d.scale_factor\n"
        "def h(d, x):\n"
        "    return to_specimen(x, d.factors, 'length'), upscale(x, d.factors, 'time')\n",
        encoding="utf-8",
    )
    found = hand_scalings(tmp_path)
    assert [s.split(": ", 1)[1] for s in found] == [
        "x * d.factors.length",
        "t * tf",
        "x / factors.impulse",
        "lam * x",
        "x * float(d.factors.mass)",
        "b.height * inputs['scale']",
        "x / f.velocity",
        "x * ft",
    ]


def test_every_allowed_function_exists():
    """No stale allowance: each (module, function) of ALLOWED_FUNCTIONS is still defined there."""
    for rel, fn in ALLOWED_FUNCTIONS:
        tree = ast.parse((SRC / rel).read_text(encoding="utf-8"))
        names = {n.name for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}
        assert fn in names, f"{rel}: {fn} is allowed but no longer defined"


def _table1(lam: float, gam: float, sig: float) -> dict:
    """Paper Table 1 (general law), generalised to a gravity ratio varsigma (module
    :mod:`blastscale.similitude.factors`: the paper's linear and angular accelerations are swapped
    there, corrected here: linear varsigma, angular varsigma / lambda)."""
    return {
        "length": lam,
        "displacement": lam,
        "time": math.sqrt(lam / sig),
        "velocity": math.sqrt(sig * lam),
        "acceleration": sig,
        "angle": 1.0,
        "angular_velocity": math.sqrt(sig / lam),
        "angular_acceleration": sig / lam,
        "mass": gam * lam**3,
        "inertia": gam * lam**5,
        "impulse": gam * math.sqrt(sig * lam**3),
        "momentum": gam * math.sqrt(sig) * lam**3.5,
        "force": gam * sig * lam**3,
        "pressure": gam * sig * lam,
        "energy": gam * sig * lam**4,
        "density": gam,
        "gravity": sig,
        "friction": 1.0,
    }


@pytest.mark.parametrize("lam, gam, sig", [(1 / 20, 1.0, 1.0), (1 / 200, 1.0, 1.0), (0.1, 2.5, 1.0), (0.05, 0.8, 30.0)])
def test_to_specimen_and_upscale_round_trip_table_1(lam, gam, sig):
    """to_specimen multiplies by the dimension's factor of Table 1 and upscale divides by it, for every
    dimension (the charge and the scaled distance once a blast law fixes lambda_Z): 1e-15 relative."""
    f = scaling_factors(lam, gam, sig, scaled_distance_factor=0.7)
    expected = _table1(lam, gam, sig) | {"scaled_distance": 0.7, "charge": (lam / 0.7) ** 3}
    assert set(expected) == FIELDS
    x = 3.7
    for dim, factor in expected.items():
        s = to_specimen(x, f, dim)
        assert s == pytest.approx(x * factor, rel=1e-15, abs=0.0), dim
        assert upscale(s, f, dim) == pytest.approx(x, rel=1e-15, abs=0.0), dim
        assert to_specimen(upscale(x, f, dim), f, dim) == pytest.approx(x, rel=1e-15, abs=0.0), dim
    for dim in DIMENSIONLESS:
        assert to_specimen(x, f, dim) == x == upscale(x, f, dim)
    arr = np.array([0.5, 2.0, 7.25])
    np.testing.assert_allclose(upscale(to_specimen(arr, f, "time"), f, "time"), arr, rtol=1e-15, atol=0.0)
    assert to_specimen(None, f, "length") is None and upscale(None, f, "length") is None


def test_to_specimen_keeps_the_operation_order():
    """``to_specimen(x) == x * factor`` bit for bit (the hand products it replaced), ``upscale(x) == x / factor``."""
    f = scaling_factors(1 / 7, 1.3, 1.1)
    for x in (0.1, 1 / 3, 2.0**0.5, 123.456):
        assert to_specimen(x, f, "time") == x * f.time
        assert to_specimen(x, f, "length") == f.length * x
        assert upscale(x, f, "impulse") == x / f.impulse


def test_to_specimen_rejects_an_unknown_dimension():
    f = scaling_factors(0.1)
    with pytest.raises(BlastscaleInputError, match="'speed'"):
        to_specimen(1.0, f, "speed")
    with pytest.raises(BlastscaleInputError, match="charge"):
        to_specimen(1.0, f, "charge")  # no lambda_Z yet
