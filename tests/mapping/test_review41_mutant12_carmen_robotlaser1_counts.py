"""A ROBOTLASER1 line cut at or just before its remission count says which (MUTANT12).

Mutation review 41: the check ``len(tokens) < 9 + n`` (the ranges and the
remission count after the beam count ``n``) at ``<=`` survived. A line that ends
right after its remission count holds that count, and is refused by the count of
fields the two counts give (with the hint to check them); a line that ends right
after its ranges has no remission count, and is refused as too short after the
beam count. Field counts here are those of the line (the keyword not counted).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.mapping.io import read_carmen

_HEAD = "ROBOTLASER1 0 -0.5 1.0 0.25 8.0 0.01 0 5 1.5 1.5 1.5 1.5 1.5"


def _read(tmp_path: Path, line: str) -> None:
    path = tmp_path / "log.txt"
    path.write_text(line + "\n")
    read_carmen(path)


@pytest.mark.parametrize("n_rem", [0, 2])
def test_a_line_ending_after_its_remission_count_is_refused_by_the_counts(
    tmp_path: Path, n_rem: int
) -> None:
    # 7 head fields, the beam count, 5 ranges, the remission count: 14 fields where
    # the counts give 14 + n_rem remissions + 12 poses, speeds and timestamp.
    need = 14 + n_rem + 12
    with pytest.raises(
        ValueError,
        match=rf"log\.txt:1: .*14 fields where the counts give {need} .*"
        r"are the beam and remission counts right\?",
    ):
        _read(tmp_path, f"{_HEAD} {n_rem}")


def test_a_line_ending_after_its_ranges_is_refused_after_the_beam_count(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"log\.txt:1: .*5 fields after the beam count 5"):
        _read(tmp_path, _HEAD)
