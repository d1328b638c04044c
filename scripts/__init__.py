"""Generators of the project's generated files (docs/validation.md, the samples, the export
examples, the method-uncertainty table, figures).

Each module is run from the repository root as ``python -m scripts.<name>``
(``python -m scripts.make_validation``). They may import ``benchmarks``, ``validation`` and
``stripcoef``, never ``tests`` (the layer contract of docs/architecture.md).
"""
