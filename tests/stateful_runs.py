"""Shared pieces of the stateful (hypothesis ``RuleBasedStateMachine``) tests.

Imported by bare name (``tests/`` is on ``sys.path`` under pytest's rootdir
conftest), like the other shared test helpers.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any, TypeVar

from hypothesis import HealthCheck, settings
from hypothesis.stateful import RuleBasedStateMachine
from hypothesis.stateful import run_state_machine_as_test as _untyped_run

import hypothesis_scale

_T = TypeVar("_T")


def _pickled(obj: _T) -> _T:
    copied: _T = pickle.loads(pickle.dumps(obj))
    return copied


#: The ways a user copies a stateful object; each copy must be independent.
COPIERS: tuple[Callable[[Any], Any], ...] = (copy.copy, copy.deepcopy, _pickled)

# hypothesis leaves this one untyped.
_run: Callable[..., None] = _untyped_run


def run_machine(machine: type[RuleBasedStateMachine], *, examples: int, steps: int) -> None:
    """Run ``machine`` for ``examples`` sequences of up to ``steps`` rules each.

    ``examples`` times ``NAVKIT_HYPOTHESIS_EXAMPLES_SCALE`` (tests/hypothesis_scale.py),
    as conftest scales the ``@given`` tests.

    No example database (a failure found on one machine's sources must not
    replay elsewhere) and no deadline (first calls compile kernels).
    """
    _run(
        machine,
        settings=settings(
            max_examples=examples * hypothesis_scale.EXAMPLES_SCALE,
            stateful_step_count=steps,
            deadline=None,
            database=None,
            suppress_health_check=[HealthCheck.too_slow],
        ),
    )
