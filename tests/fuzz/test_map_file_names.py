"""Map files written by write_map round-trip through read_map, whatever their name (issue 12).

A save either writes both files and reading them gives the same map back, or
refuses up front with a ValueError and writes nothing. Other files in the
folder are never touched.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map

FIXED = settings(
    database=None, derandomize=True, deadline=None, suppress_health_check=list(HealthCheck)
)

AWKWARD = [
    "my map #2.yaml",
    "[map].yaml",
    "{map}.yaml",
    "a:b.yaml",
    "a: b.yaml",
    "quote'd.yaml",
    'double"quote.yaml',
    "`tick`.yaml",
    "ünïcødé 地図.yaml",
    "emoji 🗺.yaml",
    "sp ace.yaml",
    " leading space.yaml",
    "trailing space .yaml",
    "tab\tname.yaml",
    "new\nline.yaml",
    "back\\slash.yaml",
    "&*!%.yaml",
    "@at.yaml",
    "|pipe.yaml",
    ">gt.yaml",
    "? question.yaml",
    "- dash.yaml",
    "-leading-dash.yaml",
    "a,b.yaml",
    "yes.yaml",
    "null.yaml",
    "~.yaml",
    "1e5.yaml",
    "0x10.yaml",
    ".hidden.yaml",
    "map.YAML",
    "map.yml",
    "no_suffix",
    "map.pgm.yaml",
    "..yaml",
    "%25percent.yaml",
]


def _grid() -> OccupancyGrid:
    occupied = np.zeros((4, 5), dtype=bool)
    occupied[1, 1:4] = True
    unknown = np.zeros((4, 5), dtype=bool)
    unknown[3, :2] = True
    return OccupancyGrid.from_occupancy(
        occupied, resolution=0.05, origin=Pose2D(-1.25, 2.5, 0.3), unknown=unknown
    )


def _files(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}


def _assert_same_map(a: OccupancyGrid, b: OccupancyGrid) -> None:
    assert b.shape == a.shape
    assert np.array_equal(b.occupied(), a.occupied())
    assert np.array_equal(b.free(), a.free())
    assert np.array_equal(b.unknown(), a.unknown())
    assert b.resolution == a.resolution
    assert (b.origin.x, b.origin.y, b.origin.theta) == (a.origin.x, a.origin.y, a.origin.theta)


def _round_trip(folder: Path, name: str, grid: OccupancyGrid, *, via_methods: bool = False) -> None:
    """Save under ``name``: it reads back identically, or is refused with nothing written."""
    bystander = folder / "someone else's.pgm"
    bystander.write_bytes(b"P5\n1 1\n255\n\x00")
    before = _files(folder)
    path = folder / name
    try:
        if via_methods:
            grid.save(path)
        else:
            write_map(grid, path)
    except ValueError:
        assert _files(folder) == before, f"a refused save of {name!r} wrote files"
        return
    except OSError as exc:  # the file system itself refuses the name
        pytest.skip(f"the file system refuses {name!r}: {exc}")
    after = _files(folder)
    assert bystander.read_bytes() == b"P5\n1 1\n255\n\x00"
    assert set(after) - set(before), f"saving {name!r} wrote nothing"
    again = OccupancyGrid.load(path) if via_methods else read_map(path)
    _assert_same_map(grid, again)
    # Saving again over the same map replaces it cleanly.
    write_map(grid, path)
    _assert_same_map(grid, read_map(path))


@pytest.mark.parametrize("name", AWKWARD)
def test_awkward_names_round_trip_or_are_refused(name: str, tmp_path: Path) -> None:
    _round_trip(tmp_path, name, _grid())


@pytest.mark.parametrize("name", ["my map #2.yaml", "[map].yaml", "ünïcødé 地図.yaml"])
def test_save_and_load_round_trip_awkward_names(name: str, tmp_path: Path) -> None:
    _round_trip(tmp_path, name, _grid(), via_methods=True)


# Any printable name a file system allows: no "/" and no NUL, at most 100 characters.
NAMES = st.text(
    st.characters(blacklist_categories=("Cs",), blacklist_characters="/\x00"),
    min_size=1,
    max_size=100,
).filter(lambda n: n not in (".", "..") and len(n.encode("utf-8", "surrogatepass")) <= 200)


@settings(FIXED, max_examples=40)
@given(name=NAMES, suffix=st.sampled_from([".yaml", ".yml", "", ".YAML"]))
def test_generated_names_round_trip_or_are_refused(name: str, suffix: str) -> None:
    with tempfile.TemporaryDirectory() as folder:
        _round_trip(Path(folder), name + suffix, _grid())


test_generated_names_round_trip_or_are_refused_thoroughly = slow_twin(
    test_generated_names_round_trip_or_are_refused, max_examples=100
)


@settings(FIXED, max_examples=40)
@given(
    cells=st.lists(st.sampled_from([0, 1, 2]), min_size=6, max_size=6),
    resolution=st.floats(1e-3, 10.0),
    x=st.floats(-1e6, 1e6),
    y=st.floats(-1e6, 1e6),
    theta=st.floats(-3.14, 3.14),
)
def test_map_metadata_round_trips_exactly(
    cells: list[int], resolution: float, x: float, y: float, theta: float
) -> None:
    states = np.array(cells).reshape(2, 3)
    grid = OccupancyGrid.from_occupancy(
        states == 1, resolution=resolution, origin=Pose2D(x, y, theta), unknown=states == 2
    )
    with tempfile.TemporaryDirectory() as folder:
        write_map(grid, Path(folder) / "m.yaml")
        _assert_same_map(grid, read_map(Path(folder) / "m.yaml"))


test_map_metadata_round_trips_exactly_thoroughly = slow_twin(
    test_map_metadata_round_trips_exactly, max_examples=100
)


def test_a_save_never_writes_over_another_maps_image(tmp_path: Path) -> None:
    grid = _grid()
    user_image = tmp_path / "map.pgm"
    user_image.write_bytes(b"P5\n1 1\n255\n\x7f")
    with pytest.raises(ValueError):
        write_map(grid, tmp_path / "map.yaml")  # map.pgm is not this map's image
    assert user_image.read_bytes() == b"P5\n1 1\n255\n\x7f"
    assert not (tmp_path / "map.yaml").exists()
    for name in ("map.pgm", "MAP.PGM", "photo.png"):
        with pytest.raises(ValueError):
            write_map(grid, tmp_path / name)
    assert sorted(os.listdir(tmp_path)) == ["map.pgm"]
