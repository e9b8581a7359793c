"""read_map's errors naming a Latin-1 image name print and log (review 52, FRESH).

A map YAML saved in Latin-1 names its image with bytes that are not UTF-8,
which read_map keeps as surrogate escapes (to look the file up as written).
The "does not exist" error showed them escaped (review 46), but "is a
directory" and the errors of reading the image (a truncated PGM, a file
Pillow cannot identify) kept the surrogates: ``str(exc).encode("utf-8")``
raised UnicodeEncodeError, and a strict UTF-8 log handler printed
"--- Logging error ---" instead of the message.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from navkit.mapping.io import read_map

_META = (
    b"resolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
    b"occupied_thresh: 0.65\nfree_thresh: 0.196\n"
)


def _latin1_target(tmp_path: Path, name: bytes, make: str) -> Path:
    target = os.path.join(os.fsencode(tmp_path), name)
    try:
        if make == "directory":
            os.mkdir(target)
        else:
            with open(target, "wb") as fh:
                fh.write(b"P5 2 2 255\n\x00" if make == "truncated" else b"not an image at all")
    except (OSError, UnicodeError):
        pytest.skip("this file system refuses names that are not UTF-8")
    yaml_path = tmp_path / "map.yaml"
    yaml_path.write_bytes(b"image: " + name + b"\n" + _META)
    return yaml_path


@pytest.mark.parametrize(
    ("name", "make", "words"),
    [
        (b"dir\xfc", "directory", "is a directory"),
        (b"bad\xfc.pgm", "truncated", "truncated"),
        (b"odd\xfc.png", "junk", "map image"),
    ],
)
def test_the_error_names_the_image_printably(
    tmp_path: Path, name: bytes, make: str, words: str
) -> None:
    yaml_path = _latin1_target(tmp_path, name, make)
    with pytest.raises(ValueError, match=words) as info:
        read_map(yaml_path)
    message = str(info.value)
    message.encode("utf-8")  # printable and loggable: no surrogates left
    assert "\\udcfc" in message  # the byte shown, as the missing-image error shows it
