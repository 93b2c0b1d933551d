"""Prototype vs reduced-scale model: up-scaling and comparison (one contract for every engine).

* :mod:`.compare` -- ``upscale_dataset`` (each variable / its ``dimension``'s factor),
  ``compare_responses`` (per body and point: first peaks, differences, outcomes), ``first_peak``;
* :mod:`.upscale` -- ``upscale``, ``upscale_summary``: the one up-scaling rule;
* :mod:`.structure3d` -- ``compare_structure3d`` (any structure on MuJoCo, any load method; a
  block's summary carries its planar view);
* :mod:`.prototype3d` -- ``prototype_structure3d`` (the prototype alone);
* :mod:`.ensemble` -- ``ensemble_compare`` for chaotic structures (circular columns; the
  prototype's ensemble alone without a design);
* :mod:`.intervals` -- ``wilson_interval``, ``odds_text``: the binomial interval of k of n (an ensemble's
  odds, honest for small n);
* :mod:`.rocking_similarity` -- planar rocking through the same contract (with its overturning figures);
* :mod:`.block3d_similarity` -- the single block's planar view of a 3D run (``block_dataset``,
  ``block_summary``, ``block_similarity``, ``block_view``: rotation about y, sliding of the
  supporting edge, uplift);
* :mod:`.capacity` -- ``model_capacity_curve``: a reduced-scale model's capacity curve, up-scaled to the
  prototype (the specimen side of the capacity: the engine gives one body's curve on plain arrays);
* :mod:`.planar` -- the planar rocking runs outside the Study (planner, odds, sweeps' outcome and fragility
  modes, reproduced numbers, the CLI's capacity commands): ``first_swing_of``, ``first_swing_under``,
  ``history_of``, ``critical_of``, ``capacity_of``;
* :mod:`.systems` -- ``Settings3D`` (the 3D settings), ``System3D`` / ``Systems3D`` (one system, the design's
  two: ``Systems3D.of_design``), ``run_system`` (one system on the 3D engine).

Many-case studies (sweeps, fragility, similarity maps) live in :mod:`blastscale.sweeps`.
"""
