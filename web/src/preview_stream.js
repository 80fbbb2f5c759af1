// The path tracer's image of the resting view, streamed by the service
// over a WebSocket (/v1/preview) and drawn over the rasterised view until
// the camera moves again. Frames: 16 bytes (little-endian uint32 seq,
// samples, width, height), then a PNG. Only frames of the latest view show.

export class PreviewStream {
  constructor(url, canvas, onFrame, onError) {
    this.url = url;
    this.canvas = canvas;
    this.onFrame = onFrame;
    this.onError = onError;
    this.seq = 0;
    this.samples = 0;
    this.frames = 0;
    this.queued = null;
    this.connect();
  }

  connect() {
    this.socket = new WebSocket(this.url);
    this.socket.binaryType = 'arraybuffer';
    this.socket.onopen = () => {
      if (this.queued) this.socket.send(this.queued);
      this.queued = null;
    };
    this.socket.onmessage = (event) => this.receive(event.data);
    this.socket.onclose = (event) => {
      if (event.code !== 1000) this.onError(`preview stream closed: ${event.reason || event.code}`);
    };
  }

  // `view`: as /v1/cull takes it. Shows nothing until its first frame.
  show(view) {
    this.send({ seq: ++this.seq, view });
  }

  // The camera moves: the image goes, the service stops refining.
  hide() {
    this.canvas.hidden = true;
    this.samples = 0;
    this.send({ seq: ++this.seq, stop: true });
  }

  send(message) {
    const text = JSON.stringify(message);
    if (this.socket.readyState === WebSocket.OPEN) this.socket.send(text);
    else this.queued = text;
  }

  async receive(data) {
    if (typeof data === 'string') {
      const message = JSON.parse(data);
      if (message.error && (message.seq === undefined || message.seq === this.seq)) this.onError(message.error);
      return;
    }
    const header = new DataView(data, 0, 16);
    const seq = header.getUint32(0, true), samples = header.getUint32(4, true);
    if (seq !== this.seq) return;
    const image = await createImageBitmap(new Blob([data.slice(16)], { type: 'image/png' }));
    if (seq !== this.seq) return;  // the camera moved while it decoded
    this.canvas.width = image.width;
    this.canvas.height = image.height;
    this.canvas.getContext('2d').drawImage(image, 0, 0);
    image.close();
    this.canvas.hidden = false;
    this.samples = samples;
    this.frames += 1;
    this.onFrame(samples);
  }
}
