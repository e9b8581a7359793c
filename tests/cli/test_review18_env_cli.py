"""The command in processes it does not control: warnings as errors, no ``sys.argv``,
narrow terminals, no standard output."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from navkit.cli import main
from navkit.cli._parser import version

# numba finds no folder to cache in (as under a read-only install and HOME): it
# refuses cache=True, and navkit warns (KernelCacheWarning) and compiles uncached.
_NO_CACHE_MAIN = (
    "import sys\n"
    "import numba.core.caching as caching\n"
    "impl = getattr(caching, 'CacheImpl', None) or getattr(caching, '_CacheImpl')\n"
    "impl._locator_classes = []\n"
    "from navkit.cli import main\n"
    "sys.exit(main(sys.argv[1:]))\n"
)


def _tiny_map(folder: Path) -> Path:
    """A free 4 x 4 map of 0.5 m cells (ROS map_server YAML + PGM)."""
    (folder / "m.pgm").write_bytes(b"P5 4 4 255 " + b"\xfe" * 16)
    yaml = folder / "m.yaml"
    yaml.write_text(
        "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return yaml


@pytest.mark.parametrize("how", ["-W error", "PYTHONWARNINGS=error"])
def test_warnings_as_errors_without_a_cache_folder_is_one_error_line(
    tmp_path: Path, how: str
) -> None:
    # The KernelCacheWarning, raised as an exception by the warning filter, ended
    # `navkit plan` (and run, demo) with a traceback of thirty lines.
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "PYTHONWARN"))}
    flags = ["-W", "error"] if how.startswith("-W") else []
    if not flags:
        env["PYTHONWARNINGS"] = "error"
    args = ["plan", str(_tiny_map(tmp_path)), "--start", "0.25,0.25", "--goal", "1.75,1.75"]
    done = subprocess.run(
        [sys.executable, *flags, "-c", _NO_CACHE_MAIN, *args],
        env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert "Traceback" not in done.stderr, done.stderr[-3000:]
    assert done.returncode == 1, done.stderr[-3000:]
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), lines
    assert "NUMBA_CACHE_DIR" in lines[0]
    assert done.stdout == ""


@pytest.mark.slow
def test_without_a_writable_cache_folder_the_plan_still_runs(tmp_path: Path) -> None:
    # The same process without -W error: one warning line, then the plan (uncached).
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "PYTHONWARN"))}
    args = ["plan", str(_tiny_map(tmp_path)), "--start", "0.25,0.25", "--goal", "1.75,1.75",
            "--quiet"]  # fmt: skip
    done = subprocess.run(
        [sys.executable, "-c", _NO_CACHE_MAIN, *args],
        env=env, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    warned = done.stderr.strip().splitlines()
    assert len(warned) == 1 and warned[0].startswith("navkit: warning: "), warned
    assert "path points" in done.stdout


def test_main_without_sys_argv_is_a_usage_error(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # An embedding interpreter may leave sys.argv unset: main() raised AttributeError.
    monkeypatch.delattr(sys, "argv")
    assert main() == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert "the following arguments are required: COMMAND" in captured.err


@pytest.mark.parametrize("columns", ["1", "5", "12", "200"])
def test_version_is_one_line_whatever_the_width(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], columns: str
) -> None:
    # argparse's version action wrapped "navkit 0.1.0" onto two lines below 14 columns.
    monkeypatch.setenv("COLUMNS", columns)
    assert main(["--version"]) == 0
    captured = capsys.readouterr()
    assert captured.out == f"navkit {version()}\n"
    assert captured.err == ""


def test_version_with_standard_output_closed_writes_nothing(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # argparse wrote the version to standard error when standard output was None.
    monkeypatch.setattr(sys, "stdout", None)
    assert main(["--version"]) == 0
    assert capsys.readouterr().err == ""


def test_run_checks_the_cache_before_making_the_scenario(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # Making greedy's scenario runs A* (its route): numba loaded there, and an
    # unusable cache came out as the library's two-line warning, not check_cache's line.
    import navkit.cli._scenarios as scenarios

    calls: list[str] = []

    def check_cache(stream: object) -> None:
        calls.append("check_cache")

    def construct(name: str, args: object) -> None:
        calls.append(f"construct {name}")
        raise ValueError("stop here")

    monkeypatch.setattr(scenarios, "check_cache", check_cache)
    monkeypatch.setattr(scenarios, "_construct", construct)
    assert main(["run", "greedy", "--trials", "1", "--workers", "1"]) == 1
    assert calls == ["check_cache", "construct greedy"]
    assert capsys.readouterr().err == "navkit: error: stop here\n"


@pytest.mark.slow
def test_run_greedy_without_a_writable_cache_folder_warns_in_one_line() -> None:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "PYTHONWARN"))}
    done = subprocess.run(
        [sys.executable, "-c", _NO_CACHE_MAIN, "run", "greedy", "--trials", "1",
         "--workers", "1", "--quiet"],
        env=env, capture_output=True, text=True, timeout=900,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    warned = done.stderr.strip().splitlines()
    assert len(warned) == 1 and warned[0].startswith("navkit: warning: "), warned


def test_help_with_standard_output_closed_writes_nothing(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # argparse wrote the help to standard error when standard output was None.
    monkeypatch.setattr(sys, "stdout", None)
    assert main(["--help"]) == 0
    assert main(["plan", "--help"]) == 0
    assert capsys.readouterr().err == ""
    assert sys.stdout is None
