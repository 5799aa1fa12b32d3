// The graph view: nodes and edges in an SVG, a small force layout, pan/zoom, drag to pin.
// It knows nothing about the KB: app.js decides what the nodes and edges are.

const SVG_NS = "http://www.w3.org/2000/svg";
const NODE_RADIUS = { class: 25, default: 21 };
const LINK_DISTANCE = 135;
const CHARGE = 9000;
// Room kept free for the legend (top) and the hint line (bottom) when fitting the view.
const INSET = { top: 46, bottom: 24, side: 10 };

function svgEl(name, attrs = {}, parent = null) {
  const el = document.createElementNS(SVG_NS, name);
  for (const [key, value] of Object.entries(attrs)) el.setAttribute(key, value);
  if (parent) parent.appendChild(el);
  return el;
}

// A stable pseudo-random number in [0, 1) per concept, so a page reload lays out alike.
function unitHash(text) {
  let h = 2166136261;
  for (let i = 0; i < text.length; i++) h = Math.imul(h ^ text.charCodeAt(i), 16777619);
  return ((h >>> 0) % 10007) / 10007;
}

function shorten(text, max) {
  return text.length > max ? text.slice(0, max - 1) + "…" : text;
}

export class Graph {
  constructor(svg, { onActivate }) {
    this.svg = svg;
    this.viewport = svg.querySelector("#viewport");
    this.edgeLayer = svg.querySelector("#edges");
    this.nodeLayer = svg.querySelector("#nodes");
    this.onActivate = onActivate;
    this.nodes = new Map();
    this.edges = new Map();
    this.selected = null;
    this.view = { x: 0, y: 0, k: 1 };
    this.alpha = 0;
    this.frame = null;
    this.showInferred = true;
    // The view follows the layout until the user pans or zooms.
    this.autoFit = true;
    this.centreView();
    this.installPanZoom();
    new ResizeObserver(() => (this.autoFit ? this.fit() : this.applyView())).observe(svg);
  }

  // ---- model -------------------------------------------------------------------------------

  hasNode(id) { return this.nodes.has(id); }

  upsertNode(id, { label, category, icon, near } = {}) {
    let node = this.nodes.get(id);
    if (!node) {
      const anchor = near && this.nodes.get(near);
      const angle = unitHash(id) * 2 * Math.PI;
      const spread = anchor ? 60 + unitHash(id + "/") * 40 : 30 * Math.sqrt(this.nodes.size);
      node = {
        id, label: id, category: "other", glyph: "other", expanded: false,
        x: (anchor ? anchor.x : 0) + Math.cos(angle) * spread,
        y: (anchor ? anchor.y : 0) + Math.sin(angle) * spread,
        vx: 0, vy: 0, fx: null, fy: null,
      };
      this.nodes.set(id, node);
      this.drawNode(node);
      this.reheat(0.8);
    }
    if (label !== undefined) node.label = label;
    if (category !== undefined) node.category = category;
    if (icon !== undefined) node.glyph = icon;  // node.icon is the drawn <use> element
    this.styleNode(node);
    return node;
  }

  removeNode(id) {
    const node = this.nodes.get(id);
    if (!node) return;
    for (const edge of this.edgesOf(id)) this.removeEdge(edge.key);
    node.el.remove();
    this.nodes.delete(id);
    if (this.selected === id) this.selected = null;
    this.reheat(0.3);
  }

  setExpanded(id, expanded) {
    const node = this.nodes.get(id);
    if (node) { node.expanded = expanded; this.styleNode(node); }
  }

  static edgeKey(s, p, o) { return `${s}\u0000${p}\u0000${o}`; }

  setEdge(s, p, o, kind) {
    const key = Graph.edgeKey(s, p, o);
    let edge = this.edges.get(key);
    if (!edge) {
      edge = { key, s, p, o, kind };
      this.edges.set(key, edge);
      this.drawEdge(edge);
      this.reheat(0.5);
    } else if (edge.kind !== kind) {
      edge.kind = kind;
    }
    this.styleEdge(edge);
    return edge;
  }

  removeEdge(key) {
    const edge = this.edges.get(key);
    if (!edge) return;
    edge.el.remove();
    this.edges.delete(key);
    this.reheat(0.2);
  }

  edgesOf(id) {
    return [...this.edges.values()].filter((e) => e.s === id || e.o === id);
  }

  select(id) {
    this.selected = id;
    for (const node of this.nodes.values()) this.styleNode(node);
    this.updateFading();
  }

  setShowInferred(show) {
    this.showInferred = show;
    for (const edge of this.edges.values()) this.styleEdge(edge);
  }

  clear() {
    for (const id of [...this.nodes.keys()]) this.removeNode(id);
  }

  // ---- drawing -----------------------------------------------------------------------------

  radius(node) { return node.category === "class" ? NODE_RADIUS.class : NODE_RADIUS.default; }

  drawNode(node) {
    const g = svgEl("g", { class: "node", tabindex: "0", role: "button", "data-id": node.id });
    node.shape = svgEl("circle", { r: this.radius(node), class: "node-shape" }, g);
    node.icon = svgEl("use", { width: 24, height: 24, x: -12, y: -12, class: "node-icon" }, g);
    node.text = svgEl("text", { class: "node-label", y: this.radius(node) + 15 }, g);
    node.title = svgEl("title", {}, g);
    node.el = g;
    this.nodeLayer.appendChild(g);
    this.installNodeEvents(node);
  }

  styleNode(node) {
    const classes = ["node", `cat-${node.category}`];
    if (node.id === this.selected) classes.push("selected");
    if (node.expanded) classes.push("expanded");
    if (node.fx !== null) classes.push("pinned");
    node.el.setAttribute("class", classes.join(" "));
    node.shape.setAttribute("r", this.radius(node));
    node.icon.setAttribute("href", `#icon-${node.glyph}`);
    node.text.setAttribute("y", this.radius(node) + 15);
    node.text.textContent = shorten(node.label, 22);
    const state = node.expanded ? "expanded" : "not expanded yet";
    node.el.setAttribute("aria-label", `${node.label} (${node.id}), ${node.category}, ${state}`);
    node.title.textContent = node.label === node.id ? node.id : `${node.label} — ${node.id}`;
  }

  drawEdge(edge) {
    const g = svgEl("g", { class: "edge", "data-s": edge.s, "data-p": edge.p, "data-o": edge.o });
    edge.path = svgEl("path", { class: "edge-line" }, g);
    edge.text = svgEl("text", { class: "edge-label" }, g);
    edge.text.textContent = edge.p === "isA" ? "is a" : edge.p;
    edge.el = g;
    this.edgeLayer.appendChild(g);
  }

  styleEdge(edge) {
    const near = this.selected !== null && (edge.s === this.selected || edge.o === this.selected);
    edge.el.setAttribute("class", `edge ${edge.kind}${near ? " near" : ""}`);
    edge.el.dataset.kind = edge.kind;
    const marker = edge.kind === "isa" ? "arrow-isa" : edge.kind === "inferred" ? "arrow-inferred" : "arrow";
    edge.path.setAttribute("marker-end", `url(#${marker})`);
    edge.el.toggleAttribute("hidden", edge.kind === "inferred" && !this.showInferred);
  }

  // Parallel edges between the same two nodes are drawn as separate arcs.
  edgeOffsets() {
    const groups = new Map();
    for (const edge of this.edges.values()) {
      const pair = edge.s < edge.o ? `${edge.s}\u0000${edge.o}` : `${edge.o}\u0000${edge.s}`;
      if (!groups.has(pair)) groups.set(pair, []);
      groups.get(pair).push(edge);
    }
    const offsets = new Map();
    for (const list of groups.values()) {
      const visible = list.filter((e) => !e.el.hasAttribute("hidden"));
      visible.forEach((edge, i) => {
        const centred = i - (visible.length - 1) / 2;
        // Normalise the bend to the pair's canonical direction so arcs do not overlap.
        const sign = edge.s < edge.o ? 1 : -1;
        offsets.set(edge.key, centred * 34 * sign);
      });
    }
    return offsets;
  }

  render() {
    for (const node of this.nodes.values()) {
      node.el.setAttribute("transform", `translate(${node.x.toFixed(1)},${node.y.toFixed(1)})`);
    }
    const offsets = this.edgeOffsets();
    for (const edge of this.edges.values()) {
      const a = this.nodes.get(edge.s);
      const b = this.nodes.get(edge.o);
      if (!a || !b) continue;
      const dx = b.x - a.x;
      const dy = b.y - a.y;
      const len = Math.hypot(dx, dy) || 1;
      const nx = -dy / len;
      const ny = dx / len;
      const bend = offsets.get(edge.key) || 0;
      const cx = (a.x + b.x) / 2 + nx * bend;
      const cy = (a.y + b.y) / 2 + ny * bend;
      // Start and end on the node circles, aimed at the control point.
      const ra = this.radius(a) + 2;
      const rb = this.radius(b) + 4;
      const da = Math.hypot(cx - a.x, cy - a.y) || 1;
      const db = Math.hypot(cx - b.x, cy - b.y) || 1;
      const x1 = a.x + ((cx - a.x) / da) * ra;
      const y1 = a.y + ((cy - a.y) / da) * ra;
      const x2 = b.x + ((cx - b.x) / db) * rb;
      const y2 = b.y + ((cy - b.y) / db) * rb;
      edge.path.setAttribute("d", `M${x1.toFixed(1)},${y1.toFixed(1)} Q${cx.toFixed(1)},${cy.toFixed(1)} ${x2.toFixed(1)},${y2.toFixed(1)}`);
      // The midpoint of a quadratic Bézier.
      const mx = 0.25 * x1 + 0.5 * cx + 0.25 * x2;
      const my = 0.25 * y1 + 0.5 * cy + 0.25 * y2;
      edge.text.setAttribute("x", mx.toFixed(1));
      edge.text.setAttribute("y", (my - 3).toFixed(1));
    }
  }

  updateFading() {
    // Fade nodes by graph distance from the selection, as the reference explorer does.
    const depth = new Map();
    if (this.selected && this.nodes.has(this.selected)) {
      depth.set(this.selected, 0);
      const queue = [this.selected];
      while (queue.length) {
        const id = queue.shift();
        for (const edge of this.edgesOf(id)) {
          const other = edge.s === id ? edge.o : edge.s;
          if (!depth.has(other)) { depth.set(other, depth.get(id) + 1); queue.push(other); }
        }
      }
    }
    for (const node of this.nodes.values()) {
      const d = depth.has(node.id) ? depth.get(node.id) : 3;
      node.el.dataset.depth = String(Math.min(d, 3));
    }
    this.markNear(this.selected, "near");
  }

  // Edge labels are shown for the selected concept's edges and the hovered one's, not all at once.
  markNear(id, cls) {
    for (const edge of this.edges.values()) {
      edge.el.classList.toggle(cls, id !== null && (edge.s === id || edge.o === id));
    }
  }

  // ---- layout ------------------------------------------------------------------------------

  reheat(alpha) {
    this.alpha = Math.max(this.alpha, alpha);
    this.updateFading();
    if (this.frame === null) this.frame = requestAnimationFrame(() => this.tick());
  }

  tick() {
    this.frame = null;
    const nodes = [...this.nodes.values()];
    const alpha = this.alpha;
    for (let i = 0; i < nodes.length; i++) {
      const a = nodes[i];
      for (let j = i + 1; j < nodes.length; j++) {
        const b = nodes[j];
        let dx = b.x - a.x;
        let dy = b.y - a.y;
        let d2 = dx * dx + dy * dy;
        if (d2 < 1) { dx = Math.random() - 0.5; dy = Math.random() - 0.5; d2 = 1; }
        if (d2 > 250000) continue;
        const f = (CHARGE * alpha) / d2;
        const d = Math.sqrt(d2);
        a.vx -= (dx / d) * f; a.vy -= (dy / d) * f;
        b.vx += (dx / d) * f; b.vy += (dy / d) * f;
      }
    }
    // One spring per linked pair, however many relations the pair has.
    const pairs = new Map();
    for (const edge of this.edges.values()) {
      const key = edge.s < edge.o ? `${edge.s}\u0000${edge.o}` : `${edge.o}\u0000${edge.s}`;
      pairs.set(key, edge);
    }
    const degree = new Map();
    for (const edge of pairs.values()) {
      degree.set(edge.s, (degree.get(edge.s) || 0) + 1);
      degree.set(edge.o, (degree.get(edge.o) || 0) + 1);
    }
    for (const edge of pairs.values()) {
      const a = this.nodes.get(edge.s);
      const b = this.nodes.get(edge.o);
      if (!a || !b || a === b) continue;
      const dx = b.x - a.x;
      const dy = b.y - a.y;
      const d = Math.hypot(dx, dy) || 1;
      const k = ((d - LINK_DISTANCE) / d) * 0.06 * alpha;
      const wa = 1 / (degree.get(a.id) || 1);
      const wb = 1 / (degree.get(b.id) || 1);
      a.vx += dx * k * wa; a.vy += dy * k * wa;
      b.vx -= dx * k * wb; b.vy -= dy * k * wb;
    }
    for (const node of nodes) {
      // Pulled harder vertically than sideways, so the layout fits the wide panel.
      node.vx -= node.x * 0.005 * alpha;
      node.vy -= node.y * 0.026 * alpha;
      if (node.fx !== null) {
        node.x = node.fx; node.y = node.fy; node.vx = 0; node.vy = 0;
        continue;
      }
      node.vx *= 0.6; node.vy *= 0.6;
      node.x += Math.max(-40, Math.min(40, node.vx));
      node.y += Math.max(-40, Math.min(40, node.vy));
    }
    this.render();
    if (this.autoFit) this.fit();
    this.alpha *= 0.975;
    if (this.alpha > 0.004) this.frame = requestAnimationFrame(() => this.tick());
    else this.alpha = 0;
  }

  // ---- interaction -------------------------------------------------------------------------

  centreView() {
    const rect = this.svg.getBoundingClientRect();
    this.view = { x: rect.width / 2, y: rect.height / 2, k: 1 };
    this.applyView();
  }

  applyView() {
    const { x, y, k } = this.view;
    this.viewport.setAttribute("transform", `translate(${x.toFixed(1)},${y.toFixed(1)}) scale(${k.toFixed(3)})`);
  }

  zoomBy(factor, cx, cy) {
    this.autoFit = false;
    const rect = this.svg.getBoundingClientRect();
    const px = cx === undefined ? rect.width / 2 : cx;
    const py = cy === undefined ? rect.height / 2 : cy;
    const k = Math.max(0.2, Math.min(4, this.view.k * factor));
    const ratio = k / this.view.k;
    this.view.x = px - (px - this.view.x) * ratio;
    this.view.y = py - (py - this.view.y) * ratio;
    this.view.k = k;
    this.applyView();
  }

  fit() {
    if (!this.nodes.size) { this.centreView(); return; }
    if (this.svg.getBoundingClientRect().width === 0) return;
    const xs = [...this.nodes.values()].map((n) => n.x);
    const ys = [...this.nodes.values()].map((n) => n.y);
    const pad = 48;
    const minX = Math.min(...xs) - pad;
    const maxX = Math.max(...xs) + pad;
    const minY = Math.min(...ys) - pad;
    const maxY = Math.max(...ys) + pad;
    const rect = this.svg.getBoundingClientRect();
    const width = rect.width - 2 * INSET.side;
    const height = rect.height - INSET.top - INSET.bottom;
    const k = Math.max(0.2, Math.min(1.4, width / (maxX - minX), height / (maxY - minY)));
    this.view = { k, x: rect.width / 2 - k * (minX + maxX) / 2,
      y: INSET.top + height / 2 - k * (minY + maxY) / 2 };
    this.applyView();
  }

  toGraph(clientX, clientY) {
    const rect = this.svg.getBoundingClientRect();
    return { x: (clientX - rect.left - this.view.x) / this.view.k, y: (clientY - rect.top - this.view.y) / this.view.k };
  }

  installPanZoom() {
    this.svg.addEventListener("wheel", (event) => {
      event.preventDefault();
      const rect = this.svg.getBoundingClientRect();
      this.zoomBy(Math.exp(-event.deltaY * 0.0015), event.clientX - rect.left, event.clientY - rect.top);
    }, { passive: false });
    let pan = null;
    this.svg.addEventListener("pointerdown", (event) => {
      if (event.target.closest(".node")) return;
      pan = { x: event.clientX, y: event.clientY, vx: this.view.x, vy: this.view.y };
      this.autoFit = false;
      this.svg.setPointerCapture(event.pointerId);
      this.svg.classList.add("panning");
    });
    this.svg.addEventListener("pointermove", (event) => {
      if (!pan) return;
      this.view.x = pan.vx + event.clientX - pan.x;
      this.view.y = pan.vy + event.clientY - pan.y;
      this.applyView();
    });
    const endPan = () => { pan = null; this.svg.classList.remove("panning"); };
    this.svg.addEventListener("pointerup", endPan);
    this.svg.addEventListener("pointercancel", endPan);
    this.svg.addEventListener("keydown", (event) => {
      if (event.target !== this.svg) return;
      const step = 40;
      const moves = { ArrowLeft: [step, 0], ArrowRight: [-step, 0], ArrowUp: [0, step], ArrowDown: [0, -step] };
      if (event.key === "+" || event.key === "=") this.zoomBy(1.2);
      else if (event.key === "-") this.zoomBy(1 / 1.2);
      else if (moves[event.key]) {
        this.view.x += moves[event.key][0]; this.view.y += moves[event.key][1]; this.applyView();
      } else return;
      event.preventDefault();
    });
  }

  installNodeEvents(node) {
    const el = node.el;
    let drag = null;
    el.addEventListener("pointerdown", (event) => {
      event.stopPropagation();
      drag = { x: event.clientX, y: event.clientY, moved: false };
      el.setPointerCapture(event.pointerId);
    });
    el.addEventListener("pointermove", (event) => {
      if (!drag) return;
      if (!drag.moved && Math.hypot(event.clientX - drag.x, event.clientY - drag.y) < 4) return;
      drag.moved = true;
      this.autoFit = false;
      const p = this.toGraph(event.clientX, event.clientY);
      node.fx = p.x; node.fy = p.y; node.x = p.x; node.y = p.y;
      this.styleNode(node);
      this.reheat(0.3);
    });
    el.addEventListener("pointerup", () => {
      const clicked = drag && !drag.moved;
      drag = null;
      if (clicked) this.onActivate(node.id);
    });
    el.addEventListener("pointerenter", () => this.markNear(node.id, "hover"));
    el.addEventListener("pointerleave", () => this.markNear(null, "hover"));
    el.addEventListener("focus", () => this.markNear(node.id, "hover"));
    el.addEventListener("blur", () => this.markNear(null, "hover"));
    el.addEventListener("dblclick", () => {
      node.fx = null; node.fy = null; this.styleNode(node); this.reheat(0.3);
    });
    el.addEventListener("keydown", (event) => {
      if (event.key === "Enter" || event.key === " ") { event.preventDefault(); this.onActivate(node.id); }
    });
  }
}
