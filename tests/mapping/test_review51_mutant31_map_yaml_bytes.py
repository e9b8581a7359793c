"""Review 51 (MUTANT31): read_map's reading of YAML bytes that are not UTF-8, at its edges.

PORTFILES' 3b24558 reads a map YAML with Latin-1 bytes as map_server's
yaml-cpp does (skipped in comments, looked up as written in the image name,
refused naming the byte elsewhere), through ``surrogateescape`` and private-use
stand-ins. Mutants of it which every test passed, each killed here:

* the stand-in tables and patterns ending at byte 0xfe instead of 0xff (``ÿ``
  in a comment, in an image name, in a number, in a missing image's name);
* a UTF-32 (or UTF-16) file whose code units are not Unicode read with the
  ``surrogateescape`` meant for UTF-8 bytes, instead of refused;
* no refusal of a file that holds both a private-use character of the
  stand-ins' range and bytes that are not UTF-8: the character then read as
  a byte, and the image looked up was another file;
* the save in the other mode over a Latin-1-commented map reading the old
  YAML as UTF-8 only: the image of the other mode it replaces was left behind;
* a YAML of exactly the size limit (1 MiB) read with ``<`` for ``<=``;
* the missing image's hint (2d9f061) taking the image's own entry, a dangling
  symbolic link, for another spelling of the name;
* the refused value's byte (FRESH's ba737f3) looked for from a value's start
  to the end of the file: a Latin-1 comment after a clean value and before the
  refused one was named.
"""

from __future__ import annotations

import codecs
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_map, write_map
from navkit.mapping.io._map_files import YAML_MAX_BYTES

_MAP = Path("ros-map-server-maps") / "turtlebot3_world"


def _copy(shared_data: Path, tmp_path: Path) -> bytes:
    shutil.copy(shared_data / _MAP / "map.pgm", tmp_path / "map.pgm")
    return (shared_data / _MAP / "map.yaml").read_bytes()


def _same_map(path: Path, shared_data: Path) -> None:
    ref = read_map(shared_data / _MAP / "map.yaml")
    got = read_map(path)
    assert (got.origin, got.resolution) == (ref.origin, ref.resolution)
    assert np.array_equal(got.occupied(), ref.occupied())
    assert np.array_equal(got.free(), ref.free())


def _rename(tmp_path: Path, name: bytes) -> None:
    try:
        (tmp_path / "map.pgm").rename(tmp_path / os.fsdecode(name))
    except (OSError, UnicodeError):
        pytest.skip("the file system takes no file name that is not UTF-8")


def test_a_latin1_y_umlaut_comment_and_image_name_read(shared_data: Path, tmp_path: Path) -> None:
    # 0xff, the last byte: 'ÿ' in Latin-1 (and Windows-1252).
    text = _copy(shared_data, tmp_path)
    name = b"pl\xffe.pgm"
    _rename(tmp_path, name)
    edited = b"# Ha\xff\n" + text.replace(b"map.pgm", name)
    (tmp_path / "map.yaml").write_bytes(edited)
    _same_map(tmp_path / "map.yaml", shared_data)


def test_a_missing_image_named_with_byte_ff_is_named_printably(
    shared_data: Path, tmp_path: Path
) -> None:
    text = _copy(shared_data, tmp_path)
    (tmp_path / "map.yaml").write_bytes(text.replace(b"map.pgm", b"pl\xffe.pgm"))
    with pytest.raises(FileNotFoundError) as info:
        read_map(tmp_path / "map.yaml")
    message = str(info.value)
    message.encode("utf-8")  # no lone surrogate: it can be printed and logged
    assert "not UTF-8" in message and "'plÿe.pgm'" in message


def test_byte_ff_in_a_number_stays_refused_naming_it(shared_data: Path, tmp_path: Path) -> None:
    text = _copy(shared_data, tmp_path)
    edited = text.replace(b"resolution: 0.050000", b"resolution: 0.05\xff")
    offset = edited.index(b"\xff")
    (tmp_path / "map.yaml").write_bytes(edited)
    with pytest.raises(
        ValueError, match=rf"not a map YAML: not UTF-8 text \(byte 0xff at offset {offset}\)"
    ):
        read_map(tmp_path / "map.yaml")


@pytest.mark.parametrize("encoding", ["utf-32-le", "utf-32-be", "utf-16-le"])
def test_utf16_and_utf32_with_code_units_not_unicode_stay_refused(
    shared_data: Path, tmp_path: Path, encoding: str
) -> None:
    text = _copy(shared_data, tmp_path).decode("ascii")
    bom = {"utf-32-le": codecs.BOM_UTF32_LE, "utf-32-be": codecs.BOM_UTF32_BE,
           "utf-16-le": codecs.BOM_UTF16_LE}[encoding]  # fmt: skip
    # A comment line whose one code unit is no character: 0xffffffff in UTF-32,
    # a lone low surrogate 0xdcff in UTF-16.
    bad = b"\xff\xff\xff\xff" if encoding.startswith("utf-32") else b"\xff\xdc"
    comment = "# ".encode(encoding) + bad + "\n".encode(encoding)
    (tmp_path / "map.yaml").write_bytes(bom + comment + text.encode(encoding))
    what = encoding[:6].upper()
    with pytest.raises(ValueError, match=rf"map\.yaml: not a map YAML: not {what} text \(byte"):
        read_map(tmp_path / "map.yaml")


def test_a_private_use_name_beside_latin1_bytes_is_not_read_as_a_byte(
    shared_data: Path, tmp_path: Path
) -> None:
    # U+F7E9 is the stand-in for byte 0xe9 ('é'): a name holding it, in a file
    # with a Latin-1 comment, must not be looked up as the byte 0xe9.
    text = _copy(shared_data, tmp_path)
    name = "carte_\uf7e9.pgm"
    (tmp_path / "map.pgm").rename(tmp_path / name)
    decoy = np.full((4, 5), 254, dtype=np.uint8)  # all free: not the map
    header = b"P5\n5 4\n255\n"
    try:
        (tmp_path / os.fsdecode(b"carte_\xe9.pgm")).write_bytes(header + decoy.tobytes())
    except (OSError, UnicodeError):
        pytest.skip("the file system takes no file name that is not UTF-8")
    edited = b"# B\xfcro\n" + text.replace(b"map.pgm", name.encode("utf-8"))
    (tmp_path / "map.yaml").write_bytes(edited)
    try:
        grid = read_map(tmp_path / "map.yaml")
    except ValueError as exc:
        # Refused naming the first byte that is not UTF-8 (the comment's 0xfc).
        assert "not UTF-8 text (byte 0xfc at offset 3)" in str(exc)
    else:
        _same_map(tmp_path / "map.yaml", shared_data)
        assert grid.shape != (4, 5)


def test_a_save_in_the_other_mode_over_a_latin1_commented_map_removes_its_image(
    shared_data: Path, tmp_path: Path
) -> None:
    text = _copy(shared_data, tmp_path)
    (tmp_path / "map.yaml").write_bytes(b"# Karte B\xfcro\n" + text)
    grid = read_map(tmp_path / "map.yaml")
    write_map(grid, tmp_path / "map.yaml", mode="scale")
    # The PNG replaces the PGM the old YAML named, as for a UTF-8 YAML.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.png", "map.yaml"]
    again = read_map(tmp_path / "map.yaml")
    assert np.array_equal(again.occupied(), grid.occupied())


def test_a_yaml_of_exactly_the_size_limit_reads(shared_data: Path, tmp_path: Path) -> None:
    text = _copy(shared_data, tmp_path)
    pad = YAML_MAX_BYTES - len(text) - 2
    (tmp_path / "map.yaml").write_bytes(text + b"#" + b"x" * pad + b"\n")
    assert (tmp_path / "map.yaml").stat().st_size == YAML_MAX_BYTES
    _same_map(tmp_path / "map.yaml", shared_data)
    (tmp_path / "map.yaml").write_bytes(text + b"#" + b"x" * (pad + 1) + b"\n")
    with pytest.raises(ValueError, match="too large for a map YAML"):
        read_map(tmp_path / "map.yaml")


def test_a_dangling_link_of_the_image_name_is_no_other_spelling(
    shared_data: Path, tmp_path: Path
) -> None:
    _copy(shared_data, tmp_path)
    (tmp_path / "map.pgm").unlink()
    try:
        (tmp_path / "map.pgm").symlink_to(tmp_path / "gone.pgm")
    except OSError:
        pytest.skip("no symbolic links here")
    shutil.copy(shared_data / _MAP / "map.yaml", tmp_path / "map.yaml")
    with pytest.raises(FileNotFoundError) as info:
        read_map(tmp_path / "map.yaml")
    # No hint: the folder holds no other spelling of the name.
    assert str(info.value).endswith("map.pgm does not exist"), str(info.value)


def test_a_comment_between_a_clean_value_and_a_refused_one_is_not_named(
    shared_data: Path, tmp_path: Path
) -> None:
    text = _copy(shared_data, tmp_path)
    assert text.index(b"resolution:") < text.index(b"negate: 0")
    edited = text.replace(b"negate: 0", b"# B\xfcro\nnegate: 0\xa0")
    offset = edited.index(b"\xa0")
    (tmp_path / "map.yaml").write_bytes(edited)
    with pytest.raises(
        ValueError, match=rf"not a map YAML: not UTF-8 text \(byte 0xa0 at offset {offset}\)"
    ):
        read_map(tmp_path / "map.yaml")
