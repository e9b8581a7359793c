"""Fresh-eyes review of Field D*'s node records (issue 17): copies and old pickles.

``FieldDStar.__setstate__`` as the node records came in set the slots of the
state's second item only and expected a ``_vals`` slot: a subclass's own
attributes (the state's first item, its ``__dict__``) were dropped by
``copy.copy``, ``copy.deepcopy`` and pickle, which kept them before, and a
pickle made before the records (``_g``, ``_rhs`` and a heap with its own
``pos`` array) raised AttributeError on loading. Both are fixed; copies also
get cache-line aligned keys again, as a fresh planner's.
"""

from __future__ import annotations

import base64
import copy
import pickle
import zlib
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.planning import FieldDStar

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]

# pickle.dumps(planner, protocol=2) under navkit at commit 1b3fa1d (before the node
# records) of: FieldDStar(np.ones((3, 4))), plan((0, 0), (3, 4)),
# update_costs([(1, 1)], np.inf); zlib-compressed and base64-encoded.
_OLD_PICKLE = (
    "eNrtV91zE1UUTz+pgZZACy2gKFigRYylFVssmlUKUVbTuvixghg3m0127WY3Z3fTUimmxUmaqHV0hnHESuHBYTrOyHSm"
    "yjBMrTP3PuiDf4fP/gd6797dFFuRD1908GYme+6559y793d+Oedkolo2pJFhzQlndckwNCMdTltaMhxPaYqejCdtR7KC"
    "R6k8cJyKEOichKrYWajuENcEAoG4LMmqkoSamNjgTlXJSJN5rWzkMtmxcFw2LSWcyemOJlmWNBaMW4psGrZj5WQnCHXM"
    "LGgk2SrU84ECrJGJW1KR7aBiUCEIDWIV2T0BD4j15KlLjmbsh2AR1gqwbgoaBWjq4Kt4rgDrvQ2TzliW+IXEamKv9cGG"
    "cmkKNgrQ3MHXuHsdgpZYLHbsdzLcLz7gwKZEWW0QA8SFWtDRFPh/3I8DNquEXa0CtDmwJeGSLi7rimTA1rJY585M3YZt"
    "fC1bS1mKrcKDZXFtZRYfNa1heIhvdikYT8N2tU516f2wSjj7iAA7KGdbCrBTZTRN9cGjlKbtAuwiNFVXE3S3S9Cfie1e"
    "PIfPo4WhwRYOf6njS/jjEXw9xOGlMJ5Fk4DKjRw/nutFM51Bjl2pgcMf4Rvtp/YpG/9khqf78yk0iy7Xc3h+8CyaPIm+"
    "qPZ8Ahy+iBfRFRtdxVdDyzveZFhxx9cizAfPV4S8f7S/3QoLAvQeCnSHAJ0O7E0waNOmpMNjfA1fW4R9YtBXxWVF1+Hx"
    "sthY0ZhG3CD5AcIlBryrzJqa4cATUa6BHRHlQkwoQhc7QFWkLOzv8OPRTePRI8CTXjwOqM0U5uvEdL33miuftd7T2zkQ"
    "vMX6rezRPLqAFnfg6TxFoxv9wMSuHl/CNxlkebTkaScqYtdpvt0V0Dw+b3vipzt7mQRPUVh7Behz4GDCv+jT9KL9Ahxy"
    "L8pXF+EZdRe96hmS73R0zUz1j7d5MQpxt1fgK+hipGdwqHWZYgv4E3QJXdiD5jZVlFvQ9IkD+Hu0uJnbjZbQDTSDp1s2"
    "cKh4GH+IZroOblu2INT8rIWwaRp9PbCVw5/jb9Ei+g59g+ca79oezx7BS3hhHH3VtmLlX5dtnqXRigjAOfBcJVrP02gd"
    "FmDAo+URRss+Eiv84/318YH6p/vAUQp0VIAXHHixAvQxCjQvwEsU6KoCvMyApunD7wMgRh0HBRhy4JWEAwJrflRblnQF"
    "jkcjv16eTeX7f2Fqkn8UKwuvlsQaOh3OwGtR/wosn+mmOSyRNJSE10uscdLNUcUijdMbZVZRDLfAiHydN7XMURveJPXG"
    "PcG0tLRmwAm/eUsrZkZxLNJvZU1bCQ6Rr+6BIJysHLtamIK3BDgl0swUz5IXeduHI07heEcAicKxvQAJliOaqipR8PP6"
    "vQqROxD+xit/T153ddYdCSBTUiQFUBxIJVgFIpXf1HOOZhqQjkZ+82LugmypNqg+yBoF+V0Bhr0ft85A/uk/UtpD3O0r"
    "e4aiYwhgOpD1KrtLYiAduEtiO2OajgpWiVGc/tVwwOYDPKnUDoPT1bHCnyuLTcsqv/KPlMR1y1pW+kdXk70Ip9kho1qS"
    "HDnG17MXcnu09/ygnKFBGRfgLA1KdQHeZ4mglVg2/2UGikCeXnJCgEkHziVyRfggEf4DIgLPoQ=="
)


class _Tagged(FieldDStar):
    """A subclass with an instance __dict__ (no __slots__ of its own)."""


def _history() -> FieldDStar:
    planner = FieldDStar(np.ones((3, 4)))
    planner.plan((0, 0), (3, 4))
    planner.update_costs([(1, 1)], np.inf)
    return planner


@pytest.mark.parametrize("make_copy", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_a_subclass_keeps_its_attributes_through_copies(make_copy: Callable[[Any], Any]) -> None:
    planner = _Tagged(np.ones((4, 4)))
    planner.label = "kitchen"  # type: ignore[attr-defined]
    twin = make_copy(planner)
    assert type(twin) is _Tagged
    assert getattr(twin, "label", None) == "kitchen"


@pytest.mark.parametrize("make_copy", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_a_subclass_copy_plans_as_the_original(make_copy: Callable[[Any], Any]) -> None:
    planner = _Tagged(np.ones((4, 4)))
    first = planner.plan((0, 0), (4, 4))
    twin = make_copy(planner)
    twin.update_costs([(1, 1)], np.inf)
    planner.update_costs([(1, 1)], np.inf)
    a, b = planner.replan(), twin.replan()
    assert a.cost == b.cost and np.array_equal(a.points, b.points)
    assert b.cost > first.cost


def test_a_pickle_made_before_the_node_records_loads_and_replans() -> None:
    old = pickle.loads(zlib.decompress(base64.b64decode("".join(_OLD_PICKLE))))
    fresh = _history()
    assert old.shape == fresh.shape
    np.testing.assert_array_equal(old.costs, fresh.costs)
    # The pending change (cell (1, 1) blocked) is repaired as by a planner that lived
    # through the same history here.
    a, b = old.replan(), fresh.replan()
    assert a.cost == pytest.approx(b.cost, rel=1e-12)
    np.testing.assert_allclose(a.points, b.points, rtol=0, atol=1e-12)
    # And it plans on afterwards.
    c, d = old.plan((3, 0), (0, 4)), fresh.plan((3, 0), (0, 4))
    assert c.cost == pytest.approx(d.cost, rel=1e-12)


@pytest.mark.parametrize("make_copy", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_a_copy_keeps_the_heap_keys_aligned_as_a_fresh_planner(
    make_copy: Callable[[Any], Any],
) -> None:
    # Speed only: node_records places the keys at a fixed offset in a cache line.
    planner = FieldDStar(np.ones((9, 7)))
    planner.plan((0, 0), (9, 7))
    twin = make_copy(planner)
    fresh_keys, twin_keys = planner._heap[1], twin._heap[1]
    assert twin_keys.ctypes.data % 64 == fresh_keys.ctypes.data % 64
    np.testing.assert_array_equal(twin_keys, fresh_keys)
    assert np.shares_memory(twin._g, twin._vals) and np.shares_memory(twin._rhs, twin._vals)
