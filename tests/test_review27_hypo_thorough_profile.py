"""NAVKIT_HYPOTHESIS_PROFILE=thorough: every @given test runs at least 1000 examples.

And NAVKIT_HYPOTHESIS_EXAMPLES_SCALE=k (review 48, FLAKEC): k times its count, the
stateful machines too.
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, rule

import hypothesis_scale
from stateful_runs import run_machine

_DRAWN: list[int] = []


@settings(max_examples=5, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])  # fmt: skip
@given(st.integers(0, 10**6))
def _modest(x: int) -> None:
    _DRAWN.append(x)


@settings(max_examples=1500, deadline=None, database=None)
@given(st.integers(0, 10))
def _already_thorough(x: int) -> None:
    pass


@pytest.fixture
def conftest(pytestconfig: pytest.Config) -> Any:
    """The suite's top conftest module (``import conftest`` may find a package's)."""
    top = Path(__file__).with_name("conftest.py")
    found = [
        plugin for plugin in pytestconfig.pluginmanager.get_plugins()
        if getattr(plugin, "__file__", None) == str(top)
    ]  # fmt: skip
    assert len(found) == 1
    return found[0]


@given(st.integers(0, 10**6))
def _plain(x: int) -> None:  # no @settings: the profile's count
    _DRAWN.append(x)


class _Method:
    @settings(max_examples=7, deadline=None, database=None)
    @given(st.integers(0, 10**6))
    def method(self, x: int) -> None:
        _DRAWN.append(x)


def _collect(
    conftest: Any, monkeypatch: pytest.MonkeyPatch, profile: str, *tests: object, scale: int = 1
) -> None:
    # The scale too: these tests hold also under NAVKIT_HYPOTHESIS_EXAMPLES_SCALE.
    monkeypatch.setattr(conftest, "_PROFILE", profile)
    monkeypatch.setattr(conftest, "EXAMPLES_SCALE", scale)
    for test in tests:
        # Restored after the test: the hook rewrites the settings in place.
        function = getattr(test, "__func__", test)
        monkeypatch.setattr(function, "_hypothesis_internal_use_settings",
                            function._hypothesis_internal_use_settings)  # fmt: skip
    items = [SimpleNamespace(obj=test) for test in tests]
    conftest.pytest_collection_modifyitems(items)  # type: ignore[arg-type]


def test_the_thorough_profile_raises_every_count_and_keeps_the_other_settings(
    conftest: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    _collect(conftest, monkeypatch, "thorough", _modest, _already_thorough, _Method().method)
    kept = _modest._hypothesis_internal_use_settings  # type: ignore[attr-defined]
    assert kept.max_examples == conftest.THOROUGH_EXAMPLES == 1000
    assert kept.deadline is None and kept.database is None
    assert HealthCheck.too_slow in kept.suppress_health_check
    _DRAWN.clear()
    _modest()
    assert len(_DRAWN) == 1000
    assert _already_thorough._hypothesis_internal_use_settings.max_examples == 1500  # type: ignore[attr-defined]
    assert _Method.method._hypothesis_internal_use_settings.max_examples == 1000  # type: ignore[attr-defined]


def test_the_default_profile_keeps_each_tests_count(
    conftest: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    _collect(conftest, monkeypatch, "navkit", _modest, _Method().method)
    assert _modest._hypothesis_internal_use_settings.max_examples == 5  # type: ignore[attr-defined]
    assert _Method.method._hypothesis_internal_use_settings.max_examples == 7  # type: ignore[attr-defined]
    _DRAWN.clear()
    _modest()
    assert len(_DRAWN) == 5


def test_the_scale_multiplies_every_count_once(
    conftest: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    profile_count = _plain._hypothesis_internal_use_settings.max_examples  # type: ignore[attr-defined]
    # _modest twice: the items of a parametrized test share their function.
    _collect(conftest, monkeypatch, "navkit", _modest, _modest, _plain, _Method().method, scale=3)
    kept = _modest._hypothesis_internal_use_settings  # type: ignore[attr-defined]
    assert kept.max_examples == 15
    assert kept.deadline is None and kept.database is None
    assert HealthCheck.too_slow in kept.suppress_health_check
    assert _plain._hypothesis_internal_use_settings.max_examples == 3 * profile_count  # type: ignore[attr-defined]
    assert _Method.method._hypothesis_internal_use_settings.max_examples == 21  # type: ignore[attr-defined]
    _DRAWN.clear()
    _modest()
    assert len(_DRAWN) == 15


def test_the_scale_multiplies_the_thorough_count(
    conftest: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    _collect(conftest, monkeypatch, "thorough", _modest, _already_thorough, scale=2)
    assert _modest._hypothesis_internal_use_settings.max_examples == 2000  # type: ignore[attr-defined]
    assert _already_thorough._hypothesis_internal_use_settings.max_examples == 3000  # type: ignore[attr-defined]


def test_the_scale_is_read_from_the_environment() -> None:
    assert hypothesis_scale.examples_scale({}) == 1
    assert hypothesis_scale.examples_scale({hypothesis_scale.VARIABLE: "4"}) == 4
    for text in ("0", "-2", "2.5", "four", ""):
        with pytest.raises(ValueError, match=r"NAVKIT_HYPOTHESIS_EXAMPLES_SCALE .*at least 1"):
            hypothesis_scale.examples_scale({hypothesis_scale.VARIABLE: text})


class _Counted(RuleBasedStateMachine):
    runs = 0

    def __init__(self) -> None:
        super().__init__()
        type(self).runs += 1

    @rule(x=st.integers(0, 10**6))
    def step(self, x: int) -> None:
        pass


def test_the_scale_multiplies_a_stateful_machines_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(hypothesis_scale, "EXAMPLES_SCALE", 3)
    monkeypatch.setattr(_Counted, "runs", 0)
    run_machine(_Counted, examples=4, steps=2)
    assert _Counted.runs == 12
