// The gesture recorder: a slider per arm, hand and waist joint (names and limits from the robot
// description, served by /api/joints), the pose sent to the simulator as the sliders move,
// keyframes added from the sliders, re-timed, reordered and removed, saved as a gesture file the
// `gesture` leaf plays (file: ...), loaded back, and played on the robot.

import { act, el, getJson, postJson, toast } from "./api.js";

const DEG = 180 / Math.PI;
const SEND_EVERY = 120; // ms between two poses sent while a slider is dragged
const STEP = 1.0; // seconds between a new keyframe and the previous one

export class GestureView {
  constructor() {
    this.joints = [];
    this.values = new Map();
    this.inputs = new Map();
    this.frames = [];
    this.live = false;
    this.sendTimer = null;
    this.kfBody = document.querySelector("#kf-table tbody");
    this.status = document.getElementById("g-status");
    this.nameInput = document.getElementById("g-name");
    document.getElementById("g-neutral").onclick = () => { for (const j of this.joints) this.setValue(j.name, j.neutral); this.sendPose(); };
    document.getElementById("kf-add").onclick = () => this.addFrame();
    document.getElementById("g-save").onclick = () => this.save();
    document.getElementById("g-play").onclick = () => this.play();
    document.getElementById("g-load").onclick = () => this.load(document.getElementById("g-load-select").value);
  }

  async init() {
    const data = await getJson("/api/joints");
    this.joints = data.joints;
    this.live = data.live;
    // start from where the robot's arms are, read before the sliders exist: read after, it would
    // overwrite a slider the user (or a test) moved in the meantime
    const now = this.live ? await getJson("/api/pose").catch(() => null) : null;
    const start = (now && now.joints) || {};
    document.getElementById("g-live").textContent = data.live
      ? "The pose follows the sliders in the simulator."
      : "Recording only: the pose is applied live in a tree server with --backend sim.";
    const groups = new Map();
    for (const joint of this.joints) {
      if (!groups.has(joint.group)) groups.set(joint.group, el("fieldset", {}, el("legend", {}, joint.group)));
      const initial = start[joint.name] ?? joint.neutral;
      const input = el("input", { type: "range", min: joint.lower, max: joint.upper, step: 0.01, value: initial,
        "data-joint": joint.name, "aria-label": joint.name });
      const shown = el("span", { class: "v" });
      input.addEventListener("input", () => { this.values.set(joint.name, Number(input.value)); shown.textContent = deg(input.value); this.scheduleSend(); });
      this.inputs.set(joint.name, { input, shown });
      this.values.set(joint.name, initial);
      shown.textContent = deg(initial);
      groups.get(joint.group).append(el("label", { class: "slider", title: `${joint.name}: ${deg(joint.lower)}..${deg(joint.upper)}` },
        el("span", {}, pretty(joint.name)), input, shown));
    }
    document.getElementById("sliders").replaceChildren(...groups.values());
    await this.refreshList();
    this.drawFrames();
  }

  setValue(name, value) {
    const parts = this.inputs.get(name);
    if (!parts) return;
    parts.input.value = value;
    parts.shown.textContent = deg(value);
    this.values.set(name, value);
  }

  pose() { return Object.fromEntries([...this.values].map(([k, v]) => [k, Math.round(v * 1e4) / 1e4])); }

  scheduleSend() {
    if (!this.live || this.sendTimer) return;
    this.sendTimer = setTimeout(() => { this.sendTimer = null; this.sendPose(); }, SEND_EVERY);
  }

  async sendPose() {
    if (!this.live) return;
    try { await postJson("/api/pose", { joints: this.pose() }); }
    catch (error) { toast(error.message, true); }
  }

  addFrame() {
    const t = this.frames.length ? this.frames[this.frames.length - 1].t + STEP : STEP;
    this.frames.push({ t: Math.round(t * 100) / 100, joints: this.pose() });
    this.drawFrames();
  }

  drawFrames() {
    const rows = this.frames.map((frame, i) => {
      const time = el("input", { type: "number", step: "0.1", min: "0", value: frame.t, "aria-label": `time of keyframe ${i + 1}` });
      time.addEventListener("change", () => { frame.t = Number(time.value); });
      return el("tr", { "data-frame": i },
        el("td", {}, `${i + 1}. `, time),
        el("td", {},
          el("button", { onclick: () => this.showFrame(frame), title: "put the sliders here" }, "Show"),
          el("button", { onclick: () => this.move(i, -1), title: "earlier", disabled: i === 0 ? "" : null }, "↑"),
          el("button", { onclick: () => this.move(i, 1), title: "later", disabled: i === this.frames.length - 1 ? "" : null }, "↓"),
          el("button", { onclick: () => { this.frames.splice(i, 1); this.drawFrames(); }, title: "remove" }, "✕")));
    });
    this.kfBody.replaceChildren(...rows);
  }

  // Reordering swaps the poses and keeps the times in place, so times still increase.
  move(i, delta) {
    const j = i + delta;
    if (j < 0 || j >= this.frames.length) return;
    const a = this.frames[i], b = this.frames[j];
    [a.joints, b.joints] = [b.joints, a.joints];
    this.drawFrames();
  }

  showFrame(frame) {
    for (const [name, value] of Object.entries(frame.joints)) this.setValue(name, value);
    this.sendPose();
  }

  async save() {
    const name = this.nameInput.value.trim();
    if (!this.frames.length) { toast("add at least one keyframe first", true); return false; }
    try {
      const result = await postJson(`/api/gestures/${encodeURIComponent(name)}`, { keyframes: this.frames });
      this.status.textContent = `saved ${result.file}`;
      this.status.dataset.saved = name;
      toast(`saved ${name}`);
      await this.refreshList();
      return true;
    } catch (error) {
      this.status.textContent = error.message;
      toast(error.message, true);
      return false;
    }
  }

  async play() {
    const name = this.nameInput.value.trim();
    if (!(await this.save())) return;
    const ok = await act(postJson(`/api/gestures/${encodeURIComponent(name)}/play`), `playing ${name}`);
    if (ok) this.status.textContent = `playing ${name}`;
  }

  async load(name) {
    if (!name) return;
    const data = await act(getJson(`/api/gestures/${encodeURIComponent(name)}`));
    if (!data) return;
    this.nameInput.value = name;
    this.frames = data.keyframes.map((k) => ({ t: k.t, joints: { ...this.pose(), ...k.joints } }));
    this.drawFrames();
    this.status.textContent = `loaded ${data.file}: ${data.keyframes.length} keyframes`;
  }

  async refreshList() {
    const data = await act(getJson("/api/gestures"));
    if (!data) return;
    const select = document.getElementById("g-load-select");
    select.replaceChildren(...data.gestures.map((g) => el("option", { value: g }, g)));
  }
}

function deg(rad) { return `${(Number(rad) * DEG).toFixed(0)}°`; }
function pretty(name) { return name.replace(/^(left|right)_(hand_)?/, "").replace(/_joint$/, "").replace(/_/g, " "); }
