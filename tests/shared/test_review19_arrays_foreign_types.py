"""Foreign array types and array-likes (review 19): the defects the lens found, one by one.

* A big-endian ``memoryview`` (``memoryview(np.array(..., ">f8"))``, a buffer from
  a file or a message) raised Python's ``NotImplementedError`` wherever a pair or
  a short sequence is unpacked (``clamp``, ``(row, col)`` cells, Field D* nodes,
  ``RangeNoise`` tables, the ``OccupancyGridMsgFields`` origin).
* Objects NumPy reads only through ``__array__`` or ``__array_interface__`` were
  refused where a pose, a twist, a pair or a stream is unpacked.
* A masked 0-d array was read as its data by ``tick_delta``'s ``bits``, the
  ``unknown_cost`` of the cost grids, a ``footprint`` radius and the value an
  ``RegulatedPurePursuit`` clearance callable returns.
* Read-only arrays (a memory map opened with mode ``"r"``, a ``Path2D``'s points,
  ``np.frombuffer`` of a message) reached three kernels as they were: a second
  compilation of ``rollout_kernel``, ``cast_edge_rays`` and
  ``point_polyline_distances`` on their first call.
* Cost grids of dtype object holding Python numbers were refused.
"""

from __future__ import annotations

import array
import math
import re
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import box

from kernel_signatures import compiled_signatures
from navkit._shared.validation import has_array_protocol, kernel_input, unpack
from navkit.control import RegulatedPurePursuit
from navkit.estimation import MeasurementLog
from navkit.geometry import Pose2D, Twist2D, as_pose, as_twist
from navkit.kinematics import tick_delta
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan, traversal_costs, validate_costs
from navkit.planning import astar
from navkit.planning.grid import MapPlanner
from navkit.planning.reactive import GreedyStep
from navkit.sim import RangeNoise, World


class ArrayOnly:
    """Readable by NumPy only through ``__array__`` (with NumPy 2's ``copy=``)."""

    def __init__(self, data: np.ndarray) -> None:
        self._data = data

    def __array__(self, dtype: object = None, copy: bool | None = None) -> np.ndarray:
        return np.array(self._data, dtype=dtype, copy=True if copy else None)


class InterfaceOnly:
    """Readable by NumPy only through ``__array_interface__``."""

    def __init__(self, data: np.ndarray) -> None:
        self._data = data
        self.__array_interface__ = data.__array_interface__


pytestmark = pytest.mark.filterwarnings("ignore:the matrix subclass:PendingDeprecationWarning")


def _big_endian_view(values: list[float]) -> memoryview:
    return memoryview(np.array(values, dtype=">f8"))


# --------------------------------------------------------------------------- unpack


@pytest.mark.parametrize(
    "value",
    [
        pytest.param(_big_endian_view([1.5, -2.0]), id="memoryview >f8"),
        pytest.param(memoryview(np.array([1.5, -2.0])), id="memoryview <f8"),
        pytest.param(memoryview(array.array("d", [1.5, -2.0])), id="memoryview of array.array"),
        pytest.param(ArrayOnly(np.array([1.5, -2.0])), id="__array__"),
        pytest.param(InterfaceOnly(np.array([1.5, -2.0], dtype=">f8")), id="__array_interface__"),
    ],
)
def test_unpack_reads_buffers_and_array_protocols_as_numpy_does(value: object) -> None:
    assert [float(x) for x in unpack(value, "clamp")] == [1.5, -2.0]


def test_unpack_gives_the_1d_rows_of_a_matrix() -> None:
    rows = unpack(np.asmatrix([[1.0, 2.0], [3.0, 4.0]]), "odometry")
    assert [row.shape for row in rows] == [(2,), (2,)]
    assert type(rows[0]) is np.ndarray


def test_unpack_of_what_has_no_items_is_a_type_error_for_the_caller_to_word() -> None:
    with pytest.raises(TypeError):
        unpack(ArrayOnly(np.array(1.0)), "pair")  # a 0-d array has no items
    with pytest.raises(TypeError):
        unpack(memoryview(np.array(1.0)), "pair")


def test_has_array_protocol() -> None:
    assert has_array_protocol(ArrayOnly(np.zeros(2)))
    assert has_array_protocol(InterfaceOnly(np.zeros(2)))
    assert has_array_protocol(np.zeros(2))
    assert not has_array_protocol([1.0, 2.0])
    assert not has_array_protocol(ArrayOnly)  # the class itself is no array


# --------------------------------------------------------------------------- the callers


def test_a_big_endian_clamp_is_the_same_clamp() -> None:
    scan = LaserScan(
        [1.0, 1.5, 2.0], angle_min=-0.5, angle_increment=0.5, range_min=0.1, range_max=4.0
    )

    def run(clamp: object) -> np.ndarray:
        grid = OccupancyGrid.from_occupancy(np.zeros((40, 40), dtype=bool), resolution=0.1,
                                            origin=(-2.0, -2.0, 0.0))  # fmt: skip
        integrate_scan(grid, scan, (0.0, 0.0, 0.0), clamp=clamp)  # type: ignore[arg-type]
        return np.array(grid.logodds, copy=True)

    plain = run((-1.5, 2.5))
    for clamp in (_big_endian_view([-1.5, 2.5]), ArrayOnly(np.array([-1.5, 2.5]))):
        assert np.array_equal(run(clamp), plain)


def test_big_endian_cells_plan_as_their_values() -> None:
    costs = np.ones((5, 6))
    costs[1:4, 3] = np.inf
    plain = astar(costs, (0, 0), (4, 5))
    cell = memoryview(np.array([0, 0], dtype=">i8"))
    goal = memoryview(np.array([4, 5], dtype=">i4"))
    assert np.array_equal(astar(costs, cell, goal).points, plain.points)  # type: ignore[arg-type]


def test_a_greedy_step_cell_from_buffers_and_array_protocols() -> None:
    waypoint = np.array([0.1, 0.2])
    for cell in (memoryview(np.array([10, 12], dtype=">i8")), ArrayOnly(np.array([10, 12]))):
        assert GreedyStep(cell, waypoint, 1.0, 2.0, 3).cell == (10, 12)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"^cell must be a \(row, col\) pair"):
        GreedyStep(ArrayOnly(np.array(10)), waypoint, 1.0, 2.0, 3)  # type: ignore[arg-type]


def test_big_endian_noise_tables_are_their_values() -> None:
    plain = RangeNoise(limits=(1.0, math.inf), sigma=(0.01, 0.02), bias=(0.0, 0.01))
    foreign = RangeNoise(
        limits=_big_endian_view([1.0, math.inf]),
        sigma=_big_endian_view([0.01, 0.02]),
        bias=ArrayOnly(np.zeros(2)),
    )
    assert foreign.limits == plain.limits
    assert foreign.sigma == plain.sigma
    assert foreign.bias == (0.0, 0.0)


@pytest.mark.parametrize(
    "wrap",
    [ArrayOnly, InterfaceOnly, lambda a: memoryview(a.astype(">f8"))],
    ids=["__array__", "__array_interface__", "memoryview >f8"],
)
def test_poses_and_twists_from_array_protocols(wrap: object) -> None:
    values = np.array([1.0, -2.0, 0.5])
    assert as_pose(wrap(values)) == Pose2D(1.0, -2.0, 0.5)  # type: ignore[operator]
    assert as_twist(wrap(values)) == Twist2D(1.0, -2.0, 0.5)  # type: ignore[operator]
    with pytest.raises(ValueError, match=r"^origin must have length 3"):
        as_pose(wrap(np.zeros(4)), "origin")  # type: ignore[operator]


def test_pose_protocol_objects_still_refuse_strings_and_numbers() -> None:
    for bad in ("1 2 3", b"123", 1.0, None, {"x": 1.0}):
        with pytest.raises(TypeError, match=r"^pose must be a Pose2D"):
            as_pose(bad)  # type: ignore[arg-type]


def test_measurement_streams_and_variance_pairs_from_buffers() -> None:
    t = np.array([0.0, 0.1, 0.2])
    v = np.array([0.5, 0.6, 0.7])
    w = np.array([0.0, 0.1, -0.1])
    plain = MeasurementLog.from_streams(odometry=(t, v, w), odometry_variance=(0.01, 0.02))
    for variance in (
        array.array("d", [0.01, 0.02]),
        memoryview(np.array([0.01, 0.02])),
        _big_endian_view([0.01, 0.02]),
        ArrayOnly(np.array([0.01, 0.02])),
    ):
        for odometry in (np.stack([t, v, w]), ArrayOnly(np.stack([t, v, w])),
                         np.asmatrix(np.stack([t, v, w]))):  # fmt: skip
            log = MeasurementLog.from_streams(odometry=odometry, odometry_variance=variance)
            for name in ("times", "values", "variances", "observed"):
                assert np.array_equal(getattr(log, name), getattr(plain, name)), name


def test_a_variance_pair_still_refuses_a_scalar_and_wrong_lengths() -> None:
    t = np.array([0.0, 0.1])
    with pytest.raises(TypeError, match=r"^odometry_variance must be a pair"):
        MeasurementLog.from_streams(odometry=(t, t, t), odometry_variance=ArrayOnly(np.array(0.1)))
    with pytest.raises(ValueError, match=r"^odometry_variance must be a pair .*got 3"):
        MeasurementLog.from_streams(odometry=(t, t, t), odometry_variance=array.array("d", [1] * 3))


# --------------------------------------------------------------------------- masked scalars


MASKED = np.ma.array(16, mask=True)


def _grid() -> OccupancyGrid:
    occupied = np.zeros((6, 7), dtype=bool)
    occupied[2, 3] = True
    unknown = np.zeros((6, 7), dtype=bool)
    unknown[5, :2] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)


def test_a_masked_bits_is_refused() -> None:
    with pytest.raises(ValueError, match=r"^bits has masked entries"):
        tick_delta(1, 2, bits=MASKED)  # type: ignore[arg-type]
    assert tick_delta(65535, 2, bits=np.ma.array(16)) == 3  # type: ignore[arg-type]


def test_a_masked_unknown_cost_is_refused() -> None:
    masked = np.ma.array(5.0, mask=True)
    with pytest.raises(ValueError, match=r"^unknown_cost has masked entries"):
        traversal_costs(_grid(), unknown_cost=masked)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"^unknown_cost has masked entries"):
        MapPlanner(_grid(), unknown_cost=masked)  # type: ignore[arg-type]
    plain = traversal_costs(_grid(), unknown_cost=5.0)
    unmasked = traversal_costs(_grid(), unknown_cost=np.ma.array(5.0))  # type: ignore[arg-type]
    assert np.array_equal(unmasked, plain)


def test_a_masked_footprint_radius_is_refused() -> None:
    world = World([box(-1.0, -1.0, 3.0, 2.0).exterior])
    with pytest.raises(ValueError, match=r"^footprint has masked entries"):
        world.clearance(np.ma.array(0.15, mask=True), (0.0, 0.0, 0.0))  # type: ignore[arg-type]
    plain = world.clearance(0.15, (0.0, 0.0, 0.0))
    assert world.clearance(np.ma.array(0.15), (0.0, 0.0, 0.0)) == plain  # type: ignore[arg-type]


def test_a_masked_clearance_reading_is_refused() -> None:
    path = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]

    def tracker(reading: object) -> RegulatedPurePursuit:
        out = RegulatedPurePursuit(clearance=lambda x, y: reading)  # type: ignore[arg-type, return-value]
        out.set_path(path)
        return out

    for masked in (np.ma.array(0.3, mask=True), np.ma.masked):
        with pytest.raises(ValueError, match=re.escape("clearance(x, y) has masked entries")):
            tracker(masked).step((0.0, 0.0, 0.0), 0.05)
    plain = tracker(0.3).step((0.0, 0.0, 0.0), 0.05)
    assert tracker(np.ma.array(0.3)).step((0.0, 0.0, 0.0), 0.05) == plain


# --------------------------------------------------------------------------- cost grids


def test_object_cost_grids_of_python_numbers_are_their_values() -> None:
    plain = np.array([[1.0, 2.0], [np.inf, 1.5]])
    held = np.array([[1, Fraction(2)], [math.inf, np.float32(1.5)]], dtype=object)
    assert np.array_equal(validate_costs(held), plain)
    assert np.array_equal(astar(held, (0, 0), (1, 1)).points, astar(plain, (0, 0), (1, 1)).points)


@pytest.mark.parametrize(
    ("item", "message"),
    [
        (True, "real-valued numeric array, got dtype object"),
        ("2.0", "real-valued numeric array, got dtype object"),
        (None, "real-valued numeric array, got dtype object"),
        (1 + 0j, "real-valued numeric array, got dtype object"),
        (10**400, "must hold finite numbers, got an integer too large for a float"),
    ],
)
def test_object_cost_grids_refuse_what_is_no_real_number(item: object, message: str) -> None:
    held = np.array([[1.0, 2.0], [3.0, 4.0]], dtype=object)
    held[1, 1] = item
    with pytest.raises(ValueError, match=r"^costs .*" + re.escape(message)):
        validate_costs(held)


# --------------------------------------------------------------------------- kernel layouts


def test_kernel_input_passes_kernel_ready_arrays_and_copies_the_rest() -> None:
    plain = np.arange(6.0).reshape(2, 3)
    assert kernel_input(plain) is plain
    frozen = plain.copy()
    frozen.flags.writeable = False
    broadcast = np.broadcast_to(plain[0], (2, 3))
    for other in (frozen, np.asfortranarray(plain), plain[:, ::-1], broadcast):
        out = kernel_input(other)
        assert out.flags.c_contiguous and out.flags.writeable and out.dtype == np.float64
        assert np.array_equal(out, other)
        assert not np.shares_memory(out, other)


def test_read_only_and_foreign_layouts_compile_no_second_kernel(tmp_path: Path) -> None:
    """rollout, World.raycast and the cross-track distances of a run: one signature each."""
    setup = f"""
import numpy as np
from shapely.geometry import box
from navkit.geometry import Twist2D, rollout
from navkit.planning.grid import Path2D
from navkit.sim import Robot, Simulation, World
from navkit.kinematics import DiffDrive

twists = np.array([[1.0, 0.0, 0.1]] * 4)
steps = np.full(4, 0.1)
np.array(twists).tofile({str(tmp_path / "twists.bin")!r})
mapped = np.memmap({str(tmp_path / "twists.bin")!r}, dtype=np.float64, mode="r", shape=(4, 3))
frozen = steps.copy()
frozen.flags.writeable = False
rollout((0.0, 0.0, 0.0), twists, steps)
rollout((0.0, 0.0, 0.0), mapped, frozen)
rollout((0.0, 0.0, 0.0), twists.astype(">f8"), np.broadcast_to(0.1, (4,)))

world = World([box(0.0, 0.0, 4.0, 3.0).exterior])
angles = np.linspace(-1.0, 1.0, 5)
world.raycast((1.0, 1.0, 0.0), angles, range_max=5.0)
angles.flags.writeable = False
world.raycast((1.0, 1.0, 0.0), angles, range_max=5.0)
world.raycast((1.0, 1.0, 0.0), angles[::-1], range_max=5.0)

robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
route = Path2D(np.array([[1.0, 1.0], [2.0, 1.0]]), "world", 1.0, 1.0, 0)
for reference in ([[1.0, 1.0], [2.0, 1.0]], route):
    Simulation(world, robot, lambda _obs: Twist2D(0.4, 0.0, 0.2), start=(1.0, 1.0, 0.0),
               duration=0.2, reference_path=reference).run()
"""
    signatures = compiled_signatures(
        setup,
        [
            "navkit.geometry._integrate_kernels",
            "navkit.sim._lidar_kernels",
            "navkit.sim._polyline_distance_kernels",
        ],
    )
    for name in (
        "_integrate_kernels.rollout_kernel",
        "_lidar_kernels.cast_edge_rays",
        "_polyline_distance_kernels.point_polyline_distances",
    ):
        assert len(signatures[name]) == 1, (name, signatures[name])
