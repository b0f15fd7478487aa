// The page's copy of what happened: every event since the server started (or the saved log),
// folded exactly as stuart_bt/run/snapshot.py folds them (tree -> nodes, status -> node status,
// leaf -> last result, blackboard -> table), plus the segments the timeline scrubs through.
//
// A segment is one built tree and the events after it, up to the next tree that is not a
// speech-only "<say>" tree (the mission executor builds one per sentence).

export class Store {
  constructor() {
    this.events = [];
    this.segments = []; // {start, end|null, file, description, root, nodes: Map, order: []}
    this.blackboard = new Map();
    this.listeners = { reset: [], events: [] };
  }

  on(kind, fn) { this.listeners[kind].push(fn); }

  reset(hello) {
    this.events = [];
    this.segments = [];
    this.blackboard = new Map();
    this.info = hello.info || {};
    this.replay = !!hello.replay;
    this.add(hello.events || [], false);
    for (const fn of this.listeners.reset) fn(hello);
  }

  add(batch, notify = true) {
    for (const event of batch) {
      const index = this.events.length;
      this.events.push(event);
      if (event.kind === "tree" && event.root) {
        if (event.file === "<say>" && this.segments.length) continue;
        const last = this.segments[this.segments.length - 1];
        if (last) last.end = index;
        this.segments.push(makeSegment(event, index));
      } else if (event.kind === "blackboard" && event.key !== undefined) {
        this.blackboard.set(String(event.key), { value: event.value, t: event.t });
      }
    }
    if (notify) for (const fn of this.listeners.events) fn(batch);
  }

  // The state of a segment's nodes after its first `count` status changes (null: all of them).
  fold(segment, count = null) {
    const status = new Map();
    const last = new Map();
    const history = new Map();
    for (const path of segment.order) status.set(path, "INVALID");
    let seen = 0;
    let t = null;
    const end = segment.end === null ? this.events.length : segment.end;
    for (let i = segment.start + 1; i < end; i++) {
      const event = this.events[i];
      if (!segment.nodes.has(event.path)) continue;
      if (event.kind === "status") {
        if (count !== null && seen >= count) break;
        seen += 1;
        t = event.t;
        status.set(event.path, event.new);
        if (!history.has(event.path)) history.set(event.path, []);
        history.get(event.path).push({ t: event.t, status: event.new });
      } else if (event.kind === "leaf") {
        last.set(event.path, { outcome: event.outcome, reason: event.reason, result: event.result, t: event.t });
      }
    }
    return { status, last, history, seen, t };
  }

  // Status changes of a segment, for the timeline: [{index, t, path, new}].
  changes(segment) {
    const out = [];
    const end = segment.end === null ? this.events.length : segment.end;
    for (let i = segment.start + 1; i < end; i++) {
      const event = this.events[i];
      if (event.kind === "status" && segment.nodes.has(event.path)) out.push({ index: i, t: event.t, path: event.path, new: event.new });
    }
    return out;
  }

  ofKind(kind) { return this.events.filter((e) => e.kind === kind); }
}

function makeSegment(event, index) {
  const nodes = new Map();
  const order = [];
  const add = (node, parent, depth) => {
    nodes.set(node.path, { ...node, parent, depth, childPaths: (node.children || []).map((c) => c.path) });
    order.push(node.path);
    for (const child of node.children || []) add(child, node.path, depth + 1);
  };
  add(event.root, null, 0);
  return { start: index, end: null, file: event.file, description: event.description, t: event.t,
    root: event.root.path, nodes, order };
}

// Root first, following the RUNNING child at each level (snapshot.py's running path).
export function runningPath(segment, status) {
  const out = [];
  let path = segment.root;
  while (path && status.get(path) === "RUNNING") {
    out.push(path);
    const node = segment.nodes.get(path);
    path = node.childPaths.find((c) => status.get(c) === "RUNNING");
  }
  return out;
}
