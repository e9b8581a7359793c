"""A slow-marked twin of a hypothesis test: its thorough example count under ``-m slow``.

The default suite draws a modest number of examples; the twin runs the same body with
the same strategies, settings and pytest marks (``parametrize``...) but the thorough
count, marked ``slow``. Imported by bare name, like the other shared test helpers::

    @settings(max_examples=50, deadline=None)
    @given(st.floats(0.1, 10.0), st.integers(0, 2**32 - 1))
    def test_force_is_minus_gradient(reach: float, seed: int) -> None:
        ...

    test_force_is_minus_gradient_thoroughly = slow_twin(
        test_force_is_minus_gradient, max_examples=150
    )
"""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import given, settings


def slow_twin(test: Any, *, max_examples: int) -> Any:
    """``test`` (a ``@given`` test) with ``max_examples`` examples, marked slow.

    The twin's strategies are ``test``'s, its settings ``test``'s with ``max_examples``
    replaced, its pytest marks ``test``'s plus ``slow``. (hypothesis keeps a test's
    strategies and settings in attributes it does not document: a hypothesis release
    that renames them fails here, at import, rather than losing the thorough run.)
    """
    handle = getattr(test, "hypothesis", None)
    strategies = getattr(handle, "_given_kwargs", None)
    base = getattr(test, "_hypothesis_internal_use_settings", None)
    if handle is None or strategies is None or base is None:
        raise TypeError(f"slow_twin needs a @given test, got {test!r}")
    if max_examples <= base.max_examples:
        raise ValueError(
            f"the slow twin of {test.__name__} must run more than its "
            f"{base.max_examples} examples, got max_examples={max_examples}"
        )
    twin = settings(base, max_examples=max_examples)(given(**strategies)(handle.inner_test))
    twin.pytestmark = [*getattr(test, "pytestmark", []), pytest.mark.slow.mark]
    return twin
