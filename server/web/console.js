// The membrane web console: the jobs of membraned's HTTP API (server/http_api.h), live, and
// the selected job's progress, statistics and mesh in 3D (three.js from Debian's libjs-three,
// served by membraned). No framework: the DOM, fetch and three.js only.
'use strict';

const LIST_INTERVAL_MS = 1000;   // the job list is polled this often
const FIRST_ROWS = 50;           // rows of the first list laid out before the rest
const EVENT_WAIT_S = 15;         // an events request waits this long for news
const TOKEN_KEY = 'membrane-token';

const state = {
  token: localStorage.getItem(TOKEN_KEY) || '',
  jobs: new Map(),        // id -> {job, has_preview, row}
  selected: null,         // the selected job's id
  follow: 0,              // bumped on each selection: an older events loop stops
  previews: new Map(),    // id -> object URL of its PNG preview
  viewer: null,
  listShown: false,
};

const $ = (id) => document.getElementById(id);

// fetch of the API with the token; a 401 asks for the token (once per change) and throws.
async function api(path, options = {}) {
  const headers = {};
  if (state.token) headers.Authorization = 'Bearer ' + state.token;
  const response = await fetch(path, { ...options, headers });
  if (response.status === 401) {
    askForToken(state.token ? 'this token is not accepted' : 'this server wants a token');
    throw new Error('unauthenticated');
  }
  if (!response.ok) {
    let message = response.statusText;
    try { message = (await response.json()).error.message; } catch (e) { /* not JSON */ }
    throw new Error(message);
  }
  return response;
}

function askForToken(why) {
  setStatus(why, true);
  $('token-form').hidden = false;
  $('token').focus();
}

$('token-form').addEventListener('submit', (e) => {
  e.preventDefault();
  state.token = $('token').value.trim();
  localStorage.setItem(TOKEN_KEY, state.token);
  $('token-form').hidden = true;
  setStatus('connecting');
  refreshList();
  if (state.selected) select(state.selected);
});

function setStatus(text, error = false) {
  $('status').textContent = text;
  $('status').classList.toggle('error', error);
}

function bytes(n) {
  n = Number(n);
  if (!n) return '';
  const units = ['B', 'KiB', 'MiB', 'GiB'];
  let u = 0;
  while (n >= 1024 && u < units.length - 1) { n /= 1024; ++u; }
  return (u === 0 ? n : n.toFixed(1)) + ' ' + units[u];
}

// One formatter for every row: Date.toLocaleString builds a new one per call, for each of the
// list's rows every second.
const DATE_FORMAT = new Intl.DateTimeFormat(undefined, { dateStyle: 'short', timeStyle: 'medium' });

function time(unixSeconds) {
  if (!unixSeconds) return '';
  return DATE_FORMAT.format(new Date(unixSeconds * 1000));
}

function seconds(s) {
  return s < 10 ? s.toFixed(2) + ' s' : s < 600 ? s.toFixed(1) + ' s' : (s / 60).toFixed(1) + ' min';
}

const isDone = (job) => ['SUCCEEDED', 'FAILED', 'CANCELLED'].includes(job.state);

// ---- the job list ----

async function refreshList() {
  let list;
  try {
    list = await (await api('/api/jobs')).json();
  } catch (e) {
    if (e.message !== 'unauthenticated') setStatus('cannot list jobs: ' + e.message, true);
    return;
  }
  const count = list.jobs.length === 1 ? '1 job' : list.jobs.length + ' jobs';
  setStatus(count + ', updated ' + new Date().toLocaleTimeString());
  // The first list shows a screenful of rows in its first frame, and the rest right after it
  // is painted: the layout of a thousand rows took 0.4-0.6 s of that frame.
  const first = !state.listShown;
  showList(list, first ? FIRST_ROWS : Infinity);
  if (first) {
    state.listShown = true;
    requestAnimationFrame(() => setTimeout(() => {
      // When the first list was on screen, and when all its rows were, in ms since the
      // navigation began: for the load-time benchmark, tests/bench/web_console_load.py.
      document.body.dataset.listShownMs = String(Math.round(performance.now()));
      if (list.jobs.length <= FIRST_ROWS) {
        document.body.dataset.listCompleteMs = document.body.dataset.listShownMs;
        return;
      }
      showList(list, Infinity);
      requestAnimationFrame(() => setTimeout(() => {
        document.body.dataset.listCompleteMs = String(Math.round(performance.now()));
      }));
    }));
  }
  if (state.selected && state.jobs.has(state.selected)) {
    const job = state.jobs.get(state.selected).job;
    $('detail-state').textContent = job.state + (job.stage ? ' (' + job.stage + ')' : '');
  }
}

// Puts the first `limit` jobs of `list` (newest first, as the server lists them) in the table,
// and, when they are all of them, takes out the rows of jobs no longer listed.
function showList(list, limit) {
  const tbody = document.querySelector('#jobs tbody');
  const seen = new Set();
  let previous = null;
  for (const item of list.jobs.slice(0, limit)) {
    const id = item.job.id;
    seen.add(id);
    let entry = state.jobs.get(id);
    if (!entry) {
      entry = { row: makeRow(id) };
      state.jobs.set(id, entry);
    }
    entry.job = item.job;
    entry.has_preview = item.has_preview;
    updateRow(entry);
    // Newest first, as the server lists them; rows are moved only when out of place.
    const want = previous ? previous.nextSibling : tbody.firstChild;
    if (want !== entry.row) tbody.insertBefore(entry.row, want);
    previous = entry.row;
  }
  if (limit < list.jobs.length) return;
  for (const [id, entry] of state.jobs) {
    if (!seen.has(id)) { entry.row.remove(); state.jobs.delete(id); }
  }
  $('no-jobs').hidden = list.jobs.length > 0;
}

function makeRow(id) {
  const row = document.createElement('tr');
  row.id = 'job-' + id;
  row.dataset.id = id;
  for (let i = 0; i < 11; ++i) row.appendChild(document.createElement('td'));
  for (const i of [5, 6, 7]) row.cells[i].className = 'num';
  row.addEventListener('click', (e) => {
    if (e.target.closest('button, a')) return;
    select(id);
  });
  previewObserver.observe(row);
  return row;
}

function setText(cell, text) {
  if (cell.textContent !== text) cell.textContent = text;
}

function updateRow(entry) {
  const job = entry.job, c = entry.row.cells;
  entry.row.dataset.state = job.state;
  setText(c[1], job.id);
  setText(c[2], job.client || '');
  setText(c[3], job.state);
  c[3].className = 'state-' + job.state;
  setText(c[4], job.stage || (job.error && job.error.message ? job.error.message.slice(0, 60) : ''));
  setText(c[5], job.queue_position ? String(job.queue_position) : '');
  setText(c[6], bytes(job.upload_bytes));
  setText(c[7], bytes(job.mesh_bytes));
  setText(c[8], time(job.created_unix_seconds));
  setText(c[9], job.finished_unix_seconds
    ? seconds(job.finished_unix_seconds - job.created_unix_seconds) : '');
  const actions = job.state === 'SUCCEEDED' ? 'downloads' : isDone(job) ? 'none' : 'cancel';
  if (c[10].dataset.actions !== actions) {
    c[10].dataset.actions = actions;
    c[10].replaceChildren(...actionElements(job.id, actions));
  }
  if (entry.has_preview && entry.visible) showPreview(entry);
}

function actionElements(id, actions) {
  if (actions === 'cancel') {
    const button = document.createElement('button');
    button.textContent = 'cancel';
    button.className = 'cancel';
    button.addEventListener('click', async () => {
      button.disabled = true;
      try {
        await api('/api/jobs/' + id + '/cancel', { method: 'POST' });
      } catch (e) {
        setStatus('cannot cancel ' + id + ': ' + e.message, true);
      }
      refreshList();
    });
    return [button];
  }
  if (actions === 'downloads') {
    return ['drc', 'ply'].map((ext) => {
      const a = document.createElement('a');
      a.href = '#';
      a.className = 'download';
      a.dataset.ext = ext;
      a.textContent = '.' + ext;
      a.addEventListener('click', (e) => { e.preventDefault(); download(id, ext); });
      return a;
    });
  }
  return [];
}

// Downloads go through fetch (a plain link could not send the token), then a blob link.
async function download(id, ext) {
  try {
    const blob = await (await api('/api/jobs/' + id + '/mesh.' + ext)).blob();
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = id + '.' + ext;
    document.body.appendChild(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 60000);
    document.body.dataset.lastDownload = id + '.' + ext + ' ' + blob.size;
  } catch (e) {
    setStatus('cannot download ' + id + '.' + ext + ': ' + e.message, true);
  }
}

// Previews are fetched for the rows on screen only: a list of a thousand jobs asks for a few.
const previewObserver = new IntersectionObserver((entries) => {
  for (const e of entries) {
    const entry = state.jobs.get(e.target.dataset.id);
    if (!entry) continue;
    entry.visible = e.isIntersecting;
    if (entry.visible && entry.has_preview) showPreview(entry);
  }
});

async function showPreview(entry) {
  const id = entry.job.id;
  if (state.previews.has(id)) return;
  state.previews.set(id, null);
  try {
    const blob = await (await api('/api/jobs/' + id + '/preview.png')).blob();
    const url = URL.createObjectURL(blob);
    state.previews.set(id, url);
    const img = document.createElement('img');
    img.className = 'preview';
    img.alt = 'preview of ' + id;
    img.src = url;
    entry.row.cells[0].replaceChildren(img);
  } catch (e) {
    state.previews.delete(id);
  }
}

// ---- the selected job ----

async function select(id) {
  state.selected = id;
  const follow = ++state.follow;
  for (const row of document.querySelectorAll('#jobs tr.selected')) row.classList.remove('selected');
  const row = $('job-' + id);
  if (row) row.classList.add('selected');
  $('detail').hidden = false;
  $('detail-id').textContent = id;
  $('detail-state').textContent = '';
  document.querySelector('#stages tbody').replaceChildren();
  document.querySelector('#generations tbody').replaceChildren();
  document.querySelector('#stats tbody').replaceChildren();
  $('show-points').checked = false;
  clearViewer('The mesh is shown here once the job has succeeded.');
  let next = 0;
  // Follows the job's events until it ends or another job is selected.
  while (follow === state.follow) {
    let answer;
    try {
      answer = await (await api('/api/jobs/' + id + '/events?after=' + next + '&wait=' + EVENT_WAIT_S)).json();
    } catch (e) {
      if (follow === state.follow) clearViewer('cannot follow the job: ' + e.message);
      return;
    }
    if (follow !== state.follow) return;
    for (const event of answer.events) showEvent(event);
    next = answer.next;
    $('detail-state').textContent = answer.state;
    if (answer.done) break;
    // Nothing new: the wait ran out, or a stopping server answered at once. Not asked again
    // at once, so that a stopping server is not flooded.
    if (answer.events.length === 0) await new Promise((r) => setTimeout(r, 1000));
  }
  if (follow !== state.follow) return;
  const detail = await (await api('/api/jobs/' + id)).json();
  if (follow !== state.follow) return;
  showStatistics(detail);
  if (detail.job.state === 'SUCCEEDED') {
    showMesh(id, detail, follow);
  } else {
    const error = detail.job.error && detail.job.error.message;
    clearViewer(detail.job.state + (error ? ': ' + error : ''));
  }
}

function showEvent(event) {
  if (event.stage) {
    const s = event.stage;
    const tbody = document.querySelector('#stages tbody');
    let row = tbody.querySelector('tr[data-stage="' + s.stage + '"]');
    if (!row) {
      row = tbody.insertRow();
      row.dataset.stage = s.stage;
      for (let i = 0; i < 3; ++i) row.insertCell();
      row.cells[0].textContent = s.stage;
      row.cells[1].className = 'num';
    }
    if (s.phase === 'FINISHED') row.cells[1].textContent = s.seconds.toFixed(3);
    if (s.line) row.cells[2].textContent = s.line;
  }
  if (event.generation) {
    const g = event.generation;
    const tbody = document.querySelector('#generations tbody');
    // A generation run again by the handle retry replaces the row of that generation.
    let row = tbody.querySelector('tr[data-generation="' + g.generation + '"]');
    if (!row) {
      row = tbody.insertRow();
      row.dataset.generation = g.generation;
      for (let i = 0; i < 7; ++i) row.insertCell().className = 'num';
    }
    const values = [g.generation, g.planned_generations, g.plate_size, g.soft_voxels,
      g.started_contractions, g.backtrackings, Number(g.seconds).toFixed(3)];
    values.forEach((v, i) => { row.cells[i].textContent = String(v); });
    if (g.handle_retry) row.title = 'run again by the handle retry';
  }
}

function showStatistics(detail) {
  const rows = [];
  const j = detail.job;
  rows.push(['state', j.state], ['client', j.client || '-'], ['upload', bytes(j.upload_bytes)],
    ['mesh', bytes(j.mesh_bytes)]);
  const s = detail.statistics;
  if (s) {
    rows.push(['points', s.points], ['voxel size', s.voxel_size], ['grid', (s.grid || []).join(' x ')],
      ['generations', (s.generations || []).length], ['surface', s.surface]);
    const m = s.mesh || {};
    rows.push(['vertices', m.vertices], ['faces', m.faces], ['shells', m.shells],
      ['genus', (m.genus || []).join(', ')],
      ['closed / manifold / oriented', [m.closed, m.manifold, m.oriented].join(' / ')],
      ['self-intersections', m.self_intersections]);
    for (const [stage, t] of Object.entries(s.seconds || {})) rows.push([stage + ' (s)', Number(t).toFixed(3)]);
    for (const w of s.warnings || []) rows.push(['warning', w]);
  }
  const tbody = document.querySelector('#stats tbody');
  tbody.replaceChildren();
  for (const [k, v] of rows) {
    const row = tbody.insertRow();
    row.insertCell().textContent = k;
    row.insertCell().textContent = v === undefined ? '' : String(v);
  }
}

// ---- the 3D view ----

// The binary little-endian PLY of /api/jobs/ID/mesh.ply: x y z as float or double among the
// vertex's properties (nx ny nz follow them), triangles as "list uchar int". Positions are
// returned in double, for a caller to centre.
function parsePly(buffer) {
  const bytesView = new Uint8Array(buffer);
  const marker = 'end_header\n';
  let end = -1;
  for (let i = 0; i + marker.length <= Math.min(bytesView.length, 4096); ++i) {
    let match = true;
    for (let k = 0; k < marker.length && match; ++k) match = bytesView[i + k] === marker.charCodeAt(k);
    if (match) { end = i + marker.length; break; }
  }
  if (end < 0) throw new Error('not a PLY file');
  const header = new TextDecoder().decode(bytesView.subarray(0, end)).split('\n');
  const sizes = { float: 4, double: 8 };
  let vertices = 0, faces = 0, element = '', stride = 0;
  const offset = {}, type = {};
  for (const line of header) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'element') element = w[1];
    if (w[0] === 'element' && w[1] === 'vertex') vertices = Number(w[2]);
    if (w[0] === 'element' && w[1] === 'face') faces = Number(w[2]);
    if (w[0] === 'property' && element === 'vertex') {
      if (!(w[1] in sizes)) throw new Error('unexpected vertex property type ' + w[1]);
      offset[w[2]] = stride;
      type[w[2]] = w[1];
      stride += sizes[w[1]];
    }
  }
  if (!('x' in offset && 'y' in offset && 'z' in offset)) throw new Error('no x y z in the PLY');
  const view = new DataView(buffer, end);
  const positions = new Float64Array(vertices * 3);
  for (let i = 0; i < vertices; ++i) {
    ['x', 'y', 'z'].forEach((axis, a) => {
      const at = i * stride + offset[axis];
      positions[i * 3 + a] = type[axis] === 'double' ? view.getFloat64(at, true) : view.getFloat32(at, true);
    });
  }
  let at = vertices * stride;
  const index = new Uint32Array(faces * 3);
  for (let f = 0; f < faces; ++f) {
    const n = view.getUint8(at);
    at += 1;
    for (let k = 0; k < n; ++k, at += 4) if (k < 3) index[f * 3 + k] = view.getInt32(at, true);
  }
  return { positions, index };
}

// The shell of each vertex: connected components of the faces (union-find).
function shellsOf(vertexCount, index) {
  const parent = new Int32Array(vertexCount);
  for (let i = 0; i < vertexCount; ++i) parent[i] = i;
  const find = (x) => {
    while (parent[x] !== x) { parent[x] = parent[parent[x]]; x = parent[x]; }
    return x;
  };
  for (let i = 0; i < index.length; i += 3) {
    const a = find(index[i]);
    for (const v of [index[i + 1], index[i + 2]]) {
      const b = find(v);
      if (a !== b) parent[b] = a;
    }
  }
  const label = new Map();
  const shell = new Int32Array(vertexCount);
  for (let i = 0; i < vertexCount; ++i) {
    const r = find(i);
    if (!label.has(r)) label.set(r, label.size);
    shell[i] = label.get(r);
  }
  return { shell, count: label.size };
}

const SHELL_COLOURS = [0x6fa8dc, 0xe69138, 0x93c47d, 0xc27ba0, 0xf1c232, 0x76a5af, 0xe06666, 0x8e7cc3];

// three.js (600 kB) is fetched and run only when a mesh is first shown: as a script of the page
// it ran before console.js, and the job list was asked for only after it.
let threeLoaded = null;
function loadScript(src) {
  return new Promise((resolve, reject) => {
    const script = document.createElement('script');
    script.src = src;
    script.onload = resolve;
    script.onerror = () => reject(new Error('cannot load ' + src));
    document.head.appendChild(script);
  });
}
function loadThree() {
  if (!threeLoaded) {
    threeLoaded = loadScript('/three/three.min.js').then(() => loadScript('/three/OrbitControls.js'));
    threeLoaded.catch(() => { threeLoaded = null; });  // asked again with the next mesh
  }
  return threeLoaded;
}

function ensureViewer() {
  if (state.viewer) return state.viewer;
  const canvas = $('canvas');
  let renderer;
  try {
    // preserveDrawingBuffer: the canvas keeps its picture for screenshots and tests.
    renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    $('viewer-note').textContent = 'no WebGL in this browser: ' + e.message;
    return null;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(640, 480, false);
  renderer.setClearColor(0x20262f);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, 640 / 480, 0.01, 1000);
  scene.add(new THREE.AmbientLight(0xffffff, 0.45));
  const light = new THREE.DirectionalLight(0xffffff, 0.75);
  camera.add(light);
  light.position.set(1, 1, 2);
  scene.add(camera);
  const controls = new THREE.OrbitControls(camera, canvas);
  const viewer = { renderer, scene, camera, controls, group: null, points: null };
  const render = () => renderer.render(scene, camera);
  controls.addEventListener('change', render);
  viewer.render = render;
  state.viewer = viewer;
  return viewer;
}

function clearViewer(note) {
  const v = state.viewer;
  if (v && v.group) {
    v.scene.remove(v.group);
    v.group.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    v.group = null;
    v.points = null;
    v.render();
  }
  document.body.dataset.meshShown = '';
  $('viewer-note').textContent = note;
  $('viewer-note').hidden = false;
}

async function showMesh(id, detail, follow) {
  $('viewer-note').textContent = 'loading the mesh';
  let ply;
  try {
    ply = parsePly(await (await api('/api/jobs/' + id + '/mesh.ply')).arrayBuffer());
  } catch (e) {
    clearViewer('cannot load the mesh: ' + e.message);
    return;
  }
  if (follow !== state.follow) return;
  try {
    await loadThree();
  } catch (e) {
    clearViewer('cannot show the mesh: ' + e.message);
    return;
  }
  if (follow !== state.follow) return;
  const v = ensureViewer();
  if (!v) return;
  const n = ply.positions.length / 3;
  // Centred in double, then float32: georeferenced meshes keep their detail.
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n * 3; ++i) {
    min[i % 3] = Math.min(min[i % 3], ply.positions[i]);
    max[i % 3] = Math.max(max[i % 3], ply.positions[i]);
  }
  const centre = min.map((m, a) => (m + max[a]) / 2);
  const radius = Math.max(1e-9, Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]) / 2);
  const positions = new Float32Array(n * 3);
  for (let i = 0; i < n * 3; ++i) positions[i] = ply.positions[i] - centre[i % 3];
  const { shell, count } = shellsOf(n, ply.index);
  const colours = new Float32Array(n * 3);
  const colour = new THREE.Color();
  for (let i = 0; i < n; ++i) {
    colour.setHex(SHELL_COLOURS[shell[i] % SHELL_COLOURS.length]);
    colours.set([colour.r, colour.g, colour.b], i * 3);
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  geometry.setIndex(new THREE.BufferAttribute(ply.index, 1));
  geometry.computeVertexNormals();
  const material = new THREE.MeshPhongMaterial({ vertexColors: THREE.VertexColors, flatShading: false });
  clearViewer('');
  $('viewer-note').hidden = true;
  v.group = new THREE.Group();
  v.group.add(new THREE.Mesh(geometry, material));
  v.group.userData = { id, centre, origin: originOf(detail.job), radius };
  v.scene.add(v.group);
  v.camera.near = radius / 100;
  v.camera.far = radius * 100;
  v.camera.position.set(radius * 1.2, radius * 0.85, radius * 1.7);
  v.camera.updateProjectionMatrix();
  v.controls.target.set(0, 0, 0);
  v.controls.update();
  v.render();
  document.body.dataset.meshShown = id;
  document.body.dataset.meshShells = String(count);
  if ($('show-points').checked) showPoints(true);
}

function originOf(job) {
  const o = (job.parameters && job.parameters.origin) || [];
  return o.length === 3 ? o.map(Number) : [0, 0, 0];
}

// The sample of the input points, drawn over the mesh on demand.
async function showPoints(on) {
  const v = state.viewer;
  if (!v || !v.group) return;
  if (v.points) { v.points.visible = on; v.render(); return; }
  if (!on) return;
  const { id, centre, origin, radius } = v.group.userData;
  let sample;
  try {
    sample = new Float32Array(await (await api('/api/jobs/' + id + '/points')).arrayBuffer());
  } catch (e) {
    setStatus('no input points for ' + id + ': ' + e.message, true);
    return;
  }
  if (!v.group || v.group.userData.id !== id) return;
  // The sample is in the mesh's positions; the PLY's are those plus the job's origin.
  const positions = new Float32Array(sample.length);
  for (let i = 0; i < sample.length; ++i) positions[i] = sample[i] + origin[i % 3] - centre[i % 3];
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  v.points = new THREE.Points(geometry, new THREE.PointsMaterial({ color: 0xffffff, size: radius / 150 }));
  v.group.add(v.points);
  v.render();
  document.body.dataset.pointsShown = String(sample.length / 3);
}

$('show-points').addEventListener('change', (e) => showPoints(e.target.checked));

// ---- start ----

// The list is refreshed while the tab is seen: a hidden tab costs the server nothing, and is
// brought up to date as soon as it is shown again.
async function poll() {
  if (!document.hidden) await refreshList();
  setTimeout(poll, LIST_INTERVAL_MS);
}
document.addEventListener('visibilitychange', () => { if (!document.hidden) refreshList(); });
const fromHash = decodeURIComponent(location.hash.slice(1));
poll().then(() => { if (fromHash) select(fromHash); });
