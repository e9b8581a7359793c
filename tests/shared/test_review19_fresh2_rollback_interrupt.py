"""Review 19 (FRESH2): a Ctrl-C while a rollback waits on Windows does not lose the old files.

Since the portability review a rename on Windows is tried again for up to a second
while another program holds the file, the rollback's renames too. A Ctrl-C during
such a wait ended the rollback part-way, and the ``finally`` then removed the
backups: the targets not yet put back kept the new file (an image of this save
with the YAML of the last one) and their old version was gone. Now a first Ctrl-C
lets the rollback finish (waiting again) and is raised after it; a second one stops
the waiting, and every target is still tried once. Simulated on Linux: renames onto
a held file raise ``PermissionError`` as Windows' do.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

import navkit._shared.files as files
from fake_clock import fake_clock_for
from navkit._shared.files import atomic_paths


def _setup(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, *, names: int, refused: str, interrupts: int
) -> tuple[list[Path], dict[str, Any]]:
    """Targets with old text; renames over ``refused`` fail for good; the put-backs
    are held a little (a scanner looking at the files) and ``interrupts`` Ctrl-Cs
    arrive during the rollback's waits."""
    targets = [tmp_path / f"f{i}.txt" for i in range(names)]
    for target in targets:
        target.write_text(f"old {target.name}")
    real_replace = os.replace
    # The hold and the waits on a clock that moves only as the waits sleep: on the
    # real one a loaded machine's pause of the process can outlast the 0.3 s of
    # retries before the 0.05 s hold ends.
    clock = fake_clock_for(monkeypatch, files)
    state: dict[str, Any] = {
        "rollback": False,
        "interrupts": interrupts,
        "held_until": {},
        "put_back": [],
    }

    def replace(source: Any, target: Any) -> None:
        name = Path(target).name
        if name == refused:
            raise PermissionError(13, "Access is denied", str(target))
        if Path(source).name.startswith(".") and not Path(source).name.endswith(".txt"):
            state["rollback"] = True  # a backup (a hard link) put back: briefly held
            state["put_back"].append(name)
            until = state["held_until"].setdefault(name, clock.monotonic() + 0.05)
            if clock.monotonic() < until:
                raise PermissionError(13, "Access is denied", str(target))
        real_replace(source, target)

    def sleep(seconds: float) -> None:
        if state["rollback"] and state["interrupts"] > 0:
            state["interrupts"] -= 1
            raise KeyboardInterrupt
        clock.now += seconds

    monkeypatch.setattr(files, "_windows", lambda: True)
    monkeypatch.setattr(files, "_WINDOWS_RETRY_SECONDS", 0.3)
    monkeypatch.setattr(files.os, "replace", replace)
    monkeypatch.setattr(clock, "sleep", sleep)
    return targets, state


def _save(targets: list[Path]) -> None:
    with atomic_paths(targets) as temporaries:
        for temporary in temporaries:
            temporary.write_text("new")


def test_a_ctrl_c_while_a_put_back_waits_lets_the_rollback_finish(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    targets, state = _setup(tmp_path, monkeypatch, names=2, refused="f1.txt", interrupts=1)
    with pytest.raises(KeyboardInterrupt):
        _save(targets)
    assert state["rollback"] and state["interrupts"] == 0
    assert [t.read_text() for t in targets] == ["old f0.txt", "old f1.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f0.txt", "f1.txt"]


def test_a_second_ctrl_c_stops_the_waiting_but_every_target_is_tried(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    targets, state = _setup(tmp_path, monkeypatch, names=3, refused="f2.txt", interrupts=2)
    with pytest.raises(KeyboardInterrupt):
        _save(targets)
    assert state["interrupts"] == 0
    # Both Ctrl-Cs came during f0's waits; f1's put-back was still tried (once,
    # without waiting: held, so f1 stays new, as after any refused put-back).
    assert state["put_back"].count("f1.txt") == 1
    assert targets[2].read_text() == "old f2.txt"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f0.txt", "f1.txt", "f2.txt"]


def test_without_interrupts_a_brief_hold_on_a_put_back_is_waited_out(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    targets, _ = _setup(tmp_path, monkeypatch, names=3, refused="f2.txt", interrupts=0)
    with pytest.raises(PermissionError):
        _save(targets)
    assert [t.read_text() for t in targets] == ["old f0.txt", "old f1.txt", "old f2.txt"]
