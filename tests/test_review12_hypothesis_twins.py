"""slow_twin: the thorough run of a hypothesis test the default suite runs modestly."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin

_DRAWN: list[tuple[int, int]] = []


@pytest.mark.parametrize("k", [1, 2])
@settings(max_examples=5, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])  # fmt: skip
@given(st.integers(0, 10**6))
def _counted(k: int, x: int) -> None:
    _DRAWN.append((k, x))


def test_the_twin_runs_the_body_with_the_thorough_count() -> None:
    twin = slow_twin(_counted, max_examples=30)
    _DRAWN.clear()
    twin(k=7)
    assert len(_DRAWN) == 30 and {k for k, _ in _DRAWN} == {7}
    _DRAWN.clear()
    _counted(k=7)
    assert len(_DRAWN) == 5  # the default test keeps its count


def test_the_twin_keeps_the_settings_and_marks_and_is_slow() -> None:
    twin = slow_twin(_counted, max_examples=30)
    kept = twin._hypothesis_internal_use_settings
    assert kept.max_examples == 30
    assert kept.deadline is None and kept.database is None
    assert HealthCheck.too_slow in kept.suppress_health_check
    names = [mark.name for mark in twin.pytestmark]
    assert names == ["parametrize", "slow"]
    assert twin.pytestmark[0].args == ("k", [1, 2])
    assert [mark.name for mark in _counted.pytestmark] == ["parametrize"]  # untouched


def test_a_twin_must_run_more_examples_than_its_test() -> None:
    with pytest.raises(ValueError, match="more than its 5 examples, got max_examples=5"):
        slow_twin(_counted, max_examples=5)


def test_only_hypothesis_tests_have_twins() -> None:
    def plain() -> None:
        pass

    with pytest.raises(TypeError, match="needs a @given test"):
        slow_twin(plain, max_examples=10)
