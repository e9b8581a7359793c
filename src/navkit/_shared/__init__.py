"""Private helpers shared by every navkit layer (not part of the public API).

The bottom layer of the package: argument validation and array aliases
(:mod:`.validation`, :mod:`.types`), numba compilation options (:mod:`.jit`),
SE(2) scalar kernels (:mod:`.se2`), Bresenham line kernels (:mod:`.lines`),
the traversal-cost convention's validator (:mod:`.costs`) and matrix products
safe from overflowing partial sums (:mod:`.products`). Modules here import
nothing from navkit except :mod:`navkit.errors` and each other.
"""
