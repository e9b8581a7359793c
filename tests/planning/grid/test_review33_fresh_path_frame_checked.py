"""Review 33 (FRESH): ``Path2D.frame`` is checked as the plain ``str`` it is stored as.

Review 32 stored the frame as a plain copy of a ``str`` subclass's characters
but checked it before the copy, with the subclass's own ``==``: a case-blind
subclass's ``"GRID"`` passed and a path of frame ``"GRID"`` was made, which
its readers (``frame == "grid"``) take for neither frame. Checked: against
``_path.py`` of HEAD the first test builds the path (no error); the other two
pin what stays as it was.
"""

from __future__ import annotations

import numpy as np
import pytest

from case_blind import CaseBlind
from navkit.planning.grid import Path2D


def test_a_str_subclass_equal_to_a_frame_only_by_its_own_eq_is_refused() -> None:
    with pytest.raises(ValueError, match=r"^frame must be 'grid' or 'world', got 'GRID'$"):
        Path2D(np.zeros((1, 2)), CaseBlind("GRID"), 0.0, 0.0, 0)  # type: ignore[arg-type]


def test_a_subclass_spelling_a_frame_is_kept_as_plain_text() -> None:
    path = Path2D(np.zeros((1, 2)), CaseBlind("world"), 0.0, 0.0, 0)  # type: ignore[arg-type]
    assert type(path.frame) is str and path.frame == "world"


def test_a_non_str_frame_is_refused_as_before() -> None:
    with pytest.raises(TypeError, match=r"^frame must be 'grid' or 'world', got ndarray$"):
        Path2D(np.zeros((1, 2)), np.array("grid"), 0.0, 0.0, 0)  # type: ignore[arg-type]
