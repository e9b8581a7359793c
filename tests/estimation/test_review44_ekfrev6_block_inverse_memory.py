"""R's refined inverse held as its blocks (review 44, EKFREV6).

The information-form finish (``_information_update``) refined R⁻¹ one diagonal
block at a time but laid the blocks side by side in four dense m x m arrays (the
inverse, its bound, the scaled R and its refined inverse; 3.2 GB for a diagonal R
of 10,000 beams), found the blocks through ``np.triu(r, 1)`` (another m x m array)
and summed R⁻¹ y's exact residual over 2m + 1 terms a row (a 1000-beam update:
144 MB and 6 s; 2000 beams 360 MB and 22 s). The blocks are now kept as blocks
(``_BlockInverse``): memory and the residual's terms grow with Σ b², not m².
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from memory_peak import peak_bytes


def _scan(m: int, block: int, seed: int = 0) -> tuple[np.ndarray, ...]:
    """3 states, a prior far wider than ``m`` beams in blocks of ``block``, shuffled."""
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    p = (q * 10.0 ** np.linspace(0.0, 10.0, 3)) @ q.T
    p = 0.5 * (p + p.T)
    h = rng.normal(size=(m, 3))
    r = np.zeros((m, m))
    for first in range(0, m, block):
        at = slice(first, min(m, first + block))
        size = at.stop - at.start
        root = rng.normal(size=(size, size))
        r[at, at] = (root @ root.T + size * np.eye(size)) * 10.0 ** rng.uniform(-4.0, -2.0)
    order = rng.permutation(m)
    r = r[np.ix_(order, order)]
    r = 0.5 * (r + r.T)
    y = rng.normal(size=m) * np.sqrt(np.diag(r))
    return p, h, r, y


def test_a_thousand_beams_are_finished_in_memory_far_below_r_itself() -> None:
    p, h, r, y = _scan(1000, 1)
    peak, found = peak_bytes(lambda: kernels._information_update(p, h, r, y))
    assert found is not None and np.isfinite(found.posterior).all()
    # Before: 144 MB (five 8 MB arrays of m x m and the residual's terms); R is 8 MB.
    assert peak < r.nbytes / 4, peak


def test_blocks_of_five_take_memory_in_proportion_to_their_entries() -> None:
    p, h, r, y = _scan(600, 5)
    peak, found = peak_bytes(lambda: kernels._refined_block_inverse(r))
    assert found is not None
    # 600 blocks of 25 entries, four parts each (120 kB), not four 2.9 MB arrays (11.6 MB).
    assert peak < r.nbytes / 8, peak
    # The whole update too.
    peak, info = peak_bytes(lambda: kernels._information_update(p, h, r, y))
    assert info is not None and peak < r.nbytes / 4, peak


@settings(max_examples=30, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    m=st.integers(1, 30),
    block=st.integers(1, 7),
)
def test_the_blocks_act_as_the_dense_block_diagonal_inverse(seed: int, m: int, block: int) -> None:
    _, h, r, y = _scan(m, block, seed)
    found = kernels._refined_block_inverse(r)
    assert found is not None
    inv, bound, scaled, refined = found.dense()
    # Each block is _refined_inverse's of that block, and the rest exactly zero.
    for members in kernels._r_blocks(r):
        at = np.ix_(members, members)
        alone = kernels._refined_inverse(r[at])
        assert alone is not None
        assert inv[at].tobytes() == alone[0].tobytes()
        assert bound[at].tobytes() == alone[1].tobytes()
        assert scaled[at].tobytes() == alone[3][0].tobytes()
        assert refined[at].tobytes() == alone[3][1].tobytes()
        inv[at] = bound[at] = scaled[at] = refined[at] = 0.0
    assert not inv.any() and not bound.any() and not scaled.any() and not refined.any()
    # Its products are the dense block-diagonal matrix's, to their rounding.
    inv, bound, scaled, refined = found.dense()
    for part, dense in ((0, inv), (1, np.abs(inv)), (2, bound)):
        want = h.T @ dense @ h
        scale = np.abs(h).T @ np.abs(dense) @ np.abs(h)
        assert np.all(np.abs(found.sandwich(h, part) - want) <= 2 * (m + 2) * 2.0**-53 * scale)
    v = (y * found.d)[:, None]
    # The refined solve leaves a residual at its rounding: (D R D) w = v to about ε.
    w = found.scaled_solve(v)
    residual = kernels._exact_residual(scaled, w, v)
    assert np.all(np.abs(residual) <= 2.0**-48 * (np.abs(scaled) @ np.abs(w) + np.abs(v)))
    magnitude = np.abs(refined) @ np.abs(v)
    assert np.all(np.abs(found.scaled_magnitude(v) - magnitude) <= (m + 1) * 2.0**-53 * magnitude)


def test_the_blocks_of_a_large_r_are_found_a_few_rows_at_a_time() -> None:
    # R's blocks for 3000 beams (a 72 MB R), joined across the rows' chunks.
    m = 3000
    r = np.eye(m)
    r[5, 2999] = r[2999, 5] = 0.5
    r[1200, 1201] = r[1201, 1200] = 0.5
    peak, blocks = peak_bytes(lambda: kernels._r_blocks(r))
    assert peak < r.nbytes / 8, peak  # before: np.triu(r, 1), a 72 MB copy
    assert [5, 2999] in blocks and [1200, 1201] in blocks and len(blocks) == m - 2
