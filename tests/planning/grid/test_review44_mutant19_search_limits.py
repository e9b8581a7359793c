"""The grid searches' size limits at their exact boundary (review 44, MUTANT19's mutants).

The searches index cells with int32 (``MAX_NODES = 2**31 - 1``): a grid of
exactly that many cells is within the documented range, one more is refused.
The public entry points refuse larger grids before converting them
(:func:`~navkit.planning.grid._limits.converted_costs`), and a grid at the
maximum would need 16 GiB to search, so the boundary is tested on the private
checks themselves, with broadcast views that take no memory. Mutants that
refused the maximum itself (``>`` turned into ``>=``) survived every test.
The maximum is the documented number, not the modules' constant.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning.grid._arguments import check_search_size
from navkit.planning.grid._limits import check_node_count

# The documented maximum, written out: the checks' shared constant is under test too.
MAX_NODES = 2**31 - 1


def test_the_search_size_check_admits_the_maximum_and_refuses_one_more() -> None:
    # 2**31 - 1 is prime: (MAX_NODES, 1) is the only shape with exactly that many cells.
    check_search_size(np.broadcast_to(1.0, (MAX_NODES, 1)))
    refusal = rf"^grid has {MAX_NODES + 1} cells; .* at most {MAX_NODES}$"
    with pytest.raises(ValueError, match=refusal):
        check_search_size(np.broadcast_to(1.0, (MAX_NODES + 1, 1)), "grid")


@pytest.mark.parametrize("unit", ["cells", "nodes"])
def test_the_node_count_check_admits_the_maximum_and_refuses_one_more(unit: str) -> None:
    check_node_count(MAX_NODES, "A search", 33, unit)
    with pytest.raises(ValueError, match=rf"the maximum is 2\*\*31 - 1 = {MAX_NODES} {unit}$"):
        check_node_count(MAX_NODES + 1, "A search", 33, unit)
