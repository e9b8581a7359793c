"""A target that is a loop of symbolic links is refused before anything is written (review 44).

``atomic_paths`` gave the temporary file the target's mode with ``os.stat``,
which follows links: for ``a.json -> b.json -> a.json`` it raised ``OSError``
(``ELOOP``) after the block, once the temporary file was written (and removed),
where the command line (review 43) refuses such an output before its run. It
is now refused up front, as the system's own writers refuse it, with a
``ValueError`` naming the file; a folder that is such a loop is named too (it
was reported under the temporary file's name; since review 45 as a missing
folder, see ``test_review45_folder_loops.py``). A link that ends in a file or
in nothing is still replaced itself.
"""

from __future__ import annotations

import errno
import os
import stat
import sys
from pathlib import Path

import pytest

from navkit._shared.files import atomic_path, atomic_paths, link_loop

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")


def _tree(folder: Path) -> dict[str, str]:
    """Each entry of ``folder``: where its link points, or its text."""
    return {
        p.name: f"-> {os.readlink(p)}" if p.is_symlink() else p.read_text()
        for p in folder.iterdir()
    }


def _loops(folder: Path) -> list[Path]:
    """A link to itself, and two links to each other."""
    (folder / "self.json").symlink_to("self.json")
    (folder / "a.json").symlink_to("b.json")
    (folder / "b.json").symlink_to("a.json")
    return [folder / "self.json", folder / "a.json"]


def test_link_loop_tells_a_loop_from_a_missing_file(tmp_path: Path) -> None:
    loops = _loops(tmp_path)
    (tmp_path / "dangling.json").symlink_to("missing.json")
    (tmp_path / "real.json").write_text("{}")
    (tmp_path / "to_real.json").symlink_to("real.json")
    assert [link_loop(p) for p in loops] == [True, True]
    assert [p.exists() for p in loops] == [False, False]  # why exists() cannot tell
    for name in ("dangling.json", "missing.json", "real.json", "to_real.json"):
        assert not link_loop(tmp_path / name)
    assert link_loop(tmp_path / "a.json" / "x.json")  # a folder in the path that loops


def test_a_loop_is_refused_before_the_block_runs(tmp_path: Path) -> None:
    for target in _loops(tmp_path):
        before = _tree(tmp_path)
        ran = []
        with (
            pytest.raises(ValueError, match=rf"^{target} is a loop of symbolic links"),
            atomic_path(target) as temporary,
        ):
            ran.append(temporary)
        assert ran == []
        assert _tree(tmp_path) == before


def test_a_loop_among_targets_leaves_every_target_as_it_was(tmp_path: Path) -> None:
    first = tmp_path / "first.json"
    first.write_text("old")
    (loop,) = _loops(tmp_path)[1:]
    before = _tree(tmp_path)
    with (
        pytest.raises(ValueError, match="loop of symbolic links"),
        atomic_paths([first, loop]) as temporaries,
    ):
        for temporary in temporaries:
            temporary.write_text("new")
    assert _tree(tmp_path) == before


def test_a_loop_made_during_the_block_is_refused_before_the_renames(tmp_path: Path) -> None:
    # Before: OSError (ELOOP) from the mode's os.stat, not the refusal.
    first, second = tmp_path / "first.json", tmp_path / "second.json"
    first.write_text("old")
    with (
        pytest.raises(ValueError, match=rf"^{second} is a loop of symbolic links"),
        atomic_paths([first, second]) as (t1, t2),
    ):
        t1.write_text("new")
        t2.write_text("new")
        second.symlink_to(second.name)
    assert _tree(tmp_path) == {"first.json": "old", "second.json": "-> second.json"}


def test_a_folder_that_is_a_loop_is_named(tmp_path: Path) -> None:
    # Before: OSError (ELOOP) naming ".x.<random>.tmp.json", a name the caller never gave.
    # Review 45: a missing folder's FileNotFoundError, as every writer gives it.
    (tmp_path / "d").symlink_to("d")
    before = _tree(tmp_path)
    with pytest.raises(FileNotFoundError) as caught, atomic_path(tmp_path / "d" / "x.json"):
        pass
    assert caught.value.errno == errno.ENOENT
    assert caught.value.strerror == f"no such folder ({tmp_path / 'd'} is a loop of symbolic links)"
    assert caught.value.filename == str(tmp_path / "d")
    assert _tree(tmp_path) == before


def test_a_dangling_link_is_still_replaced_by_a_new_file(tmp_path: Path) -> None:
    link = tmp_path / "out.json"
    link.symlink_to("missing.json")
    old = os.umask(0o022)
    try:
        with atomic_path(link) as temporary:
            temporary.write_text("new")
    finally:
        os.umask(old)
    assert _tree(tmp_path) == {"out.json": "new"}
    assert stat.S_IMODE(link.lstat().st_mode) == 0o644
