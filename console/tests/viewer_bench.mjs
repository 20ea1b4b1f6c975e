// How large a mesh the console's 3D view stays responsive on: for each mesh given, the preview's
// size, fetching and parsing it, the first frame, and the median frame while orbiting, in headless
// chromium (software WebGL: SwiftShader on the CPU, so a desktop GPU is faster than this).
//   node console/tests/viewer_bench.mjs MESH...   (a daemon from build/, like the browser tests)
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { cpus, tmpdir } from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), '../..');
const adminToken = 'viewer-bench-admin-token-0123456789';
const work = mkdtempSync(path.join(tmpdir(), 'meshmark-viewer-'));

function startDaemon() {
  const daemon = spawn(process.env.MESHMARK_DAEMON ?? `${root}/build/server/meshmarkd`,
    ['--listen', '127.0.0.1:0', '--data', `${work}/data`, '--log-level', 'warn'],
    { env: { ...process.env, MESHMARK_ADMIN_TOKEN: adminToken }, stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve) => daemon.stdout.on('data', (chunk) => {
    const found = /listening on (http:\/\/[0-9.:]+)/.exec(String(chunk));
    if (found) resolve({ daemon, base: found[1] });
  }));
}

async function api(base, key, method, url, body) {
  const response = await fetch(`${base}${url}`, { method, body, headers: { Authorization: `Bearer ${key}` } });
  if (!response.ok) throw new Error(`${method} ${url}: ${response.status} ${await response.text()}`);
  return response.json();
}

async function uploadReady(base, key, file) {
  const format = path.extname(file).slice(1);
  const model = await api(base, key, 'POST', `/v1/models?format=${format}&name=${path.basename(file)}`, readFileSync(file));
  for (;;) {
    const job = await api(base, key, 'GET', `/v1/jobs/${model.job_id}`);
    if (job.state === 'succeeded') return model.id;
    if (['failed', 'canceled'].includes(job.state)) throw new Error(`${file}: ${job.error}`);
    await new Promise((r) => setTimeout(r, 500));
  }
}

// In the page: the console's own modules, timed.
const measure = (modelId) => (async (id) => {
  const { getBytes } = await import('/console/api.js');
  const { parsePreviewPly } = await import('/console/ply.js');
  const { Viewer } = await import('/console/viewer.js');
  const t0 = performance.now();
  const bytes = await getBytes(`/v1/models/${id}/preview`);
  const t1 = performance.now();
  const mesh = parsePreviewPly(bytes);
  const t2 = performance.now();
  const host = document.getElementById('viewer');
  // A pixel read back waits until the frame is drawn (finish() alone may return before).
  const sync = (v) => v.renderer.getContext().readPixels(0, 0, 1, 1, 0x1908, 0x1401, new Uint8Array(4));
  const viewer = window.benchViewer ?? (window.benchViewer = new Viewer(host));
  viewer.show([{ mesh, name: 'original' }]);
  sync(viewer);
  const t3 = performance.now();
  const frames = [];
  for (let i = 0; i < 15; i++) {
    const s = performance.now();
    viewer.camera.position.applyAxisAngle({ x: 0, y: 1, z: 0, isVector3: true }, 0.1);
    viewer.camera.lookAt(viewer.controls.target);
    viewer.render();
    sync(viewer);
    frames.push(performance.now() - s);
  }
  frames.sort((a, b) => a - b);
  return { megabytes: bytes.byteLength / 2 ** 20, triangles: mesh.indices.length / 3, fetch: t1 - t0, parse: t2 - t1,
    first: t3 - t2, frame: frames[Math.floor(frames.length / 2)] };
})(modelId);

async function main() {
  const { daemon, base } = await startDaemon();
  const created = await fetch(`${base}/v1/owners`, { method: 'POST', body: '{"name":"bench"}',
    headers: { Authorization: `Bearer ${adminToken}`, 'Content-Type': 'application/json' } });
  const key = (await created.json()).api_key;
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'] });
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
    await page.goto(base);
    await page.evaluate((k) => sessionStorage.setItem('meshmark.apiKey', k), key);
    await page.evaluate(() => { document.getElementById('console-view').hidden = false; document.getElementById('model').hidden = false; });
    console.log(`viewer: headless chromium, SwiftShader, ${cpus().length} cores (${cpus()[0].model}); ms, one run each`);
    console.log('triangles | preview MiB | fetch | parse | first frame | median frame');
    for (const file of process.argv.slice(2)) {
      const id = await uploadReady(base, key, file);
      const m = await page.evaluate(measure, id);
      console.log([m.triangles, m.megabytes.toFixed(1), m.fetch, m.parse, m.first, m.frame]
        .map((v) => (typeof v === 'number' ? Math.round(v) : v)).join(' | ') + ` | ${path.basename(file)}`);
    }
  } finally {
    await browser.close();
    daemon.kill('SIGTERM');
    rmSync(work, { recursive: true, force: true });
  }
}

main().catch((e) => { console.error(e); process.exit(1); });
