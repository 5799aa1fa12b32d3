"""What models may cost: the KB's bounds on how many models it holds and on what one holds.

Every model (knowledge_core's "minds": one per agent, made by the first write that names it) starts
as a copy of the ontology's closure, about a megabyte with the default ontology, and grows with
what is written into it. So a KB may bound both: `max_models`, the models it holds (the robot's
own, ``default``, included), and `max_statements`, the statements a model other than the robot's
holds of its own (beyond the ontology's). A write past either is refused whole (`ModelLimit`,
saying which bound): refused means nothing changed. The robot's model is the KB itself and has no
such bound; journal recovery replays what was written under any bound.
"""

from __future__ import annotations

from dataclasses import dataclass

from kb.batch import Batch
from kb.errors import KbError, ModelLimit
from kb.models import DEFAULT_MODEL, Models


def _bound(value: int | None, name: str) -> int | None:
    if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
        raise KbError(f"{name} must be a positive integer or None, got {value!r}")
    return value


@dataclass(frozen=True)
class ModelBounds:
    """None: no bound."""

    max_models: int | None = None
    max_statements: int | None = None

    def __post_init__(self) -> None:
        _bound(self.max_models, "max_models")
        _bound(self.max_statements, "max_model_statements")

    def check(self, models: Models, batch: Batch) -> None:
        """Refuse the batch (ModelLimit) when it would pass a bound; call under the KB lock."""
        names = list(dict.fromkeys(batch.models))
        new = [name for name in names if models.get(name) is None]
        if self.max_models is not None and new and len(models.names) + len(new) > self.max_models:
            raise ModelLimit(f"the KB holds {len(models.names)} models and this write would add "
                             f"{len(new)} ({', '.join(repr(n) for n in new[:5])}); the limit is "
                             f"{self.max_models} (the KB's max_models; the service's "
                             "limits.max_total_models)")
        if self.max_statements is not None:
            for name in names:
                if name != DEFAULT_MODEL:
                    self._check_size(models, batch, name, self.max_statements)

    @staticmethod
    def _check_size(models: Models, batch: Batch, name: str, limit: int) -> None:
        model = models.get(name)
        held = model.asserted if model is not None else set(models.defaults)
        own = len(held) - len(models.defaults)
        added = {t for t in (*batch.add, *batch.add_by_model.get(name, ())) if t not in held}
        removed = {t for t in (*batch.remove, *batch.remove_by_model.get(name, ())) if t in held}
        after = own + len(added) - len(removed - added)
        if after > limit and after > own:  # a model already past it may still shrink
            raise ModelLimit(f"model {name!r} would hold {after} statements of its own; the limit is {limit} "
                             "(the KB's max_model_statements; the service's limits.max_model_statements)")
