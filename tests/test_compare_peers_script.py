"""Smoke test of ``benchmarks/compare_peers.py``: it runs, checks and prints ratios.

Runs the script's cheapest workload (``rollout``: navkit against a pure-Python
loop and NumPy, no peer library needed) and the EKF workload with filterpy
treated as absent, in a subprocess with the shortest timing settings. Asserts
the table's shape, not wall-clock times.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "compare_peers.py"


@pytest.fixture(scope="module")
def run(
    tmp_path_factory: pytest.TempPathFactory,
) -> tuple[subprocess.CompletedProcess[str], dict[str, Any]]:
    if not SCRIPT.is_file():
        pytest.skip("benchmarks/ is not part of this installation")
    pytest.importorskip("pytest_benchmark")
    out = tmp_path_factory.mktemp("compare") / "results.json"
    proc = subprocess.run(
        [
            sys.executable,
            str(SCRIPT),
            "--quick",
            "--only",
            "rollout",
            "ekf-step-x1000",
            "--without",
            "filterpy",
            "--min-time",
            "0.005",
            "--repeats",
            "2",
            "--json",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=tmp_path_factory.mktemp("cwd"),
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc, json.loads(out.read_text())


def test_table_has_ratio_rows(run: tuple[subprocess.CompletedProcess[str], dict[str, Any]]) -> None:
    proc, _ = run
    rows = [line for line in proc.stdout.splitlines() if line.startswith("| rollout |")]
    assert [row.split("|")[4].strip() for row in rows] == ["pure Python", "NumPy prefix sums"]
    for row in rows:
        ratio = row.split("|")[7].strip()
        assert re.fullmatch(r"[\d,]+(\.\d+)?", ratio), row
        assert "same poses" in row
    assert "ratio peer/navkit" in proc.stdout
    assert re.search(r"^- machine: .+cores", proc.stdout, re.MULTILINE)
    assert re.search(r"^- Python \S+, NumPy \S+, numba \S+", proc.stdout, re.MULTILINE)


def test_missing_peer_row_says_not_installed(
    run: tuple[subprocess.CompletedProcess[str], dict[str, Any]],
) -> None:
    proc, _ = run
    (row,) = [line for line in proc.stdout.splitlines() if line.startswith("| ekf-step-x1000 |")]
    assert "not installed (filterpy)" in row


def test_json_matches_table(run: tuple[subprocess.CompletedProcess[str], dict[str, Any]]) -> None:
    _, data = run
    assert data["options"]["quick"] is True
    assert {"cpu", "cores", "python", "versions"} <= set(data["machine"])
    rollout = [r for r in data["rows"] if r["workload"] == "rollout"]
    assert len(rollout) == 2
    for row in rollout:
        assert row["ratio"] == pytest.approx(row["peer_median_s"] / row["navkit_median_s"])
        assert row["navkit_first_s"] > 0.0
    (ekf,) = [r for r in data["rows"] if r["workload"] == "ekf-step-x1000"]
    assert ekf["ratio"] is None and ekf["status"].startswith("not installed")


def test_without_a_peer_navkit_needs_is_refused(tmp_path: Path) -> None:
    """``--without SciPy`` once hid SciPy from navkit too: every row was an error."""
    if not SCRIPT.is_file():
        pytest.skip("benchmarks/ is not part of this installation")
    for name in ("SciPy", "scipy"):
        proc = subprocess.run(
            [sys.executable, str(SCRIPT), "--without", name, "--list"],
            capture_output=True,
            text=True,
            timeout=120,
            cwd=tmp_path,
        )
        assert proc.returncode != 0
        assert f"--without {name}: navkit itself needs scipy" in proc.stderr
        assert proc.stdout == ""
