"""navkit: typed, numba-accelerated mobile-robot navigation algorithms."""

from navkit.errors import FilterError, NavkitError, NoPathError

__version__ = "0.1.0"
"""navkit's version (PEP 440): what the installed package's metadata holds
(``importlib.metadata.version("navkit")``), which ``navkit --version`` prints."""

__all__ = ["FilterError", "NavkitError", "NoPathError", "__version__"]
