"""Input and output at the edges: scenario files (TOML), the material density library,
result files and the HTML report."""

from .materials import MATERIALS, material_density
from .scenario import Scenario, load_scenario, parse_ratio

__all__ = ["MATERIALS", "Scenario", "load_scenario", "material_density", "parse_ratio"]
