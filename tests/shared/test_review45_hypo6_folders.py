"""check_folder against the system's own answer, on random trees of links (review 45, HYPO6).

test_review45_folder_loops names each case by hand; here hypothesis builds small
trees of folders, files and symbolic links (to each other, to themselves, to
nothing) and targets through them, ``..`` included, and the system's
``os.stat`` of the target's folder is the oracle: a folder is written into, a
loop (``ELOOP``) and a missing folder (``ENOENT``) are ``FileNotFoundError``, a
file in the way (``ENOTDIR``, or a file as the folder) ``NotADirectoryError`` -
never another error - and a refused write leaves the tree as it was.
"""

from __future__ import annotations

import errno
import os
import stat
import sys
import tempfile
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit._shared.files import atomic_path, check_folder

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from link_trees import folder_refusal
from link_trees import tree as _tree

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")

_NAMES = ("a", "b", "c", "d")
# Each entry: a folder, a file, or a link to a name (a sibling, itself, a
# missing one, a path through a sibling, or up and back down).
_KINDS = st.one_of(
    st.just(("dir", "")),
    st.just(("file", "")),
    st.tuples(st.just("link"), st.sampled_from([*_NAMES, "missing", "a/b", "../x/c", "d/..", "."])),
)


def _build(root: Path, layout: dict[str, tuple[str, str]]) -> None:
    for name, (kind, to) in layout.items():
        for parent in (root, root / "x"):  # "x" holds a second copy, for "../x/c"
            parent.mkdir(exist_ok=True)
            entry = parent / name
            if kind == "dir":
                entry.mkdir()
            elif kind == "file":
                entry.write_text("file")
            else:
                entry.symlink_to(to)


def _system(folder: Path) -> str:
    """What the system says of ``folder``: 'dir', 'file', or the errno's name."""
    try:
        mode = os.stat(folder).st_mode
    except OSError as exc:
        return errno.errorcode[exc.errno or 0]
    return "dir" if stat.S_ISDIR(mode) else "file"


@settings(max_examples=200, deadline=None)
@given(
    layout=st.dictionaries(st.sampled_from(_NAMES), _KINDS, min_size=1),
    parts=st.lists(st.sampled_from([*_NAMES, "..", "missing"]), min_size=1, max_size=4),
    named=st.booleans(),
)
def test_a_folder_is_refused_as_the_system_finds_it(
    layout: dict[str, tuple[str, str]], parts: list[str], named: bool
) -> None:
    with tempfile.TemporaryDirectory() as name:
        root = Path(name)
        _build(root, layout)
        folder = root.joinpath(*parts)
        target = folder / "out.json"
        found = _system(folder)
        before = _tree(root)
        # A file at one of the path's own folders is named as the path spells it;
        # one met on the way through a link's target ("b -> a/b", "a" a file:
        # ENOTDIR) is named too, as a file the system finds (review 46: it was
        # "folder ... does not exist", where open() says "Not a directory").
        prefixes = [root.joinpath(*parts[:k]) for k in range(1, len(parts) + 1)]
        blocker = next((p for p in prefixes if _system(p) == "file"), None)
        expected: type[OSError] | None = {
            "dir": None,
            "ELOOP": FileNotFoundError,
            "ENOENT": FileNotFoundError,
            "ENOTDIR": NotADirectoryError,
            "file": NotADirectoryError,
        }[found]
        if expected is None:
            check_folder(target, "path" if named else None)
            with atomic_path(target) as temporary:
                temporary.write_text("{}")
            assert target.read_text() == "{}"
            return
        error, named_file = folder_refusal(target, named, expected)
        text = str(error)
        assert ("is a loop of symbolic links" in text) == (found == "ELOOP"), text
        if named_file is not None:
            assert _system(Path(named_file)) == "file", (text, named_file)
            if blocker is not None:
                assert named_file == str(blocker), text
        if named and expected is NotADirectoryError:
            assert text == f"path: {named_file} is a file, not a folder"
        elif named:
            assert text.startswith(f"path: folder {folder} does not exist"), text
        else:
            # A loop is no folder to the writers: ENOENT, as a missing one.
            want = errno.ENOTDIR if expected is NotADirectoryError else errno.ENOENT
            assert error.errno == want, error
            assert error.filename is not None
        with pytest.raises(expected), atomic_path(target) as temporary:
            temporary.write_text("{}")
        assert _tree(root) == before
