"""``write_json`` called from code refuses a ``path`` that is a loop of links (review 44).

The command line refuses such an output before its run (review 43); called
directly, ``write_json`` wrote the temporary file and then failed with
``OSError`` ("Too many levels of symbolic links"). It is now a ``ValueError``
naming the file, raised before anything is written.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from navkit.cli._files import write_json

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")


def test_write_json_refuses_a_loop_and_writes_nothing(tmp_path: Path) -> None:
    loop = tmp_path / "out.json"
    loop.symlink_to("out.json")
    with pytest.raises(ValueError, match=rf"^{loop} is a loop of symbolic links"):
        write_json({"a": 1}, loop)
    assert [(p.name, os.readlink(p)) for p in tmp_path.iterdir()] == [("out.json", "out.json")]
