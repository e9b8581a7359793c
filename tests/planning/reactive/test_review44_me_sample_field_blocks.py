"""sample_field evaluates its window a block of cells at a time (review 44).

CI's slow fuzz drew a window of 3.2e7 cells (``ylim = ±5e5`` m at 0.25 m): the
whole grid of points, the fields' temporaries and the record's copies of the
results, 128 bytes a cell, did not fit the fuzz's 3 GiB of address space
(MemoryError, a broken promise), and the documented maximum of 2**26 cells
needed 8 GiB.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from memory_peak import peak_bytes
from navkit.planning import (
    ConicAttraction,
    KhatibRepulsion,
    SampledField,
    sample_field,
)
from subprocess_probe import probe_outcome


def test_peak_is_the_results_plus_a_block_whatever_the_fields_temporaries() -> None:
    # 40 obstacles: the field's temporaries grow with points × obstacles. Over the
    # whole grid the peak was 3.7 times the results (44 MB for 12 MB); a block's
    # temporaries are a few MiB on top of the results themselves (18 MB).
    obstacles = np.column_stack((np.linspace(0.0, 40.0, 40), np.zeros(40)))
    field = KhatibRepulsion(obstacles, influence_radius=2.0)
    peak, sampled = peak_bytes(
        lambda: sample_field(field, xlim=(0.0, 40.0), ylim=(-10.0, 10.0), resolution=0.04)
    )
    size = sampled.potential.nbytes + sampled.force.nbytes
    assert sampled.shape == (500, 1000)
    assert peak < size + (8 << 20), f"peak {peak / 1e6:.1f} MB for {size / 1e6:.1f} MB"


@pytest.mark.parametrize("shape", [(1, 70_000), (3, 65_537), (257, 255), (70_000, 1)])
def test_blocks_give_the_values_at_every_centre_in_meshgrid_order(
    shape: tuple[int, int],
) -> None:
    # Windows of more than one block (2**14 cells), with a block's end inside a row
    # and rows longer than a block.
    field = ConicAttraction((0.3, -0.7)) + KhatibRepulsion([[0.1, 0.2]], influence_radius=5.0)
    res = 0.01
    sampled = sample_field(
        field,
        xlim=(-1.0, -1.0 + shape[1] * res),
        ylim=(-2.0, -2.0 + shape[0] * res),
        resolution=res,
    )
    assert sampled.shape == shape
    gx, gy = np.meshgrid(sampled.x, sampled.y)
    pts = np.stack((gx.ravel(), gy.ravel()), axis=1)
    assert np.array_equal(sampled.potential, field.potential(pts).reshape(shape))
    assert np.array_equal(sampled.force, field.force(pts).reshape((*shape, 2)))


def test_the_record_holds_read_only_arrays_it_alone_owns() -> None:
    sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(0, 1), ylim=(0, 1), resolution=0.5)
    assert isinstance(sampled, SampledField)
    for arr in (sampled.x, sampled.y, sampled.potential, sampled.force):
        assert not arr.flags.writeable
        assert arr.base is None  # no view of a buffer anyone else holds


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux's /proc")
def test_the_documented_maximum_fits_the_fuzzs_address_space() -> None:
    # 2**26 cells (8 × 8,388,608) under the fuzz's cap: the process's size + 3 GiB.
    outcome = probe_outcome(
        """
import json, resource
import numpy as np
from navkit.planning import BlendedAttraction, sample_field
field = BlendedAttraction(np.array([1.0, 0.5]), threshold_radius=1.0, width=0.1)
sample_field(field, xlim=(-1.0, 1.0), ylim=(-1.0, 1.0), resolution=0.5)
with open("/proc/self/status") as f:
    size = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize"))
resource.setrlimit(resource.RLIMIT_AS, (size + (3 << 30), resource.RLIM_INFINITY))
sampled = sample_field(field, xlim=(-1.0, 1.0), ylim=(-1048576.0, 1048576.0), resolution=0.25)
print(json.dumps([*sampled.shape, bool(np.isfinite(sampled.force).all())]))
""",
        timeout=600,
    )
    assert outcome == [8_388_608, 8, True]
