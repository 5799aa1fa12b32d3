// What the graph shows, read from the KB: each shown concept's details, category and edges.
// Every change (expand, refresh) re-derives a concept's edges from its current details, so facts
// that disappeared from the KB disappear from the graph too.

import { api, passing } from "./api.js";
import { isRecord, keyOf, toldAbout } from "./provenance.js";

const MAX_NEW_NEIGHBOURS = 25;
// The first rule whose class the concept has (directly or by inference) gives its colour and icon.
const CATEGORY_RULES = [
  ["robot", ["Robot"]],
  ["person", ["Human", "foaf:Person"]],
  ["furniture", ["cyc:FurniturePiece", "Furniture", "dbr:Furniture", "PhysicalSupport"]],
  ["zone", ["Zone", "ZoneOfInterest", "RegionOfSpace", "cyc:SpaceRegion", "Room"]],
  ["object", ["Artifact", "cyc:PartiallyTangible", "PhysicalEntity", "cyc:SpatialThing-Localized"]],
];

// An object's icon: the first kind whose class it has (directly or by inference); an object of
// no listed kind gets the generic object icon, any other concept its category's icon.
const OBJECT_ICONS = [
  ["cup", ["dbr:Cup"]],
  ["bottle", ["dbr:Bottle"]],
  ["fruit", ["dbr:Fruit"]],
  ["book", ["dbr:Book"]],
  ["phone", ["dbr:Smartphone"]],
  ["plant", ["dbr:Plant"]],
  ["utensil", ["dbr:Kitchen_utensil"]],
  ["bin", ["dbr:Waste_container"]],
];

export function iconOf(category, classes) {
  if (category !== "object") return category;
  const all = new Set(classes);
  const kind = OBJECT_ICONS.find(([, names]) => names.some((name) => all.has(name)));
  return kind ? kind[0] : "object";
}

function directClasses(details) {
  const entry = (details.attributes || []).find((a) => a.id === "classes");
  return entry ? entry.values.map((v) => v.id) : [];
}

function attributeIds(details, key) {
  const entry = (details.attributes || []).find((a) => a.id === key);
  return entry ? entry.values.map((v) => v.id) : [];
}

function exists(details) {
  return details.type !== "undecided" || details.relations.length > 0
    || (details.attributes || []).some((a) => a.values.length > 0);
}

export function categoryOf(details, classes) {
  if (details.type === "class") return "class";
  if (details.type !== "instance") return "other";
  const all = new Set(classes);
  for (const [category, names] of CATEGORY_RULES) {
    if (names.some((name) => all.has(name))) return category;
  }
  return "other";
}

export class Concepts {
  constructor(graph, { root, onChange }) {
    this.graph = graph;
    this.root = root;
    this.onChange = onChange;
    this.cache = new Map();       // id -> {details, category, origins, classes}
    this.predicateKinds = new Map();
    this.expanded = new Set();
    this.chain = Promise.resolve();
  }

  info(id) { return this.cache.get(id); }

  isDatatype(predicate) { return this.predicateKinds.get(predicate) === "datatype_property"; }

  forget() {
    this.cache.clear();
    this.expanded.clear();
  }

  // One change at a time, so a refresh never interleaves with an expansion.
  serial(task) {
    const run = this.chain.then(task, task);
    this.chain = run.catch(() => {});
    return run;
  }

  expand(id) {
    return this.serial(async () => {
      const info = await this.load(id);
      if (!exists(info.details)) throw new Error("the KB knows nothing about this term");
      this.expanded.add(id);
      this.graph.upsertNode(id, { label: info.details.label.default, category: info.category, icon: info.icon });
      this.graph.setExpanded(id, true);
      await this.sync(id, info);
      this.prune();
    });
  }

  // Resolves to the ids that could not be read because the service was busy or unreachable, for
  // the caller to try again: a change whose refresh failed would otherwise stay undrawn.
  refresh(ids) {
    return this.serial(async () => {
      const failed = [];
      for (const id of ids) {
        let info;
        try {
          info = await this.load(id);
        } catch (err) {
          if (passing(err)) failed.push(id);  // (a refusal, 401 or 404, stays one: not retried)
          continue;
        }
        if (!this.graph.hasNode(id)) { this.onChange(id); continue; }
        if (!exists(info.details) && id !== this.root) {
          this.expanded.delete(id);
          this.graph.removeNode(id);
        } else {
          this.graph.upsertNode(id, { label: info.details.label.default, category: info.category, icon: info.icon });
          await this.sync(id, info);
        }
        this.onChange(id);
      }
      this.prune();
      return failed;
    });
  }

  async load(id) {
    const details = await api.details(id);
    const previous = this.cache.get(id);
    const direct = directClasses(details);
    let classes = previous && previous.direct.join() === direct.join() ? previous.classes : null;
    if (classes === null) classes = details.type === "instance" ? await api.classesof(id) : [];
    const origins = Array.isArray(details.asserted) ? details.asserted : null;
    const category = categoryOf(details, classes);
    // Facts learnt from dialogue (and who told them); none when the query fails.
    const told = details.type === "instance" ? await toldAbout(id).catch(() => new Map()) : new Map();
    const info = { details, classes, direct, origins, told, category, icon: iconOf(category, classes) };
    this.cache.set(id, info);
    await this.learnPredicates(details.relations.map((r) => r[1]));
    return info;
  }

  async learnPredicates(predicates) {
    const unknown = [...new Set(predicates)].filter((p) => !this.predicateKinds.has(p));
    await Promise.all(unknown.map(async (p) => {
      try {
        this.predicateKinds.set(p, (await api.details(p)).type);
      } catch {
        this.predicateKinds.set(p, "undecided");
      }
    }));
  }

  // The edges a concept has now: relations to other resources, and "is a" links.
  edgesFrom(id, info) {
    const edges = [];
    const d = info.details;
    d.relations.forEach(([s, p, o], i) => {
      if (p === id || typeof o !== "string" || this.isDatatype(p) || s === o || isRecord([s, p, o])) return;
      const inferred = info.origins && !info.origins[i];
      const kind = inferred ? "inferred" : info.told.has(keyOf([s, p, o])) ? "told" : "asserted";
      edges.push({ s, p, o, kind });
    });
    for (const c of info.direct) edges.push({ s: id, p: "isA", o: c, kind: "isa" });
    if (d.type === "class") {
      for (const parent of attributeIds(d, "superClasses")) edges.push({ s: id, p: "isA", o: parent, kind: "isa" });
      for (const child of attributeIds(d, "subClasses")) edges.push({ s: child, p: "isA", o: id, kind: "isa" });
      for (const instance of attributeIds(d, "instances")) edges.push({ s: instance, p: "isA", o: id, kind: "isa" });
    }
    return edges;
  }

  async sync(id, info) {
    const edges = this.edgesFrom(id, info);
    const wanted = new Set(edges.map((e) => `${e.s}\u0000${e.p}\u0000${e.o}`));
    for (const edge of this.graph.edgesOf(id)) {
      if (!wanted.has(edge.key)) this.graph.removeEdge(edge.key);
    }
    const fresh = [];
    let added = 0;
    for (const e of edges) {
      const other = e.s === id ? e.o : e.s;
      if (!this.graph.hasNode(other)) {
        if (!this.expanded.has(id) || added >= MAX_NEW_NEIGHBOURS) continue;
        added += 1;
        const cached = this.cache.get(other);
        this.graph.upsertNode(other, {
          near: id, label: cached ? cached.details.label.default : other,
          category: cached ? cached.category : "other", icon: cached ? cached.icon : "other",
        });
        fresh.push(other);
      }
      this.graph.setEdge(e.s, e.p, e.o, e.kind);
    }
    // New neighbours: their labels and categories, and their links to what is already shown.
    const loaded = await Promise.all(fresh.map((n) => this.load(n).then((i) => [n, i], () => [n, null])));
    for (const [n, neighbour] of loaded) {
      if (!neighbour || !this.graph.hasNode(n)) continue;
      this.graph.upsertNode(n, { label: neighbour.details.label.default, category: neighbour.category, icon: neighbour.icon });
      for (const e of this.edgesFrom(n, neighbour)) {
        const other = e.s === n ? e.o : e.s;
        if (this.graph.hasNode(other)) this.graph.setEdge(e.s, e.p, e.o, e.kind);
      }
    }
    this.onChange(id);
  }

  // Concepts nobody expanded that lost every link are dropped.
  prune() {
    for (const id of [...this.graph.nodes.keys()]) {
      if (id === this.root || this.expanded.has(id) || id === this.graph.selected) continue;
      if (this.graph.edgesOf(id).length === 0) this.graph.removeNode(id);
    }
  }
}
