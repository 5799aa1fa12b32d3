"""What one write may cost the reasoner in derivations (issue 26: transitive chains).

kb.tboxbudget bounds what a write's TBox change costs; this bounds what its ABox facts cost. A
chain of facts along a transitive property closes into the square of its length (300 statements
``o_i behind o_i+1``, with the inverse ``inFrontOf``: 364,000 inferred triples, 23 s under the
KB lock; 400: 60 s, every query answering 503 meanwhile). So the reasoner counts its derivation
steps (each consequence it considers, and one more for each triple it adds to the closure or
takes out of it: the indexes' work, and taking it back if the write is refused) and a write past
its allowance is refused with
``ReasoningTooLarge``, every model as it was. The allowance grows with the write: ``max_steps``
plus ``per_statement`` for each statement it asserts or retracts, so a bulk load that derives a
few triples per statement passes while a small write that derives without end does not.
Recovery replays what was accepted without a budget: each record was within it.
"""

from __future__ import annotations

from dataclasses import dataclass

from kb.errors import KbError, ReasoningTooLarge


@dataclass(frozen=True)
class ReasoningBounds:
    """Derivation steps one write may take (see the module)."""

    max_steps: int = 200_000
    per_statement: int = 16

    def __post_init__(self) -> None:
        for name in ("max_steps", "per_statement"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise KbError(f"{name} must be a positive integer, got {value!r}")

    def allowance(self, statements: int) -> int:
        """The steps a write of ``statements`` asserted or retracted statements may take."""
        return self.max_steps + self.per_statement * statements


class StepBudget:
    """The steps one write has left; the reasoner spends them as it derives."""

    __slots__ = ("allowed", "left")

    def __init__(self, allowed: int) -> None:
        self.allowed = allowed
        self.left = allowed

    def spend(self, steps: int) -> None:
        self.left -= steps
        if self.left < 0:
            raise ReasoningTooLarge(
                f"the write would take the reasoner more than {self.allowed} derivation steps (facts along "
                "a transitive property close into the square of their chain's length); write it in "
                "smaller parts, or fewer facts along that property. Nothing was written")
