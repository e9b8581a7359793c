"""read_map's messages print and log when the map's folder is not UTF-8 (review 53, FRESH).

3d7803a made read_map's errors about a Latin-1 image *name* show its bytes
escaped, so that ``str(exc).encode("utf-8")`` (a strict UTF-8 log handler)
works. A YAML in a folder whose name is Latin-1 bytes (a path from
``os.listdir`` or ``sys.argv`` on Linux, surrogate escapes in a str) still gave
messages holding the surrogates: a missing YAML, a missing key, a refused
negate, a missing image beside it; only "is a directory" escaped them.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from navkit.mapping.io import read_map

pytestmark = pytest.mark.skipif(
    sys.platform == "win32" or sys.getfilesystemencoding().lower() != "utf-8",
    reason="a folder name of Latin-1 bytes as a POSIX file system with UTF-8 names holds it",
)

_TAIL = "resolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
_YAMLS = {
    "missing_image.yaml": "image: gone.pgm\nnegate: 0\n" + _TAIL,
    "missing_keys.yaml": "resolution: 0.05\norigin: [0, 0, 0]\n",
    "negate.yaml": "image: m.pgm\nnegate: 2\n" + _TAIL,
    "image_is_a_directory.yaml": "image: .\nnegate: 0\n" + _TAIL,
}


def _folder(tmp_path: Path) -> bytes:
    folder = os.fsencode(tmp_path) + b"/Karte B\xfcro"  # Latin-1 ü: not UTF-8
    try:
        os.mkdir(folder)
    except OSError as error:  # a file system that refuses such names
        pytest.skip(f"cannot make a folder of Latin-1 bytes: {error}")
    for name, text in _YAMLS.items():
        with open(folder + b"/" + name.encode(), "w", encoding="utf-8") as file:
            file.write(text)
    return folder


def _message(path: bytes) -> str:
    with pytest.raises((ValueError, OSError)) as info:
        read_map(os.fsdecode(path))
    return str(info.value)


def test_is_a_directory_names_the_folder_escaped(tmp_path: Path) -> None:
    message = _message(_folder(tmp_path) + b"/image_is_a_directory.yaml")
    assert "Karte B\\udcfcro" in message
    message.encode("utf-8")


@pytest.mark.parametrize(
    "name", ["missing.yaml", "missing_image.yaml", "missing_keys.yaml", "negate.yaml"]
)
def test_every_message_naming_the_folder_can_be_logged_as_utf8(tmp_path: Path, name: str) -> None:
    message = _message(_folder(tmp_path) + b"/" + name.encode())
    message.encode("utf-8")  # a strict UTF-8 log handler
    assert "Karte B\\udcfcro" in message  # the bytes, escaped as 3d7803a shows them
