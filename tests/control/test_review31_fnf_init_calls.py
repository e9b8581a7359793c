"""Constructors call none of their class's public methods (review 31, FNF).

``PotentialFieldController.__init__`` ended with ``self.reset()``: a subclass
overriding ``reset`` to clear state of its own, set up after
``super().__init__()``, failed to construct (``AttributeError`` in its override,
run before its own ``__init__`` went on). The base now clears its state with a
private helper. Checked against the source before the fix: the subclass test
failed there with that ``AttributeError``.

The sweep at the end reads every navkit class's ``__init__``/``__post_init__``
and finds no call of a public method on ``self`` (one remains, in the private
``FusionEstimator``, which users never subclass).
"""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

import navkit
from navkit.control import PotentialFieldController
from navkit.planning import AStarPlanner


class CountingController(PotentialFieldController):
    """A user's controller that counts its runs, reset with the rest of its state."""

    __slots__ = ("runs", "trail")

    def __init__(self, **options: float) -> None:
        super().__init__(**options)
        self.runs = 0
        self.trail: list[float] = []

    def reset(self) -> None:
        super().reset()
        self.runs += 1
        self.trail.clear()


def test_a_subclass_resetting_its_own_state_constructs() -> None:
    ctl = CountingController(max_speed=0.4)
    assert (ctl.runs, ctl.trail) == (0, [])
    cmd = ctl.step((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), 0.1)
    ctl.trail.append(cmd.vx)
    assert ctl.previous_velocity[0] > 0.0
    ctl.reset()
    assert (ctl.runs, ctl.trail) == (1, [])
    assert ctl.previous_velocity.tolist() == [0.0, 0.0]
    assert (ctl.stall_time, ctl.stalled) == (0.0, False)


def test_the_base_starts_as_after_a_reset() -> None:
    fresh = PotentialFieldController()
    used = PotentialFieldController()
    used.step((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), 0.1)
    used.reset()
    goal = (2.0, 1.0, 0.5)
    assert fresh.step((0.0, 0.0, 0.0), goal, 0.1) == used.step((0.0, 0.0, 0.0), goal, 0.1)


class FourLabel(AStarPlanner):
    """A planner whose connectivity property a user changed (to raise, here)."""

    @property
    def connectivity(self) -> int:
        raise AssertionError("read by the base's constructor")


def test_the_planner_refusal_reads_no_overridable_property() -> None:
    with pytest.raises(ValueError, match=r"connectivity=4, heuristic_weight=1\.0"):
        FourLabel(np.ones((3, 3)), connectivity=4, method="jps")


def _public_self_calls(path: Path) -> list[str]:
    found = []
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for cls in ast.walk(tree):
        if not isinstance(cls, ast.ClassDef) or cls.name.startswith("_"):
            continue
        for fn in cls.body:
            if not isinstance(fn, ast.FunctionDef) or fn.name not in ("__init__", "__post_init__"):
                continue
            for node in ast.walk(fn):
                call = node.func if isinstance(node, ast.Call) else None
                if (
                    isinstance(call, ast.Attribute)
                    and isinstance(call.value, ast.Name)
                    and call.value.id == "self"
                    and not call.attr.startswith("_")
                ):
                    found.append(f"{cls.name}.{fn.name} -> {call.attr}")
    return found


def test_no_constructor_calls_a_public_method_of_its_own() -> None:
    root = Path(navkit.__file__).parent
    found = [hit for p in sorted(root.rglob("*.py")) for hit in _public_self_calls(p)]
    assert found == ["FusionEstimator.__init__ -> check_start"]
