// The culling service's web client (Schwenk 5.4.3): three.js shows the
// objects the service ranks as covering most of the view. When the camera
// rests the page asks /v1/cull, loads what it lacks, drops what fell out
// of the top K, and shows the path tracer's streamed image of the same
// view until the camera moves again (figure 5.6's "rasterise while
// moving", in a browser). ?k=N sets K (default 256).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { RoomEnvironment } from 'three/addons/environments/RoomEnvironment.js';
import { ObjectSet } from './object_set.js';
import { PreviewStream } from './preview_stream.js';
import { Service } from './service.js';

const kRestMilliseconds = 250;  // a camera still this long has come to rest
const kCullLongSide = 1024;     // pixels the service ranks at, at most
const kPreviewLongSide = 512;   // pixels the path tracer streams, at most

const service = new Service(window.location);
const maxObjects = Number(new URLSearchParams(window.location.search).get('k') ?? 256);
const rasterCanvas = document.getElementById('raster');
const previewCanvas = document.getElementById('preview');
const text = (id, value) => (document.getElementById(id).textContent = value);
const count = (n) => (n >= 1e6 ? `${(n / 1e6).toFixed(2)} M` : n >= 1e4 ? `${(n / 1e3).toFixed(1)} k` : `${n}`);

const renderer = new THREE.WebGLRenderer({ canvas: rasterCanvas, antialias: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x303236);
scene.environment = new THREE.PMREMGenerator(renderer).fromScene(new RoomEnvironment(), 0.04).texture;
const group = new THREE.Group();
scene.add(group);

const summary = await service.scene();
showBackground(summary.background);
const c = summary.camera;
const camera = new THREE.PerspectiveCamera(c.fov, 1, c.near, c.far);
camera.position.fromArray(c.position);
camera.up.fromArray(c.up);
const controls = new OrbitControls(camera, rasterCanvas);
controls.target.fromArray(c.target);
controls.update();

let lastAnswer = null, lastRequest = null, latency = null, culls = 0, answered = -1, restTimer = 0, resting = false;
const objects = new ObjectSet(service, group, showCounters);
const preview = summary.preview
  ? new PreviewStream(service.previewUrl(), previewCanvas, showCounters, (why) => text('status', why))
  : null;

function showCounters() {
  text('objects', `${objects.loaded.size} / ${count(summary.total_objects)}`);
  text('triangles', `${count(objects.triangles)} / ${count(summary.total_triangles)}`);
  if (lastAnswer) {
    const shown = lastAnswer.objects.reduce((sum, o) => sum + o.fraction, 0);
    text('covered', `${(100 * shown).toFixed(1)} % of ${(100 * lastAnswer.covered_fraction).toFixed(1)} %`);
  }
  if (latency !== null) text('latency', `${latency.toFixed(0)} ms`);
  text('samples', preview ? (preview.samples ? `${preview.samples} spp` : 'waiting for rest') : 'off');
}

// Behind everything, what the path tracer shows there (linear colours), so
// the streamed image does not jump in look when it appears.
function showBackground(background) {
  const linear = (c) => new THREE.Color().setRGB(c[0], c[1], c[2], THREE.LinearSRGBColorSpace);
  if (background?.kind === 'color') {
    scene.background = linear(background.color);
  } else if (background?.kind === 'gradient') {
    const canvas = document.createElement('canvas');
    canvas.width = 1;
    canvas.height = 256;
    const g = canvas.getContext('2d');
    const fill = g.createLinearGradient(0, 0, 0, 256);
    fill.addColorStop(0, '#' + linear(background.top).getHexString());
    fill.addColorStop(1, '#' + linear(background.bottom).getHexString());
    g.fillStyle = fill;
    g.fillRect(0, 0, 1, 256);
    scene.background = new THREE.CanvasTexture(canvas);
    scene.background.colorSpace = THREE.SRGBColorSpace;
  }
}

// The view as the service takes it, at most `longSide` pixels on its long side.
function viewAt(longSide) {
  const w = rasterCanvas.clientWidth, h = rasterCanvas.clientHeight;
  const scale = Math.min(1, longSide / Math.max(w, h));
  return {
    camera: {
      position: camera.position.toArray(),
      target: controls.target.toArray(),
      up: camera.up.toArray(),
      fov: camera.fov,
    },
    width: Math.max(1, Math.round(w * scale)),
    height: Math.max(1, Math.round(h * scale)),
  };
}

async function rest() {
  resting = true;
  preview?.show(viewAt(kPreviewLongSide));
  const request = viewAt(kCullLongSide);
  const id = ++culls;
  try {
    const { answer, milliseconds } = await service.cull(request, maxObjects);
    if (id !== culls) return;  // the camera moved again meanwhile
    lastRequest = { ...request, max_objects: maxObjects };
    lastAnswer = answer;
    latency = milliseconds;
    text('status', '');
    await objects.update(answer.objects);
    answered = id;
  } catch (error) {
    text('status', String(error.message ?? error));
  }
  showCounters();
}

function moved() {
  if (resting) preview?.hide();
  resting = false;
  culls += 1;  // an answer on its way is for a view that is gone
  clearTimeout(restTimer);
  restTimer = setTimeout(rest, kRestMilliseconds);
}

function resize() {
  const w = rasterCanvas.clientWidth, h = rasterCanvas.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  moved();
}

controls.addEventListener('change', moved);
window.addEventListener('resize', resize);
renderer.setAnimationLoop(() => renderer.render(scene, camera));
resize();

// What a test (or a curious person at the console) may read.
window.tessera = {
  summary,
  camera,
  controls,
  objects,
  preview,
  get lastAnswer() { return lastAnswer; },
  get lastRequest() { return lastRequest; },
  // Rested, answered, and every load of the answer finished.
  settled: () => resting && answered === culls && objects.settled(),
  loadedIds: () => [...objects.loaded.keys()],
};
