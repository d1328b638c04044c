"""Which shape class a vehicle belongs to: :mod:`stripcoef.geometry.shape_class` (the rule and
its numbers live in the geometry layer, where the added-mass ``auto`` rule reads them too;
this module keeps the study's import path)."""

from stripcoef.geometry.shape_class import (CLASSES, FINNED_ROUND,  # noqa: F401
                                            FINNED_SLENDERNESS, OPEN_FILL, REVOLUTION_ROUND,
                                            ROUND_TOL, classify, features, shape_class,
                                            strip_features)
