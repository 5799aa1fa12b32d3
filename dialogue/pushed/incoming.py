"""An intent pushed from outside the service's own turns (`POST /intents`: a read replica's turns,
another process of the deployment), checked before the bus numbers it.

What the service emits itself is built to the contract (dialogue.intents.make_intent, referents
resolved against the KB); an intent that arrives whole must meet the same contract: an
hri_actions_msgs/Intent constant with its required roles and no others, every role that names an
entity (the catalogue's grounded roles) naming something the KB knows, the other roles any JSON within
dialogue.jsonvalues' bounds (the Intent model's check), and, with its response and
dialogue id, at most `max_bytes` of JSON (the bus keeps it, and every client that reads the buffer
gets it).
"""

from __future__ import annotations

from dialogue.errors import DialogueError
from dialogue.intents import IntentError, make_intent, spec_of
from dialogue.pushed.events import Emitted
from kb import KbError
from kb.protocol import KnowledgeBase
from kb.terms import format_term, parse_name


class IncomingError(DialogueError, ValueError):
    """An intent that breaks the Intent contract or names what the KB does not know."""


class IncomingTooLarge(IncomingError):
    """An intent larger than the bound of one pushed intent."""


def check_incoming(kb: KnowledgeBase, emitted: Emitted, max_bytes: int) -> None:
    """Refuse `emitted` (IncomingTooLarge, IncomingError saying what is wrong) unless the bus may
    take it. Blocking: the grounded roles are looked up in the KB."""
    size = emitted.size
    if size > max_bytes:
        raise IncomingTooLarge(f"the intent with its response is {size} bytes of JSON; the limit is "
                               f"{max_bytes} bytes (intents.max_intent_bytes)")
    intent = emitted.intent
    try:
        make_intent(intent.intent, dict(intent.data), source=intent.source, confidence=intent.confidence,
                    modality=intent.modality, priority=intent.priority)
    except IntentError as exc:
        raise IncomingError(str(exc)) from None
    for role in spec_of(intent.intent).grounded:
        value = intent.data.get(role)
        if isinstance(value, str) and value.strip():  # text: the Intent model holds to it
            _known(kb, role, value)


def _known(kb: KnowledgeBase, role: str, value: str) -> None:
    try:
        term = format_term(parse_name(value, role))
    except KbError as exc:
        raise IncomingError(f"{role} {value!r} is not a KB id: {exc}") from None
    if not (kb.exist([f"{term} ?p ?o"]) or kb.exist([f"?s ?p {term}"])):
        raise IncomingError(f"{role} {value!r} names nothing in the KB: an intent's referents are KB "
                            "entities")
