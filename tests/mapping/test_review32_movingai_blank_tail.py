"""Review 32: blank lines after a map's rows are ignored however many; counts read as words.

Also (FRESH): ``MovingAIScenarios`` refused the empty lists of a file with no
problems (``map_shapes`` of shape (0,) is not (0, 2)); its range checks, now
NumPy's reductions instead of Python's ``min``/``max`` over every element
(5.5 ms for 12,000 problems), still name the value.

The ``.map`` reader reads the rows the header announces plus a bounded margin;
it refused a map followed by more than that margin of blank lines (4 KB of
newlines, as an editor or a concatenating script may leave) as having "more
than the 2 rows", against its docstring ("blank lines ... after the rows are
ignored"). Its messages also said "1 rows" and "a row of 1 characters".
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import MovingAIScenarios, read_movingai_map, read_movingai_scenarios

TINY = "type octile\nheight 2\nwidth 3\nmap\n..@\nT.S\n"


@pytest.mark.parametrize(
    "tail",
    ["\n" * 5000, " \n\t\r\n" * 3000, "\n" * (3 << 20)],
    ids=["5000 newlines", "3000 blank CRLF lines", "3 MiB of newlines"],
)
def test_any_number_of_trailing_blank_lines_is_ignored(tmp_path: Path, tail: str) -> None:
    path = tmp_path / "tiny.map"
    path.write_text(TINY + tail, encoding="ascii")
    terrain = read_movingai_map(path).terrain
    np.testing.assert_array_equal(terrain, [list("..@"), list("T.S")])


@pytest.mark.parametrize("blanks", [10, 5000, (1 << 20) + 7])
def test_a_row_after_any_blanks_is_still_refused(tmp_path: Path, blanks: int) -> None:
    path = tmp_path / "tiny.map"
    path.write_text(TINY + "\n" * blanks + "...\n", encoding="ascii")
    with pytest.raises(ValueError, match=r"more than the 2 rows of the header's height"):
        read_movingai_map(path)


def test_counts_of_one_read_as_words(tmp_path: Path) -> None:
    path = tmp_path / "short.map"
    path.write_text(TINY.replace("T.S\n", ""), encoding="ascii")
    with pytest.raises(ValueError, match=r": 1 row after the 'map' line"):
        read_movingai_map(path)
    path.write_text("type octile\nheight 1\nwidth 3\nmap\n.\n", encoding="ascii")
    with pytest.raises(ValueError, match=r"a row of 1 character, the header's width is 3"):
        read_movingai_map(path)
    path.write_text("type octile\nheight 2\nwidth 3\nmap\n..@\n", encoding="ascii")
    with pytest.raises(ValueError, match=r": 1 row after .* height is 2"):
        read_movingai_map(path)
    scen = tmp_path / "one.scen"
    scen.write_text("version 1\n0\n", encoding="ascii")
    with pytest.raises(ValueError, match=r":2: 1 field, a problem has 9"):
        read_movingai_scenarios(scen)


def test_no_problems_from_empty_lists() -> None:
    """A file of no problems reads as an empty record; the record takes ``[]`` as well."""
    empty = MovingAIScenarios([], [], [], [], [], [])
    assert len(empty) == 0
    assert empty.map_shapes.shape == empty.start_cells.shape == empty.goal_cells.shape == (0, 2)
    assert empty.buckets.shape == empty.optimal_lengths.shape == (0,)
    with pytest.raises(ValueError, match=r"map_shapes must have shape \(0, 2\), got \(0, 3\)"):
        MovingAIScenarios([], [], np.empty((0, 3), dtype=np.int64), [], [], [])


def test_range_checks_of_integer_arrays_name_the_value() -> None:
    one = ([0], ["a.map"], [[2, 2]], [[0, 0]], [[1, 1]], [1.0])
    cases = [
        (0, [-3], r"buckets must be >= 0, got -3"),
        (2, np.array([[2**63, 2]], dtype=np.uint64), rf"map_shapes must be at most {2**63 - 1}"),
        (2, [[2**70, 2]], rf"map_shapes must be at most {2**63 - 1}, got {2**70}"),
        (3, np.array([[0, -1]], dtype=np.int8), r"start_cells must be >= 0, got -1"),
    ]
    for index, value, message in cases:
        args = list(one)
        args[index] = value
        with pytest.raises(ValueError, match=message):
            MovingAIScenarios(*args)
