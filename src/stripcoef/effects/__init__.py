"""Effects: force laws the strip-theory model lacks (tether drag, current, dead band ...).

One registry, :data:`EFFECTS` (name -> effect), read by ``simulate`` (the forces of a
model's effects) and by ``diagnose`` (each effect's identification basis over log
windows, :mod:`.windows`).

Depends on: model, logfile, base.
"""

from stripcoef.effects.laws import EFFECTS, Effect, effect_forces, get_effect

__all__ = ["EFFECTS", "Effect", "effect_forces", "get_effect"]
