"""Review 51: a ``DiffOdometry`` pickled before its scalar path's slots loads and runs on.

908ac92 (issue 17's small calls) gave ``DiffOdometry`` a scalar path for
``update`` with five slots made in ``__init__`` (the counter's modulus and
range, each wheel's metres per tick). A pickle made before then held none of
them, and its first ``update`` raised ``AttributeError: _low`` (found by
review 51's FOUND3). The class names them in ``_added_fields``, made from the
slots such a pickle holds as ``__init__`` makes them: the loaded odometry
carries on exactly as the release that saved it would have.

The pickles below are real, made by navkit at 5e5f83f (protocol 2) by
``MAKER``, with the poses that release reported for three more readings;
``test_the_pickles_are_the_old_releases`` makes them again there (slow; a git
checkout of the project).
"""

from __future__ import annotations

import base64
import pickle
from pathlib import Path

import pytest

from navkit.estimation import DiffOdometry
from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive
from old_release import made_at

MAKER = """
import base64, json, pickle
from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive
from navkit.estimation import DiffOdometry
drive = DiffDrive(track=0.5, left_radius=0.1, right_radius=0.102)
made = {}
for name, bits in (("wrapping", 16), ("plain", None)):
    odo = DiffOdometry(drive, 1000, bits, pose=Pose2D(3.0, -2.0, 0.4))
    for left, right in ((65000, 65100), (300, 520), (1400, 1300)):
        odo.update(left, right)
    made[name] = base64.b64encode(pickle.dumps(odo, protocol=2)).decode()
    later = [odo.update(left, right) for left, right in ((1500, 1450), (2600, 2900), (2700, 2650))]
    made[name + "_later"] = [[p.x, p.y, p.theta] for p in later]
print(json.dumps(made))
"""

#: Readings after the pickle was made, and the poses 5e5f83f reported for them.
LATER = ((1500, 1450), (2600, 2900), (2700, 2650))
OLD = {
    "wrapping": (
        "gAJjbmF2a2l0LmVzdGltYXRpb24uX29kb21ldHJ5CkRpZmZPZG9tZXRyeQpxACmBcQFOfXECKFgFAAAAX2Jp"
        "dHNxA0sQWAYAAABfZHJpdmVxBGNuYXZraXQua2luZW1hdGljcy5fZGlmZgpEaWZmRHJpdmUKcQUpgXEGTn1x"
        "ByhYBQAAAF9sZWZ0cQhHP7mZmZmZmZpYBgAAAF9yaWdodHEJRz+6HKwIMSbpWAYAAABfdHJhY2txCkc/4AAA"
        "AAAAAHWGcQtiWAUAAABfbGFzdHEMTXgFTRQFhnENWAcAAABfbWV0aG9kcQ5YAwAAAGFyY3EPWAUAAABfcG9z"
        "ZXEQY25hdmtpdC5nZW9tZXRyeS5fcG9zZQpQb3NlMkQKcREpgXESXXETKEdAEDQxHkHCsUe/+DKfgLafxEc/"
        "yJ1itNbdsGViWA4AAABfdGlja3NfcGVyX3JldnEUR0CPQAAAAAAAdYZxFWIu"
    ),
    "plain": (
        "gAJjbmF2a2l0LmVzdGltYXRpb24uX29kb21ldHJ5CkRpZmZPZG9tZXRyeQpxACmBcQFOfXECKFgFAAAAX2Jp"
        "dHNxA05YBgAAAF9kcml2ZXEEY25hdmtpdC5raW5lbWF0aWNzLl9kaWZmCkRpZmZEcml2ZQpxBSmBcQZOfXEH"
        "KFgFAAAAX2xlZnRxCEc/uZmZmZmZmlgGAAAAX3JpZ2h0cQlHP7ocrAgxJulYBgAAAF90cmFja3EKRz/gAAAA"
        "AAAAdYZxC2JYBQAAAF9sYXN0cQxNeAVNFAWGcQ1YBwAAAF9tZXRob2RxDlgDAAAAYXJjcQ9YBQAAAF9wb3Nl"
        "cRBjbmF2a2l0Lmdlb21ldHJ5Ll9wb3NlClBvc2UyRApxESmBcRJdcRMoR8BAEiH76RLZR0AjjbZ9X8L9R7/3"
        "Rth85ZioZWJYDgAAAF90aWNrc19wZXJfcmV2cRRHQI9AAAAAAAB1hnEVYi4="
    ),
}
OLD_LATER = {
    "wrapping": [
        [4.128422452485354, -1.494582638505042, 0.2589047907419752],
        [4.8338902685060585, -1.1118931105584755, 0.7351702370261879],
        [4.791793777858314, -1.1355572989652907, 0.28906408021643726],
    ],
    "plain": [
        [-32.12984155408938, 9.698199359251067, -1.3881945384233032],
        [-31.802042617243675, 8.965612182702218, -0.9119290921390906],
        [-31.82242897820458, 9.009390083800609, -1.3580352489488412],
    ],
}


def _loaded(name: str) -> DiffOdometry:
    odometry = pickle.loads(base64.b64decode(OLD[name]))
    assert isinstance(odometry, DiffOdometry)
    return odometry


@pytest.mark.parametrize("name", ["wrapping", "plain"])
def test_an_old_pickle_carries_on_as_its_release_did(name: str) -> None:
    odometry = _loaded(name)
    poses = [odometry.update(left, right) for left, right in LATER]
    assert [[pose.x, pose.y, pose.theta] for pose in poses] == OLD_LATER[name]


@pytest.mark.parametrize(("name", "bits"), [("wrapping", 16), ("plain", None)])
def test_an_old_pickle_has_the_slots_a_new_odometry_has(name: str, bits: int | None) -> None:
    drive = DiffDrive(track=0.5, left_radius=0.1, right_radius=0.102)
    new = DiffOdometry(drive, ticks_per_rev=1000, bits=bits, pose=Pose2D(3.0, -2.0, 0.4))
    old = _loaded(name)
    for slot in ("_modulus", "_low", "_high", "_scale_left", "_scale_right"):
        assert getattr(old, slot) == getattr(new, slot), slot
    # A reading outside the counter's range is refused alike (the scalar path's range).
    for odometry in (old, new):
        odometry.reset()
        odometry.update(65530, 10)
    if bits is not None:
        refusals = []
        for odometry in (old, new):
            with pytest.raises(ValueError) as refused:
                odometry.update(1 << bits, 3)
            refusals.append(str(refused.value))
        assert refusals[0] == refusals[1]


@pytest.mark.slow
def test_the_pickles_are_the_old_releases(tmp_path: Path) -> None:
    made = made_at("5e5f83f", MAKER, tmp_path)
    for name in ("wrapping", "plain"):
        assert made[name] == OLD[name]
        assert made[name + "_later"] == OLD_LATER[name]
