"""Every public symbol's type is known to a user's type checker (review 28, extension points).

pyright ``--verifytypes`` scored navkit 88.8 %: the records' ``__eq__ = record_eq``
(an override whose type checkers could infer differently), the scenarios'
unannotated option attributes, ``NoPathError.expanded`` and
``TrackerController.tracker`` (a private protocol) left the ``Trace`` every run
returns, and so ``Simulation.run``, ``sweep`` and every scenario, partly unknown.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("pyright") is None, reason="pyright is not installed")
def test_pyright_finds_every_public_type_known() -> None:
    proc = subprocess.run(
        ["pyright", "--verifytypes", "navkit", "--ignoreexternal", "--outputjson"],
        cwd=ROOT, capture_output=True, text=True, check=False, timeout=600,
    )  # fmt: skip
    report = json.loads(proc.stdout)
    completeness = report["typeCompleteness"]
    unknown = [
        f"{d['file']}:{d['range']['start']['line'] + 1}: {d['message']}"
        for d in report["generalDiagnostics"]
        if d["severity"] == "error"
    ]
    assert completeness["completenessScore"] == 1.0, "\n".join(unknown)
