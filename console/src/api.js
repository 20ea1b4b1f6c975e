// The daemon's public API (proto/openapi.json), with the key from session storage. Errors come
// back as Error objects whose message is the problem's "detail" in words.

const KEY = 'meshmark.apiKey';
const REQUESTER = 'meshmark.requestedBy';

export const session = {
  key: () => sessionStorage.getItem(KEY),
  signIn: (key) => sessionStorage.setItem(KEY, key),
  signOut: () => { sessionStorage.removeItem(KEY); sessionStorage.removeItem(REQUESTER); },
  // Who is asking for copies in this session (a name the person gives, kept with each copy).
  requester: () => sessionStorage.getItem(REQUESTER) ?? '',
  setRequester: (name) => sessionStorage.setItem(REQUESTER, name),
};

async function problemMessage(response) {
  let detail = '';
  try {
    const body = await response.json();
    detail = body.detail || body.title || '';
  } catch (_) { /* not JSON */ }
  if (response.status === 401) return detail || 'The API key is not valid.';
  return detail || `The daemon answered ${response.status} ${response.statusText}.`;
}

export class ApiError extends Error {
  constructor(status, message, problem) {
    super(message);
    this.status = status;
    this.problem = problem;
  }
}

export async function call(method, path, { json, body, query, accept } = {}) {
  const headers = { Authorization: `Bearer ${session.key()}` };
  if (json !== undefined) headers['Content-Type'] = 'application/json';
  if (accept) headers.Accept = accept;
  const url = path + (query ? `?${new URLSearchParams(query)}` : '');
  const response = await fetch(url, { method, headers, body: json !== undefined ? JSON.stringify(json) : body });
  if (!response.ok) {
    const clone = response.clone();
    let problem = null;
    try { problem = await clone.json(); } catch (_) { /* not JSON */ }
    throw new ApiError(response.status, await problemMessage(response), problem);
  }
  return response;
}

export const getJson = async (path, query) => (await call('GET', path, { query })).json();
export const getBytes = async (path, query) => (await call('GET', path, { query })).arrayBuffer();
export const getBlob = async (path, query) => (await call('GET', path, { query })).blob();

// A file upload with progress (fetch has no upload progress); resolves to the parsed JSON body.
export function upload(path, query, blob, onProgress) {
  return new Promise((resolve, reject) => {
    const xhr = new XMLHttpRequest();
    xhr.open('POST', `${path}?${new URLSearchParams(query)}`);
    xhr.setRequestHeader('Authorization', `Bearer ${session.key()}`);
    xhr.setRequestHeader('Content-Type', 'application/octet-stream');
    xhr.upload.onprogress = (e) => { if (e.lengthComputable) onProgress(e.loaded / e.total); };
    xhr.onload = () => {
      let body = null;
      try { body = JSON.parse(xhr.responseText); } catch (_) { /* not JSON */ }
      if (xhr.status >= 200 && xhr.status < 300) resolve(body);
      else reject(new ApiError(xhr.status, (body && (body.detail || body.title)) || `The daemon answered ${xhr.status}.`, body));
    };
    xhr.onerror = () => reject(new ApiError(0, 'The daemon could not be reached.', null));
    xhr.send(blob);
  });
}

const FINAL = new Set(['succeeded', 'failed', 'canceled']);

// Polls a job until it ends; onProgress(job) on each look.
export async function waitForJob(id, onProgress = () => {}) {
  for (;;) {
    const job = await getJson(`/v1/jobs/${encodeURIComponent(id)}`);
    onProgress(job);
    if (FINAL.has(job.state)) return job;
    await new Promise((r) => setTimeout(r, 400));
  }
}
