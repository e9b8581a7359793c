"""ROS map_server files (navkit.mapping.io): real maps in ../shared/data, round trips,
bad files, and saving that never loses a map."""

from __future__ import annotations

import errno
import math
import os
import stat
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml as pyyaml
from scipy import ndimage

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map
from navkit.mapping.io._map_files import read_image, read_pgm

MAPS = "ros-map-server-maps"


def maps(shared_data: Path) -> Path:
    return shared_data / MAPS


@pytest.mark.parametrize(
    ("yaml", "shape", "resolution", "origin"),
    [
        ("turtlebot3_world/map.yaml", (384, 384), 0.05, (-10.0, -10.0)),
        ("willow_garage_2010/willow-2010-02-18-0.10.yaml", (608, 566), 0.10, (0.0, 0.0)),
        ("lse_arena/lse_arena.yaml", (60, 80), 0.05, (0.0, 0.0)),
    ],
)
def test_real_maps_load(
    shared_data: Path,
    yaml: str,
    shape: tuple[int, int],
    resolution: float,
    origin: tuple[float, float],
) -> None:
    path = maps(shared_data) / yaml
    grid = OccupancyGrid.load(path)
    assert grid.shape == shape
    assert grid.resolution == resolution
    assert (grid.origin.x, grid.origin.y, grid.origin.theta) == (*origin, 0.0)
    assert (grid.occupied_thresh, grid.free_thresh) == (0.65, 0.196)
    # map_server's trinary reading of the raw pixels, with the image's top row last.
    pixels = read_pgm(path.with_suffix(".pgm"))
    p = (255.0 - pixels) / 255.0
    assert np.array_equal(grid.occupied(), (p > 0.65)[::-1])
    assert np.array_equal(grid.free(), (p < 0.196)[::-1])
    assert np.array_equal(grid.unknown(), ((p >= 0.196) & (p <= 0.65))[::-1])


def test_lse_arena_landmark_orientation(shared_data: Path) -> None:
    # In the image (top row = largest y) a vertical wall at x = 2 m rises from the
    # horizontal wall on the right towards the top; a short stub leaves the left
    # wall just below it. Flipped rows would put the vertical wall below y = 1.5 m.
    grid = OccupancyGrid.load(maps(shared_data) / "lse_arena" / "lse_arena.yaml")
    pixels = read_pgm(maps(shared_data) / "lse_arena" / "lse_arena.pgm")
    assert pixels[13:29, 40].max() == 0 and pixels[35:55, 40].min() == 255  # image rows
    occ_at = grid.occupied()[tuple(grid.world_to_cell([[2.025, 2.0], [2.025, 1.0]]).T)]
    assert occ_at.tolist() == [True, False]
    wall = np.argwhere(grid.occupied()[:, 40]).ravel()
    interior_wall = wall[(wall > 0) & (wall < 59)]
    assert interior_wall.tolist() == list(range(31, 47))
    y = grid.cell_to_world([[31, 40], [46, 40]])[:, 1]
    assert y == pytest.approx([1.575, 2.325])
    # The left stub at y ≈ 1.48 m spans x = 0 .. 0.8 m.
    assert grid.occupied()[29, :16].all() and not grid.occupied()[29, 16:79].any()


def test_turtlebot3_world_pillars(shared_data: Path) -> None:
    # The TurtleBot3 Gazebo world: nine pillars 1.1 m apart around the world origin,
    # inside a hexagonal wall. Their blobs must sit where the world puts them.
    grid = OccupancyGrid.load(maps(shared_data) / "turtlebot3_world" / "map.yaml")
    labels, n = ndimage.label(grid.occupied(), structure=np.ones((3, 3)))
    sizes = ndimage.sum(grid.occupied(), labels, range(1, n + 1))
    pillars = [i + 1 for i, s in enumerate(sizes) if s < 100]
    assert len(pillars) == 9
    centres = ndimage.center_of_mass(grid.occupied(), labels, pillars)
    # Continuous cell coordinates to world: x = ox + (col + 0.5) res, y = oy + (row + 0.5) res.
    world = np.array([[-10 + (c + 0.5) * 0.05, -10 + (r + 0.5) * 0.05] for r, c in centres])
    expected = np.array([[i * 1.1, j * 1.1] for i in (-1, 0, 1) for j in (-1, 0, 1)])
    for target in expected:
        assert np.min(np.hypot(*(world - target).T)) < 0.1


@pytest.mark.parametrize("mode", ["trinary", "scale"])
@pytest.mark.parametrize(
    "yaml", ["turtlebot3_world/map.yaml", "willow_garage_2010/willow-2010-02-18-0.10.yaml"]
)
def test_save_load_round_trip(shared_data: Path, tmp_path: Path, yaml: str, mode: str) -> None:
    grid = read_map(maps(shared_data) / yaml)
    image = write_map(grid, tmp_path / "copy.yaml", mode=mode)
    suffix = {"trinary": "pgm", "scale": "png"}[mode]  # map_saver's formats
    assert image == tmp_path / f"copy.{suffix}"
    assert f"image: copy.{suffix}" in (tmp_path / "copy.yaml").read_text()
    again = read_map(tmp_path / "copy.yaml")
    assert again.shape == grid.shape and again.resolution == grid.resolution
    assert again.origin == grid.origin
    assert np.array_equal(again.occupied(), grid.occupied())
    assert np.array_equal(again.free(), grid.free())
    assert np.array_equal(again.unknown(), grid.unknown())
    if mode == "scale":  # the probabilities themselves come back
        assert np.array_equal(again.logodds, grid.logodds)


def test_round_trip_with_yaw_and_custom_thresholds(tmp_path: Path) -> None:
    rng = np.random.default_rng(3)
    p = rng.random((7, 9))
    grid = OccupancyGrid(
        np.log(p / (1 - p)),
        resolution=0.2,
        origin=Pose2D(1.0, -2.0, 0.3),
        occupied_thresh=0.8,
        free_thresh=0.3,
    )
    for mode in ("trinary", "scale"):
        grid.save(tmp_path / f"{mode}.yaml", mode=mode)
        again = OccupancyGrid.load(tmp_path / f"{mode}.yaml")
        assert again.origin.theta == pytest.approx(0.3)
        assert (again.occupied_thresh, again.free_thresh) == (0.8, 0.3)
        assert np.array_equal(again.occupied(), grid.occupied())
        assert np.array_equal(again.free(), grid.free())
    with pytest.raises(ValueError, match="mode must be"):
        grid.save(tmp_path / "x.yaml", mode="raw")


def make_map_files(tmp: Path, yaml: str, pgm: bytes, name: str = "m.pgm") -> Path:
    (tmp / name).write_bytes(pgm)
    (tmp / "m.yaml").write_text(yaml)
    return tmp / "m.yaml"


GOOD_YAML = (
    "image: m.pgm  # comment\nresolution: 0.5\norigin: [1.0, 2.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
)


def test_ascii_p2_with_comments_and_16_bit(tmp_path: Path) -> None:
    pgm = b"P2\n# two rows\n3 2\n# max\n1000\n0 1000 900\n1000 1000 0\n"
    grid = OccupancyGrid.load(make_map_files(tmp_path, GOOD_YAML, pgm))
    # Image top row (0, 1000, 800) is the last grid row; 1000 = white = free.
    assert grid.occupied().tolist() == [[False, False, True], [True, False, False]]
    assert grid.free().tolist() == [[True, True, False], [False, True, True]]
    # Leading zeros are digits like any others (the P2 value 0001000 is 1000).
    padded_pgm = pgm.replace(b" 900", b" 0000900")
    padded = OccupancyGrid.load(make_map_files(tmp_path, GOOD_YAML, padded_pgm))
    assert np.array_equal(padded.logodds, grid.logodds)
    p5 = b"P5 3 1 1000\n" + np.array([0, 1000, 600], dtype=">u2").tobytes()
    grid16 = OccupancyGrid.load(make_map_files(tmp_path, GOOD_YAML, p5))
    assert grid16.occupied().tolist() == [[True, False, False]]
    assert grid16.unknown().tolist() == [[False, False, True]]


def test_negate_and_scale_modes(tmp_path: Path) -> None:
    pgm = b"P5\n4 1\n255\n" + bytes([0, 100, 200, 255])
    negated = OccupancyGrid.load(
        make_map_files(tmp_path, GOOD_YAML.replace("negate: 0", "negate: 1"), pgm)
    )
    assert negated.occupied().tolist() == [[False, False, True, True]]
    assert negated.free().tolist() == [[True, False, False, False]]
    scale = OccupancyGrid.load(make_map_files(tmp_path, GOOD_YAML + "mode: scale\n", pgm))
    # p = (255 - v) / 255: 0.608 for v = 100 is kept as a probability.
    assert scale.probability()[0, 1] == pytest.approx(155 / 255, abs=1e-6)
    assert scale.unknown().tolist() == [[False, True, True, False]]
    raw = OccupancyGrid.load(make_map_files(tmp_path, GOOD_YAML + "mode: raw\n", pgm))
    assert raw.probability()[0, 0] == pytest.approx(1e-3)
    assert raw.occupied().tolist() == [[False, True, False, False]]
    assert raw.unknown().tolist() == [[False, False, True, True]]


def test_png_maps_need_pillow(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from PIL import Image

    rgb = np.zeros((2, 3, 3), dtype=np.uint8)
    rgb[...] = [
        [[0, 0, 0], [254, 254, 254], [205, 205, 205]],
        [[254, 254, 254], [254, 254, 254], [0, 0, 0]],
    ]
    # RGB, not RGBA: trinary mode averages an alpha channel in (see the alpha test).
    Image.fromarray(rgb, "RGB").save(tmp_path / "m.png")
    (tmp_path / "m.yaml").write_text(GOOD_YAML.replace("m.pgm", "m.png"))
    grid = OccupancyGrid.load(tmp_path / "m.yaml")
    assert grid.occupied().tolist() == [[False, False, True], [True, False, False]]
    assert grid.unknown().tolist() == [[False, False, False], [False, False, True]]
    monkeypatch.setitem(sys.modules, "PIL", None)
    with pytest.raises(ImportError, match="pip install pillow"):
        OccupancyGrid.load(tmp_path / "m.yaml")


@pytest.mark.parametrize(
    ("yaml", "pgm", "error", "match"),
    [
        (GOOD_YAML.replace("resolution: 0.5\n", ""), None, ValueError, "missing .*resolution"),
        (
            GOOD_YAML.replace("negate: 0\n", "").replace("free_thresh: 0.196\n", ""),
            None,
            ValueError,
            "missing required key.*negate, free_thresh",
        ),
        (GOOD_YAML.replace("m.pgm", "absent.pgm"), None, FileNotFoundError, "absent.pgm"),
        (GOOD_YAML.replace("0.5", "-0.5"), None, ValueError, r"m.yaml: resolution must be >= 1e-6"),
        (GOOD_YAML.replace("[1.0, 2.0, 0.0]", "[1.0, 2.0]"), None, ValueError, "origin must be"),
        (GOOD_YAML.replace("0.196", "0.9"), None, ValueError, "free_thresh < occupied_thresh"),
        (GOOD_YAML + "mode: fancy\n", None, ValueError, "mode must be one of"),
        (GOOD_YAML + "this line is bad\n", None, ValueError, r"m.yaml:7: expected 'key: value'"),
        (GOOD_YAML, b"P6\n1 1\n255\n\x00", ValueError, "not a PGM image"),
        (GOOD_YAML, b"P5\n2 x\n255\n\x00\x00", ValueError, "bad PGM header field b'x'"),
        (GOOD_YAML, b"P5\n2 2\n255\n\x00", ValueError, "PGM raster truncated"),
        (GOOD_YAML, b"P5\n2 2\n", ValueError, "header ends before"),
        (GOOD_YAML, b"P5\n0 2\n255\n", ValueError, "PGM size must be positive"),
        (GOOD_YAML, b"P2\n2 1\n100\n5 200\n", ValueError, "exceed maxval 100"),
    ],
)
def test_bad_map_files(
    tmp_path: Path, yaml: str, pgm: bytes | None, error: type[Exception], match: str
) -> None:
    path = make_map_files(tmp_path, yaml, pgm if pgm is not None else b"P5\n1 1\n255\n\xff")
    with pytest.raises(error, match=match):
        OccupancyGrid.load(path)


def test_missing_yaml() -> None:
    with pytest.raises(FileNotFoundError, match="does not exist"):
        OccupancyGrid.load("/nonexistent/map.yaml")


def test_loaded_map_plans_conservatively(shared_data: Path) -> None:
    # Unknown space is impassable by default; a 0.105 m robot fits the turtlebot3 arena.
    grid = OccupancyGrid.load(maps(shared_data) / "turtlebot3_world" / "map.yaml")
    costs = grid.traversal_costs(robot_radius=0.105, inflation_radius=0.5, cost_scaling_factor=3.0)
    assert np.all(np.isinf(costs[grid.unknown()]))
    assert np.all(np.isinf(costs[grid.inflate(0.105)]))
    centre = grid.world_to_cell([[0.55, 0.55]])[0]
    assert math.isfinite(costs[tuple(centre)])


# ------------------------------------------------------------- YAML dialects
@pytest.mark.parametrize(
    "text",
    [
        # map_saver's own output, yaml-cpp style: ints, exponents without a dot.
        "image: m.pgm\nmode: trinary\nresolution: 5e-1\norigin: [1, 2, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n\n",
        # Quoted strings, a document marker, a block list and true/false negate.
        "---\nimage: 'm.pgm'\nresolution: 0.5\norigin:\n  - 1.0\n  - 2.0\n  - 0.0\n"
        'negate: false\noccupied_thresh: "0.65"\nfree_thresh: 0.196\nmode: Trinary\n',
    ],
)
def test_yaml_dialects(tmp_path: Path, text: str) -> None:
    grid = read_map(make_map_files(tmp_path, text, b"P5\n2 1\n255\n\x00\xfe"))
    assert grid.resolution == 0.5 and grid.origin == Pose2D(1.0, 2.0, 0.0)
    assert grid.occupied().tolist() == [[True, False]]
    assert grid.free().tolist() == [[False, True]]


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("- image\n- m.pgm\n", "expected 'key: value' lines, got list"),
        ("", "expected 'key: value' lines, got NoneType"),
        (GOOD_YAML + "origin: [1, 2\n", "m.yaml:7: expected 'key: value'"),
        (GOOD_YAML.replace("image: m.pgm", "image: [m.pgm]"), "image must be a file name"),
        (GOOD_YAML.replace("resolution: 0.5", "resolution: true"), "resolution must be a number"),
        (GOOD_YAML.replace("resolution: 0.5", "resolution: .nan"), "resolution must be finite"),
        (GOOD_YAML.replace("negate: 0", "negate: 2"), "negate must be 0 or 1"),
    ],
)
def test_bad_yaml(tmp_path: Path, text: str, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        read_map(make_map_files(tmp_path, text, b"P5\n1 1\n255\n\xff"))


# ------------------------------------------------- saving never loses a map
def small_grid(value: bool = True) -> OccupancyGrid:
    occupied = np.array([[value, False, False], [False, False, not value]])
    return OccupancyGrid.from_occupancy(occupied, resolution=0.25, origin=(1.0, 2.0, 0.0))


def snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


@pytest.mark.parametrize("name", ["map.pgm", "map.PGM", "Map.Pgm"])
def test_save_never_writes_over_its_own_image(tmp_path: Path, name: str) -> None:
    # save("map.pgm") used to write the image to map.pgm and then the YAML over it.
    small_grid().save(tmp_path / "map.yaml")
    before = snapshot(tmp_path)
    with pytest.raises(ValueError, match=r"ends in \.pgm"):
        small_grid(False).save(tmp_path / name)
    with pytest.raises(ValueError, match=r"ends in \.pgm"):
        write_map(small_grid(False), str(tmp_path / name))
    assert snapshot(tmp_path) == before
    assert read_map(tmp_path / "map.yaml").occupied()[0, 0]


def test_save_refuses_directories_before_writing(tmp_path: Path) -> None:
    (tmp_path / "map.pgm").mkdir()
    with pytest.raises(ValueError, match=r"map\.pgm: it is a directory"):
        write_map(small_grid(), tmp_path / "map.yaml")
    (tmp_path / "other.yaml").mkdir()
    with pytest.raises(ValueError, match=r"other\.yaml: it is a directory"):
        write_map(small_grid(), tmp_path / "other.yaml")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "other.yaml"]
    with pytest.raises(ValueError, match="must name a YAML file"):
        write_map(small_grid(), Path(""))


def test_save_refuses_a_yaml_linked_to_its_image(tmp_path: Path) -> None:
    small_grid().save(tmp_path / "map.yaml")
    os.link(tmp_path / "map.pgm", tmp_path / "alias")
    (tmp_path / "alias.pgm").symlink_to(tmp_path / "alias")
    before = snapshot(tmp_path)
    with pytest.raises(ValueError, match="are the same file"):
        write_map(small_grid(False), tmp_path / "alias")
    assert snapshot(tmp_path) == before


def fail_on_call(
    monkeypatch: pytest.MonkeyPatch, name: str, call: int, exc: BaseException
) -> list[int]:
    """Make ``os.<name>`` raise ``exc`` on its ``call``-th call (1-based)."""
    real: Callable[..., Any] = getattr(os, name)
    calls = [0]

    def wrapper(*args: Any, **kwargs: Any) -> Any:
        calls[0] += 1
        if calls[0] == call:
            raise exc
        return real(*args, **kwargs)

    monkeypatch.setattr(os, name, wrapper)
    return calls


@pytest.mark.parametrize(
    ("name", "call"),
    [
        ("fsync", 1),  # disk full while writing the image
        ("fsync", 2),  # ... while writing the YAML, the image already written
        ("replace", 1),  # renaming fails before anything is replaced
    ],
)
def test_failed_save_leaves_the_old_map_intact(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str, call: int
) -> None:
    small_grid(True).save(tmp_path / "map.yaml")
    before = snapshot(tmp_path)
    fail_on_call(monkeypatch, name, call, OSError(errno.ENOSPC, "No space left on device"))
    with pytest.raises(OSError, match="No space left"):
        small_grid(False).save(tmp_path / "map.yaml", mode="scale")
    monkeypatch.undo()
    # Old files untouched, no temporary file left behind.
    assert snapshot(tmp_path) == before
    again = read_map(tmp_path / "map.yaml")
    assert np.array_equal(again.occupied(), small_grid(True).occupied())


def test_interrupted_save_leaves_no_trace(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    fail_on_call(monkeypatch, "fsync", 2, KeyboardInterrupt())
    with pytest.raises(KeyboardInterrupt):
        small_grid().save(tmp_path / "map.yaml")
    monkeypatch.undo()
    assert list(tmp_path.iterdir()) == []


def test_save_replaces_an_existing_map(tmp_path: Path) -> None:
    small_grid(True).save(tmp_path / "map.yaml")
    (tmp_path / "map.pgm").chmod(0o640)
    small_grid(False).save(tmp_path / "map.yaml")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]
    assert np.array_equal(read_map(tmp_path / "map.yaml").occupied(), small_grid(False).occupied())
    # An existing file keeps its permissions; a new one gets the umask's.
    assert stat.S_IMODE((tmp_path / "map.pgm").stat().st_mode) == 0o640
    umask = os.umask(0o022)
    try:
        small_grid().save(tmp_path / "fresh.yaml")
    finally:
        os.umask(umask)
    assert stat.S_IMODE((tmp_path / "fresh.yaml").stat().st_mode) == 0o644
    assert stat.S_IMODE((tmp_path / "fresh.pgm").stat().st_mode) == 0o644


@pytest.mark.parametrize(
    "stem",
    [
        "my map",
        "a #b",
        "[x]",
        "{y}",
        "key: value",
        "'quoted'",
        '"double"',
        "it's",
        " lead",
        "-dash",
        "&anchor",
        "*alias",
        "!tag",
        "%percent",
        "@at",
        "`tick",
        "back\\slash",
        "tab\tname",
        "line\nbreak",
        "ünïcødé 地图 😀",
    ],
)
def test_image_names_round_trip(tmp_path: Path, stem: str) -> None:
    yaml_path = tmp_path / f"{stem}.yaml"
    image = write_map(small_grid(), yaml_path)
    assert image == tmp_path / f"{stem}.pgm" and image.is_file()
    # Quoted where plain YAML would misread it; any YAML reader gets the name back.
    assert pyyaml.safe_load(yaml_path.read_text(encoding="utf-8"))["image"] == f"{stem}.pgm"
    again = read_map(yaml_path)
    assert np.array_equal(again.occupied(), small_grid().occupied())


@pytest.mark.parametrize("stem", ["next\x85line", "bad\udcffbytes"])
def test_unreadable_image_names_are_refused_up_front(tmp_path: Path, stem: str) -> None:
    with pytest.raises(ValueError, match="image name"):
        write_map(small_grid(), tmp_path / f"{stem}.yaml")
    assert list(tmp_path.iterdir()) == []


def test_save_checks_its_arguments(tmp_path: Path) -> None:
    with pytest.raises(TypeError, match="grid must be an OccupancyGrid"):
        write_map(np.zeros((2, 2)), tmp_path / "m.yaml")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="positional"):
        write_map(small_grid(), tmp_path / "m.yaml", "scale")  # type: ignore[call-arg]
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------- issue 12: every reproduction, by name
def test_load_then_save_never_overwrites_the_maps_own_image(tmp_path: Path) -> None:
    # The issue: g = OccupancyGrid.load("map.yaml"); g.save("m.pgm") overwrote the
    # user's own image m.pgm with YAML text.
    yaml_path = make_map_files(tmp_path, GOOD_YAML, b"P5\n2 1\n255\n\x00\xfe")
    g = OccupancyGrid.load(yaml_path)
    before = snapshot(tmp_path)
    with pytest.raises(ValueError, match=r"ends in \.pgm"):
        g.save(tmp_path / "m.pgm")
    # The same for a PNG map: the YAML would overwrite the image.
    from PIL import Image

    Image.fromarray(np.array([[0, 254]], dtype=np.uint8)).save(tmp_path / "p.png")
    (tmp_path / "p.yaml").write_text(GOOD_YAML.replace("m.pgm", "p.png"))
    before = snapshot(tmp_path)
    png_map = OccupancyGrid.load(tmp_path / "p.yaml")
    for name in ("p.png", "P.PNG", "x.jpg", "x.tif"):
        with pytest.raises(ValueError, match="an image suffix: the map YAML would overwrite"):
            png_map.save(tmp_path / name)
    assert snapshot(tmp_path) == before
    # Saving over the map itself is what the user asked for.
    png_map.save(tmp_path / "m.yaml")
    assert np.array_equal(OccupancyGrid.load(tmp_path / "m.yaml").occupied(), g.occupied())


@pytest.mark.parametrize("name", ["my map #2.yaml", "[map].yaml", "#.yaml", "a # b: c.yaml"])
def test_issue_names_round_trip(tmp_path: Path, name: str) -> None:
    image = small_grid().save(tmp_path / name)
    assert image == tmp_path / (name[: -len(".yaml")] + ".pgm")
    again = OccupancyGrid.load(tmp_path / name)
    assert np.array_equal(again.occupied(), small_grid().occupied())
    assert again.origin == small_grid().origin


@pytest.mark.parametrize(
    ("line", "name"),
    [
        ("image: a#b.pgm", "a#b.pgm"),  # '#' inside a plain scalar is not a comment
        ("image: 'my map #2.pgm'", "my map #2.pgm"),
        ('image: "[map].pgm"', "[map].pgm"),
        ("image: m.pgm # the image", "m.pgm"),
    ],
)
def test_hash_and_brackets_in_image_names_are_read_as_yaml_does(
    tmp_path: Path, line: str, name: str
) -> None:
    text = GOOD_YAML.replace("image: m.pgm  # comment", line)
    grid = read_map(make_map_files(tmp_path, text, b"P5\n2 1\n255\n\x00\xfe", name=name))
    assert grid.occupied().tolist() == [[True, False]]


def test_block_list_origin(tmp_path: Path) -> None:
    text = GOOD_YAML.replace("origin: [1.0, 2.0, 0.0]", "origin:\n- 1.0\n- 2.0\n- 0.5")
    grid = read_map(make_map_files(tmp_path, text, b"P5\n2 1\n255\n\x00\xfe"))
    assert grid.origin == Pose2D(1.0, 2.0, 0.5)


def _png(width: int, height: int, body: bytes = b"") -> bytes:
    """A PNG signature and IHDR claiming ``width`` x ``height`` grey pixels."""
    import struct
    import zlib

    def chunk(kind: bytes, data: bytes) -> bytes:
        return (
            struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
        )

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + body + chunk(b"IEND", b"")


def _good_png() -> bytes:
    import io as bytes_io

    from PIL import Image

    out = bytes_io.BytesIO()
    noise = np.random.default_rng(0).integers(0, 256, (40, 40), dtype=np.uint8)
    Image.fromarray(noise).save(out, format="PNG")  # noise: the pixels need ~1.6 kB
    return out.getvalue()


BAD_IMAGES: list[tuple[str, bytes, str]] = [
    ("garbage.png", b"\x89PNG\r\n\x1a\n" + bytes(40), "not an image file Pillow can identify"),
    ("noise.png", b"not an image at all\n", "not an image file Pillow can identify"),
    ("truncated.png", _good_png()[:400], r"cannot read the image \(OSError: image file is trunc"),
    ("empty.png", b"", "the image file is empty"),
    # Sizes from the header, refused before anything is decoded.
    ("bomb.png", _png(100_000, 100_000), r"Pillow's decompression-bomb limit"),
    ("big.png", _png(17_000, 17_000), r"Pillow's decompression-bomb limit"),
    ("big.pgm", b"P5\n100000 100000\n255\n\x00", r"100000 x 100000 = 10000000000 pixels"),
    ("big2.pgm", b"P2\n20000 20000\n255\n0\n", r"20000 x 20000 = 400000000 pixels"),
    ("wide.pgm", b"P5\n99999999999999999999999 2 255\n\x00", r"header field .* out of range"),
    # The issue's OverflowError: a P2 value of 10**26.
    ("huge.pgm", b"P2\n2 1\n255\n0 100000000000000000000000000\n", r"exceeds maxval 255"),
    ("neg.pgm", b"P2\n2 1\n255\n0 -5\n", r"not a non-negative integer"),
    ("maxval0.pgm", b"P5\n1 1\n0\n\x00", r"maxval must be in 1\.\.65535, got 0"),
    ("maxval.pgm", b"P5\n1 1\n70000\n\x00\x00", r"maxval must be in 1\.\.65535, got 70000"),
    ("text.pgm", b"hello\n", r"not a PGM image"),
]


@pytest.mark.parametrize(("name", "body", "match"), BAD_IMAGES, ids=[b[0] for b in BAD_IMAGES])
def test_malformed_images_raise_value_error_naming_the_files(
    tmp_path: Path, name: str, body: bytes, match: str
) -> None:
    (tmp_path / name).write_bytes(body)
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text(GOOD_YAML.replace("m.pgm", name))
    with pytest.raises(ValueError, match=match) as info:
        read_map(yaml_path)
    assert str(yaml_path) in str(info.value) and name in str(info.value)


def test_image_size_is_checked_from_the_header_before_decoding(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from PIL import Image

    # Without Pillow's own limit, navkit's (2**28 pixels) still applies, before decoding.
    monkeypatch.setattr(Image, "MAX_IMAGE_PIXELS", None)
    (tmp_path / "big.png").write_bytes(_png(17_000, 17_000))
    (tmp_path / "m.yaml").write_text(GOOD_YAML.replace("m.pgm", "big.png"))
    with pytest.raises(ValueError, match=r"17000 x 17000 = 289000000 pixels is larger than"):
        read_map(tmp_path / "m.yaml")
    # A PGM claiming 2**28 + 1 pixels with one byte of raster: refused by size, not truncation.
    (tmp_path / "big.pgm").write_bytes(b"P5\n268435457 1\n255\n\x00")
    (tmp_path / "m.yaml").write_text(GOOD_YAML.replace("m.pgm", "big.pgm"))
    with pytest.raises(ValueError, match=r"268435457 pixels is larger than .*MAX_CELLS"):
        read_map(tmp_path / "m.yaml")


def test_yaml_pointing_at_itself_or_a_text_file(tmp_path: Path) -> None:
    (tmp_path / "self.yaml").write_text(GOOD_YAML.replace("m.pgm", "self.yaml"))
    with pytest.raises(ValueError, match=r"self\.yaml: the image key names the YAML file itself"):
        read_map(tmp_path / "self.yaml")
    hostname = Path("/etc/hostname")
    if hostname.is_file() and hostname.stat().st_size > 0:
        (tmp_path / "host.yaml").write_text(GOOD_YAML.replace("m.pgm", str(hostname)))
        with pytest.raises(ValueError, match=r"host\.yaml: map image /etc/hostname: not an image"):
            read_map(tmp_path / "host.yaml")
    (tmp_path / "folder").mkdir()
    (tmp_path / "dir.yaml").write_text(GOOD_YAML.replace("m.pgm", "folder"))
    with pytest.raises(ValueError, match=r"dir\.yaml: map image .*folder is a directory"):
        read_map(tmp_path / "dir.yaml")
    with pytest.raises(ValueError, match=r"map YAML file .* is a directory"):
        read_map(tmp_path / "folder")


@pytest.mark.parametrize(
    ("content", "match"),
    [
        (b"P5\n2 1\n255\n\x00\xfe", r"this is a PGM image, not a map YAML"),  # the .pgm
        (_png(2, 2), r"this is a PNG image, not a map YAML"),
        (b"image: m.pgm\nresolution: 0.1\xff\xfe\n", r"not UTF-8 text \(byte 0xff at offset 28\)"),
        (b"\x00\x01\x02binary", r"expected 'key: value' lines"),
        (b"a: " + b"[" * 100_000, r"(nested too deeply|expected 'key: value')"),
        (b"resolution: 1" + b"0" * 5000 + b"\n", r"(unreadable YAML value|must be)"),
        (b"image: m.pgm\n" + b"#" * (1 << 20), r"too large for a map YAML"),
    ],
)
def test_malformed_yaml_raises_value_error_naming_the_file(
    tmp_path: Path, content: bytes, match: str
) -> None:
    (tmp_path / "m.pgm").write_bytes(b"P5\n1 1\n255\n\xff")
    path = tmp_path / "given.yaml"
    path.write_bytes(content)
    with pytest.raises(ValueError, match=match) as info:
        read_map(path)
    assert str(path) in str(info.value)


@pytest.mark.parametrize(
    ("old", "new", "match"),
    [
        ("resolution: 0.5", "resolution: 1e-9", r"resolution must be >= 1e-6"),
        ("resolution: 0.5", "resolution: 1" + "0" * 400, r"resolution must be a finite number"),
        ("[1.0, 2.0, 0.0]", "[1e12, 2.0, 0.0]", r"origin x and y must lie within ±1e9 m"),
        ("[1.0, 2.0, 0.0]", "[.inf, 2.0, 0.0]", r"origin must be finite"),
        ("image: m.pgm  # comment", 'image: "m\\0.pgm"', r"image must be a file name"),
        ("negate: 0", "negate: [0]", r"negate must be 0 or 1"),
    ],
)
def test_yaml_values_out_of_range(tmp_path: Path, old: str, new: str, match: str) -> None:
    path = make_map_files(tmp_path, GOOD_YAML.replace(old, new), b"P5\n1 1\n255\n\xff")
    with pytest.raises(ValueError, match=match) as info:
        read_map(path)
    assert str(path) in str(info.value)


def test_pillow_errors_become_value_errors(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from PIL import Image

    (tmp_path / "m.png").write_bytes(_good_png())
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text(GOOD_YAML.replace("m.pgm", "m.png"))
    assert read_map(yaml_path).shape == (40, 40)
    for exc in (
        Image.DecompressionBombError("Image size (400000000 pixels) exceeds limit"),
        Image.UnidentifiedImageError("cannot identify"),
        OSError("image file is truncated"),
        SyntaxError("broken PNG file"),
        EOFError(),
        ValueError("tile cannot extend outside image"),
    ):

        def broken(*args: Any, error: BaseException = exc, **kwargs: Any) -> Any:
            raise error

        monkeypatch.setattr(Image, "open", broken)
        with pytest.raises(ValueError, match=r"m\.yaml: map image .*m\.png: ") as info:
            read_map(yaml_path)
        assert type(info.value) is ValueError
    monkeypatch.undo()

    def refused(*args: Any, **kwargs: Any) -> Any:
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(Image, "open", refused)
    with pytest.raises(PermissionError):
        read_map(yaml_path)


def test_32_bit_images_are_clipped_to_grey_levels(tmp_path: Path) -> None:
    from PIL import Image

    Image.fromarray(np.array([[-5, 0, 70000, 65535]], dtype=np.int32), mode="I").save(
        tmp_path / "m.tif"
    )
    (tmp_path / "m.yaml").write_text(GOOD_YAML.replace("m.pgm", "m.tif"))
    grid = read_map(tmp_path / "m.yaml")
    assert grid.occupied().tolist() == [[True, True, False, False]]
    assert grid.free().tolist() == [[False, False, True, True]]


def test_paths_must_be_paths(tmp_path: Path) -> None:
    for bad in (3, None, b"map.yaml", ["map.yaml"]):
        with pytest.raises(TypeError, match=r"path must be a str or an os\.PathLike"):
            read_map(bad)  # type: ignore[arg-type]
        with pytest.raises(TypeError, match=r"path must be a str or an os\.PathLike"):
            write_map(small_grid(), bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="NUL"):
        read_map("map\x00.yaml")
    # "" would be the working directory ("." is a folder, not a map).
    with pytest.raises(ValueError, match="path must not be empty"):
        read_map("")
    with pytest.raises(ValueError, match="path must not be empty"):
        write_map(small_grid(), "")
    with pytest.raises(TypeError, match="mode must be a str"):
        write_map(small_grid(), tmp_path / "m.yaml", mode=None)  # type: ignore[arg-type]
    assert list(tmp_path.iterdir()) == []


def test_save_never_writes_over_another_maps_image(tmp_path: Path) -> None:
    # map.yaml names floor.pgm; saving the edited map as floor.yaml would write
    # floor.pgm, the original map's image, so map.yaml would show the edit.
    small_grid(True).save(tmp_path / "floor.yaml")
    (tmp_path / "floor.yaml").rename(tmp_path / "map.yaml")
    g = OccupancyGrid.load(tmp_path / "map.yaml")
    before = snapshot(tmp_path)
    with pytest.raises(ValueError, match=r"floor\.pgm already exists and is not the image of"):
        small_grid(False).save(tmp_path / "floor.yaml")
    # A YAML at the path that names another image does not own floor.pgm either.
    (tmp_path / "floor.yaml").write_text(GOOD_YAML)
    with pytest.raises(ValueError, match="already exists and is not the image"):
        small_grid(False).save(tmp_path / "floor.yaml")
    (tmp_path / "floor.yaml").unlink()
    assert snapshot(tmp_path) == before
    assert np.array_equal(OccupancyGrid.load(tmp_path / "map.yaml").occupied(), g.occupied())
    # Replacing a map (its YAML names the image) is what save is for.
    small_grid(False).save(tmp_path / "map2.yaml")
    small_grid(True).save(tmp_path / "map2.yaml")
    assert np.array_equal(read_map(tmp_path / "map2.yaml").occupied(), small_grid(True).occupied())


@pytest.mark.parametrize(
    ("occupied_thresh", "free_thresh"), [(0.45, 0.2), (0.9, 0.6), (0.65, 0.196)]
)
def test_unknown_pixels_stay_unknown_whatever_the_thresholds(
    tmp_path: Path, occupied_thresh: float, free_thresh: float
) -> None:
    """Unknown pixels used to be stored at p = 0.5, which thresholds not around 0.5 class."""
    yaml = GOOD_YAML.replace("0.65", str(occupied_thresh)).replace("0.196", str(free_thresh))
    (tmp_path / "m.yaml").write_text(yaml)
    # Pixels: black, a grey in the unknown band (map_server's -1), white.
    grey = round(255 * (1 - 0.5 * (occupied_thresh + free_thresh)))
    (tmp_path / "m.pgm").write_bytes(b"P5 3 1 255\n" + bytes([0, grey, 254]))
    grid = read_map(tmp_path / "m.yaml")
    assert grid.occupied().tolist() == [[True, False, False]]
    assert grid.unknown().tolist() == [[False, True, False]]
    assert grid.free().tolist() == [[False, False, True]]
    if free_thresh <= 0.5 <= occupied_thresh:
        assert grid.logodds[0, 1] == 0.0  # no evidence either way


@pytest.mark.parametrize("mode", ["trinary", "scale"])
@pytest.mark.parametrize(
    ("occupied_thresh", "free_thresh"), [(0.3, 0.25), (0.8, 0.79), (0.5, 0.497)]
)
def test_write_read_keeps_the_classes_with_narrow_or_off_centre_bands(
    tmp_path: Path, mode: str, occupied_thresh: float, free_thresh: float
) -> None:
    middle = 0.5 * (occupied_thresh + free_thresh)
    grid = OccupancyGrid.from_probabilities(
        [[0.05, middle, 0.95, 0.5, free_thresh, occupied_thresh]], resolution=0.1,
        occupied_thresh=occupied_thresh, free_thresh=free_thresh,
    )  # fmt: skip
    write_map(grid, tmp_path / "m.yaml", mode=mode)
    back = read_map(tmp_path / "m.yaml")
    for view in ("occupied", "free", "unknown"):
        assert np.array_equal(getattr(back, view)(), getattr(grid, view)()), view


def test_unknown_cells_that_no_grey_level_can_hold_are_refused(tmp_path: Path) -> None:
    # Between p = 0.499 and 0.5 lies no (255 - k) / 255: 127 reads as 0.50196, 128 as 0.49804.
    grid = OccupancyGrid.from_probabilities(
        [[0.4995, 0.9, 0.1]], resolution=0.1, occupied_thresh=0.5, free_thresh=0.499
    )
    for mode in ("trinary", "scale"):
        with pytest.raises(ValueError, match=r"no 8-bit grey level .* unknown"):
            write_map(grid, tmp_path / "m.yaml", mode=mode)
    assert list(tmp_path.iterdir()) == []
    known = OccupancyGrid.from_probabilities(  # nothing unknown to write: fine
        [[0.9, 0.1]], resolution=0.1, occupied_thresh=0.5, free_thresh=0.499
    )
    write_map(known, tmp_path / "m.yaml")
    assert read_map(tmp_path / "m.yaml").occupied().tolist() == [[True, False]]


def test_16_bit_png_spans_its_full_range(tmp_path: Path) -> None:
    """A 16-bit image is scaled by its depth, not by the largest value it holds."""
    from PIL import Image

    (tmp_path / "m.yaml").write_text(GOOD_YAML.replace("m.pgm", "m.png"))
    for pixels, occupied, free in (
        ([0, 200, 255], [True, True, True], [False, False, False]),  # all near black
        ([0, 40000, 65535], [True, False, False], [False, False, True]),
    ):
        Image.fromarray(np.array([pixels], dtype=np.uint16)).save(tmp_path / "m.png")
        grid = read_map(tmp_path / "m.yaml")
        assert grid.occupied().tolist() == [occupied]
        assert grid.free().tolist() == [free]


def nav2_cell(rgba: tuple[int, int, int, int], mode: str, negate: bool) -> int:
    """Nav2 map_io.cpp's loadMapFromFile for one 8-bit pixel, thresholds 0.65 / 0.196."""
    r, g, b, a = rgba
    channels = [r, g, b] + ([a] if mode == "trinary" else [])  # alpha averaged in trinary
    shade = sum(channels) / len(channels) / 255.0
    occ = shade if negate else 1.0 - shade
    if mode == "scale" and a != 255:
        return -1
    if occ > 0.65:
        return 100
    if occ < 0.196:
        return 0
    return -1 if mode == "trinary" else 50


@pytest.mark.parametrize("negate", [False, True])
@pytest.mark.parametrize("mode", ["trinary", "scale"])
def test_alpha_channels_are_read_as_map_server_reads_them(
    tmp_path: Path, mode: str, negate: bool
) -> None:
    """Trinary averages alpha in with the colours; scale makes non-opaque pixels unknown."""
    from PIL import Image

    pixels = [
        (205, 205, 205, 255),  # map_saver's unknown grey, opaque: 217.5 on average
        (0, 0, 0, 0),
        (255, 255, 255, 0),
        (0, 0, 0, 128),
        (254, 254, 254, 255),
        (0, 0, 0, 255),
        (100, 100, 100, 200),
    ]
    Image.fromarray(np.array([pixels], dtype=np.uint8), "RGBA").save(tmp_path / "m.png")
    text = GOOD_YAML.replace("m.pgm", "m.png").replace("negate: 0", f"negate: {int(negate)}")
    (tmp_path / "m.yaml").write_text(text + f"mode: {mode}\n")
    grid = read_map(tmp_path / "m.yaml")
    expected = [nav2_cell(p, mode, negate) for p in pixels]
    assert grid.occupied().tolist() == [[v == 100 for v in expected]]
    assert grid.free().tolist() == [[v == 0 for v in expected]]
    # Scale's in-between values (50 here) keep their p: neither occupied nor free.
    assert grid.unknown().tolist() == [[v in (-1, 50) for v in expected]]


def test_palette_and_colour_key_images_are_read_as_map_server_reads_them(
    tmp_path: Path,
) -> None:
    """Palette colours are averaged (not Pillow's luma); a tRNS colour key is alpha."""
    from PIL import Image

    (tmp_path / "m.yaml").write_text(GOOD_YAML.replace("m.pgm", "m.png") + "mode: scale\n")
    palette = Image.new("P", (2, 1))
    # Pure green averages to 85 (p = 0.667: occupied); its luma 150 (p = 0.41) is not.
    palette.putpalette([0, 255, 0, 250, 250, 250] + [0] * 762)
    palette.putdata([0, 1])
    palette.save(tmp_path / "m.png")
    grid = read_map(tmp_path / "m.yaml")
    assert grid.occupied().tolist() == [[True, False]]
    assert grid.free().tolist() == [[False, True]]
    keyed = Image.fromarray(np.array([[0, 250]], dtype=np.uint8), "L")
    keyed.save(tmp_path / "m.png", transparency=250)  # 250 is transparent
    grid = read_map(tmp_path / "m.yaml")
    assert grid.occupied().tolist() == [[True, False]]
    assert grid.unknown().tolist() == [[False, True]]


def test_grey_levels_on_a_threshold_are_decided_as_map_server_decides_them(
    tmp_path: Path,
) -> None:
    """map_server computes 1 - v / 255: level 204 is free under free_thresh 0.2."""
    assert 1.0 - 204 / 255 < 0.2 <= (255 - 204) / 255
    text = GOOD_YAML.replace("0.196", "0.2")
    grid = read_map(make_map_files(tmp_path, text, b"P5 2 1 255 \xcc\xc8"))
    assert grid.free().tolist() == [[True, False]]
    assert grid.unknown().tolist() == [[False, True]]
    # Writing: a cell just outside the free band must not become level 204.
    cells = OccupancyGrid.from_probabilities(
        [[0.2, 0.0]], resolution=0.5, occupied_thresh=0.65, free_thresh=0.2
    )
    assert cells.unknown().tolist() == [[True, False]]
    write_map(cells, tmp_path / "w.yaml", mode="scale")
    image, alpha = read_image(tmp_path / "w.png")
    assert alpha is not None and alpha.tolist() == [[255.0, 255.0]]  # p = 0.2 is evidence
    assert 1.0 - image[0, 0] / 255 >= 0.2
    assert read_map(tmp_path / "w.yaml").unknown().tolist() == [[True, False]]


def test_trinary_save_keeps_free_cells_under_a_tiny_free_thresh(tmp_path: Path) -> None:
    """map_saver's free 254 reads as p = 1/255; below that free_thresh, write 255."""
    grid = OccupancyGrid.from_probabilities(
        [[0.0, 1.0, 0.5]], resolution=0.5, occupied_thresh=0.65, free_thresh=0.002
    )
    write_map(grid, tmp_path / "m.yaml", mode="trinary")
    again = read_map(tmp_path / "m.yaml")
    assert again.free().tolist() == grid.free().tolist() == [[True, False, False]]
    assert again.unknown().tolist() == grid.unknown().tolist()
    write_map(OccupancyGrid.from_occupancy([[False]], resolution=0.5), tmp_path / "m.yaml")
    assert read_pgm(tmp_path / "m.pgm").tolist() == [[254.0]]  # map_saver's free grey kept


@pytest.mark.parametrize("key", ["image", "resolution", "negate", "mode"])
def test_duplicate_map_keys_are_refused(tmp_path: Path, key: str) -> None:
    """yaml-cpp (map_server) keeps a duplicate's first value, PyYAML its last: refuse it."""
    first = {
        "image": "m.pgm",
        "resolution": "0.5",
        "negate": "0",
        "mode": "trinary",
    }[key]
    text = GOOD_YAML + ("mode: trinary\n" if key == "mode" else "") + f"{key}: {first}\n"
    with pytest.raises(ValueError, match=rf"m.yaml:\d+: .*duplicate key '{key}'"):
        read_map(make_map_files(tmp_path, text, b"P5 1 1 255 \x00"))
    # Duplicates of keys map_server ignores are ignored too; so are YAML merges.
    ok = GOOD_YAML + "note: a\nnote: b\n"
    assert read_map(make_map_files(tmp_path, ok, b"P5 1 1 255 \x00")).shape == (1, 1)


# ------------------------------- scale maps: PNG with alpha, as Nav2's map_saver writes


def nav2_scale_load(
    grey: np.ndarray, alpha: np.ndarray | None, occupied_thresh: float, free_thresh: float,
    *, inclusive: bool,
) -> np.ndarray:
    """Nav2 map_io.cpp's loadMapFromFile in scale mode (negate 0), vectorised.

    ``inclusive``: the thresholds as the Eigen version (2025) compares them
    (``>=``, ``<=``); else as the earlier per-pixel loop (``>``, ``<``).
    """
    occ = 1.0 - grey / 255.0
    if inclusive:
        occupied, free = occ >= occupied_thresh, occ <= free_thresh
    else:
        occupied, free = occ > occupied_thresh, occ < free_thresh
    scaled = np.rint((occ - free_thresh) / (occupied_thresh - free_thresh) * 100.0)
    cells = np.where(occupied, 100, np.where(free, 0, scaled)).astype(np.int64)
    if alpha is not None:
        cells[alpha < 255] = -1  # every pixel that is not fully opaque
    return cells


def scale_test_grid(occupied_thresh: float = 0.65, free_thresh: float = 0.196) -> OccupancyGrid:
    """Occupied, free, never observed (log-odds 0) and in-between cells, plus random ones."""
    rng = np.random.default_rng(5)
    p = np.concatenate([[0.999, 0.001, 0.5, 0.3, 0.6, 0.2, 0.64, 0.197], rng.random(32)])
    logodds = np.log(p / (1.0 - p)).reshape(5, 8)
    logodds[1, ::3] = 0.0  # more never observed cells
    return OccupancyGrid(
        logodds, resolution=0.05, origin=Pose2D(-1.0, 2.0, 0.4),
        occupied_thresh=occupied_thresh, free_thresh=free_thresh,
    )  # fmt: skip


def test_scale_maps_are_written_as_png_with_alpha_and_read_by_nav2_as_meant(
    tmp_path: Path,
) -> None:
    # A scale map used to be a PGM: its unknown cells were mid greys, which
    # map_server reads as in-between occupancy values, never as unknown (-1).
    from PIL import Image

    grid = scale_test_grid()
    image = write_map(grid, tmp_path / "m.yaml", mode="scale")
    assert image == tmp_path / "m.png"
    assert pyyaml.safe_load((tmp_path / "m.yaml").read_text())["image"] == "m.png"
    with Image.open(image) as png:  # decoded by Pillow, not by navkit
        assert png.mode == "RGBA"
        rgba = np.asarray(png).astype(np.float64)
    assert np.array_equal(rgba[..., 0], rgba[..., 1])
    assert np.array_equal(rgba[..., 0], rgba[..., 2])
    grey, alpha = rgba[::-1, :, 0], rgba[::-1, :, 3]  # grid row order
    never_observed = grid.logodds == 0.0
    occ_t, free_t = grid.occupied_thresh, grid.free_thresh
    for inclusive in (False, True):
        nav2 = nav2_scale_load(grey, alpha, occ_t, free_t, inclusive=inclusive)
        assert np.array_equal(nav2 == -1, never_observed)
        assert np.all(nav2[grid.occupied()] == 100) and np.all(nav2[grid.free()] == 0)
        # The other cells are values (ones next to a threshold may round to 0 or 100).
        between = grid.unknown() & ~never_observed
        assert between.sum() >= 5
        expected = 100.0 * (grid.probability() - free_t) / (occ_t - free_t)
        assert np.all(np.abs(nav2[between] - expected[between]) <= 1.0)
    # Write then read back: the same classes, the unknown cells' log-odds exactly and
    # the in-between probabilities to half a grey level (occupied and free cells come
    # back certain, as map_server's 100 and 0).
    back = read_map(tmp_path / "m.yaml")
    assert (back.resolution, back.origin) == (grid.resolution, grid.origin)
    for view in ("occupied", "free", "unknown"):
        assert np.array_equal(getattr(back, view)(), getattr(grid, view)()), view
    assert np.array_equal(back.logodds == 0.0, never_observed)
    between = grid.unknown()
    np.testing.assert_allclose(
        back.probability()[between], grid.probability()[between], atol=0.5 / 255 + 1e-12
    )
    # Saving what was read gives the same map again.
    write_map(back, tmp_path / "again.yaml", mode="scale")
    assert np.array_equal(read_map(tmp_path / "again.yaml").logodds, back.logodds)


@pytest.mark.parametrize(("occupied_thresh", "free_thresh"), [(0.45, 0.2), (0.9, 0.6)])
def test_scale_maps_keep_unknown_cells_with_off_centre_thresholds(
    tmp_path: Path, occupied_thresh: float, free_thresh: float
) -> None:
    # Thresholds that class p = 0.5 as known: read_map stores unknown pixels at the
    # middle of the band; a scale save must write those cells transparent again.
    yaml = GOOD_YAML.replace("0.65", str(occupied_thresh)).replace("0.196", str(free_thresh))
    grey = round(255 * (1 - 0.5 * (occupied_thresh + free_thresh)))
    grid = read_map(make_map_files(tmp_path, yaml, b"P5 3 1 255\n" + bytes([0, grey, 254])))
    assert grid.unknown().tolist() == [[False, True, False]]
    write_map(grid, tmp_path / "s.yaml", mode="scale")
    rgba, alpha = read_image(tmp_path / "s.png")
    assert alpha is not None and alpha.tolist() == [[255.0, 0.0, 255.0]]
    nav2 = nav2_scale_load(rgba, alpha, occupied_thresh, free_thresh, inclusive=False)
    assert nav2.tolist() == [[100, -1, 0]]
    back = read_map(tmp_path / "s.yaml")
    assert np.array_equal(back.logodds, grid.logodds)


def test_a_scale_map_yaml_may_not_take_its_png_image_name(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"ends in \.png, the image's own name"):
        write_map(scale_test_grid(), tmp_path / "m.png", mode="scale")
    assert list(tmp_path.iterdir()) == []


def test_png_bytes_decode_to_the_pixels(tmp_path: Path) -> None:
    from PIL import Image

    from navkit.mapping.io import _map_files

    rng = np.random.default_rng(2)
    rgba = rng.integers(0, 256, (37, 53, 4), dtype=np.uint8)
    for pixels in (rgba, rgba[:1, :1]):
        (tmp_path / "x.png").write_bytes(_map_files.png_bytes(pixels))
        with Image.open(tmp_path / "x.png") as png:
            png.load()
            assert png.mode == "RGBA"
            assert np.array_equal(np.asarray(png), pixels)
    with pytest.raises(ValueError, match="pixels must have shape"):
        _map_files.png_bytes(rgba[..., 0])


def test_a_scale_map_without_pillow_names_it_and_writes_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(sys.modules, "PIL", None)
    with pytest.raises(ImportError, match=r"scale-mode map image .*needs Pillow"):
        write_map(scale_test_grid(), tmp_path / "m.yaml", mode="scale")
    assert list(tmp_path.iterdir()) == []
    write_map(scale_test_grid(), tmp_path / "m.yaml")  # trinary: a PGM, no Pillow needed
