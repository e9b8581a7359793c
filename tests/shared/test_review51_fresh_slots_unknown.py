"""A pickle naming a slot its class no longer has is a ValueError naming both (review 51, FRESH).

:func:`navkit._shared.frozen.restore_slots` set each slot of a pickled state
with ``object.__setattr__``: a slot dropped (or renamed without a ``renamed``
entry) since the pickle was made raised ``AttributeError`` ("object has no
attribute"), as a ``PotentialFieldController`` pickled at 0123de4, before
908ac92 (its ``mode``), did as it loaded. A record's restore raises a
``ValueError`` naming the class for the same case
(:func:`navkit._shared.frozen.restore_read_only`); this one does too now.
"""

from __future__ import annotations

import base64
import pickle
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit._shared.frozen import restore_slots

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at


class _Slotted:
    __slots__ = ("values",)

    def __setstate__(self, state: Any) -> None:
        restore_slots(self, state)

    @property
    def size(self) -> int:
        return int(self.values.size)


@pytest.mark.parametrize("name", ["dropped", "size"])  # no slot; a property without setter
def test_a_state_naming_an_attribute_the_class_cannot_hold_is_refused(name: str) -> None:
    obj = object.__new__(_Slotted)
    with pytest.raises(ValueError, match=rf"_Slotted has no attribute '{name}': this pickle"):
        obj.__setstate__((None, {"values": np.zeros(2), name: 1}))


def test_a_state_of_its_own_slots_still_loads() -> None:
    obj = object.__new__(_Slotted)
    obj.__setstate__((None, {"values": np.zeros(3)}))
    assert obj.size == 3


OLD_COMMIT = "0123de4"
MAKER = """
import base64, json, pickle
from navkit.control import PotentialFieldController
print(json.dumps(base64.b64encode(pickle.dumps(PotentialFieldController())).decode()))
"""
#: MAKER's pickle, made by navkit at OLD_COMMIT (2026-11-30, before 908ac92).
OLD_PICKLE = (
    "gASVQAMAAAAAAACMKm5hdmtpdC5jb250cm9sLl9wb3RlbnRpYWxfZmllbGRfY29udHJvbGxlcpSMGFBv"
    "dGVudGlhbEZpZWxkQ29udHJvbGxlcpSTlCmBlE59lCiMB19hbmNob3KUTowEX3BpZJRoAIwEX1BpZJST"
    "lCmBlE59lCiMCGludGVncmFslEcAAAAAAAAAAIwOaW50ZWdyYWxfbGltaXSURz/wAAAAAAAAjAJrZJRH"
    "P7mZmZmZmZqMAmtplEcAAAAAAAAAAIwCa3CUR0AIAAAAAAAAjApsYXN0X2Vycm9ylE51hpRijApfc3Rp"
    "bGxfZm9ylEcAAAAAAAAAAIwJX3ZlbG9jaXR5lIwWbnVtcHkuX2NvcmUubXVsdGlhcnJheZSMDF9yZWNv"
    "bnN0cnVjdJSTlIwFbnVtcHmUjAduZGFycmF5lJOUSwCFlEMBYpSHlFKUKEsBSwKFlGgXjAVkdHlwZZST"
    "lIwCZjiUiYiHlFKUKEsDjAE8lE5OTkr/////Sv////9LAHSUYolDEAAAAAAAAAAAAAAAAAAAAACUdJRi"
    "jAphdHRyYWN0aW9ulIwkbmF2a2l0LnBsYW5uaW5nLnJlYWN0aXZlLl9hdHRyYWN0aW9ulIwRQmxlbmRl"
    "ZEF0dHJhY3Rpb26Uk5QpgZRdlChoFmgZSwCFlGgbh5RSlChLAUsChZRoI4lDEAAAAAAAAAAAAAAAAAAA"
    "AACUdJRiRz/wAAAAAAAARz/wAAAAAAAARz/wAAAAAAAARz/wAAAAAAAARz/gAAAAAAAARz/DMzMzMzMz"
    "Rz/wAAAAAAAARz/wAAAAAAAAZWKMDmdvYWxfdG9sZXJhbmNllEc/qZmZmZmZmowQaW5mbHVlbmNlX3Jh"
    "ZGl1c5RHP+MzMzMzMzOMBWtfcmVwlEc/qZmZmZmZmowJbWF4X2FjY2VslEc/8AAAAAAAAIwJbWF4X2Rl"
    "Y2VslEdAAAAAAAAAAIwJbWF4X29tZWdhlEdAAAAAAAAAAIwJbWF4X3NwZWVklEc/4AAAAAAAAIwEbW9k"
    "ZZSMBG9tbmmUjAxzdGFsbF9yYWRpdXOURz+pmZmZmZmajA1zdGFsbF90aW1lb3V0lEdAAAAAAAAAAHWG"
    "lGIu"
)


def test_a_controller_pickled_before_908ac92_loads_its_mode_as_drive() -> None:
    # It was refused here, naming 'mode', until review 52 (FOUND4) mapped the option's
    # old name to today's (8c31a76 renamed it, the same values): it loads and steps
    # as a new controller.
    from navkit.control import PotentialFieldController
    from navkit.geometry import Pose2D

    old = pickle.loads(base64.b64decode("".join(OLD_PICKLE)))
    fresh = PotentialFieldController()
    assert old.drive == "omni" and repr(old) == repr(fresh)
    pose, target = Pose2D(0.1, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0)
    for _ in range(3):
        assert old.step(pose, target, 0.05) == fresh.step(pose, target, 0.05)


@pytest.mark.slow
def test_the_pickle_is_the_old_release(tmp_path: Path) -> None:
    assert made_at(OLD_COMMIT, MAKER, tmp_path) == "".join(OLD_PICKLE)
