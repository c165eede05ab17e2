// The browser's half of our pages' message codec (owl_web/codec.py is the server's half).
// One WebSocket per page to the server's /ws. A subscription names a channel and its parameters;
// the server answers with updates ({"type": "update", "id", "data"}) or one-line errors
// ({"type": "error", "id", "error"}). A binary message is a frame: a 4-byte big-endian header
// length, a JSON header (an update) and a payload such as an image. The socket reconnects by
// itself and subscribes again to what was subscribed.

const RETRY_FIRST = 500;  // ms before the first reconnection, doubling up to RETRY_MOST
const RETRY_MOST = 5000;
const text = new TextDecoder();

export function unpackFrame(buffer) {
  const length = new DataView(buffer).getUint32(0);
  const header = JSON.parse(text.decode(new Uint8Array(buffer, 4, length)));
  return [header, new Uint8Array(buffer, 4 + length)];
}

export class OwlSocket {
  // onStatus(connected, detail) hears about the connection, e.g. to show it on the page.
  // this.connected says whether the socket is open now.
  // path is relative to the page, so the socket is found wherever the page is served: at its own
  // address, under the front door, or behind a proxy's path prefix.
  constructor(onStatus = () => {}, path = 'ws') {
    const url = new URL(path, location.href);
    url.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
    url.hash = '';
    this.url = url.href;
    this.onStatus = onStatus;
    this.subscriptions = new Map();  // id -> {channel, params, onUpdate, onError}
    this.pendingCommands = new Map();  // command id -> onAnswer, until its done or error comes
    this.nextId = 1;
    this.connected = false;
    this.retry = RETRY_FIRST;
    this.connect();
  }

  connect() {
    const socket = new WebSocket(this.url);
    socket.binaryType = 'arraybuffer';
    socket.onopen = () => {
      this.connected = true;
      this.retry = RETRY_FIRST;
      this.onStatus(true, '');
      for (const [id, entry] of this.subscriptions) this.sendSubscribe(id, entry);
    };
    socket.onmessage = (event) => this.receive(event.data);
    socket.onclose = (event) => {
      if (this.socket !== socket) return;
      this.connected = false;
      // The server's own reason when it gave one; 1006 (no reason) is a server that stopped or
      // cannot be reached, which is what a student needs to read.
      const reason = event.reason || (event.code === 1009 ? 'a message was too big' : '');
      const line = reason ? `connection closed: ${reason}` : "lost the connection to this page's server (did it stop?)";
      this.onStatus(false, `${line}; trying again every few seconds`);
      // a command's answer cannot come on a new connection
      for (const answer of this.pendingCommands.values()) answer(`${line}: the command's outcome is unknown`);
      this.pendingCommands.clear();
      setTimeout(() => this.connect(), this.retry);
      this.retry = Math.min(this.retry * 2, RETRY_MOST);
    };
    this.socket = socket;
  }

  // Returns the subscription's id; unsubscribe(id) ends it. onUpdate(data, payload) gets each update
  // (payload: the bytes of a binary frame, else undefined), onError(line) each error line.
  subscribe(channel, params, onUpdate, onError) {
    const id = this.nextId++;
    const entry = { channel, params, onUpdate, onError };
    this.subscriptions.set(id, entry);
    if (this.socket.readyState === WebSocket.OPEN) this.sendSubscribe(id, entry);
    return id;
  }

  unsubscribe(id) {
    if (!this.subscriptions.delete(id)) return;
    this.send({ type: 'unsubscribe', id });
  }

  // A command to the server ({"type": "command", "name", ...args}), e.g. the robot view's
  // "hold_imu". Sent only while connected (a command is for now, not for after a reconnection).
  // onAnswer(null, result) hears that it was done (result: what came of it, when the server says,
  // else undefined), onAnswer(line) its one-line error; without onAnswer the error line goes to
  // onStatus. Returns the command's id, or null if not sent.
  command(name, args = {}, onAnswer = null) {
    if (this.socket.readyState !== WebSocket.OPEN) return null;
    const id = `command-${this.nextId++}`;
    if (onAnswer) this.pendingCommands.set(id, onAnswer);
    this.send({ ...args, type: 'command', id, name });
    return id;
  }

  sendSubscribe(id, entry) {
    this.send({ ...entry.params, type: 'subscribe', id, channel: entry.channel });
  }

  send(message) {
    if (this.socket.readyState === WebSocket.OPEN) this.socket.send(JSON.stringify(message));
  }

  receive(data) {
    let message;
    let payload;
    if (typeof data === 'string') {
      message = JSON.parse(data);
    } else {
      [message, payload] = unpackFrame(data);
    }
    const answer = this.pendingCommands.get(message.id);
    if (answer && (message.type === 'done' || message.type === 'error')) {
      this.pendingCommands.delete(message.id);
      if (message.type === 'error') answer(message.error);
      else answer(null, message.result);
      return;
    }
    const entry = this.subscriptions.get(message.id);
    if (message.type === 'update' && entry) {
      entry.onUpdate(message.data, payload);
    } else if (message.type === 'error') {
      if (entry && entry.onError) entry.onError(message.error);
      else this.onStatus(true, message.error);
    }
  }
}
