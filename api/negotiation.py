"""HTTP content negotiation: pick the best offered media type for an ``Accept`` header."""

from __future__ import annotations

from collections.abc import Sequence

from api.errors import ApiError
from kb.formats import TABLE, find_format, rdf_format

#: The media types an RDF document may be sent as (POST /kb/load).
RDF_UPLOAD_TYPES = tuple(fmt.media_type for fmt in TABLE)


def _ranges(accept: str) -> list[tuple[str, float]]:
    ranges = []
    for part in accept.split(","):
        media, *params = (p.strip() for p in part.split(";"))
        if not media:
            continue
        quality = 1.0
        for param in params:
            name, _, value = param.partition("=")
            if name.strip().lower() == "q":
                try:
                    quality = float(value)
                except ValueError:
                    quality = 0.0
        ranges.append((media.lower(), quality))
    return ranges


def _quality(offer: str, ranges: list[tuple[str, float]]) -> float:
    kind = offer.split("/")[0]
    best, specificity = 0.0, -1
    for media, quality in ranges:
        if media == offer:
            level = 2
        elif media == f"{kind}/*":
            level = 1
        elif media == "*/*":
            level = 0
        else:
            continue
        if level > specificity:
            best, specificity = quality, level
    return best


def negotiate(accept: str | None, offers: Sequence[str]) -> str:
    """The offer the client prefers (the first offer on a tie, or when there is no Accept);
    406 with the offers listed when none is acceptable."""
    if not accept or not accept.strip():
        return offers[0]
    ranges = _ranges(accept)
    scored = [(_quality(offer, ranges), -i, offer) for i, offer in enumerate(offers)]
    quality, _, offer = max(scored)
    if quality <= 0:
        raise ApiError(406, "not_acceptable",
                       f"cannot answer with {accept!r}; available: {', '.join(offers)}",
                       {"available": list(offers)})
    return offer


def upload_format(format: str | None, content_type: str | None) -> str:
    """The canonical RDF format of an uploaded document: ``?format=`` (any name of a format; an
    unknown one is the KB's error) or else its Content-Type (415 when it names no RDF format)."""
    if format:
        return rdf_format(format).name
    # Only media types name a format in a Content-Type (not "turtle" or "json").
    found = find_format(content_type or "") if "/" in (content_type or "") else None
    if found is not None:
        return found.name
    raise ApiError(415, "unsupported_media_type",
                   f"send the document as one of {', '.join(RDF_UPLOAD_TYPES)} (or give ?format=)",
                   {"accepted": list(RDF_UPLOAD_TYPES)})
