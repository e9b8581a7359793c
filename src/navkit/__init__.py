"""navkit: typed, numba-accelerated mobile-robot navigation algorithms."""

from navkit.errors import NavkitError, NoPathError

__version__ = "0.1.0"

__all__ = ["NavkitError", "NoPathError", "__version__"]
