// Facts learnt from dialogue: each has a record in the KB (RDF reification: a ToldFact with
// rdf:subject/predicate/object, toldBy, toldAt), so the viewer can show who told it and when,
// and draw it apart from perception's facts. The records themselves are not drawn as concepts.

import { api } from "./api.js";

const RECORD_PREDICATES = new Set(["rdf:subject", "rdf:predicate", "rdf:object", "toldBy", "toldAt", "toldAs"]);

// A relation of a record (told_… rdf:subject cup_1): shown as its fact's provenance instead.
export function isRecord(triple) {
  return RECORD_PREDICATES.has(triple[1]);
}

export function keyOf(triple) {
  return JSON.stringify(triple);
}

// The facts told about a concept (as subject or object): fact key -> {who, at}.
export async function toldAbout(id) {
  const told = new Map();
  const rest = ["?r rdf:predicate ?p", "?r toldBy ?who", "?r toldAt ?at"];
  const [asSubject, asObject] = await Promise.all([
    api.query([`?r rdf:subject ${id}`, "?r rdf:object ?o", ...rest]),
    api.query([`?r rdf:object ${id}`, "?r rdf:subject ?s", ...rest]),
  ]);
  for (const row of asSubject) told.set(keyOf([id, row.p, row.o]), { who: row.who, at: row.at });
  for (const row of asObject) told.set(keyOf([row.s, row.p, id]), { who: row.who, at: row.at });
  return told;
}

// "told by person_bob · 2025-06-01 10:30"
export function describe(told) {
  const when = String(told.at).replace("T", " ").slice(0, 16);
  return `told by ${told.who} · ${when}`;
}
