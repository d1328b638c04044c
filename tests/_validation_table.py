"""The whole-log validation (:func:`stripcoef.diagnose.validate.validate_changes`) scored from
a table instead of free simulations: the RMS error of each DOF by the set of changes kept,
the model surgery replaced by the set itself, so that a test checks a validation rule alone
(tests/test_diagnose_validate_skill.py, tests/test_diagnose_validate_own.py)."""

import numpy as np

from stripcoef.diagnose import heldout, validate

#: The prior model as the table's scorer sees it (no change kept)
PRIOR = "prior"


def install(monkeypatch, changes, table, missing=None, trivial=None):
    """Patch the validation to read ``table`` ({frozenset of kept changes: RMS errors per
    DOF}) for the ``changes``; a set the table lacks scores ``missing`` (None: a KeyError);
    ``trivial`` ({"hold": [...], "zero": [...]}) replaces the trivial predictors' errors."""
    def sse(val_log, model, dofs, **_):
        kept = frozenset() if model == PRIOR else frozenset(changes) - model[1]
        e = table[kept] if missing is None else table.get(kept, missing)
        return np.array([[x * x for x in e]] * 4), np.ones(4)

    monkeypatch.setattr(validate, "_changes", lambda per: list(changes))
    monkeypatch.setattr(validate, "calibrated_model",
                        lambda prior, per, fits, key: ("model", frozenset(key)))
    monkeypatch.setattr(heldout, "segment_squared_errors", sse)
    if trivial is not None:
        monkeypatch.setattr(heldout, "hold_last_velocity_errors",
                            lambda log, dofs, **_: list(trivial["hold"]))
        monkeypatch.setattr(heldout, "zero_velocity_errors",
                            lambda log, dofs, **_: list(trivial["zero"]))
