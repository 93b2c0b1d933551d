"""Test planning: from a similar model to a shot a laboratory can fire safely (docs/planning.md).

* the shot: the charge in a real explosive and the safety envelope (:mod:`.shot`, over
  :mod:`blastscale.blast.explosives` and :mod:`blastscale.blast.safety`);
* the instruments the lab must set (:mod:`.instruments`), the debris zone (:mod:`.debris`);
* the odds: the lab's tolerances by Monte Carlo through the planar kernels or small 3D ensembles
  (:mod:`.odds`);
* the planner: lambda, gamma (through the materials), the law and the specimen's burst searched
  against the lab's constraints for any structure, designs ranked by trustworthiness then safety
  (:mod:`.planner`, :mod:`.candidates`; the 3D stage of the structures without a planar path:
  :mod:`.plan3d`, :mod:`.plan3d_designs`), the Pareto front (:mod:`.pareto`);
* the test card of a study (:mod:`.card`).

Above the sweeps (the 3D ensembles run as one), below the report and the files.
"""

from .card import study_test_card
from .odds import Odds, Tolerances, ensemble_odds_3d, planar_odds
from .plan3d import design_scenario
from .planner import Plan, PlanInfeasible, plan

__all__ = [
    "plan",
    "Plan",
    "PlanInfeasible",
    "design_scenario",
    "study_test_card",
    "planar_odds",
    "ensemble_odds_3d",
    "Odds",
    "Tolerances",
]
