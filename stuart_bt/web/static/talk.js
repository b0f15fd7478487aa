// Push-to-talk: while the button (or the space bar, when no text box has the focus) is held,
// the microphone's samples go to /ws/audio as int16 PCM at the AudioContext's rate; on release
// the server transcribes the press and submits it like heard speech, and answers with what it
// heard and how it was understood, which the console's log shows like a typed line.

const BLOCK = 4096; // samples per message (8 KiB), well under the server's frame limit

export class PushToTalk {
  constructor(button, log) {
    this.button = button;
    this.log = log; // (kind, text) -> a line in the console's log
    this.socket = null;
    this.pending = null; // the start in progress, so a quick release waits for it
    this.held = false;
    button.addEventListener("pointerdown", (e) => { e.preventDefault(); this.press(); });
    for (const name of ["pointerup", "pointerleave", "pointercancel"]) button.addEventListener(name, () => this.release());
    window.addEventListener("keydown", (e) => {
      if (e.code === "Space" && !e.repeat && this.spaceIsOurs(e)) { e.preventDefault(); this.press(); }
    });
    window.addEventListener("keyup", (e) => { if (e.code === "Space" && this.held) { e.preventDefault(); this.release(); } });
  }

  spaceIsOurs(e) {
    const tag = (e.target && e.target.tagName) || "";
    return !["INPUT", "TEXTAREA", "SELECT", "BUTTON"].includes(tag) && !e.target.isContentEditable &&
      this.button.offsetParent !== null; // the console view is showing
  }

  connect() {
    if (this.socket && this.socket.readyState <= WebSocket.OPEN) return this.opened;
    const scheme = location.protocol === "https:" ? "wss" : "ws";
    this.socket = new WebSocket(`${scheme}://${location.host}/ws/audio`);
    this.socket.binaryType = "arraybuffer";
    this.socket.addEventListener("message", (e) => this.onMessage(JSON.parse(e.data)));
    this.socket.addEventListener("close", () => { this.socket = null; });
    this.opened = new Promise((resolve, reject) => {
      this.socket.addEventListener("open", () => resolve(this.socket), { once: true });
      this.socket.addEventListener("error", () => reject(new Error("the audio socket did not open")), { once: true });
    });
    return this.opened;
  }

  press() {
    if (this.held) return;
    this.held = true;
    this.button.classList.add("recording");
    this.pending = this.begin().catch((e) => { this.log("warning", `push-to-talk: ${e.message}`); this.end(); });
  }

  async begin() {
    const socket = await this.connect();
    this.stream = await navigator.mediaDevices.getUserMedia({
      audio: { channelCount: 1, echoCancellation: false, noiseSuppression: false, autoGainControl: false } });
    this.context = new AudioContext();
    const source = this.context.createMediaStreamSource(this.stream);
    const processor = this.context.createScriptProcessor(BLOCK, 1, 1);
    socket.send(JSON.stringify({ type: "start", rate: this.context.sampleRate }));
    processor.onaudioprocess = (e) => {
      if (socket.readyState === WebSocket.OPEN && this.context) socket.send(toInt16(e.inputBuffer.getChannelData(0)));
    };
    source.connect(processor);
    processor.connect(this.context.destination);
  }

  async release() {
    if (!this.held) return;
    this.held = false;
    this.button.classList.remove("recording");
    await this.pending;
    if (this.socket && this.socket.readyState === WebSocket.OPEN && this.context) {
      this.socket.send(JSON.stringify({ type: "stop" }));
      this.log("listening", "transcribing…");
    }
    this.end();
  }

  end() {
    if (this.context) this.context.close();
    if (this.stream) for (const track of this.stream.getTracks()) track.stop();
    this.context = null;
    this.stream = null;
  }

  onMessage(m) {
    if (m.type === "heard") {
      const what = m.kind === "no_speech" ? "no speech heard" : `“${m.text}” → ${m.kind}` +
        (m.intents.length ? ": " + m.intents.map((i) => i.action).join(", ") : "");
      this.log("spoken", `${what} (${m.audio_s.toFixed(1)} s, confidence ${m.confidence.toFixed(2)})${m.cut ? " (cut)" : ""}`);
    } else if (m.type === "cut") {
      this.log("warning", m.message);
    } else if (m.type === "error") {
      this.log("warning", `push-to-talk: ${m.error}`);
    }
  }
}

function toInt16(floats) {
  const out = new Int16Array(floats.length);
  for (let i = 0; i < floats.length; i++) out[i] = Math.max(-1, Math.min(1, floats[i])) * 0x7fff;
  return out.buffer;
}
