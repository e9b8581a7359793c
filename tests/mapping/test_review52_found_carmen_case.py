"""CARMEN message names in another letter case (review 52, FOUND4).

CARMEN's readers (its playback's ``strncmp``, MRPT's and GMapping's
``strcmp``/``==``) match message names exactly: a line starting ``flaser`` is
no FLASER line for them, and ``read_carmen`` skips it as they do. A log of
such lines only was refused as "no FLASER or ROBOTLASER1 lines", leaving the
reader to guess why; the error now names the first such line.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.mapping.io import read_carmen

LINE = "3 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n"


@pytest.mark.parametrize("kind", ["flaser", "Flaser", "robotlaser1", "odom"])
def test_a_log_of_lower_case_names_only_is_refused_naming_the_first(
    tmp_path: Path, kind: str
) -> None:
    path = tmp_path / "log.txt"
    path.write_text("PARAM robot_front_laser_max 50.0 host 0.5\n" + f"{kind} {LINE}" * 2)
    with pytest.raises(
        ValueError,
        match=rf"no FLASER or ROBOTLASER1 lines \(line 2 starts with '{kind}': CARMEN's "
        r"message names are upper case",
    ):
        read_carmen(path)


def test_lower_case_lines_beside_laser_lines_are_skipped_as_carmen_skips_them(
    tmp_path: Path,
) -> None:
    path = tmp_path / "log.txt"
    path.write_text(f"FLASER {LINE}flaser 3 9.0 9.0 9.0 0 0 0 0 0 0 2.0 host 2.0\nFLASER {LINE}")
    log = read_carmen(path)
    assert len(log.scans) == 2 and all(s.ranges[0] == 1.0 for s in log.scans)


def test_a_log_without_any_laser_line_is_refused_as_before(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"
    path.write_text("PARAM robot_front_laser_max 50.0 host 0.5\nSYNC x host 1.0\n")
    with pytest.raises(ValueError, match=r"no FLASER or ROBOTLASER1 lines$"):
        read_carmen(path)
