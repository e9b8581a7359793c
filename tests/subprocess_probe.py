"""Run a probe script in a fresh Python process and read the JSON it prints last.

For what only a fresh process shows: numba not yet imported, signal handlers as
at start-up, the collector and numba's settings untouched by the test session.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from typing import Any


def probe_outcome(script: str, *args: str, timeout: float = 300) -> Any:
    """The JSON value on the last line ``script`` prints (it must exit 0).

    Python warnings are off in the probe (``PYTHONWARNINGS=ignore``), so that a
    dependency's warning cannot land on the line read.
    """
    done = subprocess.run(
        [sys.executable, "-c", script, *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        env={**os.environ, "PYTHONWARNINGS": "ignore"},
        check=False,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])
