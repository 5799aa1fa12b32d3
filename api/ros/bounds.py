"""The service's limits on what one ROS request may carry, as REST has them.

REST bounds a request by its counts (patterns, statements, models) and by its body's size; a ROS
message has no body limit of its own, so the text a request carries (every string of it) is held
to the same number: ``limits.max_body_bytes`` characters.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from api.errors import ApiError
from api.limits import check_count
from api.settings import Limits


class RequestBounds:
    def __init__(self, limits: Limits) -> None:
        self.limits = limits

    def check(self, *, patterns: Sequence[str] = (), statements: Sequence[str] = (),
              models: Sequence[str] = (), texts: Iterable[str] = ()) -> None:
        """``ApiError`` (413, ``too_many_<what>`` or ``request_too_large``) past a limit."""
        check_count(patterns, self.limits.max_patterns, "patterns")
        check_count(statements, self.limits.max_statements, "statements")
        check_count(models, self.limits.max_models, "models")
        size = sum(len(text) for group in (patterns, statements, models, texts) for text in group)
        limit = self.limits.max_body_bytes
        if size > limit:
            raise ApiError(413, "request_too_large",
                           f"the request carries {size} characters of text; the limit is {limit} "
                           "(limits.max_body_bytes, as for a REST request's body)",
                           {"length": size, "limit": limit})
