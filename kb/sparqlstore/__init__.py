"""The SPARQL 1.1 store backend: a KB mirrored to, or read back from, a remote store."""
