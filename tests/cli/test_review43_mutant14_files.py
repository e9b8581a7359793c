"""``write_json`` over an existing file (review 43, MUTANT14).

A mutation review of ``navkit.cli._files`` found writing into an existing
regular file directly (as into a device or a pipe), not through a temporary
file renamed over it, unseen by every test: the file's content was right
either way. Written directly, a reader saw a partial file while it was
written, and an interrupted write left one; the replaced file is a new one,
so a hard link to the old file keeps the old content. Nor did a test see an
error that names its own file (the temporary file's) renamed after the target.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from navkit.cli._files import json_text, named_write_errors, write_json


def test_an_existing_file_is_replaced_not_written_into(tmp_path: Path) -> None:
    target = tmp_path / "out.json"
    target.write_text('{"old": true}\n', encoding="utf-8")
    old = tmp_path / "old.json"
    os.link(target, old)
    assert write_json({"new": [1.5, 2]}, target) == target
    assert json.loads(target.read_text(encoding="utf-8")) == {"new": [1.5, 2]}
    assert old.read_text(encoding="utf-8") == '{"old": true}\n'
    assert not os.path.samefile(old, target)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old.json", "out.json"]


def test_an_error_that_names_its_file_keeps_that_name() -> None:
    # The temporary file's or the folder's name, as the system gave it: the file
    # that failed, not the target (unseen by the mutation review too).
    with pytest.raises(PermissionError) as caught, named_write_errors(Path("out.json")):
        raise PermissionError(13, "Permission denied", "maps/.out.json.tmp")
    assert caught.value.filename == "maps/.out.json.tmp"
    full = r"^\[Errno 28\] No space left on device: 'out\.json'$"
    with pytest.raises(OSError, match=full), named_write_errors(Path("out.json")):
        raise OSError(28, "No space left on device")


def test_number_lists_are_laid_out_from_the_data_json_dumps_accepted() -> None:
    # Integer keys and tuples, as json.dumps writes them: keys as strings, tuples as
    # lists (laid out from the data itself, "1": was 1: and the tuple one line).
    data = {1: ({"a": (1.5, 2)},)}
    text = json_text(data, number_lists_on_one_line=True)
    assert text == '{\n  "1": [\n    {\n      "a": [1.5, 2]\n    }\n  ]\n}'
    assert json.loads(text) == json.loads(json.dumps(data))
