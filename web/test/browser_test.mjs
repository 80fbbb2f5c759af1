// The web client in Debian's chromium (Playwright drives it), against a
// real tessera-cull on 127.0.0.1: the page loads exactly the objects the
// service ranks top K for its view, before and after the camera moves (a
// mouse drag), shows a picture that is not blank, and after a rest shows
// the path tracer's streamed image.
//   node test/browser_test.mjs --cull BIN [--scene S] [--k K] [--screenshot F]
//                              [--preview-spp N] [--wait-spp N]
import { spawn } from 'node:child_process';
import { once } from 'node:events';
import { writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import { chromium } from 'playwright-core';

const { values: args } = parseArgs({
  options: {
    cull: { type: 'string' },
    scene: { type: 'string', default: 'builtin:plant:40000' },
    k: { type: 'string', default: '48' },
    screenshot: { type: 'string' },  // the page at the end (F), and its rasterised first view (F-raster.png)
    chromium: { type: 'string', default: '/usr/bin/chromium' },
    'preview-spp': { type: 'string', default: '16' },  // the service's sample limit
    'wait-spp': { type: 'string', default: '2' },      // samples the streamed image must reach
  },
});
if (!args.cull) throw new Error('--cull BIN (tessera-cull) is required');
const web = join(dirname(fileURLToPath(import.meta.url)), '..');
const k = Number(args.k);

function check(condition, what) {
  if (!condition) throw new Error(`FAILED: ${what}`);
  console.log(`ok: ${what}`);
}

async function startService() {
  const service = spawn(args.cull, [args.scene, '--listen', '127.0.0.1:0', '--web', web, '--threads', '2',
                                    '--preview-spp', args['preview-spp']], { stdio: ['ignore', 'pipe', 'inherit'] });
  let out = '';
  for await (const chunk of service.stdout) {
    out += chunk;
    const match = /listening on [\d.]+:(\d+)/.exec(out);
    if (match) return { service, port: Number(match[1]) };
  }
  throw new Error(`tessera-cull ended before listening: ${out}`);
}

// What the service answers for the page's own last request, sent again.
async function serviceAnswer(port, request) {
  const response = await fetch(`http://127.0.0.1:${port}/v1/cull`, { method: 'POST', body: JSON.stringify(request) });
  if (!response.ok) throw new Error(`/v1/cull: ${response.status}`);
  return response.json();
}

// Distinct colours and spread of a PNG, measured in the page (chromium decodes it).
async function pictureStats(page, png) {
  return page.evaluate(async (base64) => {
    const bytes = Uint8Array.from(atob(base64), (ch) => ch.charCodeAt(0));
    const image = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
    const canvas = new OffscreenCanvas(image.width, image.height);
    const g = canvas.getContext('2d');
    g.drawImage(image, 0, 0);
    const { data } = g.getImageData(0, 0, image.width, image.height);
    const colours = new Set();
    let sum = 0, sum2 = 0;
    for (let i = 0; i < data.length; i += 4) {
      const y = 0.2126 * data[i] + 0.7152 * data[i + 1] + 0.0722 * data[i + 2];
      sum += y;
      sum2 += y * y;
      colours.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
    }
    const n = data.length / 4;
    return { colours: colours.size, deviation: Math.sqrt(Math.max(0, sum2 / n - (sum / n) ** 2)) };
  }, png.toString('base64'));
}

async function settle(page, what) {
  await page.waitForFunction(() => window.tessera?.settled(), null, { timeout: 60000 }).catch(async (e) => {
    const status = await page.textContent('#status').catch(() => '');
    throw new Error(`${what}: the page did not settle (${status || e.message})`);
  });
}

// Every object id any /v1/cull answer named, as the page received them.
const answeredIds = new Set();

async function checkLoadedSet(page, port, what) {
  const state = await page.evaluate(() => ({
    request: window.tessera.lastRequest,
    answer: window.tessera.lastAnswer,
    loaded: window.tessera.loadedIds(),
    requested: window.tessera.objects.requested,
    meshes: window.tessera.objects.group.children.length,
  }));
  const top = state.answer.objects.map((o) => o.id);
  const again = (await serviceAnswer(port, state.request)).objects.map((o) => o.id);
  check(top.length > 0 && top.length <= k, `${what}: the service ranked ${top.length} objects (K = ${k})`);
  check(JSON.stringify(again) === JSON.stringify(top), `${what}: the page's top K are the service's for its view`);
  const sorted = (ids) => [...ids].sort((a, b) => a - b).join(',');
  check(sorted(state.loaded) === sorted(top), `${what}: the page holds exactly those ${top.length} objects`);
  check(state.meshes === top.length, `${what}: its scene holds ${state.meshes} object roots, one per loaded object`);
  const outside = state.requested.filter((id) => !answeredIds.has(id));
  check(outside.length === 0, `${what}: it fetched ${state.requested.length} objects, none outside the answers`);
  return { top };
}

const { service, port } = await startService();
const browser = await chromium.launch({
  executablePath: args.chromium,
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking',
         '--disable-component-update', '--disable-sync', '--no-first-run'],
});
try {
  const page = await browser.newPage({ viewport: { width: 800, height: 500 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('response', async (response) => {
    if (!response.url().endsWith('/v1/cull') || !response.ok()) return;
    for (const o of (await response.json()).objects) answeredIds.add(o.id);
  });
  await page.goto(`http://127.0.0.1:${port}/?k=${k}`);
  await settle(page, 'first view');
  const first = await checkLoadedSet(page, port, 'first view');
  // The rasterised view alone (the streamed image may already lie over it).
  await page.evaluate(() => (document.getElementById('preview').style.visibility = 'hidden'));
  const rasterShot = await page.screenshot();
  if (args.screenshot) writeFileSync(args.screenshot.replace(/\.png$/, '') + '-raster.png', rasterShot);
  const raster = await pictureStats(page, rasterShot);
  await page.evaluate(() => (document.getElementById('preview').style.visibility = ''));
  check(raster.colours > 50 && raster.deviation > 4,
        `the page is not blank (${raster.colours} colours, deviation ${raster.deviation.toFixed(1)})`);

  // A drag turns the camera; the page settles on the new view's top K.
  const box = await page.locator('#raster').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 8; ++i) await page.mouse.move(box.x + box.width / 2 + 8 * i, box.y + box.height / 2 + i);
  await page.mouse.up();
  await page.waitForFunction(() => document.getElementById('preview').hidden, null, { timeout: 5000 });
  check(true, 'the streamed image went away as the camera moved');
  await settle(page, 'after the drag');
  const second = await checkLoadedSet(page, port, 'after the drag');
  check(JSON.stringify(second.top) !== JSON.stringify(first.top), 'the drag changed the ranked objects');

  // At rest the path tracer's image arrives and refines.
  await page.waitForFunction((spp) => window.tessera.preview?.samples >= spp && !document.getElementById('preview').hidden,
                             Number(args['wait-spp']), { timeout: 300000 });
  const previewPng = Buffer.from((await page.evaluate(() => document.getElementById('preview').toDataURL('image/png')))
                                  .split(',')[1], 'base64');
  const traced = await pictureStats(page, previewPng);
  check(traced.colours > 50 && traced.deviation > 4,
        `the streamed path-traced image shows (${traced.colours} colours, deviation ${traced.deviation.toFixed(1)})`);
  const shot = await page.screenshot();
  if (args.screenshot) writeFileSync(args.screenshot, shot);
  check(errors.length === 0, `no errors in the page${errors.length ? ': ' + errors.join('; ') : ''}`);
  console.log('browser test passed');
} finally {
  await browser.close();
  service.kill();
  await once(service, 'exit');
}
