"""``navkit run`` to the end, in this process: its table, notices and every output file.

Coverage review (session 30): the default suite ran ``navkit run`` only to its
refusals; the path of a run that finishes (the compilation notice, the summary
line, ``--json``, ``--plot`` and ``--animate``) ran in slow tests alone.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from navkit.cli import main


def test_a_run_prints_its_table_and_writes_every_output(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    files = {
        "--json": tmp_path / "r.json",
        "--plot": tmp_path / "r.png",
        "--animate": tmp_path / "r.gif",
    }
    argv = ["run", "demo", "--trials", "1", "--seed", "3", "--workers", "1"]
    for option, path in files.items():
        argv += [option, str(path)]
    assert main(argv) == 0
    out, err = capsys.readouterr()
    # One trial per leg of the tour (3 legs), run here: the summary says so.
    assert "\n3 trials in " in out and "(this process), seed 3" in out
    assert out.count("wrote ") == 3
    for path in files.values():
        assert f"wrote {path}" in out
    assert "Traceback" not in err
    result = json.loads(files["--json"].read_text(encoding="utf-8"))
    assert (result["scenario"], result["seed"], len(result["trials"])) == ("demo", 3, 3)
    assert files["--plot"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert files["--animate"].read_bytes()[:6] in (b"GIF87a", b"GIF89a")


def test_a_quiet_run_writes_nothing_on_stderr(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "r.json"
    assert (
        main(["run", "demo", "--trials", "1", "--workers", "1", "--quiet", "--json", str(target)])
        == 0
    )
    out, err = capsys.readouterr()
    assert err == ""
    assert out.strip().splitlines()[-1] == f"wrote {target}"
    assert json.loads(target.read_text(encoding="utf-8"))["seed"] == 0
