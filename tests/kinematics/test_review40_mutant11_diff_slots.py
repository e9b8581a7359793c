"""A DiffDrive takes no new attributes: a mistyped or misplaced setting fails loudly.

Review 40 (mutation testing, MUTANT11). ``DiffDrive.__slots__`` deleted passed every
test (review 39's MUTANT10 left it unpinned): instances then get a ``__dict__`` and
``drive.wheel_radius = 0.06`` (the constructor's keyword, but no attribute of the
drive) is accepted without a word while ``forward`` keeps the old radius. The class
documents itself as an ordinary class with ``__slots__``; with them the assignment
raises ``AttributeError``.
"""

from __future__ import annotations

import pickle

import pytest

from navkit.kinematics import DiffDrive


@pytest.mark.parametrize("name", ["wheel_radius", "trak", "left_radiuss"])
def test_a_new_attribute_is_refused_and_the_drive_unchanged(name: str) -> None:
    drive = DiffDrive(track=0.3, wheel_radius=0.05)
    before = drive.forward([10.0, 12.0])
    with pytest.raises(AttributeError):
        setattr(drive, name, 0.06)
    assert not hasattr(drive, name)
    assert not hasattr(drive, "__dict__")
    assert drive.forward([10.0, 12.0]) == before


def test_the_documented_parameters_stay_read_only() -> None:
    drive = DiffDrive(track=0.3, left_radius=0.05, right_radius=0.051)
    for name in ("track", "left_radius", "right_radius"):
        with pytest.raises(AttributeError):
            setattr(drive, name, 1.0)
    assert (drive.track, drive.left_radius, drive.right_radius) == (0.3, 0.05, 0.051)


def test_a_copy_is_as_closed_as_the_original() -> None:
    copy = pickle.loads(pickle.dumps(DiffDrive(track=0.3, wheel_radius=0.05)))
    with pytest.raises(AttributeError):
        copy.wheel_radius = 0.06  # type: ignore[attr-defined]
    assert copy.forward([10.0, 12.0]) == DiffDrive(track=0.3, wheel_radius=0.05).forward(
        [10.0, 12.0]
    )
