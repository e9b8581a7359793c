"""Review 51 (FRESH): a controller and its shallow copy pickled before 3bf2b94 both load.

Before 3bf2b94 a shallow copy of a ``PotentialFieldController`` shared its
original's heading PID (the ``_Pid`` holding the integrator and last error: the
reason they moved into the controller's own slots). A pickle of the two holds
that ``_Pid`` once. Since 6f4692d a loading controller takes the old run state
from its ``_Pid``; the first of the two took it and deleted it from the shared
``_Pid``, and the second loaded without an integrator: its first step raised
``AttributeError`` ("no attribute '_integral'"). Each loading controller now
takes a ``_Pid`` of its own and leaves the shared one's state for the others:
both step on as the controller stepped today.

The pickle below is real: made by navkit at a0dd033 (3bf2b94's parent, protocol
2) by ``MAKER``; ``test_the_pickle_is_the_old_release`` makes it again there
(slow; a git checkout of the project).
"""

from __future__ import annotations

import base64
import pickle
import sys
from pathlib import Path

import pytest

from navkit.control import PotentialFieldController

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at

OLD_COMMIT = "a0dd033"
MAKER = """
import base64, copy, json, pickle
from navkit.control import PotentialFieldController
ctl = PotentialFieldController(kp=1.0, ki=0.5, kd=0.1)
for k in range(3):
    ctl.step((0.0, 0.0, 0.2 * k), (2.0, 1.0, 1.0), dt=0.1)
twin = copy.copy(ctl)
assert twin._pid is ctl._pid
print(json.dumps({"pickle": base64.b64encode(pickle.dumps([ctl, twin], protocol=2)).decode(),
                  "run": [ctl._pid.integral, ctl._pid.last_error]}))
"""
#: The shared PID's integrator and last error when the two were pickled.
OLD_RUN = (0.24000000000000002, 0.6)
OLD_PICKLE = (
    "gAJdcQAoY25hdmtpdC5jb250cm9sLl9wb3RlbnRpYWxfZmllbGRfY29udHJvbGxlcgpQb3RlbnRpYWxG"
    "aWVsZENvbnRyb2xsZXIKcQEpgXECTn1xAyhYBwAAAF9hbmNob3JxBGNudW1weS5fY29yZS5tdWx0aWFy"
    "cmF5Cl9yZWNvbnN0cnVjdApxBWNudW1weQpuZGFycmF5CnEGSwCFcQdjX2NvZGVjcwplbmNvZGUKcQhY"
    "AQAAAGJxCVgGAAAAbGF0aW4xcQqGcQtScQyHcQ1ScQ4oSwFLAoVxD2NudW1weQpkdHlwZQpxEFgCAAAA"
    "ZjhxEYmIh3ESUnETKEsDWAEAAAA8cRROTk5K/////0r/////SwB0cRViiWgIWBAAAAAAAAAAAAAAAAAA"
    "AAAAAAAAcRZoCoZxF1JxGHRxGWJYBAAAAF9waWRxGmNuYXZraXQuY29udHJvbC5fcG90ZW50aWFsX2Zp"
    "ZWxkX2NvbnRyb2xsZXIKX1BpZApxGymBcRxOfXEdKFgIAAAAaW50ZWdyYWxxHkc/zrhR64UeuVgOAAAA"
    "aW50ZWdyYWxfbGltaXRxH0c/8AAAAAAAAFgCAAAAa2RxIEc/uZmZmZmZmlgCAAAAa2lxIUc/4AAAAAAA"
    "AFgCAAAAa3BxIkc/8AAAAAAAAFgKAAAAbGFzdF9lcnJvcnEjRz/jMzMzMzMzdYZxJGJYCgAAAF9zdGls"
    "bF9mb3JxJUc/yZmZmZmZmlgJAAAAX3ZlbG9jaXR5cSZoBWgGSwCFcSdoDIdxKFJxKShLAUsChXEqaBOJ"
    "aAhYGAAAAMOpw4EMw51JLMORP8Opw4EMw51JLMOBP3EraAqGcSxScS10cS5iWAoAAABhdHRyYWN0aW9u"
    "cS9jbmF2a2l0LnBsYW5uaW5nLnJlYWN0aXZlLl9hdHRyYWN0aW9uCkJsZW5kZWRBdHRyYWN0aW9uCnEw"
    "KYFxMV1xMihoBWgGSwCFcTNoDIdxNFJxNShLAUsChXE2aBOJaAhYEAAAAAAAAAAAAAAAAAAAAAAAAABx"
    "N2gKhnE4UnE5dHE6Ykc/8AAAAAAAAEc/8AAAAAAAAEc/8AAAAAAAAEc/8AAAAAAAAEc/4AAAAAAAAEc/"
    "wzMzMzMzM0c/8AAAAAAAAEc/8AAAAAAAAGViWAUAAABkcml2ZXE7WAQAAABvbW5pcTxYDgAAAGdvYWxf"
    "dG9sZXJhbmNlcT1HP6mZmZmZmZpYEAAAAGluZmx1ZW5jZV9yYWRpdXNxPkc/4zMzMzMzM1gFAAAAa19y"
    "ZXBxP0c/qZmZmZmZmlgJAAAAbWF4X2FjY2VscUBHP/AAAAAAAABYCQAAAG1heF9kZWNlbHFBR0AAAAAA"
    "AAAAWAkAAABtYXhfb21lZ2FxQkdAAAAAAAAAAFgJAAAAbWF4X3NwZWVkcUNHP+AAAAAAAABYDAAAAHN0"
    "YWxsX3JhZGl1c3FERz+pmZmZmZmaWA0AAABzdGFsbF90aW1lb3V0cUVHQAAAAAAAAAB1hnFGYmgBKYFx"
    "R059cUgoaARoDmgaaBxoJUc/yZmZmZmZmmgmaCloL2gxaDtoPGg9Rz+pmZmZmZmaaD5HP+MzMzMzMzNo"
    "P0c/qZmZmZmZmmhARz/wAAAAAAAAaEFHQAAAAAAAAABoQkdAAAAAAAAAAGhDRz/gAAAAAAAAaERHP6mZ"
    "mZmZmZpoRUdAAAAAAAAAAHWGcUliZS4="
)


def _stepped() -> PotentialFieldController:
    """The controller of ``MAKER``, built and stepped today."""
    ctl = PotentialFieldController(kp=1.0, ki=0.5, kd=0.1)
    for k in range(3):
        ctl.step((0.0, 0.0, 0.2 * k), (2.0, 1.0, 1.0), 0.1)
    return ctl


def test_a_controller_and_its_copy_pickled_sharing_a_pid_both_step_on() -> None:
    pair = pickle.loads(base64.b64decode("".join(OLD_PICKLE)))
    fresh = [_stepped(), _stepped()]
    for ctl in pair:
        assert (ctl._integral, ctl._last_error) == OLD_RUN
    # Each has a PID of its own again: one's steps leave the other's as they were.
    assert pair[0]._pid is not pair[1]._pid
    for k in range(3, 8):
        pose, target = (0.05 * k, 0.0, 0.2 * k), (2.0, 1.0, 1.0)
        for ctl, today in zip(pair, fresh, strict=True):
            assert ctl.step(pose, target, 0.1) == today.step(pose, target, 0.1)
        assert (pair[1]._integral, pair[1]._last_error) == (
            fresh[1]._integral, fresh[1]._last_error
        )  # fmt: skip
    # Saved again, neither carries the old state any more.
    again = pickle.loads(pickle.dumps(pair))
    assert all(not hasattr(ctl._pid, "_carried") for ctl in again)


@pytest.mark.slow
def test_the_pickle_is_the_old_release(tmp_path: Path) -> None:
    # Made again by the source of OLD_COMMIT: the same bytes and run state.
    fresh = made_at(OLD_COMMIT, MAKER, tmp_path)
    assert fresh == {"pickle": "".join(OLD_PICKLE), "run": list(OLD_RUN)}
