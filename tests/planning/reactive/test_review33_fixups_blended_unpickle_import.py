"""Review 33 (FIXUPS): an unpickled ``BlendedAttraction`` imports scipy.special when loaded.

The field imports ``scipy.special`` when it is built, so that the first
``force()`` of a control loop does not pay the import (0.3 s). A field
unpickled in a fresh process (a sweep's worker) is rebuilt without
``__post_init__``: it paid the import at its first ``force()`` again.
Checked: against ``_attraction.py`` of HEAD the first test reads False; the
others pin that copies (subclasses' included) stay as they were.
"""

from __future__ import annotations

import copy
import pickle
from dataclasses import dataclass

import numpy as np

from navkit.planning.reactive import BlendedAttraction, ParaboloidAttraction
from subprocess_probe import probe_outcome

_LOAD = """
import json, pickle, sys
field = pickle.loads(bytes.fromhex(sys.argv[1]))
print(json.dumps([type(field).__name__, "scipy.special" in sys.modules]))
"""


def test_an_unpickled_blended_field_imports_scipy_special_when_loaded() -> None:
    data = pickle.dumps(BlendedAttraction((1.0, 2.0), width=0.2)).hex()
    assert probe_outcome(_LOAD, data, timeout=120) == ["BlendedAttraction", True]


def test_other_attractions_do_not_import_it() -> None:
    data = pickle.dumps(ParaboloidAttraction((1.0, 2.0))).hex()
    assert probe_outcome(_LOAD, data, timeout=120) == ["ParaboloidAttraction", False]


@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class _Scaled(BlendedAttraction):
    scale: float = 2.0


class _Tagged(BlendedAttraction):
    pass


def test_copies_keep_fields_subclass_attributes_and_forces() -> None:
    pts = np.array([[3.0, 4.0], [1.1, 2.0], [1.0, 2.0]])
    tagged = _Tagged((1.0, 2.0), width=0.2)
    tagged.__dict__["owner"] = tagged  # a link back to the field itself
    for field in (BlendedAttraction((1.0, 2.0), width=0.2), _Scaled((1.0, 2.0), scale=3.0), tagged):
        for copied in (copy.deepcopy(field), pickle.loads(pickle.dumps(field))):
            assert type(copied) is type(field) and repr(copied) == repr(field)
            assert copied.goal_xy.flags.writeable is False
            np.testing.assert_array_equal(copied.force(pts), field.force(pts))
    assert copy.deepcopy(tagged).__dict__["owner"] is not tagged
    copied = pickle.loads(pickle.dumps(tagged))
    assert copied.__dict__["owner"] is copied
    assert pickle.loads(pickle.dumps(_Scaled((1.0, 2.0), scale=3.0))).scale == 3.0
