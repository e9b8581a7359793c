"""Review 49 mutation review (MUTANT29): the Field D* heap's key bits with the JIT off.

The descent's tournament compares first key components as their bit patterns
(review 48), read with numba's bitcast when compiled and with NumPy's view
when ``NUMBA_DISABLE_JIT=1``. Those patterns must be unsigned: a negative key
or -0.0 sets the sign bit, which sends the family to the float comparison.
Read as int64 in the Python fallback (a mutant that survived every test, the
review-48 tests running the heap compiled only), a negative pattern is below
2**63 as a float, no tie is taken, and the signed patterns of negative keys
order backwards: the heap popped -1 before -40. Pops of distinct keys here
must come out in float order with the JIT off as on.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from subprocess_probe import jit_outcome

# Distinct keys (no tie between two whole keys): negative first components in
# full families at every level, then -0.0 beside +0.0 (one first component as
# floats) with distinct second components, then non-negative ones.
_PROBE = """
import json
import numpy as np
from navkit.planning.grid._dstar_heap import heap_new, heap_pop, heap_push
rng = np.random.default_rng(49)
keys = [(-float(v), float(v % 3)) for v in rng.permutation(np.arange(1, 41))]
keys += [(-0.0 if i % 2 else 0.0, float((7 * i) % 23) + 0.5 * i) for i in range(20)]
keys += [(float(v), 1.0) for v in rng.permutation(np.arange(1, 21))]
nodes, heap_keys, pos, size = heap_new(len(keys))
for node, (k0, k1) in enumerate(keys):
    heap_push(nodes, heap_keys, pos, size, node, k0, k1)
order = [heap_pop(nodes, heap_keys, pos, size) for _ in keys]
want = sorted(range(len(keys)), key=lambda n: keys[n])
print(json.dumps([order, want]))
"""


def test_the_heap_pops_signed_keys_in_float_order_with_the_jit_off() -> None:
    order, want = jit_outcome(_PROBE, disable_jit=True)
    assert sorted(order) == sorted(want)
    assert order == want
