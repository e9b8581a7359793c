"""Pickles of the first days' filters load and step on (review 52, FOUND4: a survey of old pickles).

A survey of 25 public classes pickled at 98fb796, 5e5f83f, 0123de4, 9019098,
98b4639, 908ac92, ccccbd5, e042e26 and f96b926 (23 to 30 November and 1
December 2026; ``tests/old_release.made_at``), loaded here and used beside one
built and used alike today, found two kinds the earlier surveys (from 908ac92
on) had missed:

* ``CompassCalibration`` pickled before its unwrapping's correction (db2738d,
  1 December) raised AttributeError ``_correction`` at its first reading. It
  gets a correction of 0 with the last unwrapped yaw it held: the next readings
  unwrap as that release unwrapped them.
* ``PlanarFusion`` pickled before it reduced itself (1efa428, 1 December) raised
  AttributeError ``_t`` as it loaded (before 908ac92 and at it) or ``_history``
  at its first call (ccccbd5 to f96b926). Its estimate, process noise, gates
  and time now go into a filter as ``PlanarFusion`` builds one, which steps on
  as a filter built today with them.

Real pickle bytes (the filters' zlib-compressed); a slow test makes them again.
"""

from __future__ import annotations

import base64
import math
import pickle
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import CompassCalibration, PlanarFusion

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at

#: CompassCalibration(unwrap=True) given 10, 200 and 350 degrees, pickled at 908ac92.
COMPASS_908AC92 = (
    "gASVcAAAAAAAAACMGm5hdmtpdC5lc3RpbWF0aW9uLl9jb21wYXNzlIwSQ29tcGFzc0NhbGlicmF0aW9ulJOU"
    "KYGUTn2UKIwIX2luaXRpYWyUR0AkAAAAAAAAjAVfbGFzdJRHP9ZXGErnRIiMB191bndyYXCUiHWGlGIu"
)
#: PlanarFusion(t0=0.0) after update_odometry(0.1, 0.5, 0.1, v_variance=0.01,
#: omega_variance=0.01), pickled at 98b4639 (its time in a slot, _t) and at
#: f96b926 (its time in its buffer), zlib-compressed.
FUSION = {
    "98b4639": (
        "eNprYJnqK8kABj2SeYll2ZkleqnFJZm5iSWZ+Xl68WmlxUB6Sg9PQE5iXmKRG4Q7eYpm4xS/2ikaPSzxSaVp"
        "U3rE8kpzCyr14pPzi1L1cktzSjITi4oSK4H64otSk/PzikuKSpNLgPp6WMEqp/Sw56VAlEye4s3QOsWZMWlK"
        "+5SgKRrejN623mxtUzI4e1hTSioLUkGamNIspnR2QOSZexhtpvj5+Xn9BwIw4c1QMiWp06mAm4Ehaf3lznzN"
        "lfYMULDQNF1pm02Lfdax3V8err9vryBzNOh6xE77A/8CW5M5V9ovVW+5zyZaClcPAxOuiV1ukQqAiyuzcJ/I"
        "Ol68H8aXdUnreVhVgqGPEPDN2eB9mr8Srk8lTn7rRAOEPej2wsDqY4K3Zrm3wMX5Am84MLFhqkM3T3rD3BVC"
        "SPrQ/YHLPDv7pdLCO97bz5oJAitJ9ie5+nbItb4O3LGOTPtmkqyvWmSd+8OqKWTqa0HT9wAaXjvtidWP3Rxc"
        "gHjz0UADmr6GGrC9pKdf4uJhpz25+pbhyI8H0PKFEpXyox9afnRAyz8HcORHhuOo+dEBR35sQDOvAS0/KuHI"
        "jw448iOp6SC/blnaHu/79pzMjKsfexNWDykXiY+/JYvW3Ixd+t5effIKM8/z7wnqsz9v92XeA22HzVyrLxz1"
        "0HHo/LrQsX2ipoOxi1zzBi8VBz39D8dLnVUc8t3CDvjLfLCf/iH9ziXdDyTH64GwNRsbJD5QPX2TCiD10U6a"
        "u4PY+IXUg+9Jdo9Gcpk6LxH6SE0/o/Uv/vr36uH8rTtjN5EcPtOl4wokpDaRHD68CZFBAWxbcIaPLX9p8mW+"
        "Hgxzb1V22MRb7yQYPps4Nq5Xud8JF3fZVrY/3gWh75/JDWcJ640Y4fNmRf3CnXsnw9XtnDmP4cjx9/aktvdI"
        "DY+p19RecOsJ2g12fRBAbnlHvr4pwJZ3D1t8emJJavGUDI4MblBbPoMX1pJnBXJEO501oMrrCdFQ47Iz81KK"
        "p4C6Fxz5Kfm5qSVFlWDjmNzrP0D7KhxJpZnAXkZeMbBHUZyTmQzqJgBVMPuBrC4BCRakpqaAdTHCdWWogQyB"
        "KWGuTCwHKmBAVQDkwhRwABXEFwG9BlTFhKqKCWETT2JycmpOahG4wwTqn6CqZPZmgaos7WGKL8QSSGzg7o5o"
        "p5MCI/kN55HS4AanEC5gp7I4M6U0MQdbomODJDoDUtvOYKOZ4kumuNvvBCud1cMaX55flI3FDl1YnBVwjDa6"
        "Rxvdo43u0Ub3aKN7tNE92ugebXTTqdHNFF9AqC05ms/x53NoOFbgaUOSmtRBRpa2TUnSAwBOVM6a"
    ),
    "f96b926": (
        "eNprYJlqIMgABj2SeYll2ZkleqnFJZm5iSWZ+Xl68WmlxUB6Sg9PQE5iXmKRG4Q7eYpm4xS/2ikaPSzxSaVp"
        "U3rE8kpzCyr14pPzi1L1cktzSjITi4oSK4H64otSk/PzikuKSpNLgPp6WMEqp/Sw56VAlEye4s3QOsWZMWlK"
        "+5SgKRrejL4ljK1TMjh7WFNKKgtSQXqY0iymdHZApJl7GG2m+Pn5ef0HAjDhzVAyJanTaQE3A0PS+sud+Zor"
        "7RmgYKFputI2mxb7rGO7vzxcf99eQeZo0PWInfYH/gW2JnOutF+q3nKfTbQUrh4GJlwTu9wiFQAXV2bhPpF1"
        "vHg/jC/rktbzsKoEQx8h4Juzwfs0fyVcn0qc/NaJBgh70O2FgdXHBG/Ncm+Bi/MF3nBgYsNUh26e9Ia5K4SQ"
        "9KH7A5d5dvZLpYV3vLefNRMEVpLsT3L17ZBrfR24Yx2Z9s0kWV+1yDr3h1VTyNTXgqbvATS8dtoTqx+7ObgA"
        "YfOJtZ8AaEAzp6EG7M4SSs2lmnth+pbhyL8H0PKREpXyrx9a/nVAy28HcORfhuOo+dcBR/5tQDOvAS3/KuHI"
        "vw448i+p6XLJojU3Y5e+t1efvMLM8/x7gurtz9t9mfdA22Ez1+oLRz10HDq/LnRsn6jpYOwi17zBS8VBT//D"
        "8VJnFYd8t7AD/jIfoObBaAYHQuZP/5B+55LuB5Lj6UDYmo0NEh+onl5JBZD6aCfN3cHJzLj6sTdheyD14HuS"
        "3aORXKbOS4Q+SL1KvH/z65al7fG+b0+s+0frd+rW71cP52/dGbuJ5PCZLh1XICG1ieTw4U2IDApg24IzfGz5"
        "S5Mv8/VgmHurssMm3nonwfDZxLFxvcr9Tri4y7ay/fEuCH3/TG44S1hvxAifNyvqF+7cOxmubufMeQxHjpOe"
        "T6ZeU3vBrSdoN9j1oZXDdNM3BdhS72GLT08sSS2eksGRwQ1q+mfwQhv+3qxAjminswZUeT0hGmpcdmZeSvEU"
        "UG+EIz8lPze1pKgSbByTe/0HaNeGI6k0E9gpySsGdkCKczKTQd0KoApmP5DVJSDBgtTUFLAuRriuDDWQITAl"
        "zJWJ5UAFDKgKgFyYAg6ggvgioNeAqphQVTEhbOJJTE5OzUktAvevQP0ZVJXM3ixQlaU9fPEw74BDbArCO0II"
        "maLU4syU0sQcLMHJBAlOAfRWADjYmOILsWhh82ZrA2lyUmAkvxU/Ulr/4HDkgscAthTNBokCA1Ib8tAoKiAU"
        "RaMVHP4KDhqOFXiihtQ2BcjI0rYpSXoA2/fWjw=="
    ),
}


def _load(text: str, compressed: bool = False) -> object:
    raw = base64.b64decode(text)
    return pickle.loads(zlib.decompress(raw) if compressed else raw)


def _fresh_compass() -> CompassCalibration:
    calibration = CompassCalibration(unwrap=True)
    for heading in (10.0, 200.0, 350.0):
        calibration(heading)
    return calibration


def test_an_old_compass_calibration_unwraps_on() -> None:
    old = _load(COMPASS_908AC92)
    assert isinstance(old, CompassCalibration) and old.initial_deg == 10.0
    fresh = _fresh_compass()
    readings = [90.0, -170.0, 170.0, 10.0, 200.0]
    got = [old(r) for r in readings]
    assert got == [fresh(r) for r in readings]
    # Continuous across the calls: no step of 2π between successive yaws.
    assert np.all(np.abs(np.diff(got)) < math.pi)
    assert pickle.loads(pickle.dumps(old))(30.0) == fresh(30.0)


def _fresh_fusion() -> PlanarFusion:
    fusion = PlanarFusion(t0=0.0)
    fusion.update_odometry(0.1, 0.5, 0.1, v_variance=0.01, omega_variance=0.01)
    return fusion


@pytest.mark.parametrize("commit", sorted(FUSION))
def test_an_old_fusion_filter_steps_on_as_one_built_today(commit: str) -> None:
    old = _load(FUSION[commit], compressed=True)
    assert type(old) is PlanarFusion and old.t == 0.1 and old.history == 0.0
    fresh = _fresh_fusion()
    np.testing.assert_allclose(old.x, fresh.x, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(old.P, fresh.P, rtol=1e-12, atol=1e-15)
    for filt in (old, fresh):
        filt.update_yaw(0.2, 0.01, variance=1e-3)
        filt.update_odometry(0.3, 0.4, 0.05, v_variance=0.01, omega_variance=0.01)
    np.testing.assert_allclose(old.x, fresh.x, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(old.P, fresh.P, rtol=1e-9, atol=1e-12)
    # A copy and a pickle of the loaded filter are today's.
    again = pickle.loads(pickle.dumps(old))
    np.testing.assert_array_equal(again.x, old.x)


class _Tagged(PlanarFusion):
    __slots__ = ("tag",)


def test_a_subclass_still_restores_what_it_adds() -> None:
    fusion = _Tagged(t0=0.0)
    fusion.tag = "left"
    fusion.update_odometry(0.1, 0.5, 0.1, v_variance=0.01, omega_variance=0.01)
    copy = pickle.loads(pickle.dumps(fusion))
    assert type(copy) is _Tagged and copy.tag == "left"
    np.testing.assert_array_equal(copy.x, fusion.x)


MAKER = """
import base64, json, pickle
from navkit.estimation import CompassCalibration, PlanarFusion
calibration = CompassCalibration(unwrap=True)
for heading in (10.0, 200.0, 350.0):
    calibration(heading)
fusion = PlanarFusion(t0=0.0)
fusion.update_odometry(0.1, 0.5, 0.1, v_variance=0.01, omega_variance=0.01)
print(json.dumps([base64.b64encode(pickle.dumps(o)).decode() for o in (calibration, fusion)]))
"""


@pytest.mark.slow
@pytest.mark.parametrize("commit", ["0123de4", "908ac92", "ccccbd5", "f96b926"])
def test_pickles_made_again_by_old_commits_load_and_step_on(commit: str, tmp_path: Path) -> None:
    compass, fusion = made_at(commit, MAKER, tmp_path)
    fresh = _fresh_compass()
    assert _load(compass)(90.0) == fresh(90.0)  # type: ignore[operator]
    old = _load(fusion)
    assert isinstance(old, PlanarFusion)
    today = _fresh_fusion()
    for filt in (old, today):
        filt.update_yaw(0.2, 0.01, variance=1e-3)
    np.testing.assert_allclose(old.x, today.x, rtol=1e-9, atol=1e-12)
