"""ScanMapper's trajectory as a growing float64 array: values, copies and old pickles.

The mapper kept one Pose2D per scan in a list (about 140 bytes a scan); it now keeps
rows ``[x, y, theta]`` in an array with spare rows (24 bytes a scan). The rows are
the matcher's poses bit for bit, the motion model reads them unchanged, copies are
independent, and pickles of the list layout still load.
"""

from __future__ import annotations

import base64
import copyreg
import gc
import io
import math
import pickle
import tracemalloc
import zlib
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from room_scans import room_scan

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, ScanMapper, ScanMatcher

N_BEAMS = 90

# pickle.dumps(_run(7), protocol=2) under navkit at commit 2db20da (the list layout:
# a ``_poses`` slot holding Pose2D), zlib-compressed and base64-encoded.
_OLD_PICKLE = (
    "eNrtWn1sFEUUv7ZC4XotaEsBsUWh6iFa5Uv8KOwp6NievdZt1VWpy97ecLPhbvfe7pb2TFCMcgvRaKMxivyBMSFR"
    "VBJN1DQRSq6JRgOa1D9IYzQSjEbEKOm/GJzdvbulH3yVu9Lqvj9u5+bNvPd+M7M3v7k324pFWdiyWdLr40IiIcnR"
    "el4TBZk3v2HV20bLzXYRPEueh6LQVij2c9M9Hg8vxoR4AkrQoUaPJSiQKaTgKm6a2WKTijFMQ32DQ4tP9r3VxFWY"
    "lTFB03klosSxriZhetZ9FNs19XxC0bC3lX4sX++FUtTXu8uUdxDz/QpTViLm5GFTvjVgBgszubKc1S5V0jF4SSli"
    "fvuM+/CHzccQcywp1Z058AZihthVQbl2gwFlLPi4UqsT3oJjGpR3QIV/1DBEVSnibRHFzoQgi0lkfoNZdAhm0yG4"
    "2s/5sgB5nahYI3ANYr6uNpYW+5q4GZZxJapEIhpUinJnPEFxiYqK6+OdMV0SVFVIenkVi4qs6WqnqHuhym7mlSO2"
    "FuYEPduhWqTdIljUvFg2C16YyxVR62GYZ01CTNAleRnMT8G1LCww4DoWavzBoqA/6E9BbcZkRE8maM+FXDHtsWkl"
    "XL9zhwE3sLDIHyyxrDXA4lAo1HSGivUR9OhQF95J5nLzajyuuOKKK664ckWk/2D//v7XApnHZI/yzfQn6d3pvuFB"
    "T7LYM+Fs5Pr3MrmAz/UcC8gVxjNyrMf7nCTQRsBZmN7VchmgRjxHv0Ht6T3plwsKkHrwBfI1SWPhGVFnj1hm3Ao7"
    "fxnz1Ff/q+mD+QZ3kUtgQiAWCtslvp3/VZS5d9EXmHK/Ke4U/n9Qpl8MPlfALcOdQxflxW+K591zC87f7LfAJjcF"
    "nqmxWM4EMNPzMeKCQpxY0p0PmGPvqGdZnxzH5QugGoFiUh5Thz8mkOvnIfbcT0aBT1yuuOKKK65MnMCNZH4KbmLh"
    "Zh38YW42reIVM18s4Ug2KbwEMb9YyeojdsZZUaWoJMMtpBQdqrPNOIWsYQOWsnArN9PpwHfDbbl2wxRJqHcUZWcr"
    "hC64PWfSVtGQlFinLiky3IGYn21VZwqWhYmZ2V4e2gor/MRJZJNKUkWsPPRKssCAVSzcaSaXq4JVKVhNFpkJYrbU"
    "XQhTO6GSJxKVMTNPTX/MFOoP9kuk6KOxFsBZHk5qeTpnjc/p5fwtNLEuL9GbTbrHs2TGfxoaz8EyD0fG87rN7xlp"
    "aiRjpzy1uMukFnezcI8O94aJwyLIhZhDAwtriMMViMMOiMMGCN39/87t/mvD2L6xFhd0kWAVmHNdCbTUmTuBdhkC"
    "lDfcR3nD/X5SHizmZtl2unlJx6pgMg0N1gWrOG+2XhXkKIb1IaelpuMET2tjGB6gzMO67Pf2CLWIYzENHkTZBWeT"
    "LVXRLRd8F5aiRAfk0J1yU69hQRVJxvZDjnL2WcqIpOmCLGJodPRWsLoSowhMTRNiWsPNA6feP81VWhparcWGeQ7m"
    "OtPxfDhMKD4rgjglYjkPzYgZzKDLKbMQIJS91XgkQ+8yRBJaUKDo9RPPfFRSZt+6NG9HatDaAY/46VLIuh1dMIBl"
    "oc28CvnF4Jy5vUffQ0zv2m179sWHEPNN3QdfVg38Y0A7C4+aTb5r+Lw9VHEYMV/91d7wK9dCIw08e/qlvfsMeIyF"
    "x80mR/siBzpW+RAzUN3T1qbsQMxx9ALfOOdPAzgWnjCb/HSi6ZXixadp25JUcmPPGsT8/umC2u7BpAFPsvCU2eT4"
    "u0PbexpOIebHmTWr1fltdB1Wh/7YvW6/ARtY6CA+TBxmagOmo6fq8DRpo0PLh+v/BQKXedg="
)


def _steps(k: int) -> Iterator[tuple[LaserScan, tuple[float, float, float] | None]]:
    """The scans of the old pickle and after: every third one without odometry."""
    for i in range(k):
        pose = (0.15 * i - 1.0, 0.05 * i, 0.2 * i - 0.3)
        yield room_scan(*pose, beams=N_BEAMS), (pose if i % 3 != 2 else None)


def _mapper() -> ScanMapper:
    return ScanMapper(resolution=0.5, matcher=ScanMatcher(levels=2))


def _run(k: int) -> ScanMapper:
    mapper = _mapper()
    for scan, odom in _steps(k):
        mapper.update(scan, odometry=odom)
    return mapper


class _OldState:
    """Stands in for ScanMapper when reading the old pickle: keeps its raw state."""

    state: Any = None

    def __setstate__(self, state: Any) -> None:
        self.state = state


class _RawUnpickler(pickle.Unpickler):
    def find_class(self, module: str, name: str) -> Any:
        if name == "ScanMapper":
            return _OldState
        return super().find_class(module, name)


def _old_bytes() -> bytes:
    return zlib.decompress(base64.b64decode("".join(_OLD_PICKLE)))


def _rows(poses: list[Pose2D]) -> np.ndarray:
    return np.array([[p.x, p.y, p.theta] for p in poses], dtype=np.float64).reshape(-1, 3)


def test_a_pickle_of_the_list_layout_loads_with_the_same_trajectory() -> None:
    raw = _RawUnpickler(io.BytesIO(_old_bytes())).load()
    _, slots = raw.state
    poses = slots["_poses"]
    assert len(poses) == 7 and all(type(p) is Pose2D for p in poses)  # the old layout
    loaded = pickle.loads(_old_bytes())
    assert len(loaded) == 7
    # Bit for bit the poses the old mapper recorded.
    assert loaded.trajectory.tobytes() == _rows(poses).tobytes()
    assert loaded.pose == poses[-1]
    assert not loaded.trajectory.flags.writeable
    # It maps on as a mapper run here over the same scans (the same matcher code:
    # equal up to the floating point of the machine that made the pickle).
    fresh = _run(7)
    np.testing.assert_allclose(loaded.trajectory, fresh.trajectory, rtol=0, atol=1e-9)
    more = list(_steps(30))[7:]  # past the first two growths of the array
    for scan, odom in more:
        loaded.update(scan, odometry=odom)
        fresh.update(scan, odometry=odom)
    assert len(loaded) == len(fresh) == 30
    np.testing.assert_allclose(loaded.trajectory, fresh.trajectory, rtol=0, atol=1e-9)
    np.testing.assert_allclose(loaded.map.logodds, fresh.map.logodds, rtol=0, atol=1e-6)
    # The rows read before the load are still the old poses.
    assert loaded.trajectory[:7].tobytes() == _rows(poses).tobytes()


class _OldLayoutPickler(pickle.Pickler):
    """Pickles a ScanMapper as the list-layout code did: its default slotted state."""

    def reducer_override(self, obj: Any) -> Any:
        if type(obj) is not ScanMapper:
            return NotImplemented
        _, slots = obj.__getstate__()
        path = slots.pop("_path")
        del slots["_path_len"], slots["_pose"]
        slots["_poses"] = [Pose2D(*row) for row in path.tolist()]
        return copyreg.__newobj__, (ScanMapper,), (None, slots)  # type: ignore[attr-defined]


def _old_layout(mapper: ScanMapper) -> bytes:
    out = io.BytesIO()
    _OldLayoutPickler(out, protocol=2).dump(mapper)
    return out.getvalue()


def test_an_old_pickle_of_a_mapper_without_scans_loads_and_maps() -> None:
    start = Pose2D(1.0, -0.5, 0.25)
    mapper = ScanMapper(resolution=0.5, pose=start, matcher=ScanMatcher(levels=2))
    loaded = pickle.loads(_old_layout(mapper))
    assert len(loaded) == 0 and loaded.pose == start
    assert loaded.trajectory.shape == (0, 3)
    scan, _ = next(_steps(1))
    loaded.update(scan)
    mapper.update(scan)
    assert loaded.trajectory.tobytes() == mapper.trajectory.tobytes()
    assert len(loaded) == 1 and loaded.pose == start


def test_the_old_layout_rebuilt_here_reads_as_the_real_old_pickle() -> None:
    # _old_layout stands for the old code in the test above: on the mapper the real
    # old pickle holds, it gives the same state.
    loaded = pickle.loads(_old_bytes())
    again = pickle.loads(_old_layout(loaded))
    assert again.trajectory.tobytes() == loaded.trajectory.tobytes()
    assert again.pose == loaded.pose and len(again) == len(loaded)


def test_copies_are_independent_and_leave_the_spare_rows_out(
    duplicate: Callable[[Any], Any],
) -> None:
    mapper = _run(17)  # 17 rows in an array of 24
    before = mapper.trajectory
    twin = duplicate(mapper)
    assert twin.trajectory.tobytes() == before.tobytes() and twin.pose == mapper.pose
    assert twin._path.shape == (17, 3)  # only the filled rows were copied
    steps = list(_steps(40))
    for scan, odom in steps[17:40]:  # the copy grows its array twice
        twin.update(scan, odometry=odom)
    mapper.update(*steps[5])  # and the original goes its own way
    assert len(twin) == 40 and len(mapper) == 18
    assert twin.trajectory[:17].tobytes() == before.tobytes()
    assert mapper.trajectory[:17].tobytes() == before.tobytes()
    assert mapper.trajectory[17].tobytes() != twin.trajectory[17].tobytes()


@pytest.mark.slow  # exhaustive (review 42: the default suite's budget)
def test_a_long_run_keeps_24_bytes_a_scan_and_nothing_more() -> None:
    # The list of Pose2D took about 140 bytes a scan. Now the trajectory array's
    # rows account for what grows with the scans; a few bytes a scan of noise.
    mapper = ScanMapper(resolution=0.1)
    scan = room_scan(0.013, 0.021, 0.0, beams=N_BEAMS)
    for _ in range(50):  # compile, build the levels, settle the match
        mapper.update(scan, odometry=(0.0, 0.0, 0.0))
    gc.collect()
    tracemalloc.start()
    try:
        beside = []
        # The first traced window takes a one-off few kB, and a later one may too
        # (other tests' lazily built caches): a leak per scan shows in every window.
        for n in (150, 300, 300, 300):
            before = tracemalloc.get_traced_memory()[0]
            rows = mapper._path.shape[0]
            for _ in range(n):
                mapper.update(scan, odometry=(0.0, 0.0, 0.0))
            gc.collect()
            grown = tracemalloc.get_traced_memory()[0] - before
            beside.append((grown - 24 * (mapper._path.shape[0] - rows)) / n)
            # Grown by half when full: at most a third of the rows spare.
            assert len(mapper) <= mapper._path.shape[0] <= 1.5 * len(mapper), len(mapper)
    finally:
        tracemalloc.stop()
    assert min(abs(b) for b in beside[1:]) < 10.0, beside
    assert len(mapper) == 1100
    assert mapper.trajectory.shape == (1100, 3)


class _RecordingMatcher(ScanMatcher):
    """A ScanMatcher that records the guess the mapper starts each match from."""

    def __init__(self) -> None:
        super().__init__(levels=2)
        self.guesses: list[Pose2D] = []

    def _match(self, levels: Any, points: Any, start: Pose2D) -> Any:
        self.guesses.append(start)
        return super()._match(levels, points, start)


@settings(max_examples=6, deadline=None)
@given(
    odometry=st.lists(st.booleans(), min_size=2, max_size=40),
    heading=st.floats(-math.pi, math.pi),
)
def test_rows_are_the_matched_poses_and_feed_the_motion_model(
    odometry: list[bool], heading: float
) -> None:
    matcher = _RecordingMatcher()
    mapper = ScanMapper(resolution=0.5, matcher=matcher)
    results = []
    for i, with_odometry in enumerate(odometry):
        # A turn of 0.4 rad a scan takes theta across ±π.
        pose = (0.1 * math.sin(i), 0.1 * math.cos(0.5 * i), heading + 0.4 * i)
        scan = room_scan(*pose, beams=N_BEAMS)
        results.append(mapper.update(scan, odometry=pose if with_odometry else None))
        # pose is the matcher's pose itself, read without copying the trajectory.
        assert mapper.pose is results[-1].pose
    path = mapper.trajectory
    assert path.shape == (len(odometry), 3) and len(mapper) == len(odometry)
    assert path.tobytes() == _rows([r.pose for r in results]).tobytes()
    # The constant-velocity guess, as the list layout computed it from the poses.
    for i in range(2, len(odometry)):
        if odometry[i] and odometry[i - 1]:
            continue  # an odometry increment, not the motion model
        last, prev = results[i - 1].pose, results[i - 2].pose
        expected = last.compose(last.relative_to(prev))
        got = matcher.guesses[i]
        assert (got.x, got.y, got.theta) == (expected.x, expected.y, expected.theta)


test_rows_are_the_matched_poses_and_feed_the_motion_model_thoroughly = slow_twin(
    test_rows_are_the_matched_poses_and_feed_the_motion_model, max_examples=40
)
