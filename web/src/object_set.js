// The objects the page holds: it loads those a cull answer names that it
// lacks and drops those that fell out of the answer. A load that finishes
// after its object fell out is thrown away, so the scene always holds a
// subset of the latest answer, and all of it once the loads settle.
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

export class ObjectSet {
  constructor(service, group, onChange) {
    this.service = service;
    this.group = group;
    this.onChange = onChange;
    this.loader = new GLTFLoader();
    this.loaded = new Map();   // id -> {root, triangles}
    this.loading = new Map();  // id -> promise
    this.wanted = new Set();
    this.requested = [];       // every object URL asked for, in order (the test reads it)
  }

  get triangles() {
    let sum = 0;
    for (const o of this.loaded.values()) sum += o.triangles;
    return sum;
  }

  settled() {
    return this.loading.size === 0;
  }

  // `objects`: the answer's [{id, triangles, ...}], most covering first.
  update(objects) {
    this.wanted = new Set(objects.map((o) => o.id));
    for (const [id, object] of this.loaded) {
      if (!this.wanted.has(id)) {
        this.drop(object);
        this.loaded.delete(id);
      }
    }
    const loads = [];
    for (const o of objects) {
      if (this.loaded.has(o.id) || this.loading.has(o.id)) continue;
      const load = this.load(o).finally(() => this.loading.delete(o.id));
      this.loading.set(o.id, load);
      loads.push(load);
    }
    this.onChange();
    return Promise.allSettled(loads);
  }

  async load(object) {
    const url = this.service.objectUrl(object.id);
    this.requested.push(object.id);
    this.loader.setRequestHeader(this.service.headers());
    const gltf = await this.loader.loadAsync(url);
    if (!this.wanted.has(object.id) || this.loaded.has(object.id)) {
      this.drop({ root: gltf.scene });
      return;
    }
    this.group.add(gltf.scene);
    this.loaded.set(object.id, { root: gltf.scene, triangles: object.triangles });
    this.onChange();
  }

  drop(object) {
    object.root.removeFromParent();
    object.root.traverse((node) => {
      if (!node.isMesh && !node.isLine && !node.isPoints) return;
      node.geometry.dispose();
      for (const material of [].concat(node.material)) {
        for (const value of Object.values(material)) if (value?.isTexture) value.dispose();
        material.dispose();
      }
    });
  }
}
