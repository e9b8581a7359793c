"""A RangeNoise pickled before ``absolute`` existed loads with no absolute term (review 49, FRESH).

``RangeNoise`` is a slotted frozen dataclass: its pickle is the field values in
order, and loading one sets as many fields as it holds. Pickles made before
review 49 hold three (``limits``, ``sigma``, ``bias``), so ``absolute`` was left
unset: the loaded noise's ``repr`` and ``==`` raised ``AttributeError``, and a
``Lidar`` holding it raised ``AttributeError`` on its first scan. navkit loads
its older pickles (``Pose2D``, ``EncoderReading``, ``MapPlanner``); a noise
without an absolute term is ``absolute`` zeros, as the default.
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Pose2D
from navkit.sim import Lidar, RangeNoise, World

#: ``RangeNoise(limits=(1.0, inf), sigma=(0.01, 0.02), bias=(0.0, 0.005))`` pickled by
#: navkit before review 49 (commit 0bf260c), protocols 2 and 5.
OLD_PICKLES = [
    b"\x80\x02cnavkit.sim._noise\nRangeNoise\nq\x00)\x81q\x01]q\x02(G?\xf0\x00\x00\x00\x00\x00"
    b"\x00G\x7f\xf0\x00\x00\x00\x00\x00\x00\x86q\x03G?\x84z\xe1G\xae\x14{G?\x94z\xe1G\xae\x14{"
    b"\x86q\x04G\x00\x00\x00\x00\x00\x00\x00\x00G?tz\xe1G\xae\x14{\x86q\x05eb.",
    b"\x80\x05\x95h\x00\x00\x00\x00\x00\x00\x00\x8c\x11navkit.sim._noise\x94\x8c\nRangeNoise"
    b"\x94\x93\x94)\x81\x94]\x94(G?\xf0\x00\x00\x00\x00\x00\x00G\x7f\xf0\x00\x00\x00\x00\x00"
    b"\x00\x86\x94G?\x84z\xe1G\xae\x14{G?\x94z\xe1G\xae\x14{\x86\x94G\x00\x00\x00\x00\x00\x00"
    b"\x00\x00G?tz\xe1G\xae\x14{\x86\x94eb.",
]

EXPECTED = RangeNoise(limits=(1.0, math.inf), sigma=(0.01, 0.02), bias=(0.0, 0.005))


@pytest.mark.parametrize("data", OLD_PICKLES, ids=["protocol2", "protocol5"])
def test_an_older_pickle_loads_without_an_absolute_term(data: bytes) -> None:
    noise = pickle.loads(data)
    assert type(noise) is RangeNoise
    assert noise.absolute == (0.0, 0.0)
    assert noise == EXPECTED
    assert repr(noise) == repr(EXPECTED)
    assert hash(noise) == hash(EXPECTED)
    # And it pickles again as a noise of today's.
    assert pickle.loads(pickle.dumps(noise)) == EXPECTED


def test_a_lidar_with_an_older_noise_scans_as_with_todays() -> None:
    old = pickle.loads(OLD_PICKLES[1])
    world = World([box(0.0, 0.0, 4.0, 3.0).exterior])
    pose = Pose2D(1.0, 1.2, 0.4)
    got = Lidar(n_beams=36, noise=old).scan(world, pose, seed=4)
    want = Lidar(n_beams=36, noise=EXPECTED).scan(world, pose, seed=4)
    np.testing.assert_array_equal(got.ranges, want.ranges)


def test_todays_pickles_keep_their_absolute_term() -> None:
    noise = RangeNoise(limits=(0.5, math.inf), sigma=(0.0, 0.05), absolute=(0.015, 0.0))
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        assert pickle.loads(pickle.dumps(noise, protocol=protocol)) == noise
