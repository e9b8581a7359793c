"""``quaternion_to_yaw``'s one-quaternion fast path under every ``np.seterr(under=)`` mode.

The fast path caught ``FloatingPointError`` for a subnormal yaw, which covers
``under="raise"`` only: under ``"warn"`` it emitted NumPy's "underflow
encountered in arctan2" (an error under ``-W error``), under ``"call"`` it called
the caller's ``np.seterrcall`` handler, where the general way (a batch, a
byte-swapped array) is silent. The oracle is the general way on the same values.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from navkit.geometry import quaternion_to_yaw

# Quaternions whose yaw is subnormal (or whose arguments are tiny), given as the
# fast path takes them (a list of floats) and as the general way does (">f8").
_TINY_YAWS = [
    (0.0, 0.0, 1e-310, 1.0),
    (0.0, 0.0, -1e-310, 1.0),
    (0.0, 0.0, 5e-324, 1.0),
    (1e-160, 1e-160, 0.0, 1.0),
    (0.0, 0.0, 1e-300, 1e10),
    (1.0, 5e-324, 1.0, -1.7e308),
    (0.0, 0.0, 1e-310, 3.0),
    (0.0, 0.0, -1e-310, -1.0),  # w < 0: the same rotation as (0, 0, 1e-310, 1)
    (0.0, 0.0, 1.0, 1e-310),  # a yaw a subnormal short of pi: nothing tiny, still silent
]


def _general(q: tuple[float, ...]) -> float:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return float(quaternion_to_yaw(np.array(q, dtype=">f8")))


@pytest.mark.parametrize("q", _TINY_YAWS)
@pytest.mark.parametrize("mode", ["warn", "print", "log", "call", "raise", "ignore"])
def test_one_quaternion_is_silent_under_every_underflow_mode(
    q: tuple[float, ...], mode: str, capsys: pytest.CaptureFixture[str]
) -> None:
    want = _general(q)
    calls: list[str] = []

    class _Log:
        def write(self, message: str) -> None:
            calls.append(message)

    handler = _Log() if mode == "log" else (lambda kind, flag: calls.append(kind))
    old_call = np.seterrcall(handler)
    try:
        with np.errstate(under=mode), warnings.catch_warnings():  # type: ignore[call-overload]
            warnings.simplefilter("error")
            for given in (list(q), tuple(q), np.array(q), tuple(np.float64(v) for v in q)):
                got = quaternion_to_yaw(given)
                assert isinstance(got, float)
                assert math.copysign(1.0, got) == math.copysign(1.0, want)
                assert got == want or (math.isnan(got) and math.isnan(want))
    finally:
        np.seterrcall(old_call)
    assert calls == []  # no seterrcall handler called, no log written
    assert capsys.readouterr().out == ""  # under "print" nothing printed


def test_the_tiny_cases_do_take_the_fast_path_and_have_subnormal_yaws() -> None:
    # The cases above must reach the arithmetic this file pins: their yaws are
    # subnormal (but the last, pi), and NumPy's arctan2 flags those.
    for q in _TINY_YAWS[:-1]:  # the last: pi
        yaw = _general(q)
        assert 0.0 < abs(yaw) < 2.2250738585072014e-308, (q, yaw)
    assert _general(_TINY_YAWS[-1]) == math.pi
    with np.errstate(under="raise"), pytest.raises(FloatingPointError):
        np.arctan2(np.float64(1e-310), np.float64(1.0))


def test_ordinary_yaws_unchanged_under_warn() -> None:
    rng = np.random.default_rng(34)
    with np.errstate(under="warn"), warnings.catch_warnings():
        warnings.simplefilter("error")
        for q in rng.normal(size=(500, 4)) * 10.0 ** rng.integers(-300, 300, size=(500, 1)):
            one = quaternion_to_yaw(list(map(float, q)))
            assert one == float(quaternion_to_yaw(q.astype(">f8")))
