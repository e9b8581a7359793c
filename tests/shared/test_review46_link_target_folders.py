"""A file met through a symbolic link's target: "not a folder", from every writer (review 46).

With ``a`` a file and ``b -> a/b``, a target ``b/out.json`` (or ``b/x/out.json``)
was refused as a missing folder (``FileNotFoundError``, "folder b does not
exist"), where ``open`` says "Not a directory": ``check_folder`` looked for a
file in the path as spelled (``b``, then its folder) and never followed ``b``.
Review 45 decided that a file where a folder should be is
``NotADirectoryError`` naming the file (a loop of links stays a missing folder);
the file is now found along the link's target too, and named as the link spells
it (``a``; ``.`` and ``..`` tidied away where that names the same file). Nothing
is written and nothing is changed. ``tests/shared/test_review45_hypo6_folders.py``
checks the same against ``os.stat`` on random trees of links.
"""

from __future__ import annotations

import errno
import sys
from collections.abc import Callable
from functools import partial
from pathlib import Path

import numpy as np
import pytest

from navkit._shared.files import atomic_paths, check_folder
from navkit.cli import main
from navkit.cli._files import write_json
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from link_trees import file_in_link as _file_in_link
from link_trees import loop as _loop
from link_trees import tree as _tree

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")

_GRID = OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=0.1)


def _system_says_not_a_folder(target: Path) -> None:
    """The system's own writer refuses ``target`` with ENOTDIR (the case is the real one)."""
    with pytest.raises(NotADirectoryError):
        open(target, "w").close()


def _refused(call: Callable[[], object], blocker: Path, name: str | None) -> None:
    with pytest.raises(NotADirectoryError) as caught:
        call()
    if name is None:
        assert caught.value.errno == errno.ENOTDIR
        assert caught.value.filename == str(blocker)
    else:
        assert str(caught.value) == f"{name}: {blocker} is a file, not a folder"


@pytest.mark.parametrize("below", [(), ("x",), ("x", "y")])
def test_check_folder_names_the_file_in_the_links_target(
    tmp_path: Path, below: tuple[str, ...]
) -> None:
    link, blocker = _file_in_link(tmp_path)
    target = link.joinpath(*below, "out.json")
    _system_says_not_a_folder(target)
    before = _tree(tmp_path)
    _refused(lambda: check_folder(target, "--json"), blocker, "--json")
    _refused(lambda: check_folder(target), blocker, None)
    assert _tree(tmp_path) == before


def test_a_chain_of_links_is_followed_to_the_file(tmp_path: Path) -> None:
    # b -> c/b, c -> d/.., d -> f (a file), and an absolute link e -> <tmp>/b.
    (tmp_path / "f").write_text("keep me")
    (tmp_path / "d").symlink_to("f")
    (tmp_path / "c").symlink_to(Path("d", ".."))
    (tmp_path / "b").symlink_to(Path("c", "b"))
    (tmp_path / "e").symlink_to(tmp_path / "b")
    for start in ("b", "e"):
        target = tmp_path / start / "x" / "out.json"
        _system_says_not_a_folder(target)
        # d is the first part the system finds to be a file (through its link to f).
        _refused(partial(check_folder, target, "path"), tmp_path / "d", "path")
        _refused(partial(check_folder, target), tmp_path / "d", None)


def test_dots_in_a_links_target_are_tidied_when_they_name_the_same_file(tmp_path: Path) -> None:
    (tmp_path / "sub").mkdir()
    (tmp_path / "a").write_text("keep me")
    (tmp_path / "b").symlink_to(Path("sub", "..", ".", "a", "b"))
    # "sub/.." through a link to a folder elsewhere is not the link's own folder:
    # there the name is kept as the link spells it.
    (tmp_path / "far" / "inner").mkdir(parents=True)
    (tmp_path / "far" / "a").write_text("another file")
    (tmp_path / "jump").symlink_to(Path("far", "inner"))
    (tmp_path / "c").symlink_to(Path("jump", "..", "a", "b"))
    _refused(lambda: check_folder(tmp_path / "b" / "out.json", "path"), tmp_path / "a", "path")
    kept = tmp_path / "jump" / ".." / "a"
    _refused(lambda: check_folder(tmp_path / "c" / "out.json", "path"), kept, "path")


def test_a_loop_and_a_missing_folder_through_links_are_still_missing_folders(
    tmp_path: Path,
) -> None:
    loop = _loop(tmp_path)
    (tmp_path / "to_loop").symlink_to(Path("a", "x"))
    (tmp_path / "dir").mkdir()
    (tmp_path / "to_missing").symlink_to(Path("dir", "missing", "x"))
    folder = tmp_path / "to_loop" / "y"
    with pytest.raises(FileNotFoundError) as caught:
        check_folder(folder / "out.json", "path")
    assert str(caught.value).startswith(f"path: folder {folder} does not exist (")
    assert str(caught.value).endswith(" is a loop of symbolic links)")
    assert loop.is_symlink()
    folder = tmp_path / "to_missing" / "y"
    with pytest.raises(FileNotFoundError) as caught:
        check_folder(folder / "out.json", "path")
    assert str(caught.value) == f"path: folder {folder} does not exist"


def test_a_link_to_a_file_is_still_named_itself(tmp_path: Path) -> None:
    # Unchanged (review 45): the part of the path that is a file, as spelled.
    (tmp_path / "a").write_text("keep me")
    (tmp_path / "b").symlink_to("a")
    _refused(
        lambda: check_folder(tmp_path / "b" / "x" / "out.json", "path"), tmp_path / "b", "path"
    )


@pytest.mark.parametrize("below", [(), ("x",)])
def test_every_writer_says_not_a_folder_and_writes_nothing(
    tmp_path: Path, below: tuple[str, ...]
) -> None:
    link, blocker = _file_in_link(tmp_path)
    folder = link.joinpath(*below)
    kept = tmp_path / "kept.json"
    kept.write_text("old")
    before = _tree(tmp_path)

    def both() -> None:
        with atomic_paths([kept, folder / "out.json"]):
            raise AssertionError("the block ran")  # pragma: no cover

    _refused(lambda: write_map(_GRID, folder / "m.yaml"), blocker, None)
    _refused(lambda: _GRID.save(folder / "m.yaml", mode="scale"), blocker, None)
    _refused(both, blocker, None)
    _refused(lambda: write_json({"a": 1}, folder / "out.json"), blocker, "path")
    assert _tree(tmp_path) == before


@pytest.mark.parametrize("writer", ["save_figure", "animate_trace"])
def test_the_plot_writers_say_not_a_folder(tmp_path: Path, writer: str) -> None:
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from navkit.geometry import Twist2D
    from navkit.kinematics import DiffDrive
    from navkit.plot import animate_trace, plot_grid, save_figure
    from navkit.sim import Robot, Simulation, World

    link, blocker = _file_in_link(tmp_path)
    before = _tree(tmp_path)
    ax = plot_grid(_GRID)
    try:
        if writer == "save_figure":
            _refused(lambda: save_figure(ax, link / "out.png"), blocker, "path")
        else:
            robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
            trace = Simulation(
                World(),
                robot,
                lambda obs: Twist2D(0.2, 0.0, 0.0),
                start=(0.0, 0.0, 0.0),
                duration=0.2,
            ).run()
            call = lambda: animate_trace(trace, link / "out.gif", max_frames=2, dpi=20)  # noqa: E731
            _refused(call, blocker, "path")
    finally:
        plt.close("all")
    assert _tree(tmp_path) == before


@pytest.mark.parametrize(("option", "suffix"), [("--json", ".json"), ("--plot", ".png")])
def test_the_command_says_not_a_folder_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str, suffix: str
) -> None:
    if suffix == ".png":
        pytest.importorskip("matplotlib")
    link, blocker = _file_in_link(tmp_path)
    before = _tree(tmp_path)
    assert main(["demo", "--quiet", option, str(link / "x" / f"out{suffix}")]) == 1
    out, err = capsys.readouterr()
    assert (out, err) == ("", f"navkit: error: {option}: {blocker} is a file, not a folder\n")
    assert _tree(tmp_path) == before
