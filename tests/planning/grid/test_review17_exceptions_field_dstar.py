"""FieldDStar after an exception raised part-way through a search (exception safety).

A ``KeyboardInterrupt`` (Ctrl-C in a notebook, a ROS 2 node shutting down) is
delivered between two Python calls: on a large grid most likely as soon as a
long call returns, a compiled search kernel or the clearing of the planner's
arrays at the start of a search. The planner must then be left either without a
plan (:meth:`FieldDStar.replan` raises ``RuntimeError`` until the next plan) or
with a search that the next replan completes into the path a fresh planner
returns; never with the last plan's ends over half-cleared arrays, which a
repair after :meth:`FieldDStar.update_costs` turned into an out-of-bounds read
in the kernels (a segmentation fault, before session 21's fix).

The interrupts are injected where a user could not: the function blanking the
planner's node records (``clear_box``, review 27; ``fill`` of the records
before) is wrapped to raise once, before or after it blanked them, and the
path kernel's name in the module is wrapped to raise once it returned.
"""

from __future__ import annotations

import contextlib
import math
import subprocess
import sys
import textwrap
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.errors import NoPathError
from navkit.planning import FieldDStar, Path2D
from navkit.planning.grid import _field_dstar


def _arm_clear(monkeypatch: pytest.MonkeyPatch, which: str) -> None:
    """Make the next blanking of the records raise, ``which``: "before" or "after" it."""
    real = _field_dstar.clear_box
    armed = [True]

    def interrupted(*args: Any) -> int:
        if armed[0] and which == "before":
            armed[0] = False
            raise KeyboardInterrupt
        blanked = real(*args)
        if armed[0]:
            armed[0] = False
            raise KeyboardInterrupt
        return blanked

    monkeypatch.setattr(_field_dstar, "clear_box", interrupted)


def _costs(seed: int, n: int = 16, density: float = 0.2) -> np.ndarray[Any, Any]:
    rng = np.random.default_rng(seed)
    costs = rng.uniform(1.0, 4.0, (n, n))
    costs[rng.random((n, n)) < density] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0  # the corner cells of the ends stay passable
    return costs


def _same(got: Path2D, want: Path2D) -> None:
    assert got.frame == want.frame
    assert math.isclose(got.cost, want.cost, rel_tol=1e-9, abs_tol=1e-12)
    assert got.points.shape == want.points.shape
    np.testing.assert_allclose(got.points, want.points, atol=1e-9)


_PLANS: dict[str, tuple[Callable[[FieldDStar], Path2D], Callable[[FieldDStar], Path2D]]] = {
    # name: (plan from scratch, its replan)
    "plan": (lambda p: p.plan((0, 0), (16, 16)), lambda p: p.replan()),
    "plan_cells": (lambda p: p.plan_cells((0, 0), (15, 15)), lambda p: p.replan()),
    "plan_world": (
        lambda p: p.plan_world((0.25, 0.25), (15.75, 15.75)),
        lambda p: p.replan_world(),
    ),
}


def _fresh_replan(costs: np.ndarray[Any, Any], method: str) -> Path2D:
    """What ``method``'s replan returns on a fresh planner after its plan (after
    plan_cells, replan() gives the node part of plan_cells' path)."""
    plan, replan = _PLANS[method]
    fresh = FieldDStar(costs)
    plan(fresh)
    return replan(fresh)


@pytest.mark.parametrize("which", ["before", "after"])
@pytest.mark.parametrize("method", sorted(_PLANS))
def test_a_plan_interrupted_while_clearing_leaves_no_plan(
    which: str, method: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    costs = _costs(3)
    plan, replan = _PLANS[method]
    planner = FieldDStar(costs)
    planner.plan((16, 0), (0, 16))  # an earlier plan, whose ends must not survive
    _arm_clear(monkeypatch, which)
    with pytest.raises(KeyboardInterrupt):
        plan(planner)
    # Before the fix the earlier plan's ends were kept over the cleared arrays: this
    # replan returned the earlier path, and one after update_costs read out of bounds.
    with pytest.raises(RuntimeError, match="call plan"):
        replan(planner)
    with pytest.raises(RuntimeError, match="call plan"):
        planner.replan_world()
    # The planner plans again as a fresh one, and repairs as one.
    _same(plan(planner), plan(FieldDStar(costs)))
    planner.update_costs([(8, c) for c in range(2, 14)], np.inf)
    costs[8, 2:14] = np.inf
    _same(replan(planner), _fresh_replan(costs, method))


_CRASHES = textwrap.dedent(
    """
    import faulthandler
    import numpy as np
    faulthandler.enable()
    from navkit.planning import FieldDStar
    from navkit.planning.grid import _field_dstar

    real = _field_dstar.clear_box

    def interrupted(planner, call):
        def clear_box(*args):
            real(*args)
            raise KeyboardInterrupt
        _field_dstar.clear_box = clear_box
        try:
            call()
        except KeyboardInterrupt:
            pass
        _field_dstar.clear_box = real

    def outcome(call):
        try:
            call()
        except RuntimeError as exc:
            return "RuntimeError " + str(exc)
        return "planned"

    # A plan interrupted while clearing its arrays, then a change and a replan.
    planner = FieldDStar(np.random.default_rng(0).uniform(1.0, 5.0, (30, 30)))
    planner.plan((0, 0), (30, 30))
    interrupted(planner, lambda: planner.plan((5, 5), (20, 25)))
    planner.update_costs([(10, c) for c in range(5, 25)], np.inf)
    print(outcome(planner.replan), flush=True)

    # A hopeless repair replaced by a fresh search (see
    # test_review10_field_dstar_abort_mutants), interrupted while clearing the arrays.
    _field_dstar._REPAIR_MIN_WORK = 0
    _field_dstar._REPAIR_PROBE_MIN_WORK = 1
    n = 30
    planner = FieldDStar(np.ones((n, n)))
    planner.plan((n // 2, 0), (n // 2 + 1, n))
    planner.update_costs([(r, n // 2) for r in range(n - 2)], np.inf)
    interrupted(planner, planner.replan)
    print(outcome(planner.replan), flush=True)
    """
)


def test_the_interrupted_searches_that_crashed_the_interpreter_leave_no_plan() -> None:
    # In a child process: a regression ends in a segmentation fault (as both cases
    # did before the fix), which must fail this test, not end the test run.
    done = subprocess.run(
        [sys.executable, "-c", _CRASHES], capture_output=True, text=True, timeout=300, check=False
    )
    assert done.returncode == 0, done.stderr[-3000:]
    lines = done.stdout.splitlines()
    assert len(lines) == 2
    for line in lines:
        assert line.startswith("RuntimeError replan() repairs a previous search"), line


@settings(max_examples=30, deadline=None, database=None)
@given(
    seed=st.integers(0, 2**16),
    method=st.sampled_from(sorted(_PLANS)),
    interrupted=st.sampled_from(["plan", "replan"]),
    after=st.integers(1, 4),
)
def test_an_interrupt_after_any_kernel_call_leaves_a_planner_that_replans_as_a_fresh_one(
    seed: int, method: str, interrupted: str, after: int
) -> None:
    costs = _costs(seed)
    plan, replan = _PLANS[method]
    planner = FieldDStar(costs)
    try:
        plan(planner)
    except NoPathError:
        return  # a grid with no path: nothing to interrupt
    rng = np.random.default_rng(seed)
    flat = rng.choice(16 * 16, 6, replace=False)
    cells = np.stack([flat // 16, flat % 16], axis=1)
    values = rng.choice([1.0, 2.5, np.inf], 6)
    planner.update_costs(cells, values)
    costs[cells[:, 0], cells[:, 1]] = values
    real = getattr(_field_dstar, "extract_path")  # noqa: B009 - not re-exported
    calls = [0]

    def interrupted_kernel(*args: Any) -> Any:
        out = real(*args)
        calls[0] += 1
        if calls[0] == after:
            raise KeyboardInterrupt
        return out

    # Not the monkeypatch fixture: hypothesis runs many examples per test call.
    setattr(_field_dstar, "extract_path", interrupted_kernel)  # noqa: B010
    try:
        with contextlib.suppress(KeyboardInterrupt, NoPathError, ValueError):
            (plan if interrupted == "plan" else replan)(planner)
    finally:
        setattr(_field_dstar, "extract_path", real)  # noqa: B010
    # Whatever kernel call was interrupted, the next replan is that of a fresh plan on
    # these costs (the same ends).
    try:
        want: Path2D | type[Exception] = _fresh_replan(costs, method)
    except (NoPathError, ValueError) as exc:
        want = type(exc)
    try:
        got: Path2D | type[Exception] = replan(planner)
    except (NoPathError, ValueError) as exc:
        got = type(exc)
    if isinstance(got, type) or isinstance(want, type):
        assert got == want
    else:
        _same(got, want)
