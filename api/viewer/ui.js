// Small DOM helpers shared by the panels.

export function el(name, attrs = {}, ...children) {
  const node = document.createElement(name);
  for (const [key, value] of Object.entries(attrs)) node.setAttribute(key, value);
  for (const child of children) {
    if (child === null || child === undefined) continue;
    node.append(child instanceof Node ? child : String(child));
  }
  return node;
}

// Names longer than this may wrap between the words inside them (living_room stays whole).
const LONG_NAME = 12;

// A name that may wrap only between its words, never inside one: after a prefix's colon or a space,
// and in a long name after an underscore or a dash and where a camelCase word starts
// ("cyc:object|Found|In|Location").
export function breakable(text) {
  const names = String(text).split(/(?<=[:\s/])/u);
  const parts = names.flatMap((name) => (name.length > LONG_NAME
    ? name.split(/(?<=[_\-])|(?<=[a-z0-9])(?=[A-Z])/u) : [name]));
  return parts.flatMap((part, i) => (i ? [document.createElement("wbr"), part] : [part]));
}

// A term shown as a button that opens it in the graph.
export function termButton(term, label, onOpen, current = false) {
  const text = label && label !== term ? `${label} (${term})` : term;
  const button = el("button", { type: "button", class: `term${current ? " current" : ""}`, title: `Show ${term}` },
    ...breakable(text));
  button.addEventListener("click", () => onOpen(term));
  return button;
}

// A relation [s, p, o] written back as a statement the KB parses.
export function statementOf([s, p, o], datatype) {
  const object = typeof o === "string" ? (datatype || /\s/.test(o) ? JSON.stringify(o) : o) : String(o);
  return `${s} ${p} ${object}`;
}

// A clarification: the robot asks back and commits to nothing but the raw input.
export function isQuestion(answer) {
  const reply = (answer.response || "").trim();
  return reply.endsWith("?") && answer.intents.every((i) => i.intent === "__raw_user_input__");
}
