// The console: sign in, the library, a model's view, copies and traces. Everything goes through
// the public API (api.js); every name a user gave is put on the page as text, never as HTML.
import { session, call, getJson, getBytes, getBlob, upload, waitForJob, ApiError } from '/console/api.js';
import { parsePreviewPly } from '/console/ply.js';
import { storedZip, zipEntryNames } from '/console/zip.js';

const $ = (id) => document.getElementById(id);
const FORMATS = ['obj', 'off', 'ply', 'stl', 'glb', 'gltf', '3mf'];
const state = { models: [], model: null, copies: [], viewer: null, original: null, trace: null };

function el(tag, text, attributes = {}) {
  const node = document.createElement(tag);
  if (text !== undefined) node.textContent = String(text);
  for (const [k, v] of Object.entries(attributes)) node.setAttribute(k, v);
  return node;
}

function button(text, onClick, label) {
  const b = el('button', text, { type: 'button' });
  if (label) b.setAttribute('aria-label', label);
  b.addEventListener('click', onClick);
  return b;
}

function showMessage(text) {
  $('message').textContent = text;
  $('message').hidden = !text;
}

async function guarded(work) {
  try {
    showMessage('');
    return await work();
  } catch (e) {
    if (e instanceof ApiError && e.status === 401) signOut('Your API key is not valid (any more): sign in again.');
    else showMessage(e.message || String(e));
    return undefined;
  }
}

function download(blob, name) {
  const a = el('a', '', { href: URL.createObjectURL(blob), download: name });
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

// ---- sign in ----

async function signIn(event) {
  event.preventDefault();
  session.signIn($('api-key').value.trim());
  try {
    await getJson('/v1/models');
  } catch (e) {
    session.signOut();
    showMessage(e instanceof ApiError && e.status === 401 ? 'That API key is not valid: check it and try again.' : e.message);
    return;
  }
  $('api-key').value = '';
  enterConsole();
}

function signOut(message = '') {
  session.signOut();
  $('console-view').hidden = true;
  $('signed-in').hidden = true;
  $('sign-in-view').hidden = false;
  showMessage(message);
}

function enterConsole() {
  showMessage('');
  $('sign-in-view').hidden = true;
  $('console-view').hidden = false;
  $('signed-in').hidden = false;
  $('requested-by').value = session.requester();
  refreshModels();
}

// ---- the library ----

async function refreshModels() {
  const body = await guarded(() => getJson('/v1/models'));
  if (!body) return;
  state.models = body.models ?? body;
  renderModels();
  if (state.models.some((m) => m.state === 'preparing')) setTimeout(refreshModels, 700);
}

function progressText(model) {
  const job = model.preparation;
  if (model.state !== 'preparing' || !job) return model.state;
  if (job.state === 'queued') return 'preparing (queued)';
  return `preparing ${Math.round((job.progress ?? 0) * 100)} %${job.stage ? ` (${job.stage})` : ''}`;
}

function renderModels() {
  const body = $('models').tBodies[0];
  body.replaceChildren();
  for (const m of state.models) {
    const row = el('tr');
    row.append(el('td', m.name), el('td', progressText(m), { 'data-state': m.state }), el('td', m.vertices ?? ''),
      el('td', m.created_at ?? ''));
    const actions = el('td');
    if (m.state === 'ready') actions.append(button('Open', () => openModel(m.id), `Open ${m.name}`));
    if (m.state === 'failed') actions.append(el('span', m.error ?? 'failed', { class: 'hint' }));
    actions.append(' ', button('Delete', () => deleteModel(m), `Delete ${m.name}`));
    row.append(actions);
    body.append(row);
  }
}

async function deleteModel(m) {
  if (!window.confirm(`Delete the model "${m.name}" and every record of its copies?`)) return;
  await guarded(async () => {
    try {
      await call('DELETE', `/v1/models/${m.id}`);
    } catch (e) {
      if (!(e instanceof ApiError && e.status === 409)) throw e;
      if (!window.confirm(`${e.message}\nDelete it anyway? Its copies can then never be traced.`)) return;
      await call('DELETE', `/v1/models/${m.id}`, { query: { confirm: m.id } });
    }
    if (state.model?.id === m.id) { state.model = null; $('model').hidden = true; }
    await refreshModels();
  });
}

// ---- uploads: a file, a ZIP, or a folder (packed into a ZIP) ----

const extension = (name) => name.toLowerCase().split('.').pop();

async function packageFiles(files) {
  if (files.length === 1 && extension(files[0].name) !== 'zip') {
    const format = extension(files[0].name);
    if (!FORMATS.includes(format)) throw new Error(`"${files[0].name}" is not a mesh format meshmark reads (${FORMATS.join(', ')}).`);
    return { blob: files[0], format, name: files[0].name.replace(/\.[^.]*$/, '') };
  }
  if (files.length === 1) {
    const names = zipEntryNames(await files[0].arrayBuffer());
    const main = names.find((n) => ['gltf', 'obj', 'glb', 'ply', 'stl', 'off'].includes(extension(n)));
    if (!main) throw new Error('The ZIP holds no mesh file (a .gltf or .obj with its companion files).');
    return { blob: files[0], format: extension(main), name: files[0].name.replace(/\.zip$/i, '') };
  }
  const entries = await Promise.all(files.map(async (f) => ({
    name: (f.webkitRelativePath || f.name).split('/').slice(-1)[0], bytes: new Uint8Array(await f.arrayBuffer()) })));
  const main = entries.find((e) => ['gltf', 'obj'].includes(extension(e.name))) ?? entries.find((e) => FORMATS.includes(extension(e.name)));
  if (!main) throw new Error('The folder holds no mesh file.');
  return { blob: storedZip(entries), format: extension(main.name), name: main.name.replace(/\.[^.]*$/, '') };
}

// What would fix each kind of refusal, keyed by what the validation report counts.
const FIXES = [
  [(r) => r.vertices !== undefined && r.vertices < 100, 'upload the full-resolution original, or subdivide it: a mark needs at least a few hundred vertices'],
  [(r) => r.nonmanifold_edges > 0 || r.nonmanifold_vertices > 0, 'repair the non-manifold edges and vertices (e.g. MeshLab: Cleaning and Repairing) and export again'],
  [(r) => r.zero_area_faces > 0, 'remove the zero-area (degenerate) faces and export again'],
  [(r) => r.isolated_vertices > 0 && r.vertices - r.isolated_vertices < 100, 'export the mesh with its faces, not as a point cloud'],
];

function reportInWords(problem) {
  const report = problem?.report ?? {};
  const lines = [...new Set([...(report.problems ?? []), ...(report.sphere_problems ?? [])])];
  if (!lines.length) lines.push(problem?.detail ?? 'The daemon refused the file.');
  if (report.vertices !== undefined) {
    lines.push(`What was read: ${report.vertices} vertices, ${report.faces} faces, ${report.components} part(s)` +
      `${report.closed_genus_zero ? ', closed' : `, ${report.boundary_loops ?? 0} hole(s)`}.`);
  }
  const fixes = FIXES.filter(([applies]) => applies(report)).map(([, fix]) => fix);
  lines.push(`What would fix it: ${fixes.length ? fixes.join('; ') : 'export the original as a triangle mesh at full resolution'}.`);
  return lines;
}

async function uploadFiles(files) {
  if (!files.length) return;
  const refusal = $('upload-refusal');
  refusal.hidden = true;
  const progress = $('upload-progress');
  await guarded(async () => {
    const pack = await packageFiles(files);
    const name = $('upload-name').value.trim() || pack.name;
    progress.hidden = false;
    progress.value = 0;
    try {
      await upload('/v1/models', { format: pack.format, name }, pack.blob, (f) => { progress.value = f; });
    } catch (e) {
      if (!(e instanceof ApiError) || e.status !== 422) throw e;
      refusal.replaceChildren(el('strong', 'This mesh cannot be watermarked.'), ...reportInWords(e.problem).map((l) => el('p', l)));
      refusal.hidden = false;
    } finally {
      progress.hidden = true;
      $('upload-name').value = '';
    }
    await refreshModels();
  });
}

function dropZone(zone, onFiles) {
  zone.addEventListener('dragover', (e) => { e.preventDefault(); zone.classList.add('over'); });
  zone.addEventListener('dragleave', () => zone.classList.remove('over'));
  zone.addEventListener('drop', async (e) => {
    e.preventDefault();
    zone.classList.remove('over');
    onFiles(await droppedFiles(e.dataTransfer));
  });
}

// Files dropped, folders walked.
async function droppedFiles(transfer) {
  const entries = Array.from(transfer.items ?? []).map((i) => i.webkitGetAsEntry?.()).filter(Boolean);
  if (!entries.length) return Array.from(transfer.files);
  const files = [];
  const walk = async (entry) => {
    if (entry.isFile) files.push(await new Promise((ok, fail) => entry.file(ok, fail)));
    else {
      const reader = entry.createReader();
      for (let batch; (batch = await new Promise((ok, fail) => reader.readEntries(ok, fail))).length;) for (const e of batch) await walk(e);
    }
  };
  for (const entry of entries) await walk(entry);
  return files;
}

// ---- a model: its view and its copies ----

async function viewer() {
  if (!state.viewer) {
    try {
      const { Viewer } = await import('/console/viewer.js');
      state.viewer = new Viewer($('viewer'));
    } catch (e) {
      $('view-caption').textContent = `The 3D view could not start here (${e.message}).`;
    }
  }
  return state.viewer;
}

async function openModel(id) {
  await guarded(async () => {
    state.model = await getJson(`/v1/models/${id}`);
    $('model-title').textContent = state.model.name;
    $('model').hidden = false;
    $('trace').hidden = true;
    state.original = parsePreviewPly(await getBytes(`/v1/models/${id}/preview`));
    await showOriginal();
    await refreshCopies();
  });
}

async function showOriginal() {
  const v = await viewer();
  if (!v) return;
  v.show([{ mesh: state.original, name: 'original' }]);
  $('view-legend').hidden = true;
  $('view-original').hidden = true;
  $('view-caption').textContent = `The original: ${state.original.indices.length / 3} triangles.`;
}

async function lookAtCopy(copy) {
  await guarded(async () => {
    const marked = parsePreviewPly(await getBytes(`/v1/jobs/${copy.job_id}/preview`));
    const v = await viewer();
    if (!v) return;
    const layers = [{ mesh: marked, displacement: true, name: 'copy' }, { mesh: state.original, name: 'original', opacity: 0.35 }];
    v.show(layers);
    v.setVisible('original', false);
    const legend = $('view-legend');
    legend.replaceChildren(el('span', '', { class: 'legend-bar' }),
      el('span', marked.displacement ? `blue inward, red outward: ±${layers[0].scale.toPrecision(2)} % of the diagonal` : 'no displacement to show (the copy is on other vertices)'));
    legend.hidden = false;
    $('view-original').hidden = false;
    $('view-caption').textContent = `The copy for ${copy.recipient || copy.payload}, coloured by how far the mark moved each vertex.`;
  });
}

async function refreshCopies() {
  const body = await guarded(() => getJson(`/v1/models/${state.model.id}/embeddings`));
  if (!body) return;
  state.copies = body.embeddings ?? body;
  const rows = $('copies').tBodies[0];
  rows.replaceChildren();
  for (const c of state.copies) {
    const row = el('tr');
    const p = c.parameters ?? {};
    row.append(el('td', c.recipient), el('td', c.payload), el('td', c.created_at), el('td', c.requested_by || '—'),
      el('td', `${p.scheme ?? 'spread'}, strength ${p.strength ?? 'default'}`), el('td', c.state));
    const actions = el('td');
    if (c.state === 'ready') {
      actions.append(button('Download', () => downloadCopy(c), `Download the copy for ${c.recipient}`), ' ',
        button('Look', () => lookAtCopy(c), `Look at the copy for ${c.recipient}`));
    }
    row.append(actions);
    rows.append(row);
  }
}

async function downloadCopy(c) {
  await guarded(async () => {
    const response = await call('GET', `/v1/jobs/${c.job_id}/result`);
    const disposition = response.headers.get('Content-Disposition') ?? '';
    const suffix = (disposition.match(/filename="[^".]*\.([^"]+)"/) ?? [])[1] ?? state.model.format;
    download(await response.blob(), `${state.model.name}-${c.recipient || c.payload}.${suffix}`);
  });
}

function recipientsFromText(text) {
  return text.split(/\r?\n/).map((line) => line.split(',')[0].trim().replace(/^"|"$/g, ''))
    .filter((name, i) => name && !(i === 0 && name.toLowerCase() === 'recipient'));
}

async function makeCopies(event) {
  event.preventDefault();
  let text = $('recipients').value;
  const csv = $('recipients-csv').files[0];
  if (csv) text += `\n${await csv.text()}`;
  const recipients = [...new Set(recipientsFromText(text))];
  if (!recipients.length) return showMessage('Name at least one recipient.');
  const requester = $('requested-by').value.trim();
  session.setRequester(requester);
  const request = requester ? { recipients, requested_by: requester } : { recipients };
  await guarded(async () => {
    const accepted = await (await call('POST', `/v1/models/${state.model.id}/embed`, { json: request })).json();
    const list = $('embed-progress');
    list.replaceChildren();
    await Promise.all(accepted.copies.map(async (copy) => {
      const item = el('li', `${copy.recipient}: queued`);
      list.append(item);
      const job = await waitForJob(copy.job_id, (j) => { item.textContent = `${copy.recipient}: ${j.state} ${Math.round((j.progress ?? 0) * 100)} %`; });
      item.textContent = `${copy.recipient}: ${job.state === 'succeeded' ? 'ready' : `${job.state}: ${job.error ?? ''}`}`;
    }));
    $('recipients').value = '';
    $('recipients-csv').value = '';
    await refreshCopies();
  });
}

async function downloadAll() {
  await guarded(async () => download(await getBlob(`/v1/models/${state.model.id}/copies.zip`), `${state.model.name}-copies.zip`));
}

// ---- tracing a leak ----

function traceStarted(title) {
  $('trace').hidden = false;
  $('trace-title').textContent = title;
  $('trace-progress').value = 0;
  $('verdict').textContent = 'Checking the suspect…';
  $('verdict').className = 'verdict none';
  $('evidence').tBodies[0].replaceChildren();
  $('report').hidden = true;
}

async function traceOnModel(files) {
  if (!files.length || !state.model) return;
  const model = state.model;
  traceStarted(`Trace against ${model.name}`);
  await guarded(async () => {
    const pack = await packageFiles(files);
    const accepted = await upload(`/v1/models/${model.id}/detect`, { format: pack.format }, pack.blob, () => {});
    const job = await waitForJob(accepted.job_id, (j) => { $('trace-progress').value = j.progress ?? 0; });
    await showVerdict(model, job, `${model.name}`);
  });
}

async function traceInLibrary(files) {
  if (!files.length) return;
  traceStarted('Trace across the library');
  await guarded(async () => {
    const pack = await packageFiles(files);
    const search = await upload('/v1/detect', { format: pack.format }, pack.blob, () => {});
    const tried = [];
    for (const candidate of search.candidates) {
      const job = await waitForJob(candidate.job_id, (j) => { $('trace-progress').value = j.progress ?? 0; });
      tried.push(candidate.model_name);
      if (job.state === 'succeeded' && job.result.detected) {
        const model = await getJson(`/v1/models/${candidate.model_id}`);
        if (state.model?.id !== model.id) await openModel(model.id);
        $('trace').hidden = false;
        return showVerdict(model, job, model.name);
      }
    }
    $('verdict').textContent = `Not found: the suspect was compared with the ${search.models_compared} models of your library; ` +
      `the closest (${tried.join(', ')}) were checked and none carries your mark.`;
  });
}

function chance(log10p) {
  if (log10p === undefined || log10p === null) return 'unknown';
  return log10p > -4 ? Number(10 ** log10p).toPrecision(3) : `below 1 in 10^${Math.floor(-log10p)}`;
}

async function showVerdict(model, job, modelName) {
  if (job.state !== 'succeeded') {
    $('verdict').textContent = `The check did not finish: ${job.error ?? job.state}.`;
    return;
  }
  const r = job.result;
  const copies = (await getJson(`/v1/models/${model.id}/embeddings`)).embeddings ?? [];
  const copy = r.match ? copies.find((c) => c.id === r.match.embedding_id) : null;
  const verdict = $('verdict');
  if (copy) {
    verdict.textContent = `This suspect is the copy of “${modelName}” handed out to ${copy.recipient || copy.payload} on ${copy.created_at}; ` +
      `the chance that this is a coincidence is ${chance(r.match.log10_p_value)}.`;
    verdict.className = 'verdict';
  } else if (r.detected) {
    verdict.textContent = `This suspect carries your mark on “${modelName}” (chance of coincidence ${chance(r.log10_p_value)}), but its payload matches no copy you handed out.`;
  } else {
    verdict.textContent = `Not found: no mark of yours was read in the suspect against “${modelName}” (chance of coincidence ${chance(r.log10_p_value)}).`;
  }
  const rows = $('evidence').tBodies[0];
  const add = (k, v) => { const tr = el('tr'); tr.append(el('th', k, { scope: 'row' }), el('td', v)); rows.append(tr); };
  if (copy) add('Bits read wrong', `${r.match.bit_errors ?? '—'} of ${r.bits} (of the payload of ${copy.recipient || copy.payload}'s copy)`);
  else add('Bits read', r.bits);
  add('p-value', chance(r.log10_p_value));
  add('Alignment', `${r.alignment?.quality ?? '—'} (overlap ${r.alignment?.overlap?.toFixed?.(3) ?? '—'}, residual ${r.alignment?.rms?.toExponential?.(2) ?? '—'} of the diagonal)`);
  state.trace = job;
  $('report').hidden = false;
  await showAlignedSuspect(job);
}

async function showAlignedSuspect(job) {
  const suspect = parsePreviewPly(await getBytes(`/v1/jobs/${job.id}/preview`));
  const v = await viewer();
  if (!v || !state.original) return;
  v.show([{ mesh: state.original, name: 'original' }, { mesh: suspect, name: 'suspect', colour: 0xeb781e, opacity: 0.6 }]);
  $('view-legend').hidden = true;
  $('view-original').hidden = true;
  $('view-caption').textContent = 'The suspect (orange) as the detector aligned it over the original (grey).';
}

async function downloadReport() {
  if (!state.trace) return;
  await guarded(async () => download(await getBlob(`/v1/jobs/${state.trace.id}/report`), `evidence-${state.trace.id}.html`));
}

// ---- wiring ----

function wire() {
  $('sign-in-form').addEventListener('submit', signIn);
  $('sign-out').addEventListener('click', () => signOut());
  $('upload-file').addEventListener('change', (e) => uploadFiles(Array.from(e.target.files)).then(() => { e.target.value = ''; }));
  $('upload-folder').addEventListener('change', (e) => uploadFiles(Array.from(e.target.files)).then(() => { e.target.value = ''; }));
  dropZone($('upload-drop'), uploadFiles);
  $('library-suspect').addEventListener('change', (e) => traceInLibrary(Array.from(e.target.files)).then(() => { e.target.value = ''; }));
  dropZone($('library-trace'), traceInLibrary);
  $('trace-file').addEventListener('change', (e) => traceOnModel(Array.from(e.target.files)).then(() => { e.target.value = ''; }));
  dropZone($('trace-drop'), traceOnModel);
  $('embed-form').addEventListener('submit', makeCopies);
  $('download-all').addEventListener('click', downloadAll);
  $('report').addEventListener('click', downloadReport);
  $('view-reset').addEventListener('click', () => state.viewer?.reset());
  $('view-flat').addEventListener('change', (e) => state.viewer?.setFlat(e.target.checked));
  $('view-original').addEventListener('click', (e) => {
    const showing = e.target.dataset.showing === 'yes';
    state.viewer?.setVisible('original', !showing);
    e.target.dataset.showing = showing ? 'no' : 'yes';
    e.target.textContent = showing ? 'Show the original' : 'Hide the original';
  });
  if (session.key()) enterConsole();
}

wire();
