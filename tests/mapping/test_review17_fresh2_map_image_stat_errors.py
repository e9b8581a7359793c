"""read_map_yaml's one ``stat`` of the image reads its errors as ``Path.exists`` did.

Session 21 replaced ``Path.exists`` / ``Path.is_file`` by one ``stat``, reading as
"does not exist" the errno values ``Path.exists`` ignores. ``Path.exists`` also
ignores three Windows error codes (``winerror`` 21, 123 and 1921: a drive not
ready, an invalid name such as ``map?.pgm``, a name that cannot be resolved),
whose ``errno`` is another (``EINVAL`` for 123): those must still read as a
missing image (``FileNotFoundError`` naming the YAML), not escape as a bare
``OSError``. Windows' errors are simulated (an ``OSError`` carrying a
``winerror``, as Windows raises it); other errors still propagate as they did.
"""

from __future__ import annotations

import errno
import os
import pathlib
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import _map_files, write_map

GRID = OccupancyGrid.from_occupancy(np.eye(4, 6, dtype=bool), resolution=0.5)


class _WindowsError(OSError):
    """An ``OSError`` as Windows raises it: with its ``winerror`` code."""

    def __init__(self, code: int, winerror: int) -> None:
        super().__init__(code, os.strerror(code))
        self.winerror = winerror


def _failing_image_stat(monkeypatch: pytest.MonkeyPatch, image: Path, error: OSError) -> None:
    real_stat = Path.stat

    def stat(self: Path, *args: object, **kwargs: object) -> os.stat_result:
        if self == image:
            raise error
        return real_stat(self, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(Path, "stat", stat)


@pytest.mark.parametrize("winerror", [21, 123, 1921])
def test_the_windows_errors_path_exists_ignores_read_as_a_missing_image(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, winerror: int
) -> None:
    yaml_path = tmp_path / "map.yaml"
    write_map(GRID, yaml_path, mode="trinary")
    image = tmp_path / "map.pgm"
    error = _WindowsError(errno.EINVAL, winerror)
    _failing_image_stat(monkeypatch, image, error)
    # What Path.exists, the check before, makes of it (where pathlib has the list).
    ignored = getattr(pathlib, "_IGNORED_WINERRORS", None)
    if ignored is not None:
        assert winerror in ignored
        assert not image.exists()
    with pytest.raises(FileNotFoundError, match=r"map\.yaml: map image .* does not exist"):
        _map_files.read_map_yaml(yaml_path)


def test_other_errors_still_propagate(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    yaml_path = tmp_path / "map.yaml"
    write_map(GRID, yaml_path, mode="trinary")
    image = tmp_path / "map.pgm"
    for error in (_WindowsError(errno.EACCES, 5), OSError(errno.EACCES, "Permission denied")):
        with monkeypatch.context() as patch:
            _failing_image_stat(patch, image, error)
            with pytest.raises(OSError) as caught:
                _map_files.read_map_yaml(yaml_path)
            assert caught.value is error
    assert _map_files.read_map_yaml(yaml_path).image == image
