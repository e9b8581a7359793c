"""navkit's JSON output has LF line ends on Windows too (the portability review).

Windows' text mode writes ``os.linesep`` (CRLF) for each ``\\n``; the pure-Python
``_pyio`` text layer does the same where ``os.linesep`` is CRLF, which the tests
use to write as Windows would.
"""

from __future__ import annotations

import _pyio
import builtins
import io
import json
import os
import threading
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.cli._files import write_json

_JSON = st.recursive(
    st.none() | st.booleans() | st.integers(-10**6, 10**6) | st.text(max_size=8),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=5), inner,
                                                                max_size=3),
    max_leaves=8,
)  # fmt: skip


@given(data=_JSON)
@settings(max_examples=30, deadline=None)
def test_json_has_the_same_bytes_as_on_linux(
    tmp_path_factory: pytest.TempPathFactory, data: object
) -> None:
    folder = tmp_path_factory.mktemp("json")
    write_json(data, folder / "linux.json")
    with pytest.MonkeyPatch.context() as monkeypatch:
        monkeypatch.setattr(os, "linesep", "\r\n")
        monkeypatch.setattr(io, "open", _pyio.open)
        monkeypatch.setattr(builtins, "open", _pyio.open)
        # The simulation writes CRLF where nothing asks for LF:
        (folder / "probe.txt").write_text("a\n", encoding="utf-8")
        write_json(data, folder / "windows.json")
    assert (folder / "probe.txt").read_bytes() == b"a\r\n"
    written = (folder / "windows.json").read_bytes()
    assert written == (folder / "linux.json").read_bytes()
    assert b"\r" not in written
    assert json.loads(written) == data


def test_json_into_a_pipe_has_lf(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    if not hasattr(os, "mkfifo"):
        pytest.skip("no named pipes")
    fifo = tmp_path / "out.fifo"
    os.mkfifo(fifo)
    got: list[bytes] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()))
    reader.start()
    monkeypatch.setattr(os, "linesep", "\r\n")
    monkeypatch.setattr(builtins, "open", _pyio.open)
    write_json({"a": [1, 2]}, fifo)
    reader.join(timeout=30)
    assert got == [json.dumps({"a": [1, 2]}, indent=2).encode() + b"\n"]
