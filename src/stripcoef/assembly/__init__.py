"""⑤ Assembly: strips, sections and hull terms into one :class:`~stripcoef.model.HydroModel`.

:mod:`.mass` (displaced volume, mass properties), :mod:`.added_mass` (per-strip section
matrices, the strip integral with its 3D corrections, entrained water), :mod:`.damping`
(cross-flow, friction and form drag) and :mod:`.estimate` (the pipeline function).

Depends on: hull, sections, geometry, strips, model, base.
"""

from stripcoef.assembly.estimate import EstimateOptions, estimate

__all__ = ["EstimateOptions", "estimate"]
