"""What README.md and docs/index.md tell a new user, checked against navkit (review 43, DOCREV).

The subpackage tables of ``README.md`` and ``docs/index.md`` name every file
format ``navkit.mapping.io`` reads; the README's development notes name every
``mypy`` target ``.ci/run`` checks; the getting-started page's "a real map"
says what ``navkit demo`` runs on without the data sets, as a fresh clone is.
"""

from __future__ import annotations

import inspect
import re
from pathlib import Path

import navkit.mapping.io
from navkit.sim.scenarios import Demo

ROOT = Path(__file__).resolve().parents[1]

# The words that name the format each reader of navkit.mapping.io reads.
FORMATS = {
    "read_map": "map_server",
    "read_carmen": "CARMEN",
    "read_bag_imu": "bags",
    "read_bag_odometry": "bags",
    "read_bag_scans": "bags",
    "read_movingai_map": "MovingAI",
    "read_movingai_scenarios": "MovingAI",
}


def _io_row(page: str) -> str:
    text = (ROOT / page).read_text(encoding="utf-8")
    row = re.search(r"^\| \[?`navkit\.mapping\.io`.*$", text, re.M)
    assert row is not None, f"{page} has no navkit.mapping.io row"
    return row[0]


def test_every_reader_is_in_the_formats_checked() -> None:
    readers = {name for name in navkit.mapping.io.__all__ if name.startswith("read_")}
    assert readers == set(FORMATS)


def test_readme_and_home_page_name_every_format_mapping_io_reads() -> None:
    for page in ("README.md", "docs/index.md"):
        row = _io_row(page)
        missing = sorted({word for word in FORMATS.values() if word not in row})
        assert not missing, f"{page}'s navkit.mapping.io row leaves out {missing}"


def test_readme_names_every_mypy_target_ci_checks() -> None:
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    readme = (ROOT / "README.md").read_text(encoding="utf-8").split("## Development", 1)[1]
    versions = re.findall(r"^mypy --strict --python-version (\S+) src/navkit$", ci, re.M)
    platforms = re.findall(r"^mypy --strict --platform (\S+) src/navkit$", ci, re.M)
    assert versions and platforms
    for target in versions + platforms:
        assert target in readme, f"README's development notes leave out mypy's {target} target"


def test_getting_started_says_what_the_demo_runs_on_without_the_data() -> None:
    # Demo's default map falls back to a synthetic office when the data sets are absent.
    assert inspect.signature(Demo).parameters["map"].default == "auto"
    page = (ROOT / "docs" / "getting-started.md").read_text(encoding="utf-8")
    install = page.split("## Install", 1)[1].split("```bash", 1)[0]
    assert "real map" in install
    assert "synthetic office" in install, "the page promises a real map a fresh clone lacks"
