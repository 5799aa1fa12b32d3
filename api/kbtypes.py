"""The KBs a service process may run on: its own in-process KB (standalone or the writer of a
shared store), or a reader's view of the shared store. Both offer the same knowledge_core API."""

from __future__ import annotations

from typing import TypeAlias

from kb import KB
from kb.sparqlstore.remote import RemoteKB

AnyKB: TypeAlias = KB | RemoteKB
