// The map: the occupancy picture, markers with their headings, the robot's pose and path (pose
// events), and the editing: add / rename / move / delete markers (saved to the marker file by
// the server, each edit carrying the marker as last seen so concurrent edits are never lost),
// click to walk to a point and drag to set the heading, and "go" to a marker.
//
// Coordinates: map frame, metres, x forward, y left, yaw counter-clockwise (REP-103). The picture's
// row 0 is the highest y; the canvas draws y upwards.

import { el, getJson, postJson, toast } from "./api.js";

const DEG = 180 / Math.PI;

export class MapView {
  constructor(store, jobs) {
    this.store = store;
    this.jobs = jobs; // follows a walk or a Go to its end (a toast when it fails)
    this.canvas = document.getElementById("map-canvas");
    this.ctx = this.canvas.getContext("2d");
    this.tableBody = document.querySelector("#marker-table tbody");
    this.poseBox = document.getElementById("robot-pose");
    this.cursor = document.getElementById("map-cursor");
    this.image = new Image();
    this.info = null;
    this.markers = {};
    this.version = null;
    this.path = [];
    this.pose = null;
    this.objects = new Map(); // id -> {x, y, label}: the last spatial memory, put-downs, minus picks
    this.view = { k: 1, x: 0, y: 0 };
    this.gesture = null; // pointer interaction in progress
    this.wire();
  }

  async load() {
    try {
      this.info = await getJson("/api/map");
      await new Promise((resolve, reject) => { this.image.onload = resolve; this.image.onerror = reject; this.image.src = "/api/map.png"; });
    } catch (error) {
      this.info = null;
    }
    await this.loadMarkers();
    this.fit();
  }

  async loadMarkers() {
    try {
      const doc = await getJson("/api/markers");
      this.setMarkers(doc);
    } catch (error) {
      document.getElementById("markers-file").textContent = error.message;
    }
  }

  setMarkers(doc) {
    this.markers = doc.markers;
    this.version = doc.version;
    document.getElementById("markers-file").textContent = `version ${doc.version}`;
    this.drawTable();
    this.draw();
  }

  reset() {
    this.path = [];
    this.pose = null;
    this.objects.clear();
    this.onEvents(this.store.events);
  }

  onEvents(batch) {
    let moved = false;
    for (const event of batch) {
      if (event.kind === "pose") {
        this.pose = { x: event.x, y: event.y, yaw: event.yaw };
        this.path.push([event.x, event.y]);
        moved = true;
      } else if (event.kind === "memory" && Array.isArray(event.objects)) {
        // perception's spatial memory (stuart_bt.memory/1): what the robot believes is where now
        this.objects = new Map(event.objects.map((o) => [o.id || o.label, { x: o.x, y: o.y, label: o.label,
          confidence: o.confidence }]));
        moved = true;
      } else if (event.kind === "leaf" && event.outcome === "SUCCESS" && event.skill === "release" && event.result) {
        const label = event.result.object;  // put down: known again where it was put
        if (label && event.result.position) {
          this.objects.set(label, { x: event.result.position.x, y: event.result.position.y, label });
          moved = true;
        }
      } else if (event.kind === "leaf" && event.outcome === "SUCCESS" && event.skill === "pick" && event.result) {
        for (const [key, o] of this.objects) if (o.label === event.result.object) this.objects.delete(key);
        moved = true;
      }
    }
    if (this.path.length > 20000) this.path = this.path.slice(-20000);
    if (moved && this.pose) {
      this.poseBox.textContent = `x ${this.pose.x.toFixed(2)} m, y ${this.pose.y.toFixed(2)} m, yaw ${(this.pose.yaw * DEG).toFixed(0)}°`;
    }
    if (moved) this.draw();
  }

  // -- geometry -------------------------------------------------------------------------------
  toScreen(x, y) {
    const { resolution, origin, height } = this.info;
    const px = (x - origin[0]) / resolution;
    const py = height - (y - origin[1]) / resolution;
    return [this.view.x + px * this.view.k, this.view.y + py * this.view.k];
  }

  toWorld(sx, sy) {
    const { resolution, origin, height } = this.info;
    const px = (sx - this.view.x) / this.view.k;
    const py = (sy - this.view.y) / this.view.k;
    return [origin[0] + px * resolution, origin[1] + (height - py) * resolution];
  }

  fit() {
    this.resize();
    if (!this.info) return;
    const w = this.canvas.width, h = this.canvas.height;
    const k = Math.min(w / this.info.width, h / this.info.height) * 0.95;
    this.view = { k, x: (w - this.info.width * k) / 2, y: (h - this.info.height * k) / 2 };
    this.draw();
  }

  resize() {
    const rect = this.canvas.getBoundingClientRect();
    if (rect.width && (this.canvas.width !== Math.round(rect.width) || this.canvas.height !== Math.round(rect.height))) {
      this.canvas.width = Math.round(rect.width);
      this.canvas.height = Math.round(rect.height);
    }
  }

  // -- drawing --------------------------------------------------------------------------------
  draw() {
    const ctx = this.ctx;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
    if (!this.info) return;
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(this.image, this.view.x, this.view.y, this.info.width * this.view.k, this.info.height * this.view.k);
    if (this.path.length > 1) {
      ctx.strokeStyle = "#2f6fd6";
      ctx.lineWidth = 2;
      ctx.beginPath();
      this.path.forEach(([x, y], i) => { const [sx, sy] = this.toScreen(x, y); if (i) ctx.lineTo(sx, sy); else ctx.moveTo(sx, sy); });
      ctx.stroke();
    }
    for (const [name, m] of Object.entries(this.markers)) {
      const dragging = this.gesture && this.gesture.marker === name ? this.gesture : null;
      this.arrow(dragging ? dragging.x : m.x, dragging ? dragging.y : m.y, m.yaw, "#d97706", m.display_name || name);
    }
    if (this.gesture && this.gesture.kind !== "move" && this.gesture.kind !== "pan") {
      const g = this.gesture;
      this.arrow(g.x, g.y, g.yaw ?? 0, g.kind === "walk" ? "#2e9e5b" : "#d97706", g.kind === "walk" ? "walk here" : "new marker");
    }
    for (const o of this.objects.values()) {
      const [sx, sy] = this.toScreen(o.x, o.y);
      ctx.fillStyle = "#7c3aed";
      ctx.globalAlpha = o.confidence === undefined ? 1 : Math.max(0.3, o.confidence);
      ctx.fillRect(sx - 4, sy - 4, 8, 8);
      ctx.globalAlpha = 1;
      ctx.fillText(o.label, sx + 6, sy + 4);
    }
    if (this.pose) this.robot(this.pose);
  }

  arrow(x, y, yaw, colour, label) {
    const ctx = this.ctx;
    const [sx, sy] = this.toScreen(x, y);
    const r = Math.max(6, 0.25 / this.info.resolution * this.view.k);
    ctx.fillStyle = colour;
    ctx.strokeStyle = colour;
    ctx.beginPath();
    ctx.arc(sx, sy, r * 0.45, 0, 2 * Math.PI);
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(sx, sy);
    ctx.lineTo(sx + Math.cos(yaw) * r * 1.6, sy - Math.sin(yaw) * r * 1.6);
    ctx.stroke();
    ctx.fillStyle = "#1d2430";
    ctx.font = "12px system-ui";
    ctx.fillText(label, sx + r * 0.7, sy - r * 0.7);
  }

  robot(pose) {
    const ctx = this.ctx;
    const [sx, sy] = this.toScreen(pose.x, pose.y);
    const r = Math.max(8, 0.3 / this.info.resolution * this.view.k);
    const c = Math.cos(pose.yaw), s = Math.sin(pose.yaw);
    const point = (f, l) => [sx + (c * f - s * l) * r, sy - (s * f + c * l) * r];
    ctx.fillStyle = "rgba(47,111,214,0.85)";
    ctx.beginPath();
    ctx.moveTo(...point(1.2, 0));
    ctx.lineTo(...point(-0.7, 0.7));
    ctx.lineTo(...point(-0.7, -0.7));
    ctx.closePath();
    ctx.fill();
  }

  // -- markers table --------------------------------------------------------------------------
  drawTable() {
    const names = [], labels = [];
    const rows = Object.entries(this.markers).map(([name, m]) => {
      const inputs = {
        name: el("input", { value: name, "aria-label": "name", oninput: () => fitColumn(names) }),
        label: el("input", { value: m.display_name || "", "aria-label": "label", oninput: () => fitColumn(labels) }),
        x: el("input", { value: m.x, type: "number", step: "0.05", "aria-label": "x" }),
        y: el("input", { value: m.y, type: "number", step: "0.05", "aria-label": "y" }),
        yaw: el("input", { value: Math.round(m.yaw * DEG), type: "number", step: "5", "aria-label": "yaw" }),
      };
      names.push(inputs.name);
      labels.push(inputs.label);
      const save = () => this.saveRow(name, m, inputs);
      return el("tr", { "data-marker": name },
        el("td", {}, inputs.name), el("td", {}, inputs.label), el("td", {}, inputs.x), el("td", {}, inputs.y),
        el("td", {}, inputs.yaw),
        el("td", {}, el("button", { onclick: save, title: "save this marker" }, "Save"),
          el("button", { onclick: () => this.goTo(name), title: "walk there" }, "Go"),
          el("button", { onclick: () => this.remove(name, m), title: "delete" }, "✕")));
    });
    this.tableBody.replaceChildren(...rows);
    fitColumn(names);
    fitColumn(labels);
  }

  async saveRow(name, seen, inputs) {
    const expect = { x: seen.x, y: seen.y, yaw: seen.yaw, display_name: seen.display_name };
    const values = { x: Number(inputs.x.value), y: Number(inputs.y.value), yaw: Number(inputs.yaw.value) / DEG,
      display_name: inputs.label.value };
    let doc = await this.edit({ op: "update", name, expect, ...values }, null);
    if (doc && inputs.name.value !== name) {
      doc = await this.edit({ op: "rename", name, new_name: inputs.name.value.trim() }, `renamed ${name} to ${inputs.name.value}`);
    } else if (doc) toast(`saved ${name}`);
  }

  async remove(name, seen) {
    if (!confirm(`Delete marker ${name}?`)) return;
    await this.edit({ op: "delete", name, expect: { x: seen.x, y: seen.y } }, `deleted ${name}`);
  }

  async goTo(name) {
    await this.jobs.send(postJson("/api/goto", { marker: name }), `go to ${name}`, `going to ${name}`);
  }

  async edit(request, done) {
    try {
      const doc = await postJson("/api/markers", request);
      this.setMarkers(doc);
      if (done) toast(done);
      return doc;
    } catch (error) {
      toast(error.message, true);
      if (error.status === 409 && error.data && error.data.current) this.setMarkers(error.data.current);
      return null;
    }
  }

  // -- pointer --------------------------------------------------------------------------------
  mode() { return document.querySelector("input[name=map-mode]:checked").value; }

  markerAt(sx, sy) {
    for (const [name, m] of Object.entries(this.markers)) {
      const [mx, my] = this.toScreen(m.x, m.y);
      if (Math.hypot(mx - sx, my - sy) < 12) return name;
    }
    return null;
  }

  wire() {
    const local = (e) => { const r = this.canvas.getBoundingClientRect(); return [e.clientX - r.left, e.clientY - r.top]; };
    this.canvas.addEventListener("wheel", (e) => {
      e.preventDefault();
      const [sx, sy] = local(e);
      const f = e.deltaY < 0 ? 1.15 : 1 / 1.15;
      this.view.x = sx - (sx - this.view.x) * f;
      this.view.y = sy - (sy - this.view.y) * f;
      this.view.k *= f;
      this.draw();
    }, { passive: false });
    this.canvas.addEventListener("pointerdown", (e) => {
      if (!this.info) return;
      const [sx, sy] = local(e);
      const [x, y] = this.toWorld(sx, sy);
      const mode = this.mode();
      if (mode === "move") {
        const name = this.markerAt(sx, sy);
        if (!name) return;
        this.gesture = { kind: "move", marker: name, x: this.markers[name].x, y: this.markers[name].y };
      } else if (mode === "walk" || mode === "add") {
        this.gesture = { kind: mode, x, y, yaw: null, sx, sy };
      } else {
        this.gesture = { kind: "pan", sx, sy, vx: this.view.x, vy: this.view.y };
      }
      this.canvas.setPointerCapture(e.pointerId);
    });
    this.canvas.addEventListener("pointermove", (e) => {
      if (!this.info) return;
      const [sx, sy] = local(e);
      const [x, y] = this.toWorld(sx, sy);
      this.cursor.textContent = `x ${x.toFixed(2)} m, y ${y.toFixed(2)} m`;
      const g = this.gesture;
      if (!g) return;
      if (g.kind === "pan") { this.view.x = g.vx + sx - g.sx; this.view.y = g.vy + sy - g.sy; }
      else if (g.kind === "move") { g.x = x; g.y = y; }
      else if (Math.hypot(sx - g.sx, sy - g.sy) > 8) g.yaw = Math.atan2(-(sy - g.sy), sx - g.sx);
      this.draw();
    });
    this.canvas.addEventListener("pointerup", () => this.finish());
    this.canvas.addEventListener("pointercancel", () => { this.gesture = null; this.draw(); });
    new ResizeObserver(() => { this.resize(); this.draw(); }).observe(this.canvas.parentElement);
  }

  async finish() {
    const g = this.gesture;
    this.gesture = null;
    if (!g || g.kind === "pan") return;
    if (g.kind === "move") {
      const m = this.markers[g.marker];
      this.draw();
      if (Math.hypot(g.x - m.x, g.y - m.y) > 0.01) {
        await this.edit({ op: "update", name: g.marker, x: round(g.x), y: round(g.y), expect: { x: m.x, y: m.y } }, `moved ${g.marker}`);
      }
    } else if (g.kind === "walk") {
      this.draw();
      const where = `(${g.x.toFixed(2)}, ${g.y.toFixed(2)})`;
      await this.jobs.send(postJson("/api/walk", { x: round(g.x), y: round(g.y), yaw: g.yaw }), `walk to ${where}`,
        `walking to ${where}`);
    } else if (g.kind === "add") {
      this.draw();
      const name = prompt("Name of the new marker (lower case, digits, _):", "");
      if (!name) return;
      const label = prompt("Label shown to people (optional):", name.replace(/_/g, " ")) ?? "";
      await this.edit({ op: "add", name: name.trim(), x: round(g.x), y: round(g.y), yaw: g.yaw ?? 0, display_name: label }, `added ${name}`);
    }
  }
}

function round(v) { return Math.round(v * 1000) / 1000; }

// Make a column's inputs as wide as the longest text in any of them, measured in their own font
// (padding and border added: the inputs size their border box), so no name is cut off.
const measure = document.createElement("canvas").getContext("2d");
function fitColumn(inputs) {
  if (!inputs.length) return;
  const style = getComputedStyle(inputs[0]);
  measure.font = `${style.fontStyle} ${style.fontWeight} ${style.fontSize} ${style.fontFamily}`;
  const text = Math.max(...inputs.map((input) => measure.measureText(input.value).width));
  const chrome = ["paddingLeft", "paddingRight", "borderLeftWidth", "borderRightWidth"]
    .reduce((sum, side) => sum + (parseFloat(style[side]) || 0), 0);
  const width = `${Math.ceil(text + chrome) + 2}px`; // + 2: room for the caret at the end
  for (const input of inputs) input.style.width = width;
}
