"""Run ``mypy --strict`` in-process on a user's file, as a user's setup would.

Shared by the tests that type-check user code against navkit's public API
(reviews 27 and 49): none of navkit's ``[tool.mypy]`` settings, a private
cache, and ``MYPY_CONFIG_FILE_DIR`` put back after the run (mypy's in-process
run sets it in ``os.environ``, which later tests' processes inherited).
"""

from __future__ import annotations

from pathlib import Path

import pytest


def check_strict(
    code: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    *,
    mypy_path: Path | None = None,
) -> None:
    """Assert that ``mypy --strict`` finds no error in ``code``.

    ``mypy_path`` (optional) is a folder of stubs the user's setup has (e.g.
    typed shapely names).
    """
    from mypy import api

    config = tmp_path / "mypy.ini"
    config.write_text("[mypy]\n" + (f"mypy_path = {mypy_path}\n" if mypy_path else ""))
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MYPY_CONFIG_FILE_DIR", str(tmp_path))
    stdout, stderr, status = api.run(
        [
            "--strict",
            "--config-file",
            str(config),
            "--cache-dir",
            str(tmp_path / "cache"),
            "--no-error-summary",
            str(code),
        ]
    )
    assert status == 0, stdout + stderr
