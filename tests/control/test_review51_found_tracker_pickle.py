"""Review 51 (FOUND3): a path tracker pickled before 3bf2b94 loads and steps on.

A tracker's path is a private ``Polyline``. Before 3bf2b94 it pickled as its
slots; since, it pickles as its points and is rebuilt from them
(``__reduce__``), and it gained an ``end`` slot (49dff86) that only that
rebuild sets. A tracker pickled before 3bf2b94 loaded a line without ``end``:
a ``RegulatedPurePursuit`` raised ``AttributeError`` ("'Polyline' object has no
attribute 'end'") at its first step, for every pickle from the project's first
day (908ac92) to a0dd033. Such a line is now rebuilt from its points as a new
one (its arrays read-only again: they came back writable): the loaded tracker
steps on exactly as one that took the same steps today.

The pickle below is real: made by navkit at a0dd033 (3bf2b94's parent, protocol
2) from the tracker and steps of ``MAKER``; ``test_the_pickle_is_the_old_release``
makes it again there (slow; a git checkout of the project).
"""

from __future__ import annotations

import base64
import copy
import pickle
from pathlib import Path

import numpy as np
import pytest

from navkit.control import RegulatedPurePursuit
from old_release import made_at

OLD_COMMIT = "a0dd033"
MAKER = """
import base64, json, pickle
import numpy as np
from navkit.control import RegulatedPurePursuit
tracker = RegulatedPurePursuit()
tracker.set_path(np.array([[0.0, 0.0], [1.0, 0.3], [2.0, 0.2]]))
for k in range(3):
    tracker.step((0.05 * k, 0.0, 0.1 * k), 0.05)
print(json.dumps({"pickle": base64.b64encode(pickle.dumps(tracker, protocol=2)).decode()}))
"""
OLD_PICKLE = (
    "gAJjbmF2a2l0LmNvbnRyb2wuX3JlZ3VsYXRlZF9wdXJlX3B1cnN1aXQKUmVndWxhdGVkUHVyZVB1cnN1"
    "aXQKcQApgXEBTn1xAihYEgAAAF9hcHByb2FjaF9kaXN0YW5jZXEDRz/jMzMzMzMzWAcAAABfY2Fycm90"
    "cQRHP+sMI+lTkoBHP+gAAAAAAACGcQVYCgAAAF9jbGVhcmFuY2VxBk5YEwAAAF9jbGVhcmFuY2VfZGlz"
    "dGFuY2VxB0c/4zMzMzMzM1gPAAAAX2NsZWFyYW5jZV9nYWlucQhHP/AAAAAAAABYFQAAAF9jdXJ2YXR1"
    "cmVfcmVndWxhdGlvbnEJiFgFAAAAX2xhc3RxCkc/4AAAAAAAAEcAAAAAAAAAAEc/xhY80bAVO4dxC1gP"
    "AAAAX2xvb2thaGVhZF90aW1lcQxHP/gAAAAAAABYEgAAAF9tYXhfYW5ndWxhcl9hY2NlbHENR0AJmZmZ"
    "mZmaWA4AAABfbWF4X2xvb2thaGVhZHEORz/szMzMzMzNWAoAAABfbWF4X29tZWdhcQ9OWAoAAABfbWF4"
    "X3NwZWVkcRBHP+AAAAAAAABYEwAAAF9taW5fYXBwcm9hY2hfc3BlZWRxEUc/qZmZmZmZmlgOAAAAX21p"
    "bl9sb29rYWhlYWRxEkc/0zMzMzMzM1gUAAAAX21pbl9yZWd1bGF0ZWRfc3BlZWRxE0c/0AAAAAAAAFgP"
    "AAAAX21vdGlvbl9oZWFkaW5ncRROWA0AAABfcm90YXRlX29tZWdhcRVHP/zMzMzMzM1YEgAAAF9yb3Rh"
    "dGVfdG9faGVhZGluZ3EWiFgYAAAAX3JvdGF0ZV90b19oZWFkaW5nX2FuZ2xlcRdHP+keuFHrhR9YEAAA"
    "AF9zbG93ZG93bl9yYWRpdXNxGEc/7MzMzMzMzVgGAAAAX2RyaXZlcRlYBAAAAGRpZmZxGlgNAAAAX2dv"
    "YWxfaGVhZGluZ3EbTlgPAAAAX2dvYWxfdG9sZXJhbmNlcRxHP9AAAAAAAABYBQAAAF9saW5lcR1jbmF2"
    "a2l0LmNvbnRyb2wuX3BhdGhfZm9sbG93aW5nClBvbHlsaW5lCnEeKYFxH059cSAoWAMAAABjdW1xIWNu"
    "dW1weS5fY29yZS5tdWx0aWFycmF5Cl9yZWNvbnN0cnVjdApxImNudW1weQpuZGFycmF5CnEjSwCFcSRj"
    "X2NvZGVjcwplbmNvZGUKcSVYAQAAAGJxJlgGAAAAbGF0aW4xcSeGcShScSmHcSpScSsoSwFLA4VxLGNu"
    "dW1weQpkdHlwZQpxLVgCAAAAZjhxLomIh3EvUnEwKEsDWAEAAAA8cTFOTk5K/////0r/////SwB0cTJi"
    "iWglWB0AAAAAAAAAAAAAACzClMOZe1nCtMOwPxAOLsKpY2QAQHEzaCeGcTRScTV0cTZiWAYAAABsZW5n"
    "dGhxN0dAAGRjqS4OEFgJAAAAcG9pbnRzX3h5cThoImgjSwCFcTloKYdxOlJxOyhLAUsDSwKGcTxoMIlo"
    "JVg5AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAMOwPzMzMzMzM8OTPwAAAAAAAABAwprCmcKZwpnCmcKZ"
    "w4k/cT1oJ4ZxPlJxP3RxQGJ1hnFBYlgGAAAAX3BoYXNlcUJYBQAAAHRyYWNrcUNYCQAAAF9wcm9ncmVz"
    "c3FERz+4hTXZBwPGWAcAAABfdGFyZ2V0cUVHP+noH6G/OExHP88WjFuyQ46GcUZYDgAAAF95YXdfdG9s"
    "ZXJhbmNlcUdHP9AAAAAAAAB1hnFIYi4="
)


def _stepped() -> RegulatedPurePursuit:
    """The tracker of ``MAKER``, built and stepped today."""
    tracker = RegulatedPurePursuit()
    tracker.set_path(np.array([[0.0, 0.0], [1.0, 0.3], [2.0, 0.2]]))
    for k in range(3):
        tracker.step((0.05 * k, 0.0, 0.1 * k), 0.05)
    return tracker


def _check(tracker: RegulatedPurePursuit) -> None:
    fresh = _stepped()
    assert repr(tracker) == repr(fresh)
    twin, again = copy.deepcopy(tracker), pickle.loads(pickle.dumps(tracker))
    for k in range(3, 60):
        pose = (0.05 * k, 0.01 * k, 0.1 * k)
        want = fresh.step(pose, 0.05)
        for other in (tracker, twin, again):
            assert other.step(pose, 0.05) == want
    assert tracker.done and fresh.done
    # The line as a new one's: its arrays read-only (they came back writable).
    line = tracker._state.line
    assert line is not None and line.end == (2.0, 0.2)
    assert not line.points_xy.flags.writeable and not line.cum.flags.writeable


def test_a_tracker_pickled_before_its_path_reduced_itself_loads_and_steps_on() -> None:
    _check(pickle.loads(base64.b64decode("".join(OLD_PICKLE))))


@pytest.mark.slow
def test_the_pickle_is_the_old_release(tmp_path: Path) -> None:
    # Made again by the source of OLD_COMMIT: the same bytes.
    assert made_at(OLD_COMMIT, MAKER, tmp_path) == {"pickle": "".join(OLD_PICKLE)}
