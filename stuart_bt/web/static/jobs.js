// Following what a button sent the robot to do (a walk, a Go) until it ends.
//
// The server accepts a walk at once and the robot may still find no way there, so a refusal of
// the request is not the only failure a person must see. The answer names what was started, a
// run of a tree server ({"run": id}) or a mission of the console ({"mission": id}); the event
// stream says how that ended, and an end that is not a success is a toast with its reason.

import { act, toast } from "./api.js";

export class JobWatch {
  constructor(store) {
    this.store = store;
    this.waiting = new Map(); // "run:3" | "mission:2" -> what the person asked for ("walk to ...")
  }

  // Send a request (a promise from postJson) as `act` does, then follow what it started.
  async send(request, label, done) {
    const since = this.store.events.length; // nothing arrives on the socket before this line runs
    const answer = await act(request, done);
    const key = startedKey(answer);
    if (!key) return answer;
    const events = this.store.events;
    for (let i = Math.min(since, events.length); i < events.length; i++) {
      if (endKey(events[i]) === key) { report(events[i], label); return answer; } // it ended first
    }
    this.waiting.set(key, label);
    return answer;
  }

  onEvents(batch) {
    for (const event of batch) {
      const key = endKey(event);
      if (key && this.waiting.has(key)) {
        report(event, this.waiting.get(key));
        this.waiting.delete(key);
      }
    }
  }
}

function startedKey(answer) {
  if (!answer) return null;
  if (answer.run !== undefined) return `run:${answer.run}`;
  if (answer.mission !== undefined) return `mission:${answer.mission}`;
  return null;
}

// The key of the job an event ends (a run's end; a mission finished, stopped or replaced), or null.
const MISSION_ENDS = ["finished", "stopped", "replaced"];
function endKey(event) {
  if (event.id === undefined) return null;
  if (event.kind === "run" && event.phase === "end") return `run:${event.id}`;
  if (event.kind === "mission" && MISSION_ENDS.includes(event.phase)) return `mission:${event.id}`;
  return null;
}

function report(event, label) {
  const status = String(event.status || event.phase).toLowerCase();
  if (status === "success" || status === "succeeded") return;
  const failed = !["stopped", "replaced"].includes(status);
  const why = event.reason ? `: ${event.reason}` : "";
  toast(`${label} ${failed ? "failed" : status}${why}`, failed);
}
