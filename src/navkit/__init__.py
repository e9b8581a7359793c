"""navkit: typed, numba-accelerated mobile-robot navigation algorithms."""

from navkit._shared.moved import install as _install_moved
from navkit.errors import FilterError, NavkitError, NoPathError

# Pickles of the first days name modules that moved (see navkit._shared.moved).
# Installed here, before any of navkit's packages runs: unpickling an old name
# imports its parents first (navkit, then navkit.mapping, say), and a thread
# importing an old name while another imports a package finds that package in
# sys.modules half run (importlib does not wait for a parent being imported).
_install_moved()

__version__ = "0.1.0"
"""navkit's version (PEP 440): what the installed package's metadata holds
(``importlib.metadata.version("navkit")``), which ``navkit --version`` prints."""

__all__ = ["FilterError", "NavkitError", "NoPathError", "__version__"]
