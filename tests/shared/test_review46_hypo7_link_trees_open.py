"""check_folder agrees with what ``open`` does, on random trees of links (review 46, HYPO7).

HYPO6's test (review 45) takes ``os.stat`` of the target's folder as its
oracle on one level of entries. Here the trees have two levels, links to
links, absolute targets, targets through ``..`` and through other links,
and the oracle is the writer's own step: creating the target file with
``os.open`` (then removing it). ``check_folder`` is silent exactly when
that open succeeds; where it fails with ``ENOTDIR`` it raises
``NotADirectoryError`` naming a file that the system finds is a file (on
the way to the target); with ``ENOENT`` or ``ELOOP`` it raises
``FileNotFoundError``, naming a loop exactly for ``ELOOP``. A refused check
leaves the tree as it was, and the writers (``atomic_path``) refuse alike.
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

_TOP = ("a", "b", "c")
_INNER = ("a/x", "a/y", "b/x", "c/y")
# Link targets: relative (through siblings, parents, links) and absolute ("/" marks one
# relative to the tree's root); the missing and the self-referent too.
_TARGETS = (
    "a", "b", "c", "a/x", "b/x", "x", "..", ".", "../a", "../b/x", "a/../b",
    "b/x/..", "missing", "a/x/y", "/a", "/b/x", "/c/y", "/a/x/../y",
)  # fmt: skip
_KINDS = st.one_of(
    st.just(("dir", "")),
    st.just(("file", "")),
    st.tuples(st.just("link"), st.sampled_from(_TARGETS)),
)


def _build(root: Path, layout: dict[str, tuple[str, str]]) -> None:
    # Top entries first, then those inside a top folder (skipped where it is none).
    for name in sorted(layout, key=lambda n: (n.count("/"), n)):
        kind, to = layout[name]
        entry = root / name
        if not os.path.isdir(entry.parent) or os.path.islink(entry.parent):
            continue
        if kind == "dir":
            entry.mkdir()
        elif kind == "file":
            entry.write_text("file")
        else:
            entry.symlink_to(str(root) + to if to.startswith("/") else to)


def _open_outcome(target: Path) -> str:
    """'ok' if creating ``target`` as a writer does succeeds (then removed), else its errno."""
    try:
        fd = os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except OSError as exc:
        return errno.errorcode[exc.errno or 0]
    os.close(fd)
    os.unlink(target)
    return "ok"


_PARTS = st.lists(st.sampled_from([*_TOP, "x", "y", "..", "missing"]), min_size=1, max_size=4)


@settings(max_examples=150, deadline=None)
@given(
    layout=st.dictionaries(st.sampled_from(_TOP + _INNER), _KINDS, min_size=1, max_size=7),
    parts=_PARTS,
    named=st.booleans(),
)
def test_check_folder_refuses_exactly_what_open_refuses(
    layout: dict[str, tuple[str, str]], parts: list[str], named: bool
) -> None:
    with tempfile.TemporaryDirectory() as name:
        root = Path(name)
        _build(root, layout)
        target = root.joinpath(*parts) / "out-hypo7.json"
        before = _tree(root)
        found = _open_outcome(target)
        assert _tree(root) == before
        if found == "ok":
            check_folder(target, "path" if named else None)
            return
        expected = {
            "ENOTDIR": NotADirectoryError,
            "ENOENT": FileNotFoundError,
            "ELOOP": FileNotFoundError,
        }.get(found)
        assert expected is not None, found  # no other way to fail to create a file here
        error, blocker = folder_refusal(target, named, expected)
        text = str(error)
        assert ("is a loop of symbolic links" in text) == (found == "ELOOP"), text
        if blocker is not None:
            # The file named is one: not a folder, not missing, not a loop.
            assert not stat.S_ISDIR(os.stat(blocker).st_mode), (text, blocker)
            assert os.path.commonpath([blocker, name]) == name, blocker  # inside the tree
        with pytest.raises(expected), atomic_path(target) as temporary:
            temporary.write_text("{}")
        assert _tree(root) == before


def test_the_trees_reach_every_outcome() -> None:
    # One tree of each outcome, so that the property above is not vacuous.
    with tempfile.TemporaryDirectory() as name:
        root = Path(name)
        _build(
            root,
            {
                "a": ("dir", ""),
                "b": ("link", "a/x"),
                "a/x": ("file", ""),
                "c": ("link", "c"),
                "a/y": ("link", "/b/q"),
            },
        )
        outcomes = {
            p: _open_outcome(root / p / "out.json") for p in ("a", "b", "c", "missing", "a/y")
        }
        assert outcomes == {
            "a": "ok",
            "b": "ENOTDIR",
            "c": "ELOOP",
            "missing": "ENOENT",
            "a/y": "ENOTDIR",
        }
        # Named as the link's target spells it: b (a link to the file a/x).
        with pytest.raises(NotADirectoryError, match=r"/b is a file, not a folder$"):
            check_folder(root / "a/y/out.json", "path")
    with tempfile.TemporaryDirectory() as name:
        # Links through links to a file: c -> b/x, b -> a/x, a a file.
        root = Path(name)
        _build(root, {"a": ("file", ""), "b": ("link", "a/x"), "c": ("link", "b/x")})
        assert _open_outcome(root / "c" / "out.json") == "ENOTDIR"
        with pytest.raises(NotADirectoryError, match=r"/a is a file, not a folder$"):
            check_folder(root / "c/out.json", "path")
