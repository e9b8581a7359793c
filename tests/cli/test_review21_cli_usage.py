"""The command line as a user meets it (a review through a new lens, session 25).

A mistyped choice names the closest one; the help shows examples and the exit
codes, and every example in it parses; ``--json -`` is refused instead of
making a file named ``-``; the system's errors read ``file: reason``; a
terminal that reports no size still shows the progress bar.
"""

from __future__ import annotations

import argparse
import errno
import os
import re
import select
import shlex
import sys
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.cli import _parser, _progress, main
from navkit.cli._app import one_line
from navkit.cli._parser import build_parser, closest_choice
from navkit.cli._progress import ProgressBar

SCENARIOS = ("demo", "diff-astar", "greedy", "indoor-nav", "omni-apf", "soccer")


def usage_error(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The error line of a usage error (exit code 2, the usage above it, no traceback)."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: navkit") and "Traceback" not in err
    return err.strip().splitlines()[-1]


@pytest.mark.parametrize(
    ("argv", "meant"),
    [
        (["run", "omni"], "omni-apf"),
        (["run", "omni_apf"], "omni-apf"),
        (["run", "Soccer"], "soccer"),
        (["run", "indoor"], "indoor-nav"),
        (["run", "diff"], "diff-astar"),  # a prefix, though difflib finds it too far
        (["lst"], "list"),
        (["warm-up"], "warmup"),
        (["plan", "m.yaml", "--start", "0,0", "--goal", "1,1", "--planner", "field-dstar"],
         "field_dstar"),
        (["demo", "--map", "Willow"], "willow"),
        (["warmup", "--only", "estimaton"], "estimation"),
    ],
)
def test_a_mistyped_choice_names_the_closest(
    argv: list[str], meant: str, capsys: pytest.CaptureFixture[str]
) -> None:
    line = usage_error(argv, capsys)
    # Python 3.14's suggest_on_error wording, before the list of choices.
    assert f"invalid choice: {argv[-1]!r}, maybe you meant {meant!r}? (choose from " in line


@pytest.mark.parametrize("argv", [["run", "xyz"], ["fly"], ["demo", "--map", "mars"]])
def test_nothing_close_suggests_nothing(
    argv: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    line = usage_error(argv, capsys)
    assert "invalid choice" in line and "maybe you meant" not in line


def test_argparses_own_suggestion_is_not_doubled(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # Python 3.15 suggests by default: its message is kept as it is.
    def suggesting(self: argparse.ArgumentParser, action: argparse.Action, value: object) -> None:
        if action.choices is not None and value not in action.choices:
            raise argparse.ArgumentError(action, f"invalid choice: {value!r}, maybe you meant 'x'?")

    monkeypatch.setattr(argparse.ArgumentParser, "_check_value", suggesting)
    line = usage_error(["run", "omni"], capsys)
    assert line.count("maybe you meant") == 1 and "'x'" in line


@given(name=st.sampled_from(SCENARIOS), upper=st.booleans(), underscores=st.booleans())
def test_a_choice_respelt_finds_itself(name: str, upper: bool, underscores: bool) -> None:
    spelt = name.upper() if upper else name
    spelt = spelt.replace("-", "_") if underscores else spelt
    assert closest_choice(spelt, SCENARIOS) == name


# Random text is never a scenario's name: the sampled names run the last branch.
@given(value=st.one_of(st.sampled_from(SCENARIOS), st.text(max_size=12)))
def test_a_suggestion_is_always_a_choice(value: str) -> None:
    guess = closest_choice(value, SCENARIOS)
    assert guess is None or guess in SCENARIOS
    if value in SCENARIOS:
        assert guess == value


def help_text(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    assert main([*argv, "--help"]) == 0
    return capsys.readouterr().out


def examples(text: str) -> list[list[str]]:
    """The example commands of a help text (continuation lines joined)."""
    block = text.split("examples:\n", 1)[1].split("\n\n", 1)[0].replace("\\\n", " ")
    return [shlex.split(line.split("#", 1)[0])[1:] for line in block.splitlines()]


@pytest.mark.parametrize("command", [[], ["demo"], ["run"], ["plan"], ["warmup"]])
def test_every_example_in_the_help_parses(
    command: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    found = examples(help_text(command, capsys))
    assert found and all(argv[: len(command)] == command for argv in found)
    parser = build_parser()
    for argv in found:
        args = parser.parse_args(_parser.join_negative_points(argv))  # SystemExit: broken
        assert args.command == argv[0]


def test_the_help_gives_the_exit_codes_the_command_returns(
    capsys: pytest.CaptureFixture[str],
) -> None:
    text = " ".join(help_text([], capsys).split())
    phrases = ("0 done", "1 a file, map, data set or plan failed", "2 bad arguments",
               "130 Ctrl-C", "143 SIGTERM", "129 SIGHUP", "141 standard output closed")  # fmt: skip
    for phrase in phrases:
        assert phrase in text
    # Two of them, as returned here.
    assert main(["run", "nosuch"]) == 2
    assert main(["plan", "no-such-map.yaml", "--start", "0,0", "--goal", "1,1"]) == 1


def test_examples_keep_their_lines_on_a_narrow_terminal(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("COLUMNS", "40")
    text = help_text(["plan"], capsys)
    assert "  navkit plan maps/turtlebot3_world/map.yaml --start -2,-0.5 --goal 2,0.5\n" in text
    # The prose around them is wrapped to the width as before.
    prose = text.split("Coordinates are", 1)[1]
    assert all(len(line) <= 40 for line in prose.splitlines())


def test_the_seed_range_reads_as_in_the_help(capsys: pytest.CaptureFixture[str]) -> None:
    assert "base seed in [0, 2**64)" in " ".join(help_text(["run"], capsys).split())
    assert usage_error(["run", "demo", "--seed", str(2**64)], capsys).endswith(
        f"--seed: must be in [0, 2**64), got {2**64}"
    )


def test_json_dash_is_refused_and_makes_no_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["run", "demo", "--json", "-", "--workers", "1", "--quiet"]) == 1
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == (
        "navkit: error: --json: '-' (standard output) is not supported, as the tables go "
        "there; give a file name (./- for a file named '-')\n"
    )
    assert list(tmp_path.iterdir()) == []


def test_an_unreadable_map_reads_file_then_reason(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    map_yaml = tmp_path / "map.yaml"
    map_yaml.write_text("image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n")
    opened = os.open

    def refused(path: object, *args: object, **kwargs: object) -> int:
        if os.fspath(path) == str(map_yaml):  # type: ignore[call-overload]
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(map_yaml))
        return opened(path, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(os, "open", refused)  # root reads a chmod 000 file
    assert main(["plan", str(map_yaml), "--start", "0,0", "--goal", "1,1", "--quiet"]) == 1
    assert capsys.readouterr().err == f"navkit: error: {map_yaml}: Permission denied\n"


@pytest.mark.parametrize(
    ("error", "text"),
    [
        (PermissionError(errno.EACCES, "Permission denied", "a b.yaml"),
         "a b.yaml: Permission denied"),
        (OSError(errno.ENOSPC, "No space left on device"), "No space left on device"),
        (OSError(errno.EIO, "Input/output error", b"raw"), "raw: Input/output error"),
        (OSError(errno.EBADF, "Bad file descriptor", 3), "Bad file descriptor"),
        (FileNotFoundError("map YAML file m.yaml does not exist"),
         "map YAML file m.yaml does not exist"),
        (OSError("--plot: cannot write in folder /x (Permission denied)"),
         "--plot: cannot write in folder /x (Permission denied)"),
    ],
)  # fmt: skip
def test_system_errors_read_file_then_reason(error: OSError, text: str) -> None:
    assert one_line(error) == text


@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs a pseudo-terminal")
def test_a_terminal_of_no_size_still_shows_the_bar(monkeypatch: pytest.MonkeyPatch) -> None:
    # A new pseudo-terminal reports 0 x 0, as `script` or `docker run -t` without a
    # client terminal do: tqdm drew nothing there.
    monkeypatch.setattr(_progress, "DELAY", 0.0)
    monkeypatch.delenv("COLUMNS", raising=False)
    monkeypatch.delenv("LINES", raising=False)
    leader, follower = os.openpty()
    try:
        assert os.get_terminal_size(follower) == os.terminal_size((0, 0))
        with open(follower, "w", encoding="utf-8", closefd=False) as stream:
            with ProgressBar(stream, enabled=True, description="soccer") as bar:
                bar.start(10)
                bar(4, 10)
                bar(10, 10)
                assert bar.shown
            stream.flush()
        # A pseudo-terminal hands over what was written in pieces: read until it is drained.
        chunks = []
        while select.select([leader], [], [], 0.5)[0]:
            chunk = os.read(leader, 65536)
            if not chunk:
                break
            chunks.append(chunk)
        drawn = b"".join(chunks).decode("utf-8", "replace")
    finally:
        os.close(leader)
        os.close(follower)
    assert "soccer" in drawn and "10/10" in drawn
    widest = max(len(line) for line in re.split(r"[\r\n]+", drawn))
    assert widest <= 80


def test_python_dash_m_is_the_same_command(capsys: pytest.CaptureFixture[str]) -> None:
    import subprocess

    done = subprocess.run(
        [sys.executable, "-m", "navkit", "run", "omni", "--quiet"],
        capture_output=True, text=True, timeout=120, env={**os.environ},
    )  # fmt: skip
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert done.stderr.splitlines()[-1] == usage_error(["run", "omni"], capsys)
