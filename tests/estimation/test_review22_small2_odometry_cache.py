"""Odometry fast paths read cached drive figures (issue 17, session 26).

``OmniOdometry`` keeps the rows of its drive's forward matrix as Python floats
and ``DiffOdometry`` its drive's track, both read once at construction instead
of on every ``update``. The caches are left out of pickles and copies (whose
state is what it was before them) and made again when one is restored, also
from a pickle made before the caches existed: a restored odometry carries on
bit for bit as the original does, and as ``update_batch`` does.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import DiffOdometry, OmniOdometry
from navkit.kinematics import DiffDrive, OmniDrive

_OMNI_SLOTS = {"_anchor", "_drive", "_pose", "_travel"}
_DIFF_SLOTS = {
    "_anchor",
    "_bits",
    "_drive",
    "_high",
    "_last",
    "_low",
    "_method",
    "_modulus",
    "_pose",
    "_scale_left",
    "_scale_right",
    "_ticks_per_rev",
    "_travel",
}


def _omni() -> OmniOdometry:
    # Four wheels at uneven angles: every entry of the forward rows differs.
    drive = OmniDrive([0.1, 1.7, 3.3, 4.4], wheel_radius=0.04, base_radius=0.23)
    odometry = OmniOdometry(drive, pose=(3.0, -1.0, 0.4))
    odometry.update(np.array([0.3, -0.1, 0.2, 0.05]), 0.5)
    return odometry


def _diff() -> DiffOdometry:
    drive = DiffDrive(track=0.37, left_radius=0.05, right_radius=0.051)
    odometry = DiffOdometry(drive, ticks_per_rev=1024, bits=16, pose=(1.0, 2.0, -0.3))
    odometry.update(100, 200)
    odometry.update(400, 350)
    return odometry


def _omni_walk(odometry: Any) -> list[tuple[float, float, float]]:
    rng = np.random.default_rng(7)
    poses = []
    for k in range(20):
        pose = odometry.update(rng.uniform(-2.0, 2.0, 4), 0.3 * k - 2.0)
        poses.append((pose.x, pose.y, pose.theta))
    return poses


def _diff_walk(odometry: Any) -> list[tuple[float, float, float]]:
    poses = []
    for k in range(20):
        pose = odometry.update(400 + 37 * k * k, 350 + 53 * k)
        poses.append((pose.x, pose.y, pose.theta))
    return poses


_CASES: dict[str, tuple[Callable[[], Any], Callable[[Any], Any], set[str]]] = {
    "omni": (_omni, _omni_walk, _OMNI_SLOTS),
    "diff": (_diff, _diff_walk, _DIFF_SLOTS),
}


@pytest.mark.parametrize("name", sorted(_CASES))
def test_the_pickled_state_holds_the_same_slots_as_before_the_caches(name: str) -> None:
    make, _, slots = _CASES[name]
    instance, state = make().__reduce_ex__(2)[2]
    assert instance is None
    assert set(state) == slots


@pytest.mark.parametrize("name", sorted(_CASES))
@pytest.mark.parametrize(
    "how", ["copy", "deepcopy", "pickle0", "pickle5", "older-pickle", "bare-dict"]
)
def test_a_restored_odometry_continues_bit_for_bit(name: str, how: str) -> None:
    make, walk, _ = _CASES[name]
    original = make()
    if how == "copy":
        twin = copy.copy(original)
    elif how == "deepcopy":
        twin = copy.deepcopy(original)
    elif how.startswith("pickle"):
        twin = pickle.loads(pickle.dumps(original, protocol=int(how[-1])))
    else:
        # A state without the caches, as older navkit pickled it; "older-pickle"
        # also lacks the anchor, as pickles before the start was kept apart.
        _, state = original.__reduce_ex__(2)[2]
        if how == "older-pickle":
            state = {k: v for k, v in state.items() if k not in ("_anchor", "_travel")}
            state["_pose"] = original.pose
        twin = object.__new__(type(original))
        twin.__setstate__((None, state) if how == "older-pickle" else state)
    if how == "older-pickle":
        # Summed from the origin: the same steps, another anchor; compare with a batch twin.
        reference = copy.deepcopy(twin)
        got = walk(twin)
        assert got == [tuple(p) for p in _batch_walk(name, reference)]
        return
    assert walk(twin) == walk(original)


def _batch_walk(name: str, odometry: Any) -> list[list[float]]:
    """The same walk as ``_CASES[name]``'s, one ``update_batch`` row at a time."""
    rows = []
    if name == "omni":
        rng = np.random.default_rng(7)
        for k in range(20):
            inc = rng.uniform(-2.0, 2.0, 4)
            rows.append(odometry.update_batch(inc[None, :], [0.3 * k - 2.0])[-1].tolist())
    else:
        for k in range(20):
            rows.append(odometry.update_batch([400 + 37 * k * k], [350 + 53 * k])[-1].tolist())
    return rows


@pytest.mark.parametrize("name", sorted(_CASES))
def test_the_fast_path_with_cached_figures_equals_the_batch(name: str) -> None:
    make, walk, _ = _CASES[name]
    fast = make()
    batch = copy.deepcopy(fast)
    assert [list(p) for p in walk(fast)] == _batch_walk(name, batch)
