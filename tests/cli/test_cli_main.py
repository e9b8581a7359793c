"""The navkit command (issue 14): list, run, demo, --version, exit codes, --json.

Bad arguments print the usage and exit 2; missing or malformed input prints one
line ``navkit: error: ...`` and exits 1; never a traceback.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from navkit.cli import main
from navkit.sim.scenarios import SCENARIOS, Demo


def one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), err
    assert "Traceback" not in err
    return lines[0]


def test_list_names_every_scenario(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for name, cls in SCENARIOS.items():
        assert name in out and cls.title in out


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip().startswith("navkit 0.")


def test_python_dash_m_navkit_lists_the_scenarios() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "navkit", "list"], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert "demo" in done.stdout and "omni-apf" in done.stdout


@pytest.mark.parametrize(
    "argv",
    [
        [],
        ["fly"],
        ["run", "nosuch"],
        ["run"],
        ["run", "demo", "--trials", "0"],
        ["run", "demo", "--trials", "two"],
        ["run", "demo", "--seed", "-1"],
        ["run", "demo", "--workers", "0"],
        ["demo", "--map", "mars"],
        ["plan", "m.yaml", "--start", "1", "--goal", "2,2"],
        ["plan", "m.yaml", "--start", "1,nan", "--goal", "2,2"],
        ["plan", "m.yaml", "--goal", "2,2"],
        ["plan", "m.yaml", "--start", "1,1", "--goal", "2,2", "--planner", "dijkstra"],
        ["plan", "m.yaml", "--start", "1,1", "--goal", "2,2", "--radius", "-1"],
    ],
)
def test_bad_arguments_print_usage_and_exit_2(
    argv: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "usage: navkit" in err and "Traceback" not in err


def test_run_writes_json_equal_to_the_scenarios_result(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "demo.json"
    target.write_text("old")
    argv = ["run", "demo", "--seed", "3", "--json", str(target), "--workers", "1", "--quiet"]
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert err == ""  # --quiet: no progress, no compilation notice
    assert "navkit demo: plan, track and estimate" in out and f"wrote {target}" in out
    assert "3 trials in" in out and "seed 3" in out
    data = json.loads(target.read_text())
    assert [p.name for p in tmp_path.iterdir()] == ["demo.json"]  # no temporary left
    expected = Demo().run(seed=3).to_dict()
    for d in (data, expected):
        for trial in d["trials"]:
            del trial["wall_time"], trial["values"]["plan_wall_time"]
        del d["summary"]["plan_wall_time"], d["tables"]
    assert data == expected


def test_demo_on_the_office_map(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo", "--map", "office", "--quiet", "--json", str(tmp_path / "d.json")]) == 0
    out = capsys.readouterr().out
    assert "synthetic office" in out and "3/3" in out  # every leg reached
    # The demo has no --workers: its three legs run in this process, as its summary says.
    assert "\n3 trials in " in out and " s (this process), seed 0\n" in out
    assert json.loads((tmp_path / "d.json").read_text())["summary"]["collisions"] == 0.0


def test_missing_data_is_one_line_and_exit_1(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["demo", "--map", "willow", "--data", str(tmp_path)]) == 1
    line = one_error_line(capsys.readouterr().err)
    assert "willow" in line and "not found" in line


def test_output_files_are_checked_before_running(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    for argv in (
        ["run", "demo", "--json", str(tmp_path / "no-such-folder" / "r.json")],
        ["run", "demo", "--plot", str(tmp_path / "picture.jpg")],
        ["run", "demo", "--animate", str(tmp_path / "run.png")],
        ["demo", "--json", str(tmp_path)],
    ):
        assert main(argv) == 1, argv
        one_error_line(capsys.readouterr().err)
    assert list(tmp_path.iterdir()) == []


def test_scheduler_without_distributed_names_the_extra(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setitem(sys.modules, "dask.distributed", None)  # import fails
    assert main(["run", "demo", "--scheduler", "tcp://127.0.0.1:8786", "--quiet"]) == 1
    assert "navkit[distributed]" in one_error_line(capsys.readouterr().err)


@pytest.mark.slow
def test_unreachable_scheduler_is_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    # Connecting times out after 10 s.
    assert main(["run", "demo", "--scheduler", "tcp://127.0.0.1:9", "--quiet"]) == 1
    one_error_line(capsys.readouterr().err)
