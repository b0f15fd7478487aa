// The tree view: the tree as a left-to-right graph in SVG, nodes coloured by status, the running
// path drawn thick, subtrees that collapse, zoom and pan, a details panel, and the timeline.
//
// The graph is laid out again only when the tree or the collapsed set changes; a status change
// only swaps a class on one node, so a tick never redraws the page.

import { el, short } from "./api.js";
import { BOX_H, BOX_W, layoutTree } from "./layout.js";
import { runningPath } from "./store.js";

const SVG = "http://www.w3.org/2000/svg";
const ICONS = { sequence: "→", selector: "?", parallel: "⇉" };
const NO_NODE = "Click a node for its parameters, blackboard keys, last result and failure reason.";

function svg(tag, attrs = {}) {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  return node;
}

export class TreeView {
  constructor(store) {
    this.store = store;
    this.svg = document.getElementById("tree-svg");
    this.g = document.getElementById("tree-g");
    this.select = document.getElementById("tree-select");
    this.range = document.getElementById("tl-range");
    this.label = document.getElementById("tl-label");
    this.liveButton = document.getElementById("tl-live");
    this.details = document.getElementById("node-details");
    this.segment = null;
    this.follow = true; // show the newest tree as trees are built
    this.live = true; // statuses follow the stream; false while scrubbing
    this.collapsed = new Set();
    this.state = null; // {status, last, history, seen}
    this.elements = new Map(); // path -> {group, edge}
    this.selected = null;
    this.view = { x: 20, y: 20, k: 1 };
    this.playing = null;
    this.wire();
  }

  wire() {
    this.select.addEventListener("change", () => {
      const i = Number(this.select.value);
      this.follow = i === this.store.segments.length - 1;
      this.show(this.store.segments[i]);
    });
    document.getElementById("zoom-in").onclick = () => this.zoom(1.25);
    document.getElementById("zoom-out").onclick = () => this.zoom(0.8);
    document.getElementById("zoom-fit").onclick = () => this.fit();
    document.getElementById("expand-all").onclick = () => { this.collapsed.clear(); this.layout(); };
    document.getElementById("collapse-done").onclick = () => this.collapseFinished();
    this.range.addEventListener("input", () => { this.stopPlaying(); this.scrub(Number(this.range.value)); });
    this.liveButton.onclick = () => { this.stopPlaying(); this.goLive(); };
    document.getElementById("tl-play").onclick = () => this.play();
    this.svg.addEventListener("wheel", (e) => {
      e.preventDefault();
      const rect = this.svg.getBoundingClientRect();
      this.zoom(e.deltaY < 0 ? 1.15 : 1 / 1.15, e.clientX - rect.left, e.clientY - rect.top);
    }, { passive: false });
    let drag = null;
    this.svg.addEventListener("pointerdown", (e) => {
      if (e.target.closest(".node")) return;
      drag = { x: e.clientX, y: e.clientY, vx: this.view.x, vy: this.view.y };
      this.svg.classList.add("dragging");
      this.svg.setPointerCapture(e.pointerId);
    });
    this.svg.addEventListener("pointermove", (e) => {
      if (!drag) return;
      this.view.x = drag.vx + e.clientX - drag.x;
      this.view.y = drag.vy + e.clientY - drag.y;
      this.applyView();
    });
    const end = () => { drag = null; this.svg.classList.remove("dragging"); };
    this.svg.addEventListener("pointerup", end);
    this.svg.addEventListener("pointercancel", end);
  }

  // -- data in --------------------------------------------------------------------------------
  reset() {
    this.drawBlackboard(new Set());
    this.refreshSelect();
    const segments = this.store.segments;
    this.show(segments.length ? segments[segments.length - 1] : null);
  }

  onEvents(batch) {
    if (batch.some((e) => e.kind === "blackboard")) this.scheduleBlackboard(batch);
    const segments = this.store.segments;
    const newest = segments[segments.length - 1];
    if (segments.length !== this.select.options.length) this.refreshSelect();
    if (this.follow && newest && newest !== this.segment) { this.show(newest); return; }
    if (!this.segment || this.segment.end !== null && this.segment !== newest) return;
    let changed = false;
    for (const event of batch) {
      if (!this.segment.nodes.has(event.path)) continue;
      if (event.kind === "status") {
        changed = true;
        if (!this.live) continue;
        this.state.status.set(event.path, event.new);
        this.state.seen += 1;
        this.state.t = event.t;
        if (!this.state.history.has(event.path)) this.state.history.set(event.path, []);
        this.state.history.get(event.path).push({ t: event.t, status: event.new });
        this.paintNode(event.path);
      } else if (event.kind === "leaf" && this.live) {
        this.state.last.set(event.path, { outcome: event.outcome, reason: event.reason, result: event.result, t: event.t });
        if (event.path === this.selected) this.showDetails(event.path);
      }
    }
    if (changed) {
      this.changes = this.store.changes(this.segment);
      this.range.max = this.changes.length;
      if (this.live) {
        this.range.value = this.changes.length;
        this.paintPath();
        this.updateLabel();
        if (this.selected) this.showDetails(this.selected);
      }
    }
  }

  refreshSelect() {
    this.select.replaceChildren(...this.store.segments.map((s, i) =>
      el("option", { value: i }, `${i + 1}. ${s.file || s.root} (t=${Number(s.t).toFixed(1)})`)));
    if (this.segment) this.select.value = this.store.segments.indexOf(this.segment);
  }

  show(segment) {
    const changedTree = segment !== this.segment;
    this.segment = segment;
    if (segment) this.select.value = this.store.segments.indexOf(segment);
    if (changedTree) { // another tree: the details of a node of the last one would be about nothing shown
      this.collapsed.clear();
      this.selected = null;
      this.showDetails(null);
    }
    this.changes = segment ? this.store.changes(segment) : [];
    this.range.max = this.changes.length;
    this.live = segment !== null && segment.end === null;
    this.liveButton.classList.toggle("active", this.live);
    this.state = segment ? this.store.fold(segment) : null;
    this.range.value = this.changes.length;
    this.layout();
    if (changedTree) this.fitted = this.fit();
    this.updateLabel();
  }

  // -- blackboard table: at most once per frame, however many writes a tick makes --------------
  scheduleBlackboard(batch) {
    this.freshKeys = this.freshKeys || new Set();
    for (const e of batch) if (e.kind === "blackboard") this.freshKeys.add(String(e.key));
    if (this.bbFrame) return;
    this.bbFrame = requestAnimationFrame(() => {
      this.bbFrame = null;
      const fresh = this.freshKeys;
      this.freshKeys = new Set();
      this.drawBlackboard(fresh);
    });
  }

  drawBlackboard(fresh) {
    const body = document.querySelector("#bb-table tbody");
    const keys = [...this.store.blackboard.keys()].sort();
    body.replaceChildren(...keys.map((key) => {
      const entry = this.store.blackboard.get(key);
      return el("tr", { class: fresh.has(key) ? "fresh" : "", "data-key": key },
        el("td", {}, key), el("td", { title: `written at t=${Number(entry.t).toFixed(2)}` }, short(entry.value, 240)));
    }));
  }

  // -- timeline -------------------------------------------------------------------------------
  scrub(count) {
    if (!this.segment) return;
    this.live = count >= this.changes.length && this.segment.end === null;
    this.liveButton.classList.toggle("active", this.live);
    this.state = this.store.fold(this.segment, this.live ? null : count);
    this.range.value = count;
    for (const path of this.elements.keys()) this.paintNode(path);
    this.paintPath();
    this.updateLabel();
    if (this.selected) this.showDetails(this.selected);
  }

  goLive() {
    const segments = this.store.segments;
    this.follow = true;
    const newest = segments[segments.length - 1];
    if (newest !== this.segment) this.show(newest); else this.scrub(this.changes.length);
  }

  play() {
    if (!this.segment) return;
    this.stopPlaying();
    let position = Number(this.range.value);
    if (position >= this.changes.length) position = 0;
    this.scrub(position);
    const step = () => {
      if (position >= this.changes.length) { this.playing = null; return; }
      const here = this.changes[position];
      const next = this.changes[position + 1];
      position += 1;
      this.scrub(position);
      const gap = next ? Math.min(400, Math.max(15, (next.t - here.t) * 250)) : 0;
      this.playing = setTimeout(step, gap);
    };
    this.playing = setTimeout(step, 100);
  }

  stopPlaying() { if (this.playing) clearTimeout(this.playing); this.playing = null; }

  updateLabel() {
    if (!this.segment) { this.label.textContent = "no tree yet"; return; }
    const n = this.changes.length;
    const at = Number(this.range.value);
    const t = at > 0 && this.changes[at - 1] ? this.changes[at - 1].t : this.segment.t;
    this.label.textContent = `${this.live ? "live" : "replay"} · change ${at}/${n} · t = ${Number(t).toFixed(2)} s`;
  }

  // -- drawing --------------------------------------------------------------------------------
  layout() {
    this.g.replaceChildren();
    this.elements.clear();
    if (!this.segment) return;
    const edges = svg("g");
    const boxes = svg("g");
    this.g.append(edges, boxes);
    const placed = layoutTree(this.segment.nodes, this.segment.root, (path) => !this.collapsed.has(path));
    for (const e of placed.edges) {
      const edge = svg("path", { class: "edge", d: elbow(e.x1, e.y1, e.x2, e.y2) });
      edges.append(edge);
      this.elements.set(e.to, { ...(this.elements.get(e.to) || {}), edge });
    }
    for (const [path, at] of placed.boxes) {
      const group = this.drawNode(this.segment.nodes.get(path), at.x, at.y, !this.collapsed.has(path));
      boxes.append(group);
      this.elements.set(path, { ...(this.elements.get(path) || {}), group });
    }
    for (const path of this.elements.keys()) this.paintNode(path);
    this.paintPath();
    if (this.selected) this.markSelected();
    this.applyView();
  }

  drawNode(node, x, y, open) {
    const group = svg("g", { class: "node", transform: `translate(${x},${y})`, "data-path": node.path,
      "data-name": node.name, "data-kind": node.kind });
    const title = svg("title");
    title.textContent = node.path;
    group.append(title, svg("rect", { class: "box", width: BOX_W, height: BOX_H }),
      svg("rect", { class: "band", width: 5, height: BOX_H }));
    const label = svg("text", { x: 10, y: 15 });
    const icon = ICONS[node.kind] ? `[${ICONS[node.kind]}] ` : node.category === "decorator" ? `<${node.kind}> ` : "";
    label.textContent = clip(`${icon}${node.name}${node.category === "leaf" && node.kind !== node.name ? ` (${node.kind})` : ""}`, 30);
    const sub = svg("text", { x: 10, y: 30, class: "sub" });
    sub.textContent = clip(paramsLine(node), 36);
    group.append(label, sub);
    if (node.childPaths.length) {
      const toggle = svg("g", { class: "toggler", transform: `translate(${BOX_W - 18},${BOX_H / 2 - 7})` });
      toggle.append(svg("rect", { class: "toggle", width: 14, height: 14, rx: 3 }));
      const t = svg("text", { class: "toggle-text", x: open ? 3.5 : 3, y: 11 });
      t.textContent = open ? "−" : "+";
      toggle.append(t);
      if (!open) {
        const count = svg("text", { class: "sub", x: BOX_W + 6, y: 24 });
        count.textContent = `+${countBelow(this.segment, node.path)}`;
        group.append(count);
      }
      toggle.addEventListener("click", (e) => { e.stopPropagation(); this.toggle(node.path); });
      group.append(toggle);
    }
    group.addEventListener("click", () => this.selectNode(node.path));
    group.addEventListener("dblclick", (e) => { e.preventDefault(); if (node.childPaths.length) this.toggle(node.path); });
    return group;
  }

  toggle(path) {
    if (this.collapsed.has(path)) this.collapsed.delete(path); else this.collapsed.add(path);
    this.layout();
  }

  collapseFinished() {
    for (const path of this.segment ? this.segment.order : []) {
      const node = this.segment.nodes.get(path);
      const status = this.state.status.get(path);
      if (node.childPaths.length && path !== this.segment.root && (status === "SUCCESS" || status === "FAILURE")) {
        this.collapsed.add(path);
      }
    }
    this.layout();
  }

  // A node's status: its own, or for a collapsed-away node nothing to paint.
  paintNode(path) {
    const parts = this.elements.get(path);
    if (!parts || !parts.group) return;
    const status = this.state.status.get(path) || "INVALID";
    const group = parts.group;
    group.classList.remove("RUNNING", "SUCCESS", "FAILURE", "INVALID");
    group.classList.add(status);
    group.setAttribute("data-status", status);
  }

  paintPath() {
    const onPath = new Set(this.segment ? runningPath(this.segment, this.state.status) : []);
    for (const [path, parts] of this.elements) {
      if (parts.group) parts.group.classList.toggle("onpath", onPath.has(path));
      if (parts.edge) parts.edge.classList.toggle("onpath", onPath.has(path));
    }
  }

  selectNode(path) {
    this.selected = path;
    this.markSelected();
    this.showDetails(path);
  }

  markSelected() {
    for (const [p, parts] of this.elements) if (parts.group) parts.group.classList.toggle("selected", p === this.selected);
  }

  showDetails(path) {
    const node = this.segment && this.segment.nodes.get(path);
    if (!node) { this.details.textContent = NO_NODE; return; }
    const last = this.state.last.get(path);
    const history = (this.state.history.get(path) || []).slice(-6);
    const params = Object.entries(node.params || {});
    const keys = blackboardKeys(node.params || {});
    const rows = [
      ["path", node.path], ["kind", `${node.kind} (${node.category})`],
      ["status", this.state.status.get(path) || "INVALID"],
    ];
    const list = el("dl");
    for (const [k, v] of rows) list.append(el("dt", {}, k), el("dd", { "data-field": k }, v));
    list.append(el("dt", {}, "parameters"), el("dd", {}, params.length ? el("table", { class: "kv" },
      ...params.map(([k, v]) => el("tr", {}, el("td", {}, k), el("td", {}, short(v, 200))))) : "none"));
    if (keys.length) {
      list.append(el("dt", {}, "blackboard keys"), el("dd", {}, el("table", { class: "kv" },
        ...keys.map((k) => el("tr", {}, el("td", {}, k), el("td", {}, short((this.store.blackboard.get(k.split(".")[0]) || {}).value, 120)))))));
    }
    list.append(el("dt", {}, "last result"), el("dd", { "data-field": "last" },
      last ? `${last.outcome}${last.result ? " " + short(last.result, 200) : ""} (t=${Number(last.t).toFixed(2)})` : "not finished yet"));
    if (last && last.reason) list.append(el("dt", {}, "failure reason"), el("dd", { "data-field": "reason" }, last.reason));
    if (history.length) {
      list.append(el("dt", {}, "recent changes"), el("dd", {}, history.map((h) => `${Number(h.t).toFixed(2)} ${h.status}`).join(" · ")));
    }
    this.details.replaceChildren(list);
  }

  // -- zoom and pan ---------------------------------------------------------------------------
  applyView() {
    this.g.setAttribute("transform", `translate(${this.view.x},${this.view.y}) scale(${this.view.k})`);
  }

  zoom(factor, cx = null, cy = null) {
    const rect = this.svg.getBoundingClientRect();
    cx = cx ?? rect.width / 2;
    cy = cy ?? rect.height / 2;
    const k = Math.min(4, Math.max(0.1, this.view.k * factor));
    this.view.x = cx - (cx - this.view.x) * (k / this.view.k);
    this.view.y = cy - (cy - this.view.y) * (k / this.view.k);
    this.view.k = k;
    this.applyView();
  }

  fit() {
    const rect = this.svg.getBoundingClientRect();
    let box;
    try { box = this.g.getBBox(); } catch { return false; }
    if (!box.width || !rect.width) return false;
    const k = Math.min(1.2, Math.max(0.1, Math.min((rect.width - 40) / box.width, (rect.height - 40) / box.height)));
    this.view = { k, x: 20 - box.x * k, y: 20 - box.y * k };
    this.applyView();
    return true;
  }
}

function elbow(x1, y1, x2, y2) {
  const mx = (x1 + x2) / 2;
  return `M${x1},${y1} C${mx},${y1} ${mx},${y2} ${x2},${y2}`;
}

function clip(text, n) { return text.length > n ? text.slice(0, n - 1) + "…" : text; }

function paramsLine(node) {
  const entries = Object.entries(node.params || {});
  return entries.map(([k, v]) => `${k}=${typeof v === "string" ? v : JSON.stringify(v)}`).join(" ");
}

function countBelow(segment, path) {
  const node = segment.nodes.get(path);
  return node.childPaths.reduce((n, c) => n + 1 + countBelow(segment, c), 0);
}

// "$key", "${key}" and expression names that read the blackboard (e.g. world.held).
function blackboardKeys(params) {
  const keys = new Set();
  const text = JSON.stringify(params);
  for (const m of text.matchAll(/\$\{?([A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z0-9_]+)*)/g)) keys.add(m[1]);
  for (const [k, v] of Object.entries(params)) {
    if ((k === "condition" || k === "expression" || k === "while") && typeof v === "string") {
      for (const m of v.matchAll(/\b([A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*)*)/g)) {
        if (!["and", "or", "not", "in", "null", "true", "false", "None", "True", "False"].includes(m[1])) keys.add(m[1]);
      }
    }
  }
  return [...keys];
}
