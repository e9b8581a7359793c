"""The command line of ``benchmarks/carmen_navkit.py``: its own options and the harness's."""

from __future__ import annotations

from typing import Any

import pytest

import carmen_eval as ce
import carmen_navkit as cn
from test_bench_astar import shared_data


def test_help_lists_the_extra_options_before_compiling(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    def no_warm_up(*args: Any) -> None:
        raise AssertionError("--help compiled the kernels first")

    monkeypatch.setattr(cn, "warm_up", no_warm_up)
    with pytest.raises(SystemExit) as exit_info:
        cn.main(["--help"])
    assert exit_info.value.code == 0
    out = capsys.readouterr().out
    for option in ("--audit", "--weights", "--basin", "--max-scans", "--data-dir"):
        assert option in out


def test_bad_option_stops_before_compiling(monkeypatch: pytest.MonkeyPatch) -> None:
    def no_warm_up(*args: Any) -> None:
        raise AssertionError("a bad option compiled the kernels first")

    monkeypatch.setattr(cn, "warm_up", no_warm_up)
    with pytest.raises(SystemExit) as exit_info:
        cn.main(["--audit", "--no-such-option"])
    assert exit_info.value.code == 2


def test_extra_tables_read_only_the_scans_asked_for(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """``--max-scans`` and ``--data-dir`` reach ``--basin``, ``--audit`` and ``--weights``
    (they once read every scan of the default data folder)."""
    data_dir = str(shared_data("carmen-logs").parent)
    real_load = ce.load_log
    calls: list[tuple[str, int | None, Any]] = []

    def load(name: str, *, max_scans: int | None = None, data_dir: Any = None) -> ce.CarmenData:
        calls.append((name, max_scans, data_dir))
        if max_scans is None or max_scans > 5:
            raise AssertionError(f"{name} read with max_scans={max_scans}")
        return real_load(name, max_scans=max_scans, data_dir=data_dir)

    monkeypatch.setattr(ce, "load_log", load)
    argv = ["--logs", "intel", "--max-scans", "4", "--methods", "navkit", "prior"]
    argv += ["--data-dir", data_dir, "--basin", "--audit", "--weights"]
    assert cn.main(argv) == 0
    out = capsys.readouterr().out
    assert "Basin of navkit told the noise level" in out
    assert "navkit's gross failures" in out
    assert "Rotation weight sweep" in out
    assert {call[0] for call in calls} == {"intel"}
    assert all(call[2] == data_dir for call in calls)
    # the harness's runs, the basin's, the tuned basin's, the audit's and the sweep's
    assert len(calls) >= 5
