"""The one error type of the knowledge base (knowledge_core's ``KbError``)."""


class KbError(Exception):
    """A request the KB cannot carry out; the message says what is wrong and where.

    When a batch raises it, nothing of the batch has been written.
    """
