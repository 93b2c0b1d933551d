"""Prototype vs reduced-scale model: up-scaling and comparison (one contract for every engine).

* :mod:`.compare` -- ``upscale_dataset`` (each variable / its ``dimension``'s factor),
  ``compare_responses`` (per body and point: first peaks, differences, outcomes), ``first_peak``;
* :mod:`.structure3d` -- ``compare_structure3d`` (any structure on MuJoCo, any load method),
  ``simulate_system``, ``upscale_summary``;
* :mod:`.ensemble` -- ``ensemble_compare`` for chaotic structures (circular columns);
* :mod:`.rocking_similarity`, :mod:`.block3d_similarity` -- planar rocking and the single block
  through the same contract (with their overturning / planar figures);
* :mod:`.sweeps`, :mod:`.fragility`, :mod:`.similarity_map` -- many cases (docs/sweeps.md).
"""
