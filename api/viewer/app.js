// The viewer: graph explorer, concept facts with editing, query box, chat, live KB events.

import { api, getToken, setToken } from "./api.js";
import { Graph } from "./graph.js";
import { Concepts } from "./concepts.js";
import { traceToggle } from "./trace.js";
import { describe, isRecord, keyOf } from "./provenance.js";
import { breakable, el, isQuestion, statementOf, termButton } from "./ui.js";

const ROOT = "myself";
const RETRY_FIRST_MS = 500;
const RETRY_LAST_MS = 8000;
// The speaker when none is given: ROS4HRI's nobody, which the service never adds to the KB.
const NOBODY = "__unknown_agent__";

const $ = (selector) => document.querySelector(selector);

class Viewer {
  constructor() {
    this.graph = new Graph($("#graph"), { onActivate: (id) => this.activate(id) });
    this.concepts = new Concepts(this.graph, { root: ROOT, onChange: (id) => this.conceptChanged(id) });
    this.selected = null;
    this.events = null;
    this.pending = new Set();
    this.flushTimer = null;
    this.retryDelay = RETRY_FIRST_MS;
  }

  async start() {
    this.bindControls();
    this.connectEvents();
    await this.activate(ROOT);
    await this.fillHumans();
  }

  // ---- graph and concept panel ---------------------------------------------------------------

  async activate(id) {
    this.select(id);
    try {
      await this.concepts.expand(id);
    } catch (err) {
      this.showConceptError(id, err);
      return;
    }
    this.renderConcept();
  }

  select(id) {
    this.selected = id;
    this.graph.select(id);
    this.renderConcept();
  }

  conceptChanged(id) {
    if (id === this.selected) this.renderConcept();
    this.updateKnownTerms();
  }

  showConceptError(id, err) {
    const box = $("#concept");
    box.replaceChildren(el("p", { class: "error" }, `${id}: ${err.message}`));
    $("#facts tbody").replaceChildren();
  }

  renderConcept() {
    const id = this.selected;
    const box = $("#concept");
    const body = $("#facts tbody");
    const info = id && this.concepts.info(id);
    if (!info) {
      box.replaceChildren(el("p", { class: "muted" }, id ? `Loading ${id}…` : "Select a concept in the graph."));
      body.replaceChildren();
      return;
    }
    const d = info.details;
    const chips = [];
    for (const attribute of d.attributes || []) {
      if (!attribute.values.length) continue;
      chips.push(el("div", { class: "attr" },
        el("span", { class: "attr-name" }, attribute.name),
        ...attribute.values.slice(0, 40).map((v) => termButton(v.id, v.label && v.label.default, (t) => this.activate(t)))));
    }
    // A name learnt from dialogue is no relation of `details`: its provenance goes by the heading.
    const toldNames = [...(info.told || new Map()).entries()]
      .map(([key, told]) => [JSON.parse(key), told])
      .filter(([[s, p]]) => s === d.id && p === "rdfs:label")
      .map(([[, , name], told]) => el("span", { class: "tag told", "data-told-by": told.who }, `name "${name}" ${describe(told)}`));
    box.replaceChildren(
      el("div", { class: "concept-head" },
        el("span", { class: `badge cat-${info.category}` }, info.category),
        el("h3", { id: "concept-label" }, d.label && d.label.default ? d.label.default : d.id),
        el("code", { class: "concept-id" }, d.id),
        el("span", { class: "type" }, d.type),
        ...toldNames),
      ...chips);
    const shown = d.relations.map((triple, i) => [triple, i]).filter(([triple]) => !isRecord(triple));
    const rows = shown.map(([triple, i]) => {
      const origin = info.origins ? (info.origins[i] ? "asserted" : "inferred") : null;
      const told = origin !== "inferred" && info.told ? info.told.get(keyOf(triple)) : undefined;
      const statement = statementOf(triple, this.concepts.isDatatype(triple[1]));
      const cells = triple.map((term, j) => el("td", {},
        j !== 1 && typeof term === "string" && !(j === 2 && this.concepts.isDatatype(triple[1]))
          ? termButton(term, null, (t) => this.activate(t), term === d.id)
          : j === 1 ? el("span", { class: "pred" }, ...breakable(term))
            : el("span", { class: "literal" }, typeof term === "string" ? JSON.stringify(term) : String(term))));
      const retract = el("button", { type: "button", class: "small", title: `Put "${statement}" in the form to retract it` }, "retract…");
      retract.addEventListener("click", () => {
        $("#statements").value = statement;
        $("#method").value = "retract";
        $("#statements").focus();
      });
      const actions = el("td", { class: "actions" }, origin === "inferred" ? el("span", { class: "tag inferred" }, "inferred") : retract);
      if (told) {
        cells[1].append(el("span", { class: "tag told", title: "learnt from dialogue" }, describe(told)));
        return el("tr", { class: "told", "data-told-by": told.who }, ...cells, actions);
      }
      return el("tr", { class: origin || "" }, ...cells, actions);
    });
    if (!rows.length) rows.push(el("tr", {}, el("td", { colspan: "4", class: "muted" }, "No relations.")));
    body.replaceChildren(...rows);
  }

  updateKnownTerms() {
    const list = $("#known-terms");
    list.replaceChildren(...[...this.graph.nodes.keys()].sort().map((id) => el("option", { value: id })));
  }

  // ---- live updates --------------------------------------------------------------------------

  connectEvents() {
    if (this.events) this.events.close();
    const live = $("#live");
    live.dataset.state = "connecting";
    live.textContent = "connecting…";
    const source = new EventSource(api.changesUrl());
    this.events = source;
    source.addEventListener("subscribed", () => {
      live.dataset.state = "live";
      live.textContent = "live";
      this.resync();  // whatever happened while disconnected
    });
    source.addEventListener("message", (event) => {
      for (const commit of JSON.parse(event.data)) {
        // A clear or a commit too large to list: re-read everything shown.
        if (commit.cleared || commit.truncated) { this.resync(); continue; }
        for (const [s, p, o] of [...commit.added, ...commit.removed]) this.noteChange([s, o, p]);
      }
    });
    source.addEventListener("error", () => {
      live.dataset.state = "offline";
      live.textContent = source.readyState === EventSource.CLOSED ? "events refused (token?)" : "reconnecting…";
    });
  }

  // Terms touched by a change: refresh those shown, soon, once per burst of events.
  noteChange(terms) {
    for (const term of terms) {
      if (typeof term === "string" && (this.graph.hasNode(term) || term === this.selected)) this.pending.add(term);
    }
    if (this.pending.size && this.flushTimer === null) {
      this.flushTimer = setTimeout(() => this.flush(), 120);
    }
  }

  async flush() {
    this.flushTimer = null;
    const ids = [...this.pending];
    this.pending.clear();
    this.retryLater(await this.concepts.refresh(ids));
  }

  async resync() {
    const ids = new Set(this.graph.nodes.keys());
    if (this.selected) ids.add(this.selected);
    this.retryLater(await this.concepts.refresh([...ids]));
  }

  forgetRetries() {
    if (this.flushTimer !== null) clearTimeout(this.flushTimer);
    this.flushTimer = null;
    this.pending.clear();
    this.retryDelay = RETRY_FIRST_MS;
  }

  // Terms whose refresh failed are read again, later and later while the service stays busy, and
  // the wait starts over once a refresh succeeds.
  retryLater(failed) {
    if (!failed.length) { this.retryDelay = RETRY_FIRST_MS; return; }
    for (const id of failed) this.pending.add(id);
    if (this.flushTimer === null) this.flushTimer = setTimeout(() => this.flush(), this.retryDelay);
    this.retryDelay = Math.min(this.retryDelay * 2, RETRY_LAST_MS);
  }

  // ---- forms ---------------------------------------------------------------------------------

  bindControls() {
    const token = $("#token");
    token.value = getToken();
    token.addEventListener("change", () => {
      setToken(token.value.trim());
      this.forgetRetries();  // (read again with the new token when its events resync)
      this.connectEvents();
    });

    $("#goto").addEventListener("submit", (event) => {
      event.preventDefault();
      const term = $("#goto-term").value.trim();
      if (term) this.activate(term);
    });
    $("#zoom-in").addEventListener("click", () => this.graph.zoomBy(1.25));
    $("#zoom-out").addEventListener("click", () => this.graph.zoomBy(0.8));
    $("#fit").addEventListener("click", () => { this.graph.autoFit = true; this.graph.fit(); });
    $("#reset").addEventListener("click", () => {
      this.graph.clear();
      this.concepts.forget();
      this.graph.autoFit = true;
      this.graph.centreView();
      this.activate(ROOT);
    });
    $("#show-inferred").addEventListener("change", (event) => this.graph.setShowInferred(event.target.checked));

    $("#revise").addEventListener("submit", (event) => { event.preventDefault(); this.revise(); });
    $("#statements").addEventListener("keydown", (event) => {
      if (event.key === "Enter" && (event.ctrlKey || event.metaKey)) { event.preventDefault(); this.revise(); }
    });
    $("#query").addEventListener("submit", (event) => { event.preventDefault(); this.runQuery(); });
    $("#patterns").addEventListener("keydown", (event) => {
      if (event.key === "Enter" && (event.ctrlKey || event.metaKey)) { event.preventDefault(); this.runQuery(); }
    });
    $("#chat").addEventListener("submit", (event) => { event.preventDefault(); this.sendChat(); });
    const user = $("#user-id");
    user.value = sessionStorage.getItem("situated.user") || "";
    user.addEventListener("change", () => sessionStorage.setItem("situated.user", user.value.trim()));
  }

  async revise() {
    const status = $("#revise-status");
    const statements = $("#statements").value.split("\n").map((s) => s.trim()).filter((s) => s && !s.startsWith("#"));
    const method = $("#method").value;
    if (!statements.length) { setStatus(status, "error", "Write at least one statement."); return; }
    setStatus(status, "busy", "Applying…");
    try {
      const answer = await api.revise(statements, method);
      setStatus(status, "ok", `${method}: ${statements.length} statement${statements.length > 1 ? "s" : ""} · revision ${answer.revision}`);
      $("#statements").value = "";
      // Retractions produce no event: re-read what is shown now rather than at the next resync.
      if (method === "retract") await this.resync();
    } catch (err) {
      setStatus(status, "error", err.message);
    }
  }

  async runQuery() {
    const status = $("#query-status");
    const patterns = $("#patterns").value.split("\n").map((s) => s.trim()).filter(Boolean);
    const head = $("#results thead");
    const body = $("#results tbody");
    if (!patterns.length) { setStatus(status, "error", "Write at least one pattern."); return; }
    setStatus(status, "busy", "Running…");
    let rows;
    try {
      rows = await api.query(patterns);
    } catch (err) {
      setStatus(status, "error", err.message);
      head.replaceChildren();
      body.replaceChildren();
      return;
    }
    if (rows.length && typeof rows[0] === "string") {
      // A ground query answers with the patterns that hold.
      setStatus(status, "ok", "true: every pattern holds");
      head.replaceChildren(el("tr", {}, el("th", { scope: "col" }, "holds")));
      body.replaceChildren(...rows.map((p) => el("tr", {}, el("td", {}, p))));
      return;
    }
    const columns = [...new Set(rows.flatMap((row) => Object.keys(row)))];
    setStatus(status, "ok", rows.length ? `${rows.length} row${rows.length > 1 ? "s" : ""}` : "no match");
    head.replaceChildren(el("tr", {}, ...columns.map((c) => el("th", { scope: "col" }, `?${c}`))));
    body.replaceChildren(...rows.map((row) => el("tr", {}, ...columns.map((c) => el("td", {},
      typeof row[c] === "string" ? termButton(row[c], null, (t) => this.activate(t)) : String(row[c] ?? ""))))));
  }

  async sendChat() {
    const input = $("#chat-input");
    const text = input.value.trim();
    const userId = $("#user-id").value.trim() || NOBODY;
    if (!text) return;
    input.value = "";
    const log = $("#chat-log");
    log.appendChild(el("li", { class: "msg user" }, el("span", { class: "who" }, userId), el("p", {}, text)));
    const waiting = el("li", { class: "msg robot waiting" }, el("span", { class: "who" }, "robot"), el("p", {}, "…"));
    log.appendChild(waiting);
    log.scrollTop = log.scrollHeight;
    try {
      const answer = await api.interact(userId, text);
      const question = isQuestion(answer);
      const parts = [el("span", { class: "who" }, question ? "robot asks" : "robot"), el("p", { class: "reply" }, answer.response || "(no reply)")];
      if (answer.error_msg) parts.push(el("p", { class: "error" }, answer.error_msg));
      const intents = el("details", { class: "intents", open: "" },
        el("summary", {}, `${answer.intents.length} intent${answer.intents.length === 1 ? "" : "s"}`),
        el("pre", { class: "json" }, JSON.stringify(answer.intents, null, 2)));
      parts.push(intents);
      if (answer.turn) parts.push(traceToggle("default", answer.turn));
      // Only the latest answer keeps its intents open; earlier ones fold away.
      for (const open of log.querySelectorAll("details.intents[open]")) open.removeAttribute("open");
      waiting.replaceWith(el("li", { class: `msg robot${question ? " question" : ""}` }, ...parts));
    } catch (err) {
      waiting.replaceWith(el("li", { class: "msg system error" }, el("p", {}, err.message)));
    }
    log.scrollTop = log.scrollHeight;
  }

  // The people the speaker field suggests; with no speaker chosen yet, it speaks as a person the
  // robot sees (else one the KB knows): a chat makes no new person of the KB unless asked to.
  async fillHumans() {
    try {
      const [known, seen] = await Promise.all([
        api.query(["?h rdf:type Human"]), api.query(["myself sees ?h", "?h rdf:type Human"])]);
      const ids = (rows) => rows.map((r) => r.h).sort();
      $("#known-humans").replaceChildren(...ids(known).map((h) => el("option", { value: h })));
      const user = $("#user-id");
      if (!user.value.trim()) user.value = ids(seen)[0] || ids(known)[0] || NOBODY;
    } catch {
      // Suggestions only; the field still takes any id.
    }
  }
}

function setStatus(node, kind, text) {
  node.dataset.kind = kind;
  node.textContent = text;
}

new Viewer().start();
