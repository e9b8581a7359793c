"""navkit: typed, numba-accelerated mobile-robot navigation algorithms."""

from navkit.errors import FilterError, NavkitError, NoPathError

__version__ = "0.1.0"

__all__ = ["FilterError", "NavkitError", "NoPathError", "__version__"]
