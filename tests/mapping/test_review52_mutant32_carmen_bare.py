"""A CARMEN line of its message name alone lacks its fields (review 52, MUTANT32).

Review 51 split a line's message name at any blank (``line.split(None, 1)``);
a line of the name alone has no rest. A mutant reading the name itself as the
rest (``named[-1]``) passed every test: such a line must be refused for its
missing fields, not for a field ``FLASER`` that is no number.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.mapping.io import read_carmen


@pytest.mark.parametrize(
    ("line", "said"),
    [
        ("FLASER", "malformed FLASER line: no beam count"),
        ("ODOM", "malformed ODOM line: 0 fields where"),
        ("\tROBOTLASER1 ", "malformed ROBOTLASER1 line: only 0 fields"),
    ],
)
def test_a_message_name_alone_is_refused_for_its_missing_fields(
    tmp_path: Path, line: str, said: str
) -> None:
    path = tmp_path / "log.txt"
    path.write_text("FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n" + line + "\n")
    with pytest.raises(ValueError, match=f"log.txt:2: {said}"):
        read_carmen(path)
