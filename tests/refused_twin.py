"""Offering a call to an object and to its twin: the review 52 long-run refusal tests' helper."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from navkit.errors import NavkitError


def offer(call: Callable[[Any], object], obj: Any, twin: Any) -> bool:
    """Give ``obj`` the call; whether it refused it (a call it takes, the twin takes too).

    A refusal is a ``ValueError``, ``TypeError`` or navkit error; any other
    exception propagates (the tests then fail). The twin, built and used as
    ``obj``, sees only the calls ``obj`` took, so that comparing the two after a
    stream of good and bad calls shows whether a refusal changed anything.
    """
    try:
        call(obj)
    except (ValueError, TypeError, NavkitError):
        return True
    call(twin)
    return False
