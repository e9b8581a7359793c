"""Importing navkit in processes that turn warnings into errors or strip docstrings.

Users run ``python -X dev -W error`` (every warning an exception, ResourceWarning
of unclosed files shown) and ``python -OO`` (docstrings stripped: anything that
reads ``__doc__`` at import breaks). Every package imports there without a
warning, and the command's help and list still print.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

PACKAGES = (
    "navkit", "navkit.errors", "navkit.geometry", "navkit.kinematics", "navkit.mapping",
    "navkit.mapping.io", "navkit.estimation", "navkit.planning", "navkit.planning.grid",
    "navkit.planning.reactive", "navkit.control", "navkit.behaviours", "navkit.sim",
    "navkit.sim.scenarios", "navkit.cli",
)  # fmt: skip

_SCRIPT = (
    "import importlib, sys\n"
    f"for name in {PACKAGES!r}:\n"
    "    importlib.import_module(name)\n"
    "from navkit.cli import main\n"
    "codes = [main(['--help']), main(['--version']), main(['list'])]\n"
    "print('codes', codes, 'numba' in sys.modules)\n"
)


@pytest.mark.parametrize("flags", [["-X", "dev", "-W", "error"], ["-OO", "-W", "error"]])
def test_every_package_imports_without_a_warning(flags: list[str]) -> None:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "PYTHONWARN"))}
    done = subprocess.run(
        [sys.executable, *flags, "-c", _SCRIPT],
        env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stderr == ""
    assert done.stdout.rstrip().endswith("codes [0, 0, 0] False"), done.stdout[-500:]
    assert "navkit's experiments (navkit run SCENARIO)" in done.stdout
