"""What one write may cost the reasoner: bounds on the TBox change it makes (issue 26, item 1d).

A write that changes the TBox (a subclass, a domain, a member of an intersection's RDF list...)
recompiles it and re-reasons its model under the KB lock, while every other read and write
waits. The hierarchy the compiler closes grows with the square of a chain's length (2,000
classes, each a subclass of the next: 2 million links, 9 s and 850 MB), and each schema triple is
read and compiled (an RDF list of 200,000 items: 12 s). So a write is refused, before anything
changes (``TBoxTooLarge``), when it changes more than ``max_triples`` schema triples of one model,
or when the TBox it would make gives a class or a property more than ``max_depth`` superclasses
or superproperties, or more than ``max_links`` such links in all. The closure stops as soon as a
bound is passed, so a refusal costs no more than the bounds allow. Recovery replays what was
accepted without them.
"""

from __future__ import annotations

from dataclasses import dataclass

from kb.errors import KbError, TBoxTooLarge


@dataclass(frozen=True)
class TBoxBounds:
    """The most one write may make the reasoner do (see the module)."""

    max_triples: int = 20_000
    max_links: int = 50_000
    max_depth: int = 256

    def __post_init__(self) -> None:
        for name in ("max_triples", "max_links", "max_depth"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise KbError(f"{name} must be a positive integer, got {value!r}")

    def check_triples(self, count: int, model: str) -> None:
        if count > self.max_triples:
            raise TBoxTooLarge(f"the write changes {count} schema triples of model {model!r} (subclasses, "
                               f"subproperties, domains, ranges, RDF list items...); one write may change "
                               f"at most {self.max_triples}: each recompiles the TBox and re-reasons the "
                               "model while the KB waits. Nothing was written")


@dataclass
class LinkCount:
    """The links a closure has made so far, against the bounds."""

    bounds: TBoxBounds
    total: int = 0

    def add(self, term: object, count: int, kind: str) -> None:
        if count > self.bounds.max_depth:
            raise TBoxTooLarge(f"the write would give {term} more than {self.bounds.max_depth} {kind} (a "
                               f"hierarchy that deep costs the reasoner too much); nothing was written")
        self.total += count
        if self.total > self.bounds.max_links:
            raise TBoxTooLarge(f"the write would make the TBox's closed hierarchy hold more than "
                               f"{self.bounds.max_links} {kind} links (it grows with the square of a "
                               f"chain's length); nothing was written")
