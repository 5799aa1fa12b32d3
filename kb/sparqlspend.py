"""What the expressions of one SPARQL query may build: a bound on each string and on all of them.

The time budget stops a query between solutions and inside joins, but one expression can build a
huge string without reading anything: ``BIND(CONCAT(?v, ?v) AS ?w)`` doubles a string, and
thirty of them in under 1 KB of query ask for a gigabyte. So every string an expression builds
is measured: CONCAT and REPLACE before they build it (they multiply their inputs), every other
function on its result (none makes more than a few times its input). One string longer than
``max_string`` characters, or more than ``max_total`` characters over the whole query in strings
of at least ``LARGE`` characters (rows retaining big strings) and in GROUP_CONCAT's values (kept
until they are joined), stops the query with ``QueryTooLarge``. Other small strings are bounded
by the time budget like any other per-row work.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from kb.errors import QueryTooLarge

#: Characters of the longest string an expression may build.
MAX_STRING = 1 << 20
#: Characters of all the large strings the expressions of one query may build together.
MAX_TOTAL = 1 << 25
#: Strings at least this long count towards the total.
LARGE = 4096


@dataclass
class Spend:
    """The characters one query's expressions have built so far."""

    max_string: int = MAX_STRING
    max_total: int = MAX_TOTAL
    total: int = field(default=0, init=False)

    def string(self, length: int, what: str) -> None:
        """Account for a string of ``length`` characters that ``what`` builds (or is about to)."""
        if length > self.max_string:
            raise QueryTooLarge(f"the query's {what} builds a string of {length} characters; the limit is "
                                f"{self.max_string} characters per string")
        if length >= LARGE:
            self.kept(length, what)

    def kept(self, length: int, what: str) -> None:
        """Account for ``length`` characters that ``what`` keeps until the query ends, however
        short each piece (GROUP_CONCAT's values, joined at the end)."""
        self.total += length
        if self.total > self.max_total:
            raise QueryTooLarge(f"the query's expressions build more than {self.max_total} characters of "
                                f"strings in all (the last by its {what}); make it more specific")
