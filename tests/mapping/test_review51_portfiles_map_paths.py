"""Review 51 (PORTFILES): where a map YAML's relative ``image`` is looked for, pinned.

map_server (ROS 1: ``dirname`` of the YAML path given; Nav2: its
``parent_path``) looks beside the YAML path as given: never in the working
directory, and beside a symbolic link to the YAML (a colcon
``--symlink-install`` share folder), not beside its target. Decoys with the
same name elsewhere tell the folders apart.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_map

_MAP = Path("ros-map-server-maps") / "turtlebot3_world"


def _decoy(path: Path) -> None:
    """A PGM of the real map's size, every pixel black (occupied)."""
    path.write_bytes(b"P5\n384 384\n255\n" + bytes(384 * 384))


def _site(shared_data: Path, folder: Path, image: str = "map.pgm") -> Path:
    (folder / image).parent.mkdir(parents=True, exist_ok=True)
    shutil.copy(shared_data / _MAP / "map.pgm", folder / image)
    text = (shared_data / _MAP / "map.yaml").read_text(encoding="utf-8")
    (folder / "map.yaml").write_text(text.replace("map.pgm", image), encoding="utf-8")
    return folder / "map.yaml"


@pytest.mark.parametrize("image", ["map.pgm", "images/map.pgm", "./images/../map.pgm"])
def test_a_relative_image_is_found_beside_the_yaml_not_in_the_working_directory(
    shared_data: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, image: str
) -> None:
    _site(shared_data, tmp_path / "site", image)
    _decoy(tmp_path / "map.pgm")
    (tmp_path / "images").mkdir()
    _decoy(tmp_path / "images" / "map.pgm")
    monkeypatch.chdir(tmp_path)
    ref = read_map(shared_data / _MAP / "map.yaml")
    got = read_map(Path("site") / "map.yaml")
    assert np.array_equal(got.occupied(), ref.occupied())
    assert got.unknown().sum() == ref.unknown().sum() > 0


def test_beside_a_symbolic_link_to_the_yaml_as_map_server_looks(
    shared_data: Path, tmp_path: Path
) -> None:
    target = _site(shared_data, tmp_path / "src")
    share = tmp_path / "share"
    share.mkdir()
    try:
        (share / "map.yaml").symlink_to(target)
    except (OSError, NotImplementedError):
        pytest.skip("no symbolic links here")
    with pytest.raises(FileNotFoundError, match=r"share/map\.yaml: map image .*share/map\.pgm"):
        read_map(share / "map.yaml")
    _decoy(share / "map.pgm")
    assert read_map(share / "map.yaml").occupied().all()
    (share / "map.pgm").unlink()
    (share / "map.pgm").symlink_to(target.parent / "map.pgm")  # --symlink-install links both
    ref = read_map(shared_data / _MAP / "map.yaml")
    assert np.array_equal(read_map(share / "map.yaml").occupied(), ref.occupied())
