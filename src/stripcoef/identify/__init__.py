"""Identification from measured data: the papers' methods with honest error bars.

- :mod:`.estimators` - linear least squares core (:class:`FitResult`, :func:`linear_lstsq`)
- :mod:`.steady` - steady-state regression (Caccia, Indiveri 1998, eqs. 4.15-4.17; yaw LQB..LNB)
- :mod:`.onestep` - one-step-ahead prediction least squares (Wang & Clark, Wang & Clark 2006, eqs. 8-19)
- :mod:`.pendulum` - free-decay pendulum and torsion pendulum (Eng et al., Eng et al. 2009, eqs. 1-7, 12)
- :mod:`.scaling` - similitude from a scaled model to full scale (Eng et al. 2009, eqs. 8-10)
"""

from stripcoef.identify.estimators import FitResult, linear_lstsq, residual_autocorrelation, runs_test_z

__all__ = ["FitResult", "linear_lstsq", "residual_autocorrelation", "runs_test_z"]
