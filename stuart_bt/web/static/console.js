// The console: type what the speech recogniser would hear; see how it was understood (intents),
// the missions (queue), the plan as compiled into a tree, and what the robot says. Serving one
// tree, what is said goes to that tree while it runs: answers, and the tree held and going on.
// Everything shown comes from events (utterance, mission, tree, reply, command, leaf, hold,
// resume, warning).

import { act, el, postJson, short } from "./api.js";
import { PushToTalk } from "./talk.js";

export class ConsoleView {
  constructor(store) {
    this.store = store;
    this.log = document.getElementById("console-log");
    this.queueBody = document.querySelector("#queue-table tbody");
    this.plan = document.getElementById("plan-view");
    this.missions = new Map();
    const form = document.getElementById("say-form");
    const input = document.getElementById("say-input");
    form.addEventListener("submit", async (e) => {
      e.preventDefault();
      const text = input.value.trim();
      if (!text) return;
      const result = await act(postJson("/api/say", { text }));
      if (result) input.value = "";
    });
    this.talk = new PushToTalk(document.getElementById("talk-button"), (kind, text) => {
      const last = this.store.events[this.store.events.length - 1];
      this.append(last ? last.t : 0, kind, text);
    });
  }

  reset() {
    this.log.replaceChildren();
    this.missions.clear();
    this.plan.textContent = "No mission yet.";
    this.onEvents(this.store.events);
  }

  onEvents(batch) {
    let queueChanged = false;
    for (const event of batch) {
      const line = describe(event);
      if (line) this.append(event.t, ...line);
      if (event.kind === "mission") {
        const m = this.missions.get(event.id) || { id: event.id, tasks: [] };
        if (event.tasks) m.tasks = event.tasks;
        m.phase = event.phase;
        m.status = event.status || (event.phase === "queued" ? "queued" : event.phase === "started" ? "running" : m.status);
        m.reason = event.reason || null;
        this.missions.set(event.id, m);
        queueChanged = true;
      } else if (event.kind === "tree" && event.root && event.file !== "<say>") {
        this.plan.textContent = drawPlan(event.root);
      }
    }
    if (queueChanged) this.drawQueue();
  }

  append(t, kind, text) {
    const item = el("li", { class: kind }, el("span", { class: "t" }, Number(t).toFixed(2)),
      el("span", { class: "kind" }, kind), text);
    this.log.append(item);
    while (this.log.children.length > 2000) this.log.firstChild.remove();
    this.log.scrollTop = this.log.scrollHeight;
  }

  drawQueue() {
    const rows = [...this.missions.values()].sort((a, b) => b.id - a.id).map((m) =>
      el("tr", { "data-mission": m.id, "data-status": m.status || m.phase },
        el("td", {}, m.id), el("td", {}, m.tasks.join(", ")),
        el("td", {}, `${m.status || m.phase}${m.reason ? ": " + m.reason : ""}`)));
    this.queueBody.replaceChildren(...rows);
  }
}

function describe(event) {
  switch (event.kind) {
    case "utterance": {
      const intents = (event.intents || []).map(intent).join(", ");
      return ["heard", `“${event.text}” → ${event.data_kind || "?"}${intents ? ": " + intents : ""}`];
    }
    case "mission": {
      const extra = event.reason || event.status || (event.tasks || []).join(", ");
      return ["mission", `${event.id} ${event.phase}${extra ? ": " + extra : ""}`];
    }
    case "reply": {
      const gestures = event.gestures && event.gestures.length ? ` (gestures: ${event.gestures.join(", ")})` : "";
      const from = event.source ? ` (from ${event.source})` : "";
      return ["reply", `“${event.text}”${gestures}${from}`];
    }
    case "hold":
      return ["hold", `the tree is held: ${event.reason || "hold"}${/^stop said/.test(event.reason || "") ? " (say continue, or press Continue)" : ""}`];
    case "resume":
      return ["resume", "the tree goes on"];
    case "command":
      if (event.family === "tts" && event.cmd === "say") return ["says", `“${(event.args || {}).text}”`];
      if (event.cmd === "play") return ["gesture", short((event.args || {}).name || (event.args || {}).sequence || "recorded")];
      return null;
    case "leaf":
      if (event.outcome === "FAILURE" && event.skill !== "condition") return ["failed", `${event.path}${event.reason ? ": " + event.reason : ""}`];
      return null;
    case "warning":
      return ["warning", event.message];
    case "run":
      return event.phase === "end" ? ["run", `${event.label || "run"} ended: ${event.status}${event.reason ? " (" + event.reason + ")" : ""}`] : null;
    default:
      return null;
  }
}

function intent(i) {
  const args = Object.entries(i).filter(([k, v]) => !["action", "raw_text", "confidence"].includes(k) &&
    v !== null && v !== "" && v !== 0 && !(Array.isArray(v) && !v.length)).map(([k, v]) => `${k}=${v}`);
  return `${i.action}(${args.join(", ")})`;
}

// The compiled tree, indented: compound tasks as their sequences, skills as leaves with params.
function drawPlan(root) {
  const lines = [];
  const walk = (node, depth) => {
    const params = Object.entries(node.params || {}).filter(([k]) => k !== "timeout")
      .map(([k, v]) => `${k}=${typeof v === "string" ? v : JSON.stringify(v)}`).join(" ");
    const head = node.children && node.children.length ? `${node.name} [${node.kind}]` : `${node.kind} ${node.name !== node.kind ? node.name + " " : ""}${params}`;
    lines.push("  ".repeat(depth) + head);
    for (const child of node.children || []) walk(child, depth + 1);
  };
  walk(root, 0);
  return lines.join("\n");
}
