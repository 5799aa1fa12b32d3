"""situated's knowledge base: a knowledge_core-compatible OWL/RDF KB with incremental reasoning.

``from kb import KB; kb = KB()`` gives a ready KB with the default ORO-compatible ontology.
"""

from kb.errors import KbError
from kb.kb import KB
from kb.sugar import __version__

__all__ = ["KB", "KbError", "__version__"]
