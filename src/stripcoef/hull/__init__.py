"""④ Hull-level terms: what strip theory cannot see section by section.

Lamb's ellipsoid coefficients (:mod:`.lamb`), the axisymmetric panel solver that gives the
3D added mass of a body of revolution (:mod:`.axisymmetric`), the 3D end corrections built
on it (:mod:`.corrections`) and the member decomposition of open frames (:mod:`.members`).

Depends on: sections, geometry, strips, base.
"""
