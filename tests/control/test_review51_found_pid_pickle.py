"""Review 51 (FOUND3): a PotentialFieldController pickled before 3bf2b94 loads and steps on.

3bf2b94 moved the heading PID's integrator and last error from the private
``_Pid`` object into the controller's own slots (so that a shallow copy no
longer shares them). A controller pickled before holds them in its ``_Pid``'s
state, whose slots no longer exist: loading it raised ``AttributeError``
("'_Pid' object has no attribute 'integral'"), for every pickle made from the
project's first day (908ac92) to that commit. ``_Pid`` now keeps them for the
controller's ``__setstate__``, which takes them into its slots: the loaded
controller steps on exactly as one that took the same steps today.

The pickle below is real: made by navkit at a0dd033 (3bf2b94's parent, protocol
2) from the controller and steps of ``MAKER``; ``test_the_pickle_is_the_old_release``
makes it again there (slow; a git checkout of the project).
"""

from __future__ import annotations

import base64
import copy
import pickle
from pathlib import Path

import pytest

from navkit.control import PotentialFieldController
from old_release import made_at

OLD_COMMIT = "a0dd033"
MAKER = """
import base64, json, pickle
from navkit.control import PotentialFieldController
ctl = PotentialFieldController(kp=1.0, ki=0.5, kd=0.1)
for k in range(3):
    ctl.step((0.0, 0.0, 0.2 * k), (2.0, 1.0, 1.0), dt=0.1)  # keyword-only then
pid = ctl._pid
print(json.dumps({"pickle": base64.b64encode(pickle.dumps(ctl, protocol=2)).decode(),
                  "run": [pid.integral, pid.last_error]}))
"""
#: The heading PID's integrator and last error when it was pickled (MAKER's "run").
OLD_RUN = (0.24000000000000002, 0.6)
OLD_PICKLE = (
    "gAJjbmF2a2l0LmNvbnRyb2wuX3BvdGVudGlhbF9maWVsZF9jb250cm9sbGVyClBvdGVudGlhbEZpZWxk"
    "Q29udHJvbGxlcgpxACmBcQFOfXECKFgHAAAAX2FuY2hvcnEDY251bXB5Ll9jb3JlLm11bHRpYXJyYXkK"
    "X3JlY29uc3RydWN0CnEEY251bXB5Cm5kYXJyYXkKcQVLAIVxBmNfY29kZWNzCmVuY29kZQpxB1gBAAAA"
    "YnEIWAYAAABsYXRpbjFxCYZxClJxC4dxDFJxDShLAUsChXEOY251bXB5CmR0eXBlCnEPWAIAAABmOHEQ"
    "iYiHcRFScRIoSwNYAQAAADxxE05OTkr/////Sv////9LAHRxFGKJaAdYEAAAAAAAAAAAAAAAAAAAAAAA"
    "AABxFWgJhnEWUnEXdHEYYlgEAAAAX3BpZHEZY25hdmtpdC5jb250cm9sLl9wb3RlbnRpYWxfZmllbGRf"
    "Y29udHJvbGxlcgpfUGlkCnEaKYFxG059cRwoWAgAAABpbnRlZ3JhbHEdRz/OuFHrhR65WA4AAABpbnRl"
    "Z3JhbF9saW1pdHEeRz/wAAAAAAAAWAIAAABrZHEfRz+5mZmZmZmaWAIAAABraXEgRz/gAAAAAAAAWAIA"
    "AABrcHEhRz/wAAAAAAAAWAoAAABsYXN0X2Vycm9ycSJHP+MzMzMzMzN1hnEjYlgKAAAAX3N0aWxsX2Zv"
    "cnEkRz/JmZmZmZmaWAkAAABfdmVsb2NpdHlxJWgEaAVLAIVxJmgLh3EnUnEoKEsBSwKFcSloEoloB1gY"
    "AAAAw6nDgQzDnUksw5E/w6nDgQzDnUksw4E/cSpoCYZxK1JxLHRxLWJYCgAAAGF0dHJhY3Rpb25xLmNu"
    "YXZraXQucGxhbm5pbmcucmVhY3RpdmUuX2F0dHJhY3Rpb24KQmxlbmRlZEF0dHJhY3Rpb24KcS8pgXEw"
    "XXExKGgEaAVLAIVxMmgLh3EzUnE0KEsBSwKFcTVoEoloB1gQAAAAAAAAAAAAAAAAAAAAAAAAAHE2aAmG"
    "cTdScTh0cTliRz/wAAAAAAAARz/wAAAAAAAARz/wAAAAAAAARz/wAAAAAAAARz/gAAAAAAAARz/DMzMz"
    "MzMzRz/wAAAAAAAARz/wAAAAAAAAZWJYBQAAAGRyaXZlcTpYBAAAAG9tbmlxO1gOAAAAZ29hbF90b2xl"
    "cmFuY2VxPEc/qZmZmZmZmlgQAAAAaW5mbHVlbmNlX3JhZGl1c3E9Rz/jMzMzMzMzWAUAAABrX3JlcHE+"
    "Rz+pmZmZmZmaWAkAAABtYXhfYWNjZWxxP0c/8AAAAAAAAFgJAAAAbWF4X2RlY2VscUBHQAAAAAAAAABY"
    "CQAAAG1heF9vbWVnYXFBR0AAAAAAAAAAWAkAAABtYXhfc3BlZWRxQkc/4AAAAAAAAFgMAAAAc3RhbGxf"
    "cmFkaXVzcUNHP6mZmZmZmZpYDQAAAHN0YWxsX3RpbWVvdXRxREdAAAAAAAAAAHWGcUViLg=="
)


def _stepped() -> PotentialFieldController:
    """The controller of ``MAKER``, built and stepped today."""
    ctl = PotentialFieldController(kp=1.0, ki=0.5, kd=0.1)
    for k in range(3):
        ctl.step((0.0, 0.0, 0.2 * k), (2.0, 1.0, 1.0), 0.1)
    return ctl


def _check(ctl: PotentialFieldController) -> None:
    fresh = _stepped()
    assert repr(ctl) == repr(fresh)
    assert (ctl._integral, ctl._last_error) == OLD_RUN == (fresh._integral, fresh._last_error)
    assert not hasattr(ctl._pid, "_carried")
    twin, again = copy.copy(ctl), pickle.loads(pickle.dumps(ctl))
    for k in range(3, 8):
        pose, target = (0.05 * k, 0.0, 0.2 * k), (2.0, 1.0, 1.0)
        want = fresh.step(pose, target, 0.1)
        for other in (ctl, twin, again):
            assert other.step(pose, target, 0.1) == want


def test_a_controller_pickled_before_its_pid_state_moved_loads_and_steps_on() -> None:
    _check(pickle.loads(base64.b64decode("".join(OLD_PICKLE))))


@pytest.mark.slow
def test_the_pickle_is_the_old_release(tmp_path: Path) -> None:
    # Made again by the source of OLD_COMMIT: the same bytes and run state.
    fresh = made_at(OLD_COMMIT, MAKER, tmp_path)
    assert fresh == {"pickle": "".join(OLD_PICKLE), "run": list(OLD_RUN)}
