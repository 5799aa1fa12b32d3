// A reply's trace in the chat panel: what the turn sent to the model and why (GET /dialogues/{id}/turns).
// Loaded when the reader expands it, from the turn id the interaction answered with.

import { api } from "./api.js";
import { el } from "./ui.js";

function json(value) {
  return el("pre", { class: "json" }, JSON.stringify(value, null, 2));
}

function fold(title, ...content) {
  return el("details", { class: "trace-part" }, el("summary", {}, title), ...content);
}

function exchange(ex, i) {
  const head = `request ${i + 1}${ex.repair ? " (repair)" : ""} to ${ex.model}` +
    (ex.ms === null || ex.ms === undefined ? "" : ` · ${ex.ms.toFixed(1)} ms`);
  const messages = ex.messages.map((m) => el("div", { class: `trace-message role-${m.role}` },
    el("span", { class: "trace-role" }, m.role), el("pre", { class: "trace-text" }, m.content)));
  return el("section", { class: "trace-exchange", "data-repair": String(ex.repair) },
    el("h4", {}, head),
    fold(`${ex.messages.length} prompt messages`, ...messages),
    fold("JSON schema sent", json(ex.schema)),
    el("p", { class: "trace-label" }, "raw answer"),
    el("pre", { class: "trace-text trace-raw" }, ex.raw_answer === null ? "(no answer)" : ex.raw_answer),
    ex.error ? el("p", { class: "error trace-error" }, ex.error) : null);
}

// The trace as elements: who answered, the situation, each stage's time, every request and answer.
export function renderTrace(trace) {
  const snapshot = trace.snapshot;
  const kinds = snapshot ? Object.entries(snapshot.by_kind).map(([k, n]) => `${n} ${k}`).join(", ") : "";
  const stages = el("ol", { class: "trace-stages" }, ...trace.stages.map((s) =>
    el("li", { "data-stage": s.name }, `${s.name} ${s.ms.toFixed(1)} ms`)));
  const parts = [
    el("p", { class: "trace-who" }, "answered by ",
      el("strong", { class: "trace-answered-by" }, trace.answered_by || "?"),
      ` (${trace.backend})`, trace.repaired ? " · repaired" : "", trace.locale ? ` · ${trace.locale}` : "",
      trace.role !== "__default__" ? ` · role ${trace.role}` : "", ` · shape ${trace.shape}`),
    snapshot ? el("p", { class: "trace-snapshot" },
      `KB revision ${snapshot.revision}: ${snapshot.entities} entities; in the prompt: ${kinds}; first: ` +
      snapshot.focus.join(", ")) : null,
    stages,
    ...trace.exchanges.map(exchange),
  ];
  if (trace.validation_errors.length) {
    parts.push(el("p", { class: "trace-label" }, "validation errors"),
      el("ul", { class: "trace-errors" }, ...trace.validation_errors.map((e) => el("li", {}, e))));
  }
  if (trace.notes.length) parts.push(el("ul", { class: "trace-notes" }, ...trace.notes.map((n) => el("li", {}, n))));
  if (trace.results !== null) parts.push(el("p", { class: "trace-results" }, `results ${trace.results}`));
  parts.push(fold(`${trace.intents.length} resolved intent${trace.intents.length === 1 ? "" : "s"}`, json(trace.intents)));
  return el("div", { class: "trace-body", "data-turn": trace.id }, ...parts);
}

// A folded "trace" under a reply; its content is fetched the first time it is opened.
export function traceToggle(dialogueId, turnId) {
  const box = el("details", { class: "trace", "data-turn": turnId }, el("summary", {}, "trace"));
  let loaded = false;
  box.addEventListener("toggle", async () => {
    if (!box.open || loaded) return;
    loaded = true;
    const waiting = el("p", { class: "muted" }, "Loading the trace…");
    box.appendChild(waiting);
    try {
      const { turns } = await api.turns(dialogueId);
      const trace = turns.find((t) => t.id === turnId);
      waiting.replaceWith(trace ? renderTrace(trace) : el("p", { class: "muted" }, "This turn's trace is no longer kept."));
    } catch (err) {
      loaded = false;
      waiting.replaceWith(el("p", { class: "error" }, err.message));
    }
  });
  return box;
}
