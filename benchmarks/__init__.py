"""Benchmarks: the measurements behind docs/performance.md and docs/validation.md.

Each module is a script run from the repository root as ``python -m benchmarks.<name>``
(``python -m benchmarks.bluff_shapes``). They import ``stripcoef`` and ``validation`` (the
bodies and stored references they share with the tests live in validation/), and each other,
never ``scripts`` or ``tests`` (the layer contract of docs/architecture.md).
"""
