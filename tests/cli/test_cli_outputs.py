"""Output files, data folders, seeds and pipes: the cases a run used to get wrong.

Each mistake is caught before the run starts (nothing printed on stdout, no
file written) with one line ``navkit: error: ...`` and exit code 1.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from navkit.cli import main


def one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), err
    return lines[0]


@pytest.mark.parametrize(
    ("first", "second", "name"),
    [("--json", "--plot", "r.png"), ("--json", "--animate", "r.gif")],
)
def test_two_outputs_naming_one_file_are_refused_before_running(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], first: str, second: str, name: str
) -> None:
    # Written one after the other, the picture used to replace the JSON silently.
    (tmp_path / "link").symlink_to(tmp_path)  # another spelling of the same file
    argv = ["run", "demo", "--quiet", first, str(tmp_path / name),
            second, str(tmp_path / "link" / name)]  # fmt: skip
    assert main(argv) == 1
    out, err = capsys.readouterr()
    line = one_error_line(err)
    assert first in line and second in line and "same file" in line
    assert out == ""  # refused before the run
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link"]


@pytest.mark.parametrize(
    ("option", "name"), [("--json", "r.json"), ("--plot", "r.png"), ("--animate", "r.gif")]
)
def test_an_unwritable_folder_is_refused_before_running(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    option: str,
    name: str,
) -> None:
    # A read-only folder (running as root, chmod cannot make one): creating a file fails.
    def refuse(*args: object, **kwargs: object) -> tuple[int, str]:
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tempfile, "mkstemp", refuse)
    assert main(["run", "demo", "--quiet", option, str(tmp_path / name)]) == 1
    out, err = capsys.readouterr()
    line = one_error_line(err)
    assert option in line and str(tmp_path) in line and "Permission denied" in line
    assert out == ""  # not after the run, with the table already printed
    assert list(tmp_path.iterdir()) == []


def test_the_writability_probe_leaves_nothing_behind(tmp_path: Path) -> None:
    from navkit.cli._outputs import check_output

    check_output(str(tmp_path / "r.json"), "", "--json")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("kind", ["missing", "file"])
def test_a_data_option_that_is_no_folder_is_an_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], kind: str
) -> None:
    # The demo used to fall back to its synthetic office: the typo went unnoticed.
    data = tmp_path / "data"
    if kind == "file":
        data.write_text("")
    assert main(["demo", "--quiet", "--data", str(data)]) == 1
    out, err = capsys.readouterr()
    line = one_error_line(err)
    assert "--data" in line and str(data) in line
    assert out == ""


def test_every_seed_the_library_takes_is_accepted(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Base seeds are in [0, 2**64) (navkit.sim.trial_seed); the command stopped at 2**63 - 1.
    seed = 2**64 - 1
    target = tmp_path / "r.json"
    argv = ["run", "demo", "--seed", str(seed), "--workers", "1", "--quiet", "--json", str(target)]
    assert main(argv) == 0
    assert f"seed {seed}" in capsys.readouterr().out
    assert json.loads(target.read_text())["seed"] == seed
    assert main(["run", "demo", "--seed", str(2**64)]) == 2
    assert "must be in [0, 2**64), got 18446744073709551616" in capsys.readouterr().err


def test_an_integer_too_long_to_parse_is_out_of_range(capsys: pytest.CaptureFixture[str]) -> None:
    # int() refuses more than 4300 digits: the message said "expected an integer".
    assert main(["run", "demo", "--seed", "9" * 5000]) == 2
    err = capsys.readouterr().err
    assert "argument --seed: must be in [0, " in err and "expected an integer" not in err


def test_a_closed_pipe_ends_the_command_quietly() -> None:
    # `navkit list | head -1`: stdout's reader is gone before navkit writes.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
    process = subprocess.Popen(
        [sys.executable, "-m", "navkit", "list"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
    )  # fmt: skip
    assert process.stdout is not None and process.stderr is not None
    process.stdout.close()
    err = process.stderr.read().decode()
    process.stderr.close()
    assert process.wait(timeout=120) == 141, err  # 128 + SIGPIPE, as a shell reports
    assert err == ""  # no "Exception ignored ... BrokenPipeError"


def test_json_into_a_pipe_or_device_is_written_into_it(tmp_path: Path) -> None:
    # os.replace used to put a regular file in place of the pipe (as root, `--json
    # /dev/null` replaced the system's /dev/null with the JSON).
    import stat

    from navkit.cli._files import write_json
    from navkit.cli._outputs import check_output

    fifo = tmp_path / "result.json"
    os.mkfifo(fifo)
    check_output(str(fifo), "", "--json")  # accepted before the run
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)  # so that the writer does not block
    try:
        assert write_json({"a": [1, 2.5]}, fifo) == fifo
        received = os.read(reader, 1 << 16)
    finally:
        os.close(reader)
    assert json.loads(received) == {"a": [1, 2.5]}
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result.json"]


@pytest.mark.parametrize(("option", "name"), [("--plot", "r.png"), ("--animate", "r.gif")])
def test_pictures_over_a_pipe_are_refused_before_running(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str, name: str
) -> None:
    import stat

    fifo = tmp_path / name
    os.mkfifo(fifo)
    assert main(["run", "demo", "--quiet", option, str(fifo)]) == 1
    out, err = capsys.readouterr()
    line = one_error_line(err)
    assert option in line and "not a regular file" in line
    assert out == ""
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
