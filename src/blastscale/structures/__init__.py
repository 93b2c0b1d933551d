"""Structure geometry: monolithic blocks (and, later, multi-drum columns)."""

from .block import STANDARD_GRAVITY, RectangularBlock

__all__ = ["RectangularBlock", "STANDARD_GRAVITY"]
