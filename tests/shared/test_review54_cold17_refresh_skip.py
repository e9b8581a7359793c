"""numba's registry refreshes with nothing new are skipped in navkit's compiles (review 54, COLD17).

numba refreshes its target and typing registries at every compile and again
whenever lowering meets an implementation it has not looked up before (about
3,300 refreshes of 0.3 ms in a cold ``navkit warmup``). While a navkit kernel
compiles, a refresh that finds every registry of both contexts as long as
after the last refresh (one during which nothing was registered) would install
nothing and is skipped (``navkit._shared.compile_shortcuts.refresh_unneeded``);
anything registered since makes numba's refresh run. Outside navkit's compiles
(the shortcuts off) every refresh is numba's.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

pytest.importorskip("numba")

from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba

load_numba()

from numba import njit  # noqa: E402
from numba.core import cpu  # noqa: E402
from numba.core.registry import cpu_target  # noqa: E402
from numba.extending import overload  # noqa: E402


@pytest.fixture
def real_refreshes(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[int]]:
    """Counts numba's own refreshes of the CPU target context (its registries' loading)."""
    calls: list[int] = []
    numbas: Any = cpu.CPUContext.load_additional_registries

    def counted(self: Any) -> None:
        calls.append(1)
        numbas(self)

    monkeypatch.setattr(cpu.CPUContext, "load_additional_registries", counted)
    yield calls


def test_a_refresh_with_nothing_new_is_skipped_in_a_navkit_compile(
    real_refreshes: list[int],
) -> None:
    target = cpu_target.target_context
    compile_shortcuts.begin()
    try:
        target.refresh()  # may run (nothing recorded yet), and records the state
        target.refresh()
        target.refresh()
        target.typing_context.refresh()
        target.typing_context.refresh()
        ran = len(real_refreshes)
    finally:
        compile_shortcuts.end()
    assert ran <= 1
    # The shortcuts off: numba's every time.
    del real_refreshes[:]
    target.refresh()
    target.refresh()
    assert len(real_refreshes) == 2


def test_a_refresh_runs_when_something_was_registered_since(real_refreshes: list[int]) -> None:
    target = cpu_target.target_context
    compile_shortcuts.begin()
    try:
        target.refresh()
        target.refresh()
        before = len(real_refreshes)

        def review54_cold17_twice(x):  # type: ignore[no-untyped-def]  # (as the impl's)
            raise NotImplementedError

        @overload(review54_cold17_twice)
        def _twice(x):  # type: ignore[no-untyped-def]  # (numba compares the names)
            def impl(x):  # type: ignore[no-untyped-def]
                return 2 * x

            return impl

        def uses_py(x: float) -> float:
            return review54_cold17_twice(x) + 1.0  # type: ignore[no-any-return,no-untyped-call]

        uses: Any = njit(uses_py)

        # Typing compiles the overload and registers its lowering: the refresh of
        # the lowering's lookup must run, or the call has no implementation.
        assert uses(2.5) == 6.0
        assert len(real_refreshes) > before
        state = compile_shortcuts.registry_state(target)
        assert state is not None
        target.refresh()  # nothing new since: skipped
        assert compile_shortcuts.refresh_unneeded(target, state)
    finally:
        compile_shortcuts.end()


def test_the_state_is_none_with_the_shortcuts_off() -> None:
    target = cpu_target.target_context
    assert not compile_shortcuts.active()
    assert compile_shortcuts.registry_state(target) is None
    assert not compile_shortcuts.refresh_unneeded(target, None)
    previous = compile_shortcuts.ENABLED
    compile_shortcuts.ENABLED = False
    try:
        compile_shortcuts.begin()
        try:
            assert compile_shortcuts.registry_state(target) is None
        finally:
            compile_shortcuts.end()
    finally:
        compile_shortcuts.ENABLED = previous


def test_a_registration_during_a_refresh_is_not_recorded() -> None:
    # An entry appended while numba's refresh runs may come after its registry
    # was read: that refresh's end is not recorded, so the next one runs.
    target = cpu_target.target_context
    compile_shortcuts.begin()
    try:
        target.refresh()
        before = compile_shortcuts.registry_state(target)
        assert before is not None
        registry = next(iter(target._registries))
        registry.functions.append(registry.functions[-1])  # as numba appends (a copy)
        try:
            compile_shortcuts.note_refresh(target, before)
            assert not compile_shortcuts.refresh_unneeded(
                target, compile_shortcuts.registry_state(target)
            )
        finally:
            registry.functions.pop()
    finally:
        compile_shortcuts.end()


def test_navkit_kernels_compile_and_run_with_the_skips() -> None:
    from navkit.planning import astar

    costs = np.ones((12, 12))
    costs[2:10, 6] = np.inf
    path = astar(costs, (0, 0), (11, 11))
    assert tuple(path.cells[0]) == (0, 0) and tuple(path.cells[-1]) == (11, 11)
