// Wiring: the socket feeds the store; the store feeds the four views; the header's buttons
// and state pill talk to /api. Nothing here knows how a view draws.

import { act, connect, getJson, postJson } from "./api.js";
import { ConsoleView } from "./console.js";
import { GestureView } from "./gestures.js";
import { JobWatch } from "./jobs.js";
import { MapView } from "./map.js";
import { Store } from "./store.js";
import { TreeView } from "./tree.js";

const store = new Store();
const jobs = new JobWatch(store);
const tree = new TreeView(store);
const console_ = new ConsoleView(store);
const map = new MapView(store, jobs);
const gestures = new GestureView();
const views = { tree, console: console_, map, gestures };
window.stuart = { store, ...views }; // for a look from the browser's console (and the browser tests)

store.on("reset", () => { tree.reset(); console_.reset(); map.reset(); });
store.on("events", (batch) => {
  tree.onEvents(batch);
  console_.onEvents(batch);
  map.onEvents(batch);
  jobs.onEvents(batch);
  if (batch.some((e) => ["run", "mission", "halt", "hold", "resume"].includes(e.kind))) refreshState();
});

let opened = false; // a view was chosen (by the address, a tab or the server's mode)
function showView(name) {
  opened = true;
  for (const button of document.querySelectorAll("#tabs button")) button.classList.toggle("active", button.dataset.view === name);
  for (const section of document.querySelectorAll(".view")) section.classList.toggle("active", section.id === `view-${name}`);
  if (name === "tree" && !tree.fitted) tree.fitted = tree.fit();
  if (name === "map") map.fit();
  history.replaceState(null, "", `${location.pathname}${location.search}#${name}`);
}
for (const button of document.querySelectorAll("#tabs button")) button.onclick = () => showView(button.dataset.view);

// The view the page opens on: the one in the address (#map), else the one the server is for:
// the console of a mission server (there is no tree until something is said), else the tree.
// Once a view was shown (a tab clicked, a reconnection) the page stays where the person is.
function openFirstView(info) {
  if (!opened) showView(info.mode === "mission" ? "console" : "tree");
}

const pill = document.getElementById("conn");
connect({
  onHello: (hello) => {
    store.reset(hello);
    const info = hello.info || {};
    openFirstView(hello.replay ? {} : info);
    document.getElementById("what").textContent = hello.replay
      ? `replay of ${info.file}` : `${info.mode === "mission" ? "missions" : info.file || ""} · ${info.backend || ""}`;
    document.body.dataset.mode = hello.replay ? "replay" : info.mode;
    if (info.mode === "tree") { // what is said goes to the running tree: a question, stop, continue
      document.getElementById("say-input").placeholder = "Hey Stuart, what happens in the drone cage?";
    }
    refreshState();
  },
  onEvents: (batch) => store.add(batch),
  onState: (state) => { pill.textContent = state; pill.className = `pill ${state === "live" ? "ok" : "bad"}`; },
});

const runPill = document.getElementById("run-state");
async function refreshState() {
  let state;
  try { state = await getJson("/api/state"); } catch { return; }
  runPill.textContent = state.mode === "replay" ? "replay" : state.held ? `held: ${state.held}`
    : state.busy ? `busy${state.running ? ": " + state.running : ""}` : "idle";
  runPill.className = `pill ${state.held ? "held" : state.busy ? "busy" : ""}`;
  document.getElementById("btn-run").disabled = state.mode !== "tree" || state.busy;
  document.getElementById("btn-stop").disabled = state.mode === "replay" || !state.busy;
  document.getElementById("btn-continue").disabled = state.mode === "replay" || !state.can_continue;
  document.body.dataset.busy = state.busy ? "yes" : "no";
}
setInterval(refreshState, 1000);

document.getElementById("btn-run").onclick = async () => { await act(postJson("/api/run"), "running"); refreshState(); };
document.getElementById("btn-stop").onclick = async () => { await act(postJson("/api/stop"), "stop requested"); refreshState(); };
document.getElementById("btn-continue").onclick = async () => { await act(postJson("/api/continue"), "continuing"); refreshState(); };

map.load();
gestures.init();
if (views[location.hash.slice(1)]) showView(location.hash.slice(1));
