"""A list that contains itself, given as an array: an error, not an endless walk.

NumPy refuses it (more than 64 dimensions) with a ValueError; the checks that
then look for ragged nesting (is_ragged) or, before converting, for booleans
(holds_bool) walked it one level at a time forever. Run in a child process so
that a regression fails the test (timeout) instead of hanging the suite.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

CODE = """
    from navkit._shared.costs import validate_costs
    from navkit._shared.validation import as_array, as_float_array, holds_bool, is_ragged
    from navkit.mapping import OccupancyGrid

    loop = []
    loop.append(loop)
    print(is_ragged(loop), holds_bool(loop))
    calls = {
        "as_array": lambda: as_array(loop, "mask"),
        "as_float_array": lambda: as_float_array(loop, "points"),
        "validate_costs": lambda: validate_costs(loop),
        "from_occupancy": lambda: OccupancyGrid.from_occupancy(loop, resolution=1.0),
    }
    for name, call in calls.items():
        try:
            call()
        except (TypeError, ValueError) as exc:
            print(name, type(exc).__name__)
"""


def test_a_self_containing_list_is_refused() -> None:
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(CODE)],
        check=True, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    lines = out.stdout.split("\n")
    assert lines[0] == "False False"  # not ragged: deeper than any array
    refused = dict(line.split() for line in lines[1:] if line)
    assert set(refused) == {"as_array", "as_float_array", "validate_costs", "from_occupancy"}
    assert refused["as_float_array"] == "TypeError"  # as for other unconvertible values
