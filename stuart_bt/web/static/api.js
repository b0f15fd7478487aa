// Talking to the server: JSON requests with one-sentence errors, and the event socket.
// The token (off-loopback servers only) rides in a same-site cookie set by the page request,
// so nothing here handles it; fetch sends same-origin cookies and the browser adds Origin.

export class ApiError extends Error {}

export async function getJson(url) {
  const response = await fetch(url, { credentials: "same-origin" });
  return answer(response);
}

export async function postJson(url, body = {}) {
  const response = await fetch(url, {
    method: "POST", credentials: "same-origin",
    headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  });
  return answer(response);
}

async function answer(response) {
  let data = null;
  try { data = await response.json(); } catch { data = null; }
  if (!response.ok) {
    const error = new ApiError((data && data.error) || `${response.status} ${response.statusText}`);
    error.status = response.status;
    error.data = data;
    throw error;
  }
  return data;
}

// The socket: `onHello(msg)` once per (re)connection, `onEvents(list)` per batch.
export function connect({ onHello, onEvents, onState }) {
  let retry = 500;
  const open = () => {
    const scheme = location.protocol === "https:" ? "wss" : "ws";
    const socket = new WebSocket(`${scheme}://${location.host}/ws`);
    socket.onopen = () => { retry = 500; onState("live"); };
    socket.onmessage = (message) => {
      const data = JSON.parse(message.data);
      if (data.type === "hello") onHello(data);
      else if (data.type === "events") onEvents(data.events);
      else if (data.type === "resync") { socket.close(); }
      else if (data.type === "bye") { onState("server stopped"); }
    };
    socket.onclose = () => {
      onState("disconnected");
      setTimeout(open, retry);
      retry = Math.min(retry * 2, 5000);
    };
  };
  open();
}

let toastTimer = null;
export function toast(text, isError = false) {
  const el = document.getElementById("toast");
  el.textContent = text;
  el.className = "show" + (isError ? " error" : "");
  clearTimeout(toastTimer);
  toastTimer = setTimeout(() => { el.className = ""; }, isError ? 6000 : 2500);
}

// Run an action from a button: errors become a toast, never an exception in the console.
export async function act(promise, done) {
  try {
    const result = await promise;
    if (done) toast(done);
    return result;
  } catch (error) {
    toast(error.message, true);
    return null;
  }
}

export function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs)) {
    if (key === "class") node.className = value;
    else if (key.startsWith("on")) node.addEventListener(key.slice(2), value);
    else if (value !== undefined && value !== null) node.setAttribute(key, value);
  }
  for (const child of children) {
    if (child === null || child === undefined) continue;
    node.append(child instanceof Node ? child : String(child));
  }
  return node;
}

export function short(value, max = 160) {
  const text = typeof value === "string" ? value : JSON.stringify(value);
  if (text === undefined) return "";
  return text.length > max ? text.slice(0, max - 1) + "…" : text;
}
