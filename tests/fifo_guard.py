"""A guard for tests of reads that the old code blocked for ever on a FIFO.

Shared by the map-file and bag-file swap tests (``tests/mapping``).
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from contextlib import suppress
from pathlib import Path
from typing import Any

import pytest


def unblocked(call: Callable[[], Any], fifo: Path) -> Any:
    """``call()``'s result (or exception); a call that blocks on ``fifo`` fails the test.

    The call runs in a thread so that the old code, which blocked for ever opening
    the FIFO, fails instead of hanging: the FIFO is then opened for writing and
    closed, which ends the blocked open (and the read after it) with end-of-file.
    """
    outcome: dict[str, Any] = {}

    def run() -> None:
        try:
            outcome["value"] = call()
        except BaseException as exc:  # handed to the test's thread
            outcome["error"] = exc

    worker = threading.Thread(target=run, daemon=True)
    worker.start()
    worker.join(20)  # a guard against hanging only: the reads take milliseconds
    if worker.is_alive():
        for _ in range(20):
            with suppress(OSError):
                os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
            worker.join(0.5)
            if not worker.is_alive():
                break
        pytest.fail(f"blocked reading the FIFO {fifo}")
    if "error" in outcome:
        raise outcome["error"]
    return outcome["value"]
