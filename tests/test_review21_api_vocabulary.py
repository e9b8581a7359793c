"""One vocabulary across navkit's public API (review 21: API consistency across packages).

A user of scipy.spatial or shapely expects one keyword per idea, the same
default for the same option and the same error for the same mistake, whichever
subpackage they call. Review 21 tabulated every public callable's parameters
(each package's ``__all__``, classes with their public methods) and settled the
vocabulary below; these tests keep it:

* one keyword name per idea: no public callable takes a synonym of a settled
  name, deprecated aliases listed in ``docs/deprecations.md`` excepted;
* frames in names (README "Conventions"): no parameter holding a position says
  ``point``, ``pos`` or ``location`` instead of its frame suffix;
* the same option has the same default wherever it has one;
* flags and options are keyword-only: no positional parameter defaults to a
  bool, and the positional ones with a numeric default are a short, known list
  (data such as ``Pose2D(x, y, theta=0.0)``);
* a keyword the path trackers share is readable on every one of them
  (``rotate_angle`` was readable on ``OnOffTracker`` only);
* the same bad value for the same kind of option raises the same exception type
  in every package, naming the option;
* ``data_dir`` takes a path-like wherever it is taken (``Greedy`` was typed
  ``str | None``, so ``Greedy(data_dir=Path(...))`` failed ``mypy --strict``);
* settled after the table (APIFIX): an object with a ``.pose`` takes its start
  pose as ``pose=`` (``ScanMapper(start=)`` deprecated); every sensor
  configuration is keyword-only (``RangeNoise`` took its swappable tuples by
  position); both odometries ``reset(pose)``; ``MapPlanner`` reads back every
  option it takes (``inflation_radius``, ``unknown_cost`` were missing).
"""

from __future__ import annotations

import inspect
import math
import os
import re
import typing
import warnings
from collections import defaultdict
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from fuzz.fuzz_engine import public_callables
from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit

PAGE = Path(__file__).resolve().parents[1] / "docs" / "deprecations.md"
ROW = re.compile(r"^\| `(navkit\.[\w.]+)`[^|]*\| `(\w+)`[^|]*\| `(\w+)`[^|]*\|", re.M)
DEPRECATED = {old for _where, old, _new in ROW.findall(PAGE.read_text(encoding="utf-8"))}


def _signatures() -> Iterator[tuple[str, inspect.Signature]]:
    """``(canonical name, signature)`` of every public function, constructor and method."""
    for pc in public_callables():
        target = pc.obj if pc.method is None else getattr(pc.obj, pc.method)
        try:
            sig = inspect.signature(target)
        except (TypeError, ValueError):  # a typing alias, a protocol without __init__
            continue
        params = [p for p in sig.parameters.values() if p.name not in ("self", "cls")]
        yield pc.name, sig.replace(parameters=params)


SIGNATURES = dict(_signatures())


def _is_deprecated_alias(p: inspect.Parameter) -> bool:
    return p.name in DEPRECATED and p.kind is p.KEYWORD_ONLY and p.default is None


def test_the_api_is_enumerated() -> None:
    # Guards the tests below against an enumeration that silently finds nothing.
    assert len(SIGNATURES) > 250
    assert "navkit.planning.grid.MapPlanner.plan" in SIGNATURES
    assert "robot_radius" in SIGNATURES["navkit.mapping.costmap"].parameters


# --- One keyword per idea --------------------------------------------------------------

#: The settled name of each idea and the synonyms a public callable must not take.
VOCABULARY: dict[str, tuple[str, ...]] = {
    "resolution": ("cell_size", "res", "grid_resolution", "cellsize"),
    "robot_radius": ("robot_size", "inscribed_radius", "footprint_radius", "body_radius"),
    "inflation_radius": ("inflation_distance", "inflate_radius"),
    "seed": ("rng", "random_state", "random_seed", "generator"),
    "max_iterations": ("max_iter", "maxiter", "n_iter", "iterations_max"),
    "tolerance": ("tol", "eps", "epsilon"),
    "dt": ("period", "time_step", "timestep", "delta_t"),
    "goal_tolerance": ("xy_goal_tolerance", "goal_tol", "position_tolerance", "arrival_radius"),
    "yaw_tolerance": ("goal_yaw_tolerance", "theta_tolerance", "angle_tolerance"),
    "goal_yaw": ("goal_heading", "goal_theta", "final_yaw"),
    "range_max": ("max_range", "maximum_range"),
    "range_min": ("min_range", "minimum_range"),
    "max_speed": ("v_max", "vmax", "max_velocity", "max_linear_speed", "max_vel"),
    "max_omega": ("omega_max", "max_angular_speed", "max_yaw_rate", "max_turn_rate"),
    "max_wheel_speed": ("max_wheel_velocity", "wheel_speed_limit"),
    "rotate_angle": ("align_angle", "rotate_to_heading_angle", "heading_tolerance"),
    "rotate_omega": ("turn_rate", "rotate_speed", "rotation_speed"),
    "bits": ("encoder_bits", "counter_bits"),
    "ticks_per_rev": ("cpr", "ticks_per_revolution", "counts_per_rev"),
    "mount": ("mounting", "mount_pose", "sensor_pose"),
    "times": ("timestamps", "stamps"),
    "pose": ("start_pose", "initial_pose", "init_pose", "pose0"),
    "workers": ("n_jobs", "processes", "n_workers", "num_workers", "jobs"),
    "trials": ("n_trials", "num_trials"),
    "latency": ("delay",),
    "rate": ("frequency", "freq", "hz"),
    "n_beams": ("num_beams", "beams", "n_rays"),
    "connectivity": ("neighbourhood", "neighborhood", "neighbors"),
    "path_xy": ("waypoints_xy",),
    "min_angle": ("min_rotation",),
    "mode": ("trinary",),
}


def test_one_keyword_name_per_idea() -> None:
    banned = {syn: name for name, synonyms in VOCABULARY.items() for syn in synonyms}
    found = [
        f"{where}({p.name}=): use {banned[p.name]}"
        for where, sig in SIGNATURES.items()
        for p in sig.parameters.values()
        if p.name in banned and not _is_deprecated_alias(p)
    ]
    assert not found, "\n".join(found)


def test_a_bare_radius_is_only_a_circle_s() -> None:
    # README: radii end in _radius and say whose radius they are.
    found = [
        where
        for where, sig in SIGNATURES.items()
        if "radius" in sig.parameters and where != "navkit.sim.Circle"
    ]
    assert not found


# --- Frames in the names ---------------------------------------------------------------

_FRAMELESS = re.compile(r"(^|_)(point|points|pos|position|positions|location|loc|coords?)$")


def test_positions_say_their_frame() -> None:
    # A position is _xy (world or robot frame), _cell, _node or a whole pose;
    # ``points`` alone is Path2D's field (its ``frame`` says which) and a Scene's.
    allowed = {
        ("navkit.planning.grid.Path2D", "points"),
        ("navkit.sim.Scene", "points"),
        # A ROS message's own field (info.origin.position), named as in the message.
        ("navkit.mapping.io.OccupancyGridMsgFields", "origin_position"),
    }
    found = [
        f"{where}({name})"
        for where, sig in SIGNATURES.items()
        for name in sig.parameters
        if _FRAMELESS.search(name) and (where, name) not in allowed
    ]
    assert not found, found


# --- The same option, the same default -------------------------------------------------

#: Options that mean the same wherever they appear; a deprecated alias defaults to None.
SAME_DEFAULT = (
    "cost_scaling_factor",
    "cost_weight",
    "occupied_thresh",
    "free_thresh",
    "unknown_cost",
    "inflate_around_unknown",
    "connectivity",
    "corner_cutting",
    "heuristic_weight",
    "interpolate",
    "lookahead",
    "smooth",
    "half_width",
    "continuous",
    "require_progress",
    "executor",
    "progress",
    "digits",
    "ax",
    "label",
    "color",
    "topic",
    "t",
)


def _defaults_of(name: str) -> dict[str, Any]:
    # None is "not given": a deprecated alias, or the object's own setting
    # (``OccupancyGrid.unknown(occupied_thresh=None)`` uses the grid's threshold).
    out = {}
    for where, sig in SIGNATURES.items():
        p = sig.parameters.get(name)
        if p is not None and p.default is not p.empty and p.default is not None:
            out[where] = p.default
    return out


@pytest.mark.parametrize("name", SAME_DEFAULT)
def test_the_same_option_has_the_same_default(name: str) -> None:
    defaults = _defaults_of(name)
    distinct = {repr(v) for v in defaults.values()}
    assert len(distinct) <= 1, defaults


def test_the_same_default_list_is_not_vacuous() -> None:
    several = [name for name in SAME_DEFAULT if len(_defaults_of(name)) >= 2]
    assert len(several) >= 15, several


def test_robot_radius_defaults_to_no_inflation_or_is_required() -> None:
    # robot_radius is required where it is the point (costmap, inflate) and 0 elsewhere.
    for where, sig in SIGNATURES.items():
        p = sig.parameters.get("robot_radius")
        if p is not None:
            assert p.default in (p.empty, 0.0), where


# --- Data positional, options keyword-only ---------------------------------------------

#: Positional parameters with a numeric default: data with a natural zero or an
#: optional datum, never an option (an option is keyword-only).
NUMERIC_POSITIONAL = {
    ("navkit.geometry.Pose2D", "theta"),
    ("navkit.geometry.Twist2D", "vy"),
    ("navkit.geometry.Twist2D", "omega"),
    ("navkit.sim.Compass.heading_deg", "z"),
    ("navkit.sim.TrialResult", "wall_time"),
    ("navkit.errors.NoPathError", "expanded"),  # an exception's data: NoPathError(msg, n)
}


def test_flags_and_numeric_options_are_keyword_only() -> None:
    flags, numbers = [], []
    for where, sig in SIGNATURES.items():
        for p in sig.parameters.values():
            if p.kind is not p.POSITIONAL_OR_KEYWORD or p.default is p.empty:
                continue
            if isinstance(p.default, (bool, np.bool_)):
                flags.append(f"{where}({p.name}={p.default})")
            elif isinstance(p.default, (int, float)) and (where, p.name) not in NUMERIC_POSITIONAL:
                numbers.append(f"{where}({p.name}={p.default})")
    assert not flags, flags
    assert not numbers, numbers


def test_the_numeric_positional_list_is_current() -> None:
    for where, name in NUMERIC_POSITIONAL:
        assert SIGNATURES[where].parameters[name].kind is inspect.Parameter.POSITIONAL_OR_KEYWORD


# --- Shared tracker options are readable on every tracker -------------------------------

TRACKERS = (FollowTheCarrot, OnOffTracker, RegulatedPurePursuit)


def _tracker_keywords(cls: type) -> set[str]:
    params = inspect.signature(cls).parameters.values()
    return {p.name for p in params if not _is_deprecated_alias(p)}


def _shared_tracker_keywords() -> set[str]:
    names = [_tracker_keywords(cls) for cls in TRACKERS]
    shared: set[str] = set()
    for i, a in enumerate(names):
        for b in names[i + 1 :]:
            shared |= a & b
    return shared


def test_a_keyword_two_trackers_share_is_readable_on_every_tracker_that_takes_it() -> None:
    shared = _shared_tracker_keywords()
    assert {"max_speed", "goal_tolerance", "yaw_tolerance", "rotate_angle", "drive"} <= shared
    missing = []
    for cls in TRACKERS:
        tracker = cls()
        for name in sorted(shared & _tracker_keywords(cls)):
            if not hasattr(tracker, name):
                missing.append(f"{cls.__name__}.{name}")
    assert not missing, missing


@pytest.mark.parametrize("cls", TRACKERS)
@pytest.mark.parametrize("angle", [0.3, 1.2, 1.5])
def test_rotate_angle_reads_back_what_was_given(cls: Callable[..., Any], angle: float) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tracker = cls(rotate_angle=angle, align_tolerance=0.1) if cls is FollowTheCarrot else (
            cls(rotate_angle=angle)
        )
        assert tracker.rotate_angle == angle
    with pytest.raises(AttributeError):
        tracker.rotate_angle = 0.5


# --- The same mistake, the same error --------------------------------------------------


def _options() -> list[tuple[str, Callable[..., Any], str]]:
    """``(label, call(**{option: value}), option)``: a float option from every package."""
    from navkit.control import PotentialFieldController, limit_velocity_change
    from navkit.estimation import PlanarFusion
    from navkit.geometry import Twist2D
    from navkit.kinematics import DiffDrive, OmniDrive
    from navkit.mapping import LocalGrid, OccupancyGrid, ScanMatcher, costmap
    from navkit.planning import KhatibRepulsion, MapPlanner, astar
    from navkit.sim import Lidar, Robot, Simulation, World

    grid = OccupancyGrid.from_occupancy(np.zeros((4, 4), dtype=bool), resolution=0.1)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)

    def still(_obs: object) -> Twist2D:
        return Twist2D(0.0, 0.0, 0.0)

    return [
        ("OccupancyGrid.empty", lambda **o: OccupancyGrid.empty(**{
            "width": 1.0, "height": 1.0, "resolution": 0.1, **o}), "resolution"),
        ("LocalGrid.from_points", lambda **o: LocalGrid.from_points([], **o), "resolution"),
        ("costmap", lambda **o: costmap(grid, **{
            "robot_radius": 0.1, "inflation_radius": 0.2, **o}), "inflation_radius"),
        ("ScanMatcher", lambda **o: ScanMatcher(**o), "tolerance"),
        ("DiffDrive", lambda **o: DiffDrive(**{"track": 0.3, "wheel_radius": 0.05, **o}),
         "track"),
        ("OmniDrive.three_wheel", lambda **o: OmniDrive.three_wheel(**{
            "wheel_radius": 0.05, "base_radius": 0.2, **o}), "base_radius"),
        ("PlanarFusion", lambda **o: PlanarFusion(**o), "gate_probability"),
        ("MapPlanner", lambda **o: MapPlanner(grid, **o), "robot_radius"),
        ("astar", lambda **o: astar(np.ones((3, 3)), (0, 0), (2, 2), **o), "heuristic_weight"),
        ("KhatibRepulsion", lambda **o: KhatibRepulsion([[1.0, 1.0]], **o), "influence_radius"),
        ("FollowTheCarrot", lambda **o: FollowTheCarrot(**o), "goal_tolerance"),
        ("RegulatedPurePursuit", lambda **o: RegulatedPurePursuit(**o), "max_speed"),
        ("PotentialFieldController", lambda **o: PotentialFieldController(**o), "max_accel"),
        ("limit_velocity_change", lambda **o: limit_velocity_change([0, 0, 0], [1, 0, 0], **{
            "max_accel": 1.0, "max_decel": 1.0, "dt": 0.1, **o}), "dt"),
        ("Lidar", lambda **o: Lidar(**o), "range_max"),
        ("Simulation", lambda **o: Simulation(World(), robot, still, **{
            "start": (0.0, 0.0, 0.0), **o}), "duration"),
    ]  # fmt: skip


OPTIONS = _options()
#: The same mistake everywhere: a value of the wrong type is a TypeError, a number
#: out of its domain (NaN included) a ValueError; either names the option.
MISTAKES = [
    ("True", True, TypeError),
    ("'0.5'", "0.5", TypeError),
    ("[0.5]", [0.5], TypeError),
    ("nan", math.nan, ValueError),
    ("-1e308", -1e308, ValueError),
]


@pytest.mark.parametrize(("label", "make", "option"), OPTIONS, ids=[o[0] for o in OPTIONS])
@pytest.mark.parametrize(("what", "value", "error"), MISTAKES, ids=[m[0] for m in MISTAKES])
def test_the_same_mistake_gives_the_same_error(
    label: str,
    make: Callable[..., Any],
    option: str,
    what: str,
    value: Any,
    error: type[Exception],
) -> None:
    with pytest.raises(error, match=rf"\b{option}\b"):
        make(**{option: value})


def test_the_options_are_valid_as_given() -> None:
    # Each case above fails because of the mistake, not because the call is wrong.
    for _label, make, _option in OPTIONS:
        make()


# --- data_dir takes a path wherever it is taken ----------------------------------------


def test_data_dir_takes_a_path_like_everywhere() -> None:
    import navkit.sim.scenarios as scenarios

    checked = []
    for where, sig in SIGNATURES.items():
        if "data_dir" not in sig.parameters:
            continue
        owner: Any = scenarios.find_data if where.endswith("find_data") else None
        if owner is None:
            owner = getattr(scenarios, where.split(".")[3])
        hints = typing.get_type_hints(owner if inspect.isfunction(owner) else owner.__init__)
        assert os.PathLike[str] in typing.get_args(hints["data_dir"]), where
        checked.append(where)
    assert len(checked) >= 3, checked


def test_greedy_takes_a_path_for_data_dir(tmp_path: Path) -> None:
    from navkit.sim.scenarios import Greedy

    # An empty folder: the map is not found, which the scenario notes for its trials.
    by_path = Greedy(noise=False, data_dir=tmp_path)
    by_str = Greedy(noise=False, data_dir=str(tmp_path))
    assert by_path.data_dir == by_str.data_dir == str(tmp_path)
    with pytest.raises(TypeError, match="data_dir must be a path or None, got int"):
        Greedy(data_dir=3)  # type: ignore[arg-type]


# --- Settled after the table (APIFIX) ----------------------------------------------------


def _public_classes() -> dict[str, type]:
    callables = public_callables()
    return {pc.name: pc.obj for pc in callables if pc.method is None and inspect.isclass(pc.obj)}


def test_an_object_with_a_pose_takes_its_start_as_pose() -> None:
    found, checked = [], []
    for where, cls in _public_classes().items():
        if not isinstance(inspect.getattr_static(cls, "pose", None), property):
            continue
        params = SIGNATURES[where].parameters
        checked.append(where.rsplit(".", 1)[-1])
        if "start" in params and not _is_deprecated_alias(params["start"]):
            found.append(f"{where}(start=): use pose=")
    assert not found, found
    assert {"ScanMapper", "DiffOdometry", "OmniOdometry", "PlanarFusion"} <= set(checked)


def test_sensor_configurations_are_keyword_only() -> None:
    import navkit.sim as sim

    for name in ("Compass", "Imu", "Lidar", "RangeNoise", "Robot", "WheelEncoders"):
        kinds = {p.kind for p in SIGNATURES[f"navkit.sim.{name}"].parameters.values()}
        assert kinds == {inspect.Parameter.KEYWORD_ONLY}, name
        assert getattr(sim, name).__dataclass_params__.frozen, name


def test_the_odometries_reset_alike() -> None:
    from navkit.estimation import DiffOdometry, OmniOdometry

    assert str(SIGNATURES["navkit.estimation.OmniOdometry.reset"]) == str(
        SIGNATURES["navkit.estimation.DiffOdometry.reset"]
    )
    assert OmniOdometry.reset.__doc__ and DiffOdometry.reset.__doc__


def test_map_planner_reads_back_every_option() -> None:
    from navkit.mapping import OccupancyGrid
    from navkit.planning import MapPlanner

    grid = OccupancyGrid.from_occupancy(np.zeros((6, 6), dtype=bool), resolution=0.1)
    options = {"robot_radius": 0.1, "inflation_radius": 0.3, "unknown_cost": 12.0,
               "inflate_unknown": False, "planner": "field_dstar"}  # fmt: skip
    assert set(options) == set(SIGNATURES["navkit.planning.grid.MapPlanner"].parameters) - {"grid"}
    planner = MapPlanner(grid, **options)  # type: ignore[arg-type]
    assert {name: getattr(planner, name) for name in options} == options


def _group_by_name() -> dict[str, list[str]]:
    out: dict[str, list[str]] = defaultdict(list)
    for where, sig in SIGNATURES.items():
        for name in sig.parameters:
            out[name].append(where)
    return out


def test_settled_names_are_in_use() -> None:
    # The vocabulary names ideas navkit has: each settled name is a real keyword.
    used = _group_by_name()
    unused = [name for name in VOCABULARY if name not in used]
    assert not unused, unused
