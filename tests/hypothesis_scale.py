"""``NAVKIT_HYPOTHESIS_EXAMPLES_SCALE``: every hypothesis test's example count times a whole number.

The thorough profile (``NAVKIT_HYPOTHESIS_PROFILE=thorough``) raises each count
to 1000, hours for mapping or estimation on a 2-core machine; a scale of 4 runs
each test four times its own count instead, for a hunt sized to the time at hand.
tests/conftest.py applies it to every collected ``@given`` test (after the
thorough profile's floor), :func:`stateful_runs.run_machine` to the stateful
machines. Read once, when conftest imports this module. Imported by bare name,
like the other shared test helpers.
"""

from __future__ import annotations

import os
from collections.abc import Mapping

VARIABLE = "NAVKIT_HYPOTHESIS_EXAMPLES_SCALE"


def examples_scale(environ: Mapping[str, str]) -> int:
    """The scale set in ``environ`` (1 when unset).

    Raises
    ------
    ValueError
        The variable not a whole number of at least 1 (``"2.5"``, ``"0"``, ``""``):
        a typo must not run the suite at its usual counts unnoticed.
    """
    text = environ.get(VARIABLE, "1")
    try:
        scale = int(text)
    except ValueError:
        scale = 0
    if scale < 1:
        raise ValueError(f"{VARIABLE} must be a whole number of at least 1, got {text!r}")
    return scale


EXAMPLES_SCALE = examples_scale(os.environ)
