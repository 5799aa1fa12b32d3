"""The writer's update requests to the store, each guarded by the id of the write it follows.

Every request the mirror (kb.sparqlstore.mirror) sends names a new write id and applies only where the meta
graph still holds the id of the write it follows: each operation is ``DELETE {..} INSERT {..}
WHERE { GRAPH <meta> { <root> sit:write "previous" } }`` and the last one swaps the id. So an
update that reaches the store late (a stalled store that resumes and processes a request the
writer gave up on) changes nothing once anything else was written after the write it follows,
and the writer fences off every update still in flight by swapping the id alone (``fence``).
Operations of one request run in order, so the guard holds for all of them or for none.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from rdflib import Literal, URIRef, Variable

from kb.sparqlstore import text
from kb.sparqlstore.layout import MODEL, REVISION, WRITE, Layout
from kb.terms import Triple

_S, _P, _O, _R = (Variable(n) for n in ("s", "p", "o", "r"))


def guard(layout: Layout, after: str) -> str:
    """The pattern that holds only while the store's last write is ``after``."""
    return f"GRAPH {text.term(layout.meta)} {{ {text.triple(layout.root, WRITE, Literal(after))} }}"


def guarded(layout: Layout, after: str, delete: Sequence[str] = (), insert: Sequence[str] = (),
            where: str = "") -> str:
    """One operation deleting and inserting the given ``GRAPH <g> {..}`` blocks, if the guard holds."""
    parts = []
    if any(delete):
        parts.append("DELETE {\n" + "\n".join(d for d in delete if d) + "\n}")
    if any(insert):
        parts.append("INSERT {\n" + "\n".join(i for i in insert if i) + "\n}")
    return "\n".join(parts) + f"\nWHERE {{ {guard(layout, after)} {where} }}"


def meta(layout: Layout, write: str, revision: int, models: Iterable[str]) -> list[Triple]:
    root = layout.root
    triples: list[Triple] = [(root, REVISION, Literal(revision)), (root, WRITE, Literal(write))]
    triples.extend((root, MODEL, Literal(m)) for m in models)
    return triples


def change(layout: Layout, after: str, write: str, revision: int, delete: Sequence[str],
           insert: Sequence[str], new_models: Iterable[str]) -> str:
    """A commit: its deletions, its insertions, then the new revision and write id (and any new
    models) in the meta graph."""
    operations = []
    if any(delete):
        operations.append(guarded(layout, after, delete=delete))
    if any(insert):
        operations.append(guarded(layout, after, insert=insert))
    meta_g = text.term(layout.meta)
    old = f"GRAPH {meta_g} {{ {text.triple(layout.root, REVISION, _R)} }}"
    operations.append(guarded(
        layout, after,
        delete=[f"GRAPH {meta_g} {{ {text.triple(layout.root, REVISION, _R)}\n"
                f"{text.triple(layout.root, WRITE, Literal(after))} }}"],
        insert=[text.graph_data(layout.meta, meta(layout, write, revision, new_models))],
        where=f"OPTIONAL {{ {old} }}"))
    return " ;\n".join(operations)


def fence(layout: Layout, after: str, write: str) -> str:
    """Only the write id changes: every update still in flight (following ``after``) is void."""
    mark = text.graph_data(layout.meta, [(layout.root, WRITE, Literal(after))])
    return guarded(layout, after, delete=[mark],
                   insert=[text.graph_data(layout.meta, [(layout.root, WRITE, Literal(write))])])


def rewrite(layout: Layout, after: str | None, write: str, drop: Iterable[str], insert: Sequence[str],
            revision: int, models: Iterable[str]) -> str:
    """The whole dataset replaced: the graphs of the models in ``drop`` emptied, ``insert`` (the
    models' graphs) and the meta graph written. With ``after`` None the dataset is taken over
    whatever it holds (at start); else only if its last write is ``after``."""
    graphs = [g for name in sorted(set(drop)) for g in layout.graphs(name)]
    new_meta = text.graph_data(layout.meta, meta(layout, write, revision, models))
    if after is None:
        operations = [f"DROP SILENT GRAPH {text.term(g)}" for g in [*graphs, layout.meta]]
        if any(insert):
            operations.append("INSERT DATA {\n" + "\n".join(i for i in insert if i) + "\n}")
        operations.append("INSERT DATA {\n" + new_meta + "\n}")
        return " ;\n".join(operations)
    operations = [guarded(layout, after, delete=[_all(g)], where=_all(g)) for g in graphs]
    if any(insert):
        operations.append(guarded(layout, after, insert=insert))
    operations.append(guarded(layout, after, delete=[_all(layout.meta)], insert=[new_meta],
                              where=_all(layout.meta)))
    return " ;\n".join(operations)


def state_text(layout: Layout) -> str:
    """The store's last write id and models (one row each, or none for an empty dataset)."""
    root, meta_g = layout.root, text.term(layout.meta)
    write, model = text.triple(root, WRITE, Variable("w")), text.triple(root, MODEL, Variable("m"))
    return f"SELECT ?w ?m WHERE {{ GRAPH {meta_g} {{\n{{ {write} }} UNION {{ {model} }}\n}} }}"


def _all(graph: URIRef) -> str:
    return f"GRAPH {text.term(graph)} {{ {text.triple(_S, _P, _O)} }}"
