"""Plotting (matplotlib). Every function takes ``ax=`` and returns it; no numerics live here.

Modules: :mod:`.rocking` (planar rocking: theta, theta_dot, phase portrait, prototype vs
up-scaled model, P-I diagram) and :mod:`.sim3d` (3D single-block runs). matplotlib is
imported only when a plot is drawn.
"""
