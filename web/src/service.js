// The culling service's HTTP side, as the page uses it: the scene's
// summary, a view's top-K objects, and each object's URL. A token given
// in the page's address (#token=...) goes with every request.

export class Service {
  constructor(location) {
    this.token = new URLSearchParams(location.hash.slice(1)).get('token') ?? '';
    this.origin = location.origin;
    this.host = location.host;
    this.secure = location.protocol === 'https:';
  }

  headers(extra = {}) {
    return this.token ? { ...extra, Authorization: `Bearer ${this.token}` } : extra;
  }

  async scene() {
    return this.json(await fetch(`${this.origin}/v1/scene`, { headers: this.headers() }));
  }

  // `view`: {camera: {position, target, up, fov}, width, height}.
  async cull(view, maxObjects) {
    const body = JSON.stringify({ ...view, max_objects: maxObjects });
    const started = performance.now();
    const response = await fetch(`${this.origin}/v1/cull`, {
      method: 'POST',
      headers: this.headers({ 'Content-Type': 'application/json' }),
      body,
    });
    const answer = await this.json(response);
    return { answer, milliseconds: performance.now() - started };
  }

  objectUrl(id) {
    return `${this.origin}/v1/objects/${id}.glb`;
  }

  previewUrl() {
    const query = this.token ? `?access_token=${encodeURIComponent(this.token)}` : '';
    return `${this.secure ? 'wss' : 'ws'}://${this.host}/v1/preview${query}`;
  }

  async json(response) {
    if (!response.ok) throw new Error(`${response.url}: ${response.status} ${(await response.text()).trim()}`);
    return response.json();
  }
}
