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

// A term shown as a button that opens it in the graph.
export function termButton(term, label, onOpen, current = false) {
  const text = label && label !== term ? `${label} (${term})` : term;
  const button = el("button", { type: "button", class: `term${current ? " current" : ""}`, title: `Show ${term}` }, text);
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
