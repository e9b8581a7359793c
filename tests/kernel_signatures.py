"""Which numba kernels a piece of code compiled, and for how many type signatures.

A kernel compiled for two argument type sets (read-only next to writable
arrays, int32 next to int64, a literal next to a variable) pays its
compilation twice on first use (issue 17); the compile tests run navkit's
entry points in a fresh process, so that only their compilations count, and
read the signatures of every kernel with :func:`compiled_signatures`.
"""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Sequence

_REPORT = """
import importlib as _importlib
import json as _json
from numba.core.dispatcher import Dispatcher as _Dispatcher
_counts = {}
for _name in %r:
    _module = _importlib.import_module(_name)
    for _attr, _value in vars(_module).items():
        if (isinstance(_value, _Dispatcher) and _value.py_func.__module__ == _name
                and _value.signatures):
            _counts[_name.rsplit(".", 1)[1] + "." + _attr] = [str(s) for s in _value.signatures]
print(_json.dumps(_counts))
"""


def compiled_signatures(setup: str, modules: Sequence[str]) -> dict[str, list[str]]:
    """Run ``setup`` in a fresh Python process; the signatures its kernels were compiled for.

    Returns ``{"module.kernel": [signature, ...]}`` (module without its
    package) for every numba kernel defined in ``modules`` that was compiled
    or loaded from the cache at least once.
    """
    out = subprocess.run(
        [sys.executable, "-c", setup + _REPORT % (tuple(modules),)],
        check=True,
        capture_output=True,
        text=True,
    )
    result: dict[str, list[str]] = json.loads(out.stdout.strip().splitlines()[-1])
    return result
