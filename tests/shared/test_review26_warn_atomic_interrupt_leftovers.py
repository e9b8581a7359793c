"""atomic_paths cut by an interrupt at any point: no temporary file or backup link left, no mix.

An interrupt just after ``os.open`` made a temporary file, or ``os.link`` a
backup link, left that file in the target's folder (it was listed for removal
only once the call returned); one in the removals after a save left the
backups not yet removed; and one as a rename returned left that target new
while the rollback, counting only the renames that had returned, kept it
(a map's new image beside its old YAML).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from interrupt_points import delivery_points, interrupted_at
from navkit._shared.files import atomic_paths


@pytest.mark.parametrize(("existing", "count"), [(0, 1), (1, 1), (2, 2), (1, 2), (0, 2)])
def test_an_interrupt_anywhere_leaves_only_the_targets_all_old_or_all_new(
    tmp_path: Path, existing: int, count: int
) -> None:
    targets = [tmp_path / f"map{i}.pgm" for i in range(count)]

    def reset() -> None:
        for path in tmp_path.iterdir():
            path.unlink()
        for target in targets[:existing]:
            target.write_text("old")

    def save() -> None:
        with atomic_paths(targets) as temporaries:
            for temporary in temporaries:
                # Written without a file object: one cut off as it opens is the
                # writer's own ResourceWarning, not atomic_paths'.
                os.truncate(temporary, 3)

    def state() -> tuple[str, ...]:
        return tuple(t.read_text() if t.exists() else "none" for t in targets)

    reset()
    before = state()
    points = delivery_points(save)
    assert points > 50
    for k in range(1, points + 1):
        reset()
        interrupted_at(k, save)
        left = sorted(p.name for p in tmp_path.iterdir())
        assert left == sorted(t.name for t in targets if t.exists()), f"point {k} of {points}"
        assert state() in (before, ("\0\0\0",) * count), f"interrupt at point {k}: {state()}"
