r"""Whether an out-of-library shape is needed beyond the library effect it would veto.

The selection (:func:`stripcoef.diagnose.select.diagnose_dof`) weighs each step's best
library effect against the best one-column shape outside the library
(``select._generic_shapes``: sign(v), v^3, sqrt(|v|) v, |f|, sin of an angle) and stops
when the shape's held-out error is lower: a residual that a shape outside the library
explains better is not given to a library effect (issue 33: dry friction named a linear
drag). Compared on their held-out errors alone, two columns that explain the same residual
are two non-nested models (Atkinson 1970; Davidson & MacKinnon 1981): the smaller error
of one of them says which fits this noise better, not that the other is wrong. A shape in
the span of the published laws is then a coin toss against the law: with the DOF's
quadratic drag calibrated, :math:`\sqrt{|v|}\,v` lies between :math:`v` and
:math:`v|v|`, and the drag law of the identified ROV models is exactly their sum,
:math:`X_u u + X_{u|u|} u|u|` (Wang & Clark 2006, eq. 7; Indiveri 1998, sec. 4.2.1, eq.
4.13, linear and quadratic drag identified together by least squares); Eng et al. (2009,
sec. IV, Table IV and Figs. 9-10) compare the identified linear and quadratic damping only
through the total drag curve, because the two trade against each other over the speeds of
a test. Issue 33, seed 28112027: two linear-drag logs (BlueROV2 28213032, VideoRay
28212032) whose linear drag passed every gate of a step (z 4.5 and 7.7, held-out gains 12
and 27 %) were vetoed by sqrt(|v|) v with held-out errors 0.7 and 3 % lower.

The test (:func:`needed_beyond`): the comprehensive model holding the effect and the shape
(Atkinson 1970), and the shape's evidence as a step on top of the effect's model -- the
test every step passes (:func:`stripcoef.diagnose.evidence.step_test`: the likelihood
ratio on the effective number of windows, Bretherton et al. 1999 eq. 31) at the step's
family level (:func:`stripcoef.diagnose.evidence.family_level`: ALPHA = 5 % over the DOFs
of a whole-log run). The veto stands only when the shape is needed beyond the effect; a
shape the effect's model leaves nothing to explain is not evidence against the effect. No
threshold is new: the level and the test are the selection's own.

Depends on: diagnose.fit, diagnose.evidence.
"""

from __future__ import annotations

import numpy as np

from stripcoef.diagnose.evidence import family_level, step_test
from stripcoef.diagnose.fit import _evaluate, _Generic


def needed_beyond(cfg, ev: dict, shapes, shape: dict, n_dofs: int = 1) -> dict | None:
    """The test of out-of-library ``shape`` (``select._best_shape``'s record) as a step on
    top of the model ``cfg`` (a :class:`~stripcoef.diagnose.fit._Config` holding the library
    effect, evaluated: ``ev``): ``{"statistic", "p_value", "level", "needed", ...}``
    (:func:`~stripcoef.diagnose.evidence.step_test`'s record, ``needed`` when its p-value is
    at most the step's level); None when the shape is not among ``shapes`` (``(name,
    description, column)`` triples, ``select._generic_shapes``) or cannot be fitted."""
    col = next((c for n, _, c in shapes if n == shape["shape"]), None)
    if col is None:
        return None
    try:
        joint = _evaluate(cfg.with_terms(list(cfg.terms)
                                         + [(_Generic(np.asarray(col, float)[:, None]), None)]))
    except (np.linalg.LinAlgError, ValueError):
        return None
    test = step_test(ev, joint, 1)
    level = family_level(n_dofs)
    return {**test, "level": level, "needed": bool(test["p_value"] <= level),
            "held_out_error_joint": float(joint["held_out_error"]),
            "method": "the shape as a step on top of the effect's model (Atkinson 1970's "
                      "comprehensive model; evidence.step_test at the step's level)"}


def vetoes(cfg, ev: dict, shapes, shape: dict, n_dofs: int = 1) -> bool:
    """Whether ``shape``, which beat the library effect of ``cfg`` (evaluated ``ev``) on
    the held-out error, vetoes it: only when it is needed beyond it (:func:`needed_beyond`,
    recorded in ``shape["needed_beyond_effect"]``); a shape that cannot be tested keeps the
    veto (the selection's rule before this test)."""
    test = needed_beyond(cfg, ev, shapes, shape, n_dofs)
    shape["needed_beyond_effect"] = test
    return test is None or test["needed"]
