"""Geometry: vehicle files (profiles, appendages, holes, mass, thrusters) and meshes.

A *body* is anything with ``name``, ``x_extent() -> (x_min, x_max)`` and
``parts(x, dx) -> list[Part]`` (see :mod:`stripcoef.strips`); the hull profile,
each appendage and a CAD mesh all follow it, so strips are cut the same way for all.
"""
