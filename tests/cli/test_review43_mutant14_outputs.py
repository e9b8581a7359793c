"""An output file that is a loop of symbolic links (review 43, MUTANT14).

``check_distinct`` took each output's real path with ``Path.resolve()``, which
before Python 3.13 raises ``RuntimeError("Symlink loop ...")``: ``navkit plan
m.yaml ... --json p.json`` with ``p.json -> p.json`` ended in a traceback. Its
real path is now taken as ``os.path.realpath`` takes it, and ``check_output``
refuses the loop before the run (``exists()`` says False for it; written, it
failed with "Too many levels of symbolic links" only after the run).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.cli import main
from navkit.cli._outputs import check_distinct, check_output
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")


def _loop(folder: Path, name: str) -> Path:
    link = folder / name
    link.symlink_to(name)
    return link


def test_a_link_to_itself_is_one_file_among_others(tmp_path: Path) -> None:
    loop = _loop(tmp_path, "a.png")
    check_distinct({"--plot": str(loop), "--json": str(tmp_path / "b.json")})
    with pytest.raises(ValueError, match=r"--json and --plot name the same file"):
        check_distinct({"--plot": str(loop), "--json": str(tmp_path / "." / "a.png")})


@pytest.mark.parametrize(("suffix", "option"), [(".png", "--plot"), ("", "--json")])
def test_a_loop_of_links_is_refused_before_the_run(
    tmp_path: Path, suffix: str, option: str
) -> None:
    (tmp_path / "b.png").symlink_to("c.png")
    (tmp_path / "c.png").symlink_to("b.png")
    for path in (tmp_path / "b.png", _loop(tmp_path, "a.png")):
        with pytest.raises(ValueError, match=rf"^{option}: .*\.png is a loop of symbolic links$"):
            check_output(str(path), suffix, option)
    (tmp_path / "d.png").symlink_to("missing.png")  # a dangling link is written over
    check_output(str(tmp_path / "d.png"), suffix, option)


def test_plan_names_the_loop_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:6, 6] = True
    write_map(OccupancyGrid.from_occupancy(occupied, resolution=0.1), tmp_path / "m.yaml")
    loop = _loop(tmp_path, "p.json")
    code = main(
        ["plan", str(tmp_path / "m.yaml"), "--start", "0.15,0.15", "--goal", "1.05,0.15",
         "--json", str(loop)]
    )  # fmt: skip
    captured = capsys.readouterr()
    assert code == 1
    assert captured.err == f"navkit: error: --json: {loop} is a loop of symbolic links\n"
    assert captured.out == ""  # refused before the plan, not after it


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="counts /proc/self/fd")
def test_the_writability_probe_closes_its_descriptor(tmp_path: Path) -> None:
    # Unseen by a mutation review: the probe file was removed, its descriptor left open
    # (one a check; main() may run many times in one process).
    before = len(os.listdir("/proc/self/fd"))
    for _ in range(3):
        check_output(str(tmp_path / "r.json"), "", "--json")
    assert len(os.listdir("/proc/self/fd")) == before
    assert list(tmp_path.iterdir()) == []


def test_the_extension_is_compared_ignoring_case(tmp_path: Path) -> None:
    check_output(str(tmp_path / "R.PNG"), ".png", "--plot")
    with pytest.raises(ValueError, match=r"^--animate: the file must end in \.gif, got .*R\.PNG$"):
        check_output(str(tmp_path / "R.PNG"), ".gif", "--animate")


@pytest.mark.parametrize(("suffix", "option"), [(".png", "--plot"), ("", "--json")])
def test_a_folder_is_refused_as_a_folder(tmp_path: Path, suffix: str, option: str) -> None:
    # Unseen by the mutation review: without this check a folder given to --json
    # was refused only by write_json, after the run.
    folder = tmp_path / f"out{suffix}"
    folder.mkdir()
    with pytest.raises(ValueError, match=rf"^{option}: .*out{suffix} is a folder, not a file$"):
        check_output(str(folder), suffix, option)


def test_a_missing_folder_is_named(tmp_path: Path) -> None:
    # Unseen by the mutation review: without this check the probe's mkstemp reported
    # "cannot write in folder ... (No such file or directory)", an OSError.
    missing = tmp_path / "missing"
    with pytest.raises(FileNotFoundError, match=rf"^--json: folder {missing} does not exist$"):
        check_output(str(missing / "r.json"), "", "--json")
    assert not missing.exists()


def test_a_hidden_matplotlib_package_is_missing_even_with_its_figure_module_loaded(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # As after an earlier plot in the same process (main() may run many times).
    import matplotlib.figure  # noqa: F401

    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(ImportError, match=r"^--plot needs matplotlib, which is not installed"):
        check_output("out.png", ".png", "--plot")


@pytest.mark.parametrize("kind", ["picture", "animation"])
def test_a_failed_picture_write_names_the_file(monkeypatch: pytest.MonkeyPatch, kind: str) -> None:
    # `--plot` on a full disk: "No space left on device" alone left the file unnamed.
    import navkit.plot as plot
    from navkit.cli import _outputs

    def full(*args: object, **kwargs: object) -> Path:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(plot, "plot_scene", lambda scene: None)
    monkeypatch.setattr(plot, "save_figure", full)
    monkeypatch.setattr(plot, "animate_trace", full)
    save = _outputs.save_picture if kind == "picture" else _outputs.save_animation
    with pytest.raises(OSError, match=r"No space left on device: 'out\.png'$"):
        save(None, "out.png")  # type: ignore[arg-type]
