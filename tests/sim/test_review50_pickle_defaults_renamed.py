"""Review 50 (PARKED): records pickled before they had slots load by field name.

``GameState`` and ``GreedyStep`` were dataclasses without slots before issue 11
(commit 0123de4), which also renamed their point fields (``robot`` ->
``robot_xy``, ``waypoint`` -> ``waypoint_xy``, ...). Their pickles of then hold
the instance ``__dict__``; ``restore_read_only`` zipped it onto today's fields
as if it were the list of values, so each field got a KEY: a ``GameState``
loaded silently as ``GameState(robot_xy='robot', ball_xy='ball',
teammates_xy='own_goal', ...)``, a ``GreedyStep`` as ``GreedyStep(cell='cell',
waypoint_xy='waypoint', ...)``, and a subclass's raised a bare ``zip()``
ValueError. A dict state is now restored by name, old names through the
class's ``_renamed_fields``; a name the record cannot hold, or a field left
without a value, is a ValueError naming the class.

The pickles below are real: made by navkit at commit 5e5f83f (the one before
0123de4) from a ``GameState``, a subclass of it with an attribute of its own
and a ``GreedyStep``, protocols 2 and 5; ``test_the_pickles_are_the_old_releases``
makes them again there (slow; a git checkout of the project).
"""

from __future__ import annotations

import base64
import pickle
import types
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np
import pytest

from navkit._shared.frozen import restore_read_only
from navkit.behaviours import GameState
from navkit.planning.reactive._greedy import GreedyStep
from old_release import install_module, made_at

OLD_COMMIT = "5e5f83f"
MODULE = "review50_old_records"
SUBCLASSES = "from navkit.behaviours import GameState\nclass Tagged(GameState):\n    pass\n"

#: Makes the pickles (run against the source of ``OLD_COMMIT``): base64 by "class/protocol".
MAKER = f"""
import base64, json, pickle, sys, types
import numpy as np
mod = types.ModuleType({MODULE!r})
sys.modules[mod.__name__] = mod
exec({SUBCLASSES!r}, mod.__dict__)
from navkit.behaviours import GameState
from navkit.planning.reactive._greedy import GreedyStep
kw = dict(robot=(0.0, 0.0), ball=(1.0, 0.0), teammates=[[-2.0, 1.0]], opponents=[[1.1, 0.0]],
          own_goal=(-5.0, 0.0), opponent_goal=(5.0, 0.0))
tagged = mod.Tagged(**kw)
object.__setattr__(tagged, "tag", "a")
made = {{"GameState": GameState(**kw), "Tagged": tagged,
        "GreedyStep": GreedyStep((1, 2), np.array([0.5, 0.25]), 1.0, 2.0, 3)}}
out = {{}}
for name, obj in made.items():
    for protocol in (2, 5):
        data = pickle.dumps(obj, protocol=protocol)
        out[f"{{name}}/{{protocol}}"] = base64.b64encode(data).decode()
print(json.dumps(out))
"""

OLD_PICKLES = {
    "GameState/2": (
        "gAJjbmF2a2l0LmJlaGF2aW91cnMuX3NvY2NlcgpHYW1lU3RhdGUKcQApgXEBfXECKFgFAAAAcm9ib3Rx"
        "A2NudW1weS5fY29yZS5tdWx0aWFycmF5Cl9yZWNvbnN0cnVjdApxBGNudW1weQpuZGFycmF5CnEFSwCF"
        "cQZjX2NvZGVjcwplbmNvZGUKcQdYAQAAAGJxCFgGAAAAbGF0aW4xcQmGcQpScQuHcQxScQ0oSwFLAoVx"
        "DmNudW1weQpkdHlwZQpxD1gCAAAAZjhxEImIh3ERUnESKEsDWAEAAAA8cRNOTk5K/////0r/////SwB0"
        "cRRiiWgHWBAAAAAAAAAAAAAAAAAAAAAAAAAAcRVoCYZxFlJxF3RxGGJYBAAAAGJhbGxxGWgEaAVLAIVx"
        "GmgLh3EbUnEcKEsBSwKFcR1oEoloB1gRAAAAAAAAAAAAw7A/AAAAAAAAAABxHmgJhnEfUnEgdHEhYlgI"
        "AAAAb3duX2dvYWxxImgEaAVLAIVxI2gLh3EkUnElKEsBSwKFcSZoEoloB1gRAAAAAAAAAAAAFMOAAAAA"
        "AAAAAABxJ2gJhnEoUnEpdHEqYlgNAAAAb3Bwb25lbnRfZ29hbHEraARoBUsAhXEsaAuHcS1ScS4oSwFL"
        "AoVxL2gSiWgHWBAAAAAAAAAAAAAUQAAAAAAAAAAAcTBoCYZxMVJxMnRxM2JYCQAAAHRlYW1tYXRlc3E0"
        "aARoBUsAhXE1aAuHcTZScTcoSwFLAUsChnE4aBKJaAdYEgAAAAAAAAAAAADDgAAAAAAAAMOwP3E5aAmG"
        "cTpScTt0cTxiWAkAAABvcHBvbmVudHNxPWgEaAVLAIVxPmgLh3E/UnFAKEsBSwFLAoZxQWgSiWgHWBcA"
        "AADCmsKZwpnCmcKZwpnDsT8AAAAAAAAAAHFCaAmGcUNScUR0cUViWBEAAABwb3NzZXNzaW9uX3JhZGl1"
        "c3FGRz/QAAAAAAAAWAgAAABoYXNfYmFsbHFHiVgSAAAAb3Bwb25lbnRfd2l0aF9iYWxscUhLAHViLg=="
    ),
    "GameState/5": (
        "gAWV3wEAAAAAAACMGW5hdmtpdC5iZWhhdmlvdXJzLl9zb2NjZXKUjAlHYW1lU3RhdGWUk5QpgZR9lCiM"
        "BXJvYm90lIwTbnVtcHkuX2NvcmUubnVtZXJpY5SMC19mcm9tYnVmZmVylJOUKEMQAAAAAAAAAAAAAAAA"
        "AAAAAJSMBW51bXB5lIwFZHR5cGWUk5SMAmY4lImIh5RSlChLA4wBPJROTk5K/////0r/////SwB0lGJL"
        "AoWUjAFDlHSUUpSMBGJhbGyUaAgoQxAAAAAAAADwPwAAAAAAAAAAlGgPSwKFlGgTdJRSlIwIb3duX2dv"
        "YWyUaAgoQxAAAAAAAAAUwAAAAAAAAAAAlGgPSwKFlGgTdJRSlIwNb3Bwb25lbnRfZ29hbJRoCChDEAAA"
        "AAAAABRAAAAAAAAAAACUaA9LAoWUaBN0lFKUjAl0ZWFtbWF0ZXOUaAgoQxAAAAAAAAAAwAAAAAAAAPA/"
        "lGgPSwFLAoaUaBN0lFKUjAlvcHBvbmVudHOUaAgoQxCamZmZmZnxPwAAAAAAAAAAlGgPSwFLAoaUaBN0"
        "lFKUjBFwb3NzZXNzaW9uX3JhZGl1c5RHP9AAAAAAAACMCGhhc19iYWxslImMEm9wcG9uZW50X3dpdGhf"
        "YmFsbJRLAHViLg=="
    ),
    "Tagged/2": (
        "gAJjcmV2aWV3NTBfb2xkX3JlY29yZHMKVGFnZ2VkCnEAKYFxAX1xAihYBQAAAHJvYm90cQNjbnVtcHku"
        "X2NvcmUubXVsdGlhcnJheQpfcmVjb25zdHJ1Y3QKcQRjbnVtcHkKbmRhcnJheQpxBUsAhXEGY19jb2Rl"
        "Y3MKZW5jb2RlCnEHWAEAAABicQhYBgAAAGxhdGluMXEJhnEKUnELh3EMUnENKEsBSwKFcQ5jbnVtcHkK"
        "ZHR5cGUKcQ9YAgAAAGY4cRCJiIdxEVJxEihLA1gBAAAAPHETTk5OSv////9K/////0sAdHEUYoloB1gQ"
        "AAAAAAAAAAAAAAAAAAAAAAAAAHEVaAmGcRZScRd0cRhiWAQAAABiYWxscRloBGgFSwCFcRpoC4dxG1Jx"
        "HChLAUsChXEdaBKJaAdYEQAAAAAAAAAAAMOwPwAAAAAAAAAAcR5oCYZxH1JxIHRxIWJYCAAAAG93bl9n"
        "b2FscSJoBGgFSwCFcSNoC4dxJFJxJShLAUsChXEmaBKJaAdYEQAAAAAAAAAAABTDgAAAAAAAAAAAcSdo"
        "CYZxKFJxKXRxKmJYDQAAAG9wcG9uZW50X2dvYWxxK2gEaAVLAIVxLGgLh3EtUnEuKEsBSwKFcS9oEolo"
        "B1gQAAAAAAAAAAAAFEAAAAAAAAAAAHEwaAmGcTFScTJ0cTNiWAkAAAB0ZWFtbWF0ZXNxNGgEaAVLAIVx"
        "NWgLh3E2UnE3KEsBSwFLAoZxOGgSiWgHWBIAAAAAAAAAAAAAw4AAAAAAAADDsD9xOWgJhnE6UnE7dHE8"
        "YlgJAAAAb3Bwb25lbnRzcT1oBGgFSwCFcT5oC4dxP1JxQChLAUsBSwKGcUFoEoloB1gXAAAAwprCmcKZ"
        "wpnCmcKZw7E/AAAAAAAAAABxQmgJhnFDUnFEdHFFYlgRAAAAcG9zc2Vzc2lvbl9yYWRpdXNxRkc/0AAA"
        "AAAAAFgIAAAAaGFzX2JhbGxxR4lYEgAAAG9wcG9uZW50X3dpdGhfYmFsbHFISwBYAwAAAHRhZ3FJWAEA"
        "AABhcUp1Yi4="
    ),
    "Tagged/5": (
        "gAWV4QEAAAAAAACMFHJldmlldzUwX29sZF9yZWNvcmRzlIwGVGFnZ2VklJOUKYGUfZQojAVyb2JvdJSM"
        "E251bXB5Ll9jb3JlLm51bWVyaWOUjAtfZnJvbWJ1ZmZlcpSTlChDEAAAAAAAAAAAAAAAAAAAAACUjAVu"
        "dW1weZSMBWR0eXBllJOUjAJmOJSJiIeUUpQoSwOMATyUTk5OSv////9K/////0sAdJRiSwKFlIwBQ5R0"
        "lFKUjARiYWxslGgIKEMQAAAAAAAA8D8AAAAAAAAAAJRoD0sChZRoE3SUUpSMCG93bl9nb2FslGgIKEMQ"
        "AAAAAAAAFMAAAAAAAAAAAJRoD0sChZRoE3SUUpSMDW9wcG9uZW50X2dvYWyUaAgoQxAAAAAAAAAUQAAA"
        "AAAAAAAAlGgPSwKFlGgTdJRSlIwJdGVhbW1hdGVzlGgIKEMQAAAAAAAAAMAAAAAAAADwP5RoD0sBSwKG"
        "lGgTdJRSlIwJb3Bwb25lbnRzlGgIKEMQmpmZmZmZ8T8AAAAAAAAAAJRoD0sBSwKGlGgTdJRSlIwRcG9z"
        "c2Vzc2lvbl9yYWRpdXOURz/QAAAAAAAAjAhoYXNfYmFsbJSJjBJvcHBvbmVudF93aXRoX2JhbGyUSwCM"
        "A3RhZ5SMAWGUdWIu"
    ),
    "GreedyStep/2": (
        "gAJjbmF2a2l0LnBsYW5uaW5nLnJlYWN0aXZlLl9ncmVlZHkKR3JlZWR5U3RlcApxACmBcQF9cQIoWAQA"
        "AABjZWxscQNLAUsChnEEWAgAAAB3YXlwb2ludHEFY251bXB5Ll9jb3JlLm11bHRpYXJyYXkKX3JlY29u"
        "c3RydWN0CnEGY251bXB5Cm5kYXJyYXkKcQdLAIVxCGNfY29kZWNzCmVuY29kZQpxCVgBAAAAYnEKWAYA"
        "AABsYXRpbjFxC4ZxDFJxDYdxDlJxDyhLAUsChXEQY251bXB5CmR0eXBlCnERWAIAAABmOHESiYiHcRNS"
        "cRQoSwNYAQAAADxxFU5OTkr/////Sv////9LAHRxFmKJaAlYEgAAAAAAAAAAAMOgPwAAAAAAAMOQP3EX"
        "aAuGcRhScRl0cRpiWAEAAABncRtHP/AAAAAAAABYAQAAAGhxHEdAAAAAAAAAAFgKAAAAY2FuZGlkYXRl"
        "c3EdSwN1Yi4="
    ),
    "GreedyStep/5": (
        "gAWV/wAAAAAAAACMIG5hdmtpdC5wbGFubmluZy5yZWFjdGl2ZS5fZ3JlZWR5lIwKR3JlZWR5U3RlcJST"
        "lCmBlH2UKIwEY2VsbJRLAUsChpSMCHdheXBvaW50lIwTbnVtcHkuX2NvcmUubnVtZXJpY5SMC19mcm9t"
        "YnVmZmVylJOUKJYQAAAAAAAAAAAAAAAAAOA/AAAAAAAA0D+UjAVudW1weZSMBWR0eXBllJOUjAJmOJSJ"
        "iIeUUpQoSwOMATyUTk5OSv////9K/////0sAdJRiSwKFlIwBQ5R0lFKUjAFnlEc/8AAAAAAAAIwBaJRH"
        "QAAAAAAAAACMCmNhbmRpZGF0ZXOUSwN1Yi4="
    ),
}


@pytest.fixture
def subclasses(monkeypatch: pytest.MonkeyPatch) -> types.ModuleType:
    """The subclass's module, where the pickles find it."""
    return install_module(monkeypatch, MODULE, SUBCLASSES)


def _check(record: Any, name: str, module: types.ModuleType) -> None:
    if name == "GreedyStep":
        assert type(record) is GreedyStep
        want = GreedyStep((1, 2), np.array([0.5, 0.25]), 1.0, 2.0, 3)
        assert (record.cell, record.g, record.h, record.candidates) == ((1, 2), 1.0, 2.0, 3)
        np.testing.assert_array_equal(record.waypoint_xy, want.waypoint_xy)
        assert not record.waypoint_xy.flags.writeable
        assert repr(record) == repr(want)
        return
    cls = GameState if name == "GameState" else module.Tagged
    assert type(record) is cls
    want = cls(
        robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), teammates_xy=[[-2.0, 1.0]],
        opponents_xy=[[1.1, 0.0]], own_goal_xy=(-5.0, 0.0), opponent_goal_xy=(5.0, 0.0),
    )  # fmt: skip
    assert repr(record) == repr(want)
    for field in ("robot_xy", "ball_xy", "teammates_xy", "opponents_xy", "own_goal_xy",
                  "opponent_goal_xy"):  # fmt: skip
        value = getattr(record, field)
        np.testing.assert_array_equal(value, getattr(want, field))
        assert not value.flags.writeable
    assert (record.has_ball, record.opponent_with_ball) == (False, 0)
    if name == "Tagged":
        assert record.tag == "a"
    assert repr(pickle.loads(pickle.dumps(record))) == repr(want)


@pytest.mark.parametrize("key", sorted(OLD_PICKLES))
def test_a_record_pickled_before_its_slots_loads_by_name(
    key: str, subclasses: types.ModuleType
) -> None:
    data = base64.b64decode("".join(OLD_PICKLES[key]))
    _check(pickle.loads(data), key.split("/")[0], subclasses)


@dataclass(frozen=True, slots=True)
class _Point:
    x_m: float
    y_m: float = 0.0

    _renamed_fields = MappingProxyType({"x": "x_m"})
    _added_fields = MappingProxyType({"y_m": lambda point: 0.0})

    def __setstate__(self, state: Any) -> None:
        restore_read_only(self, state, ())


def test_a_dict_state_is_restored_by_name_or_refused() -> None:
    point = object.__new__(_Point)
    point.__setstate__({"x": 2.0})  # old name, and a field added since
    assert point == _Point(2.0, 0.0)
    point = object.__new__(_Point)
    point.__setstate__({"y_m": 3.0, "x_m": 1.0})  # any order
    assert point == _Point(1.0, 3.0)
    # A name the record cannot hold, or a field with no value: refused, naming both.
    with pytest.raises(ValueError, match=r"_Point has no field 'z'"):
        object.__new__(_Point).__setstate__({"x_m": 1.0, "z": 2.0})
    with pytest.raises(ValueError, match=r"_Point holds no value for x_m"):
        object.__new__(_Point).__setstate__({"y_m": 1.0})


@pytest.mark.slow
def test_the_pickles_are_the_old_releases(tmp_path: Path, subclasses: types.ModuleType) -> None:
    # Made again by the source of OLD_COMMIT: the same bytes, and they load as above.
    fresh = made_at(OLD_COMMIT, MAKER, tmp_path)
    assert fresh == {key: "".join(parts) for key, parts in OLD_PICKLES.items()}
    for key, data in fresh.items():
        _check(pickle.loads(base64.b64decode(data)), key.split("/")[0], subclasses)
