"""A CompassCalibration pickled with a drifted unwrapping correction unwraps on exactly (review 54).

17670d7 (review 53) counts the unwrapping's whole turns as integers; before it,
``_correction`` was ``numpy.unwrap``'s running float sum of rounded ``±2π``
corrections, and a calibration pickled then holds that sum drifted off the
exact multiple of ``2π``. The commit says such a correction "is taken as its
nearest whole turns", which no test pinned (review 52's old pickles were made
before the correction existed): here a real pickle of 6cabf83 (17670d7's
parent) after 2,400 readings 170° apart (1,133 turns, its correction
-1132.9999999999907 turns, 64 ulps off) reads on as a calibration of today fed
the whole log, bit for bit.
"""

from __future__ import annotations

import base64
import math
import pickle
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import CompassCalibration

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at

#: The readings fed before pickling: 0°, 170°, 340°, 150°, ... (2,400 of them).
LOG = (np.arange(2400) * 170.0) % 360.0
#: CompassCalibration(unwrap=True) after LOG, pickled (protocol 4) at 17670d7's parent.
DRIFTED = (
    "gASVhwAAAAAAAACMGm5hdmtpdC5lc3RpbWF0aW9uLl9jb21wYXNzlIwSQ29tcGFzc0NhbGlicmF0aW9ulJOU"
    "KYGUTn2UKIwLX2NvcnJlY3Rpb26UR8C7ztlU/G6ljAhfaW5pdGlhbJRHAAAAAAAAAACMBV9sYXN0lEc/6+ze"
    "XaEVqYwHX3Vud3JhcJSIdYaUYi4="
)
#: Made again by the slow test below.
MAKER = f"""
import base64, json, pickle
import numpy as np
from navkit.estimation import CompassCalibration
cal = CompassCalibration(unwrap=True)
cal((np.arange({len(LOG)}) * 170.0) % 360.0)
print(json.dumps(base64.b64encode(pickle.dumps(cal, protocol=4)).decode()))
"""
#: Readings after the log: on through more turns, a 180° step and back.
NEXT = [0.0, 170.0, 340.0, 150.0, 330.0, 150.0, 330.0, 10.0]


def _check(encoded: str) -> None:
    old = pickle.loads(base64.b64decode(encoded))
    assert isinstance(old, CompassCalibration) and old.initial_deg == 0.0
    # The old release's sum of its corrections: not a whole number of turns.
    drifted = old._correction / (2.0 * math.pi)
    assert drifted != round(drifted) and abs(drifted - round(drifted)) < 1e-9
    today = CompassCalibration(unwrap=True)
    today(LOG)
    got = [old(r) for r in NEXT]
    want = [today(r) for r in NEXT]
    assert np.array_equal(np.array(got).view(np.int64), np.array(want).view(np.int64))
    # As the whole log unwrapped at once, exact whole turns: far from the drifted sum.
    whole = np.asarray(CompassCalibration(unwrap=True)(np.concatenate([LOG, NEXT])))
    assert got == whole[len(LOG) :].tolist()
    assert whole[-1] < -1130 * 2 * math.pi


def test_a_drifted_correction_is_taken_as_its_nearest_whole_turns() -> None:
    _check(DRIFTED)


@pytest.mark.slow
def test_the_drifted_pickle_made_again(tmp_path: Path) -> None:
    encoded = made_at("17670d7^", MAKER, tmp_path)
    assert encoded == DRIFTED
    _check(encoded)
