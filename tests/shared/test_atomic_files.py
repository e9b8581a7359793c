"""atomic_paths / atomic_path: all targets replaced at once, or none, and nothing left behind."""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

import pytest

from navkit._shared.files import atomic_path, atomic_paths


def names(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


def test_writes_a_new_file_through_a_hidden_temporary_beside_it(tmp_path: Path) -> None:
    target = tmp_path / "out.json"
    umask = os.umask(0o027)
    try:
        with atomic_path(target) as temporary:
            assert temporary.parent == tmp_path and temporary.name.startswith(".out.")
            assert temporary.suffix == ".json" and temporary.read_bytes() == b""
            temporary.write_text("new")
            assert not target.exists()  # nothing is visible before the block ends
    finally:
        os.umask(umask)
    assert names(tmp_path) == ["out.json"] and target.read_text() == "new"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640  # 0o666 less the umask


def test_replaces_an_existing_file_keeping_its_mode_even_read_only(tmp_path: Path) -> None:
    target = tmp_path / "map.pgm"
    target.write_text("old")
    target.chmod(0o444)
    with atomic_path(target) as temporary:
        temporary.write_text("new")
    assert target.read_text() == "new" and names(tmp_path) == ["map.pgm"]
    assert stat.S_IMODE(target.stat().st_mode) == 0o444


@pytest.mark.parametrize("exc", [ValueError("render failed"), KeyboardInterrupt()])
def test_a_failure_in_the_block_leaves_the_old_file_and_no_temporary(
    tmp_path: Path, exc: BaseException
) -> None:
    target = tmp_path / "a.png"
    target.write_text("old")
    with pytest.raises(type(exc)), atomic_path(target) as temporary:
        temporary.write_text("half")
        raise exc
    assert names(tmp_path) == ["a.png"] and target.read_text("utf-8") == "old"


@pytest.mark.parametrize(("name", "call"), [("fsync", 1), ("fsync", 2), ("replace", 1)])
def test_several_files_are_replaced_only_once_all_are_on_disk(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str, call: int
) -> None:
    targets = [tmp_path / "m.pgm", tmp_path / "m.yaml"]
    for t in targets:
        t.write_text("old")
    real = getattr(os, name)
    calls = [0]

    def failing(*args: object) -> object:
        calls[0] += 1
        if calls[0] == call:
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(*args)

    monkeypatch.setattr(os, name, failing)
    with pytest.raises(OSError, match="No space"), atomic_paths(targets) as temporaries:
        for t in temporaries:
            t.write_text("new")
    monkeypatch.undo()
    assert names(tmp_path) == ["m.pgm", "m.yaml"]
    assert [t.read_text() for t in targets] == ["old", "old"]
    with atomic_paths(targets) as temporaries:
        for t in temporaries:
            t.write_text("new")
    assert [t.read_text() for t in targets] == ["new", "new"]


def test_a_folder_or_a_missing_folder_is_never_written(tmp_path: Path) -> None:
    (tmp_path / "x.json").mkdir()
    with pytest.raises(OSError), atomic_path(tmp_path / "x.json") as temporary:
        temporary.write_text("new")
    assert names(tmp_path) == ["x.json"] and (tmp_path / "x.json").is_dir()
    with pytest.raises(FileNotFoundError), atomic_path(tmp_path / "no" / "y.json"):
        pass
    assert names(tmp_path) == ["x.json"]


def test_a_link_is_replaced_not_the_file_it_points_to(tmp_path: Path) -> None:
    other = tmp_path / "other.txt"
    other.write_text("keep")
    link = tmp_path / "link.txt"
    link.symlink_to(other)
    with atomic_path(link) as temporary:
        temporary.write_text("new")
    assert other.read_text() == "keep" and link.read_text() == "new" and not link.is_symlink()


def test_a_pipe_or_device_is_never_renamed_over(tmp_path: Path) -> None:
    # os.replace would put a regular file in place of the pipe (and, as root, of /dev/null).
    pipe = tmp_path / "out.json"
    os.mkfifo(pipe)
    regular = tmp_path / "map.yaml"
    # (The block never runs: on failure it raises before any rename.)
    with (
        pytest.raises(ValueError, match=r"out\.json is not a regular file"),
        atomic_paths([regular, pipe]),
    ):
        raise AssertionError("not reached")  # pragma: no cover
    assert stat.S_ISFIFO(pipe.lstat().st_mode) and names(tmp_path) == ["out.json"]
    with pytest.raises(ValueError, match="not a regular file"), atomic_path(Path(os.devnull)):
        raise AssertionError("not reached")  # pragma: no cover
    assert stat.S_ISCHR(Path(os.devnull).stat().st_mode)


@pytest.mark.parametrize("stem", ["a" * 251, "é" * 125 + "a"])
def test_a_name_at_the_length_limit_is_written(tmp_path: Path, stem: str) -> None:
    # 255 bytes with the suffix: legal, while the temporary name, 14 bytes longer,
    # would not be unless its stem is shortened (keeping the suffix).
    target = tmp_path / f"{stem}.png"
    assert len(os.fsencode(target.name)) <= 255
    with atomic_path(target) as temporary:
        assert temporary.suffix == ".png"
        assert len(os.fsencode(temporary.name)) <= 255
        temporary.write_text("new")
    assert names(tmp_path) == [target.name] and target.read_text() == "new"


def test_a_suffix_filling_the_name_is_dropped_from_the_temporary(tmp_path: Path) -> None:
    target = tmp_path / ("a." + "b" * 253)
    with atomic_path(target) as temporary:
        temporary.write_text("new")
    assert names(tmp_path) == [target.name] and target.read_text() == "new"
