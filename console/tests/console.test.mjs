// The console in a real browser (Debian's chromium, headless, driven by playwright-core) against a
// real daemon: sign in, upload, hand out copies, trace an attacked copy, take the evidence report,
// and the refusals and safety rules. Screenshots of every view go to $SCREENSHOTS for review.
//   node console/tests/console.test.mjs   (deploy/console-test.sh sets the environment)
import assert from 'node:assert/strict';
import { spawn, execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

const env = (name, fallback) => process.env[name] ?? fallback;
const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), '../..');
const daemonBinary = env('MESHMARK_DAEMON', `${root}/build/server/meshmarkd`);
const cliBinary = env('MESHMARK_CLI', `${root}/build/client/meshmark`);
const shared = env('MESHMARK_SHARED', `${root}/../shared`);
const bunny = env('MESHMARK_TEST_MESH', `${shared}/meshes/bunny.obj`);
const texturedFolder = `${shared}/assets/spot-cow-obj`;  // an OBJ with its MTL and texture
const screenshots = env('SCREENSHOTS', `${root}/build/console-screenshots`);
const adminToken = 'console-test-admin-token-0123456789';
const work = mkdtempSync(path.join(tmpdir(), 'meshmark-console-'));
mkdirSync(screenshots, { recursive: true });

function startDaemon() {
  const daemon = spawn(daemonBinary, ['--listen', '127.0.0.1:0', '--data', `${work}/data`, '--log-level', 'warn'], {
    env: { ...process.env, MESHMARK_ADMIN_TOKEN: adminToken }, stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve, reject) => {
    daemon.stdout.on('data', (chunk) => {
      const found = /listening on (http:\/\/[0-9.:]+)/.exec(String(chunk));
      if (found) resolve({ daemon, base: found[1] });
    });
    daemon.on('exit', (code) => reject(new Error(`meshmarkd exited (${code}) before listening`)));
  });
}

async function createOwner(base) {
  const response = await fetch(`${base}/v1/owners`, { method: 'POST',
    headers: { Authorization: `Bearer ${adminToken}`, 'Content-Type': 'application/json' }, body: '{"name":"studio"}' });
  assert.equal(response.status, 201);
  return (await response.json()).api_key;
}

const steps = [];
async function step(name, work) {
  const start = Date.now();
  await work();
  steps.push(`${name}: ${((Date.now() - start) / 1000).toFixed(1)} s`);
  console.log(`ok - ${name} (${((Date.now() - start) / 1000).toFixed(1)} s)`);
}

const shot = (page, name) => page.screenshot({ path: `${screenshots}/${name}.png`, fullPage: true });

// Whether the 3D view's canvas holds more than one colour (it rendered something).
const viewerColours = (page) => page.evaluate(() => {
  const source = document.querySelector('#viewer canvas');
  const canvas = document.createElement('canvas');
  canvas.width = source.width; canvas.height = source.height;
  const context = canvas.getContext('2d');
  context.drawImage(source, 0, 0);
  const pixels = context.getImageData(0, 0, canvas.width, canvas.height).data;
  const colours = new Set();
  for (let i = 0; i < pixels.length; i += 4 * 97) colours.add((pixels[i] << 16) | (pixels[i + 1] << 8) | pixels[i + 2]);
  return colours.size;
});

async function modelRow(page, name) {
  const row = page.locator('#models tbody tr', { has: page.getByRole('cell', { name, exact: true }) });
  await row.first().waitFor();
  return row.first();
}

async function run() {
  const { daemon, base } = await startDaemon();
  const key = await createOwner(base);
  const browser = await chromium.launch({ executablePath: env('CHROMIUM', '/usr/bin/chromium'),
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'] });
  const context = await browser.newContext({ acceptDownloads: true, viewport: { width: 1280, height: 1000 } });
  const page = await context.newPage();
  const dialogs = [], pageErrors = [];
  page.on('dialog', (d) => { dialogs.push(d.message()); d.accept(); });
  page.on('pageerror', (e) => pageErrors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') pageErrors.push(m.text()); });
  try {
    await page.goto(base);

    await step('an invalid key gets a clear message', async () => {
      await page.getByLabel('Your API key').fill('mmk_not_a_key');
      await page.getByRole('button', { name: 'Sign in' }).click();
      await page.locator('#message', { hasText: 'not valid' }).waitFor();
      assert.equal(await page.evaluate(() => sessionStorage.length), 0);
      await shot(page, '01-sign-in-refused');
    });

    await step('sign in; the key is in session storage only', async () => {
      await page.getByLabel('Your API key').fill(key);
      await page.getByRole('button', { name: 'Sign in' }).click();
      await page.locator('#console-view').waitFor();
      const cookies = await context.cookies();
      assert.equal(cookies.length, 0);
      assert.ok(!page.url().includes(key));
    });

    await step('upload bunny.obj and see it become ready', async () => {
      await page.getByLabel('Model name').fill('bunny');
      await page.locator('#upload-file').setInputFiles(bunny);
      const row = await modelRow(page, 'bunny');
      await row.locator('td[data-state="ready"]').waitFor({ timeout: 120000 });
      await shot(page, '02-models');
    });

    await step('a refused upload shows the reason', async () => {
      const tiny = `${work}/tetrahedron.obj`;
      writeFileSync(tiny, 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n');
      await page.locator('#upload-file').setInputFiles(tiny);
      const refusal = page.locator('#upload-refusal');
      await refusal.waitFor();
      assert.match(await refusal.innerText(), /cannot be watermarked/);
      assert.match(await refusal.innerText(), /too few/, 'the refusal says why');
      assert.match(await refusal.innerText(), /What would fix it: upload the full-resolution original/);
      await shot(page, '03-refused-upload');
    });

    await step('a name with markup shows as text and runs nothing', async () => {
      const name = '<img src=x onerror=alert(1)>';
      await page.getByLabel('Model name').fill(name);
      await page.locator('#upload-file').setInputFiles(bunny);
      await modelRow(page, name);
      assert.equal(await page.locator('#models img').count(), 0);
      await page.waitForTimeout(300);
      assert.deepEqual(dialogs, []);
      await shot(page, '04-markup-name');
    });

    await step('a folder (an OBJ with its material and texture) uploads whole', async () => {
      await page.locator('#upload-folder').setInputFiles(texturedFolder);
      const row = await modelRow(page, 'cow');
      await row.locator('td[data-state="ready"]').waitFor({ timeout: 120000 });
      // A copy in the model's format comes back as the whole asset: the OBJ with its material and texture.
      const api = (route, init = {}) => fetch(`${base}${route}`, { ...init,
        headers: { Authorization: `Bearer ${key}`, 'Content-Type': 'application/json' } }).then((r) => r.json());
      const cow = (await api('/v1/models')).models.find((m) => m.name === 'cow');
      const accepted = await api(`/v1/models/${cow.id}/embed`, { method: 'POST', body: '{"recipient":"folder-check"}' });
      let job = await api(`/v1/jobs/${accepted.job_id}`);
      while (job.state === 'queued' || job.state === 'running') {
        await page.waitForTimeout(200);
        job = await api(`/v1/jobs/${accepted.job_id}`);
      }
      assert.equal(job.state, 'succeeded', JSON.stringify(job));
      assert.equal(job.result.zipped, true);
      assert.equal(job.result.kept_whole, true);
    });

    await step('open the model: the 3D view renders', async () => {
      await (await modelRow(page, 'bunny')).getByRole('button', { name: 'Open bunny' }).click();
      await page.locator('#view-caption', { hasText: 'The original' }).waitFor();
      assert.ok(await viewerColours(page) > 8, 'the original is drawn');
      await page.getByLabel('Flat shading').check();
      await page.getByRole('button', { name: 'Reset view' }).click();
      await shot(page, '05-model-view');
    });

    await step('embed for three recipients from a list', async () => {
      await page.getByLabel(/Recipients, one per line/).fill('alice\nbob\ncarol');
      await page.getByLabel(/Asked for by/).fill('Dana (licensing)');
      await page.getByRole('button', { name: 'Make the copies' }).click();
      await page.locator('#embed-progress li', { hasText: 'carol: ready' }).waitFor({ timeout: 120000 });
      await page.locator('#embed-progress li', { hasText: 'bob: ready' }).waitFor({ timeout: 120000 });
      await page.locator('#embed-progress li', { hasText: 'alice: ready' }).waitFor({ timeout: 120000 });
      await page.locator('#copies tbody tr').nth(2).waitFor();
      assert.equal(await page.locator('#copies tbody tr').count(), 3);
      assert.equal(await page.locator('#copies tbody tr', { hasText: 'Dana (licensing)' }).count(), 3, 'who asked, per copy');
      await shot(page, '06-copies');
    });

    const copy = `${work}/bunny-bob.obj`;
    await step('download one copy', async () => {
      const [download] = await Promise.all([page.waitForEvent('download'),
        page.getByRole('button', { name: 'Download the copy for bob' }).click()]);
      await download.saveAs(copy);
      assert.match(readFileSync(copy, 'utf8').slice(0, 4096), /^v /m);
    });

    await step('the displacement view renders', async () => {
      await page.getByRole('button', { name: 'Look at the copy for bob' }).click();
      await page.locator('#view-legend', { hasText: '% of the diagonal' }).waitFor();
      assert.ok(await viewerColours(page) > 8, 'a coloured copy, not a blank canvas');
      await shot(page, '07-displacement');
    });

    const leak = `${work}/leak.obj`;
    await step('attack the copy and trace it to its recipient', async () => {
      execFileSync(cliBinary, ['attack', 'chain', '--seed', '7', '--steps',
        'simplify keep=0.5 | noise amplitude=0.1 | similarity', copy, leak]);
      await page.locator('#trace-file').setInputFiles(leak);
      await page.locator('#verdict', { hasText: 'handed out to bob' }).waitFor({ timeout: 120000 });
      assert.match(await page.locator('#verdict').innerText(), /chance that this is a coincidence is below 1 in 10\^/);
      await page.locator('#view-caption', { hasText: 'aligned' }).waitFor();
      assert.ok(await viewerColours(page) > 8);
      await shot(page, '08-trace');
    });

    await step('the evidence report names the recipient', async () => {
      const [download] = await Promise.all([page.waitForEvent('download'),
        page.getByRole('button', { name: 'Download the evidence report' }).click()]);
      const report = `${work}/report.html`;
      await download.saveAs(report);
      const html = readFileSync(report, 'utf8');
      assert.match(html, /handed out to bob/);
      assert.match(html, /Copy asked for by<\/th><td>Dana \(licensing\)</);
      assert.match(html, /data:image\/png;base64,/);
      assert.doesNotMatch(html, /<script/i);
      const viewerPage = await context.newPage();
      await viewerPage.goto(`file://${report}`);
      await viewerPage.screenshot({ path: `${screenshots}/09-evidence-report.png`, fullPage: true });
      await viewerPage.close();
    });

    await step('a leak searched across the library', async () => {
      await page.locator('#library-suspect').setInputFiles(leak);
      await page.locator('#verdict', { hasText: 'handed out to bob' }).waitFor({ timeout: 120000 });
      await shot(page, '10-library-trace');
    });

    await step('delete asks first, and again when copies were handed out', async () => {
      await (await modelRow(page, 'cow')).getByRole('button', { name: 'Delete cow' }).click();
      await page.locator('#models tbody tr', { hasText: 'cow' }).waitFor({ state: 'detached' });
      assert.equal(dialogs[0], 'Delete the model "cow" and every record of its copies?');
      assert.match(dialogs[1], /has 1 copy handed out/);
      dialogs.length = 0;
      await (await modelRow(page, 'bunny')).getByRole('button', { name: 'Delete bunny' }).click();
      await page.getByRole('cell', { name: 'bunny', exact: true }).waitFor({ state: 'detached' });
      assert.equal(dialogs.length, 2);
      assert.match(dialogs[1], /has 3 copies handed out[^]*Delete it anyway\? Its copies can then never be traced/);
      dialogs.length = 0;
      await shot(page, '11-after-delete');
    });

    await step('sign out', async () => {
      await page.getByRole('button', { name: 'Sign out' }).click();
      await page.locator('#sign-in-view').waitFor();
      assert.equal(await page.evaluate(() => sessionStorage.length), 0);
    });
    assert.deepEqual(dialogs, [], 'no dialog opened by anything on the page');
    // The refusals the steps above provoke on purpose are logged by the browser; nothing else may be.
    const expected = /status of (401|409|422)|WebGL|GPU|swiftshader/i;
    assert.deepEqual(pageErrors.filter((e) => !expected.test(e)), []);
  } finally {
    await browser.close();
    daemon.kill('SIGTERM');
    rmSync(work, { recursive: true, force: true });
  }
  console.log(`console: ${steps.length} steps passed; screenshots in ${screenshots}`);
}

run().catch((e) => { console.error(e); process.exit(1); });
