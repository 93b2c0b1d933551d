"""Plotting (matplotlib). Every function takes ``ax=`` and returns it; no numerics live here."""
