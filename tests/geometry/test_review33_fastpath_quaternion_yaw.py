"""``quaternion_to_yaw``'s plain-float fast path gives the array way's yaw bit for bit.

One quaternion as a list, tuple or float64 (4,) array of floats is computed
with plain floats; the oracle is the same quaternion taken the general way (a
byte-swapped copy, same values, and a one-row batch).
"""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import quaternion_to_yaw

_SUBNORMAL = 5e-324
_components = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False),
    st.floats(-2.0, 2.0),
    st.sampled_from([0.0, -0.0, _SUBNORMAL, -_SUBNORMAL, 2.2e-308, 1e-160, 1.7e308, -1.7e308]),
)


def _bits(value: float) -> bytes:
    return struct.pack("<d", value)


def _general(q: list[float]) -> tuple[float, float]:
    """The yaw the general (array) way: byte-swapped (4,) and a (1, 4) batch."""
    swapped = quaternion_to_yaw(np.array(q, dtype=">f8"))
    batch = quaternion_to_yaw(np.array([q]))
    assert isinstance(swapped, float)
    return swapped, float(batch[0])


def _assert_same(q: list[float]) -> None:
    swapped, batch = _general(q)
    assert _bits(swapped) == _bits(batch)
    for spelling in (q, tuple(q), np.array(q), [np.float64(v) for v in q]):
        got = quaternion_to_yaw(spelling)  # type: ignore[arg-type]
        assert type(got) is float
        assert _bits(got) == _bits(swapped), (spelling, got, swapped)


@settings(max_examples=400, deadline=None)
@given(q=st.lists(_components, min_size=4, max_size=4))
def test_fast_path_matches_general(q: list[float]) -> None:
    _assert_same(q)


@settings(max_examples=300, deadline=None)
@given(
    yaw=st.floats(-math.pi, math.pi),
    tilt=st.floats(-1e-6, 1e-6),
    scale=st.sampled_from([1.0, 1e-300, 3.0, 1e300, -1.0]),
)
def test_fast_path_matches_general_near_seam_and_gimbal(
    yaw: float, tilt: float, scale: float
) -> None:
    # The ±π seam (z ≈ ±1, w ≈ 0), and pitch ±90° (where the yaw is called 0).
    half = 0.5 * yaw
    _assert_same([scale * tilt, 0.0, scale * math.sin(half), scale * math.cos(half)])
    _assert_same([0.0, 0.0, scale, scale * tilt])
    _assert_same([0.0, 0.0, scale, -scale * tilt])
    s = math.sqrt(0.5)
    _assert_same([scale * tilt, scale * s, scale * tilt, scale * s])
    _assert_same([scale * s * math.sin(half), scale * s, tilt, scale * s])


@pytest.mark.parametrize(
    "q",
    [
        [0.0, 0.0, 0.0, 0.0],
        [-0.0, -0.0, -0.0, -0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0, -0.0],
        [0.0, 0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0, -1e-17],
        [0.0, math.sqrt(0.5), 0.0, math.sqrt(0.5)],
        [_SUBNORMAL, 0.0, _SUBNORMAL, -_SUBNORMAL],
        [1.7e308, -1.7e308, 1.7e308, 1.7e308],
        [1e-200, 1e-200, 3e-200, 1e-200],
        # Near pitch +90°, both yaw arguments below 1e-12, their hypot above / below it.
        [0.0, 0.7071067811860475, 6e-13, math.sqrt(0.5)],
        [0.0, 0.7071067811862476, 5e-13, math.sqrt(0.5)],
    ],
)
def test_fast_path_matches_general_at_named_points(q: list[float]) -> None:
    _assert_same(q)


def test_fast_path_results_named() -> None:
    # The docstring's promises, on the fast path.
    assert abs(quaternion_to_yaw([0.0, 0.0, math.sin(0.25), math.cos(0.25)]) - 0.5) < 1e-15
    assert quaternion_to_yaw((0.0, 0.0, 1.0, -0.0)) == math.pi  # wrapped to (-π, π]
    assert quaternion_to_yaw([0.0, 0.0, 0.0, 0.0]) == 0.0  # zero means no rotation
    assert quaternion_to_yaw([0.0, 1.0, 0.0, 1.0]) == 0.0  # pitch +90°: yaw called 0
    # Arguments (8.5e-13, 7.1e-13), hypot 1.1e-12: still a heading, not noise.
    near = quaternion_to_yaw([0.0, 0.7071067811860475, 6e-13, math.sqrt(0.5)])
    assert abs(near - math.atan2(8.485281374244571e-13, 7.069900220812997e-13)) < 1e-12
    # Arguments (7.1e-13, 4.2e-13), hypot 8.2e-13: the yaw is called 0.
    assert quaternion_to_yaw([0.0, 0.7071067811862476, 5e-13, math.sqrt(0.5)]) == 0.0


@pytest.mark.parametrize(
    ("q", "error", "match"),
    [
        ([0.0, 0.0, math.nan, 1.0], ValueError, "quaternion must contain only finite values"),
        ((0.0, math.inf, 0.0, 1.0), ValueError, "quaternion must contain only finite values"),
        (np.array([0.0, 0.0, -np.inf, 1.0]), ValueError, "finite"),
        ([0.0, 0.0, 1.0], ValueError, r"shape \(\.\.\., 4\)"),
        ((0.0, 0.0, 0.0, 1.0, 0.0), ValueError, r"shape \(\.\.\., 4\)"),
        ([0.0, 0.0, "z", 1.0], TypeError, "quaternion"),
        ([0.0, 0.0, 1j, 1.0], TypeError, "quaternion"),
    ],
)
def test_fast_path_refusals_are_the_general_ones(
    q: object, error: type[Exception], match: str
) -> None:
    with pytest.raises(error, match=match) as fast:
        quaternion_to_yaw(q)  # type: ignore[arg-type]
    with pytest.raises(error) as general:
        quaternion_to_yaw(np.array(q, dtype=object)[None])  # type: ignore[arg-type]
    if isinstance(q, np.ndarray):
        return
    assert type(fast.value) is type(general.value)


def test_other_spellings_still_answered() -> None:
    # Integers, other dtypes, read-only and strided views: the same yaw as floats.
    want = quaternion_to_yaw([0.0, 0.0, 1.0, 1.0])
    strided = np.array([0.0, 9.0, 0.0, 9.0, 1.0, 9.0, 1.0, 9.0])[::2]
    readonly = np.array([0.0, 0.0, 1.0, 1.0])
    readonly.flags.writeable = False
    for q in ([0, 0, 1, 1], np.array([0, 0, 1, 1]), np.float32([0, 0, 1, 1]), strided, readonly):
        assert quaternion_to_yaw(q) == want  # type: ignore[arg-type]


def test_inputs_not_modified() -> None:
    q_list = [0.0, 3.0, 4.0, 0.0]
    q_arr = np.array(q_list)
    quaternion_to_yaw(q_list)
    quaternion_to_yaw(q_arr)
    assert q_list == [0.0, 3.0, 4.0, 0.0]
    assert q_arr.tolist() == q_list


def test_oracle_takes_the_general_way(monkeypatch: pytest.MonkeyPatch) -> None:
    # The comparisons above mean something only if the oracle's spellings are validated
    # arrays and the plain ones are not.
    from navkit.geometry import _quaternion

    seen: list[object] = []
    general = _quaternion._quaternions

    def spy(value: object, name: str) -> np.ndarray:
        seen.append(value)
        return general(value, name)  # type: ignore[arg-type]

    monkeypatch.setattr(_quaternion, "_quaternions", spy)
    q = [0.0, 0.0, 0.6, 0.8]
    for plain in (q, tuple(q), np.array(q), [np.float64(v) for v in q]):
        quaternion_to_yaw(plain)  # type: ignore[arg-type]
    assert seen == []
    quaternion_to_yaw(np.array(q, dtype=">f8"))
    quaternion_to_yaw(np.array([q]))
    assert len(seen) == 2
