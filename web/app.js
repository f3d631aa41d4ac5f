// The splat dashboard. Talks only to /api/v1 of the server that serves it.
// - Campaign list: polled every second (the browser revalidates with ETags).
// - New-campaign form: built from GET /api/v1/schemas/campaign; every field
//   shows its unit from the schema's `unit` keyword; empty fields are left out
//   so the server's defaults apply; errors come back as problem documents
//   whose JSON pointers are listed next to the form.
// - Campaign detail: window table, CSV download, stick/rebound map (Chart.js
//   scatter), per-job histories grouped by unit (velocities, energies, area).
'use strict';

const API = '/api/v1';
const state = {
  selected: null,      // campaign id shown in the detail section
  selectedState: null, // its last known state
  campaigns: [],
  jobs: [],
  windows: [],
  charts: {},
  materials: [],
};

// ---------------------------------------------------------------- helpers --
function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k === 'text') e.textContent = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

function fmt(x, digits = 4) {
  if (x === null || x === undefined) return '-';
  if (typeof x !== 'number') return String(x);
  return Number(x.toPrecision(digits)).toString();
}

function seconds(s) {
  if (s === null || s === undefined) return '-';
  if (s < 60) return `${fmt(s, 2)} s`;
  if (s < 3600) return `${fmt(s / 60, 2)} min`;
  return `${fmt(s / 3600, 2)} h`;
}

function authHeaders() {
  const t = document.getElementById('token').value.trim();
  return t ? { Authorization: `Bearer ${t}` } : {};
}

async function getJson(path) {
  const r = await fetch(API + path, { headers: { Accept: 'application/json' } });
  const body = await r.json();
  if (!r.ok) throw Object.assign(new Error(body.detail || r.statusText), { problem: body });
  return body;
}

// --------------------------------------------------------- campaign list --
async function refreshCampaigns() {
  try {
    const page = await getJson('/campaigns?page_size=100');
    state.campaigns = page.campaigns;
    renderCampaigns();
    const health = await getJson('/health');
    document.getElementById('server-status').textContent =
      `splat ${health.version} (${health.git_commit.slice(0, 8)}) - ` +
      (health.running_campaign ? `running campaign ${health.running_campaign}` : 'idle') +
      (health.waiting_campaigns ? `, ${health.waiting_campaigns} waiting` : '');
  } catch (e) {
    document.getElementById('server-status').textContent = `server unreachable: ${e.message}`;
  }
}

function renderCampaigns() {
  const tbody = document.querySelector('#campaigns tbody');
  tbody.replaceChildren();
  for (const c of state.campaigns) {
    const bar = el('div', { class: 'progress', title: `${Math.round(c.progress * 100)} %` },
      el('div', { style: `width:${(c.progress * 100).toFixed(1)}%` }));
    const j = c.jobs;
    const tr = el('tr', { 'data-id': c.id, onclick: () => selectCampaign(c.id) },
      el('td', { text: c.id }), el('td', { text: c.name }),
      el('td', { class: 'state', text: c.state }), el('td', {}, bar),
      el('td', { text: `${j.succeeded + j.failed + j.cancelled + j.timed_out}/${j.total}` +
        (j.failed + j.timed_out ? ` (${j.failed + j.timed_out} failed)` : '') }),
      el('td', { text: c.state === 'active' ? seconds(c.estimated_seconds_left) : '' }),
      el('td', { text: c.running_now ? 'running' : '' }));
    if (c.id === state.selected) tr.classList.add('selected');
    tbody.append(tr);
  }
  if (state.selected !== null) {
    const c = state.campaigns.find((x) => x.id === state.selected);
    if (c && c.state !== state.selectedState) refreshDetail();
  }
}

// ----------------------------------------------------- new-campaign form --
const TEMPLATES = {
  two_mass: () => ({
    name: 'two_mass',
    two_mass: { M: 1.0, m: 2.0, k: 0.0, V0: 1.0, area: 1.0,
      adhesion: { G_c: 0.2, sigma_c: 0.5, activation: { rule: 'none' }, D_adh_max: null } },
    time: { end_time: 50.0 },
    output: { history_interval: 0 },
  }),
  particle_impact: () => {
    const p = document.getElementById('particle-material').value;
    const s = document.getElementById('substrate-material').value;
    return {
      name: 'impact',
      particle_impact: {
        particle: { material: p, radius: Number(document.getElementById('particle-radius').value) },
        substrate: { material: s },
        velocity: 500,
      },
    };
  },
};

// Starting values of the form for the two-mass template (a small campaign).
const PREFILL = {
  two_mass: { '/name': 'two-mass-window', '/velocity/range/from': 0.1,
    '/velocity/range/to': 1.5, '/velocity/range/step': 0.1, '/G_c/values': '0.1, 0.2',
    '/job/time_limit': 60 },
  particle_impact: { '/name': 'impact-window', '/velocity/pointer': '/particle_impact/velocity',
    '/velocity/range/from': 300, '/velocity/range/to': 900, '/velocity/range/step': 100,
    '/G_c/pointer': '/particle_impact/adhesion/G_c', '/G_c/values': '',
    '/job/time_limit': 3600 },
};

function resolve(schema, root) {
  if (schema && schema.$ref) {
    const path = schema.$ref.replace(/^#\//, '').split('/');
    let s = root;
    for (const p of path) s = s[p];
    return { ...s, description: schema.description || s.description };
  }
  return schema;
}

function types(schema) {
  return Array.isArray(schema.type) ? schema.type : [schema.type];
}

// Top-level fields in reading order (the served schema's keys come sorted).
const ORDER = ['name', 'description', 'tags', 'velocity', 'G_c', 'sigma_c', 'yield_drop_percent',
  'D_adh_max', 'fields', 'refinement', 'job', 'priority', 'executor'];

// One input per leaf of the schema; each carries its JSON pointer and kind.
function buildFields(schema, root, pointer, container) {
  const rank = (k) => (ORDER.includes(k) ? ORDER.indexOf(k) : ORDER.length);
  const entries = Object.entries(schema.properties || {});
  if (pointer === '') entries.sort((a, b) => rank(a[0]) - rank(b[0]));
  for (const [name, raw] of entries) {
    const sub = resolve(raw, root);
    const ptr = `${pointer}/${name}`;
    if (name === '$schema' || ptr === '/base_scene') continue;
    const t = types(sub);
    const unit = sub.unit || (sub.items && sub.items.unit);
    const label = el('label', { title: sub.description || '' }, `${name} `);
    let input = null;
    if (sub.enum) {
      input = el('select', { 'data-kind': 'enum' }, el('option', { value: '', text: '(default)' }));
      for (const v of sub.enum) input.append(el('option', { value: v, text: v }));
    } else if (t.includes('object') && sub.properties) {
      const fs = el('fieldset', {}, el('legend', { text: name, title: sub.description || '' }));
      buildFields(sub, root, ptr, fs);
      container.append(fs);
      continue;
    } else if (t.includes('array') && sub.items && resolve(sub.items, root).type === 'object') {
      input = el('textarea', { 'data-kind': 'json', rows: 2,
        placeholder: 'JSON array, e.g. [{"pointer": "/two_mass/k", "unit": "N/m", "values": [0, 0.5]}]' });
      label.classList.add('wide');
    } else if (t.includes('array')) {
      const it = types(resolve(sub.items || {}, root));
      input = el('input', { type: 'text', 'data-kind': it.includes('string') ? 'strings' : 'numbers',
        placeholder: 'comma-separated' + (it.includes('null') ? ' (null allowed)' : '') });
    } else if (t.includes('integer') || t.includes('number')) {
      input = el('input', { type: 'number', step: 'any', 'data-kind': t.includes('integer') ? 'integer' : 'number' });
      if (sub.default !== undefined) input.placeholder = String(sub.default);
    } else {
      input = el('input', { type: 'text', 'data-kind': 'string' });
      if (sub.default !== undefined) input.placeholder = String(sub.default);
    }
    input.setAttribute('data-pointer', ptr);
    input.name = ptr;
    label.append(input);
    if (unit) label.append(' ', el('span', { class: 'unit', text: unit }));
    container.append(label);
  }
}

function setPointer(doc, pointer, value) {
  const parts = pointer.split('/').slice(1);
  let o = doc;
  for (const p of parts.slice(0, -1)) o = (o[p] = o[p] || {});
  o[parts[parts.length - 1]] = value;
}

function readForm() {
  const doc = {};
  const errors = [];
  for (const input of document.querySelectorAll('#schema-fields [data-pointer]')) {
    const raw = input.value.trim();
    if (raw === '') continue;
    const ptr = input.getAttribute('data-pointer');
    const kind = input.getAttribute('data-kind');
    let v = raw;
    if (kind === 'number' || kind === 'integer') v = Number(raw);
    else if (kind === 'numbers') v = raw.split(',').map((s) => s.trim()).filter((s) => s).map((s) => (s === 'null' ? null : Number(s)));
    else if (kind === 'strings') v = raw.split(',').map((s) => s.trim()).filter((s) => s);
    else if (kind === 'json') {
      try { v = JSON.parse(raw); } catch (e) { errors.push(`${ptr}: not JSON (${e.message})`); continue; }
    }
    setPointer(doc, ptr, v);
  }
  try {
    doc.base_scene = JSON.parse(document.getElementById('base-scene').value);
  } catch (e) {
    errors.push(`/base_scene: not JSON (${e.message})`);
  }
  return { doc, errors };
}

function applyTemplate() {
  const t = document.getElementById('scene-template').value;
  document.getElementById('impact-fields').hidden = t !== 'particle_impact';
  document.getElementById('base-scene').value = JSON.stringify(TEMPLATES[t](), null, 2);
  for (const input of document.querySelectorAll('#schema-fields [data-pointer]')) input.value = '';
  for (const [ptr, v] of Object.entries(PREFILL[t])) {
    const input = document.querySelector(`#schema-fields [data-pointer="${ptr}"]`);
    if (input) input.value = v;
  }
}

async function submitCampaign(ev) {
  ev.preventDefault();
  const list = document.getElementById('form-errors');
  const result = document.getElementById('submit-result');
  list.replaceChildren();
  result.textContent = '';
  const { doc, errors } = readForm();
  if (errors.length) {
    for (const e of errors) list.append(el('li', { text: e }));
    return;
  }
  const r = await fetch(`${API}/campaigns`, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json', 'Idempotency-Key': crypto.randomUUID ? crypto.randomUUID() : String(Math.random()), ...authHeaders() },
    body: JSON.stringify(doc),
  });
  const body = await r.json();
  if (!r.ok) {
    result.textContent = `${body.title}: ${body.detail}`;
    for (const e of body.errors || []) {
      list.append(el('li', { text: `${e.pointer ?? e.parameter}: ${e.detail}` }));
    }
    return;
  }
  result.textContent = `campaign ${body.id} accepted (${body.jobs.total} jobs)`;
  await refreshCampaigns();
  selectCampaign(body.id);
}

async function setUpForm() {
  const [schema, materials] = await Promise.all([getJson('/schemas/campaign'), getJson('/materials')]);
  state.materials = materials.materials.map((m) => m.name);
  for (const id of ['particle-material', 'substrate-material']) {
    const s = document.getElementById(id);
    for (const n of state.materials) s.append(el('option', { value: n, text: n }));
  }
  buildFields(schema, schema, '', document.getElementById('schema-fields'));
  document.getElementById('scene-template').addEventListener('change', applyTemplate);
  for (const id of ['particle-material', 'substrate-material', 'particle-radius']) {
    document.getElementById(id).addEventListener('change', () => {
      document.getElementById('base-scene').value =
        JSON.stringify(TEMPLATES.particle_impact(), null, 2);
    });
  }
  applyTemplate();
  document.getElementById('new-campaign').addEventListener('submit', submitCampaign);
}

// ------------------------------------------------------- campaign detail --
async function selectCampaign(id) {
  state.selected = id;
  state.selectedState = null;
  document.getElementById('campaign-detail').hidden = false;
  document.getElementById('job-detail').hidden = true;
  for (const tr of document.querySelectorAll('#campaigns tbody tr')) {
    tr.classList.toggle('selected', Number(tr.getAttribute('data-id')) === id);
  }
  await refreshDetail();
}

async function allJobs(id) {
  const jobs = [];
  let token = null;
  do {
    const page = await getJson(`/campaigns/${id}/jobs?page_size=500` + (token ? `&page_token=${token}` : ''));
    jobs.push(...page.jobs);
    token = page.next_page_token;
  } while (token);
  return jobs;
}

async function refreshDetail() {
  const id = state.selected;
  if (id === null) return;
  const [c, w, jobs] = await Promise.all([getJson(`/campaigns/${id}`), getJson(`/campaigns/${id}/windows`), allJobs(id)]);
  if (id !== state.selected) return;
  state.selectedState = c.state;
  state.windows = w.windows;
  state.jobs = jobs;
  document.getElementById('detail-title').textContent = `Campaign ${c.id}: ${c.name}`;
  const j = c.jobs;
  document.getElementById('detail-summary').textContent =
    `${c.state}; ${j.total} jobs: ${j.succeeded} succeeded, ${j.failed} failed, ${j.timed_out} timed out, ` +
    `${j.cancelled} cancelled, ${j.running} running, ${j.queued} queued; ${c.refinement_jobs} from refinement` +
    (c.material_pair ? `; materials ${c.material_pair}` : '') + (c.description ? ` - ${c.description}` : '');
  document.getElementById('cancel-campaign').disabled = !(c.state === 'active');
  document.getElementById('csv-link').href = `${API}/campaigns/${id}/windows?format=csv`;
  renderWindows();
  renderMapAxisChoice();
  renderMap();
}

function edgeText(v, bracket) {
  if (!bracket) return '-';
  if (v === null) return bracket.rebound_velocity === null ? 'open' : '-';
  const lo = Math.min(bracket.rebound_velocity, bracket.stick_velocity);
  const hi = Math.max(bracket.rebound_velocity, bracket.stick_velocity);
  return `${fmt(v)} [${fmt(lo)}, ${fmt(hi)}]`;
}

function renderWindows() {
  const tbody = document.querySelector('#windows tbody');
  tbody.replaceChildren();
  for (const w of state.windows) {
    const params = Object.keys(w.params).length ? JSON.stringify(w.params) : '(base scene)';
    tbody.append(el('tr', {},
      el('td', { text: params }),
      el('td', { text: edgeText(w.critical_velocity, w.critical_bracket) }),
      el('td', { text: edgeText(w.maximum_velocity, w.maximum_bracket) }),
      el('td', { text: w.intervals.length }),
      el('td', { text: `${w.sticks} / ${w.rebounds} / ${w.unclassified.length}` })));
  }
}

function paramAxes() {
  const keys = new Set();
  for (const j of state.jobs) for (const k of Object.keys(j.params)) keys.add(k);
  return [...keys];
}

function renderMapAxisChoice() {
  const s = document.getElementById('map-axis');
  const current = s.value;
  const axes = paramAxes();
  s.replaceChildren(...axes.map((a) => el('option', { value: a, text: a })));
  if (!axes.length) s.append(el('option', { value: '', text: '(no parameter axis)' }));
  if (axes.includes(current)) s.value = current;
}

function yOf(params, axis) {
  const v = axis ? params[axis] : 0;
  return typeof v === 'number' ? v : 0;
}

function renderMap() {
  const axis = document.getElementById('map-axis').value;
  const groups = { stick: [], rebound: [], other: [] };
  for (const j of state.jobs) {
    const kind = j.state === 'succeeded' && (j.outcome === 'stick' || j.outcome === 'rebound') ? j.outcome : 'other';
    groups[kind].push({ x: j.velocity, y: yOf(j.params, axis), job: j });
  }
  const edges = [];
  for (const w of state.windows) {
    for (const iv of w.intervals) {
      for (const e of [iv.lower, iv.upper]) {
        if (e && e.estimate !== null) edges.push({ x: e.estimate, y: yOf(w.params, axis) });
      }
    }
  }
  const datasets = [
    { label: 'stick', data: groups.stick, backgroundColor: '#2a9d4b', pointRadius: 5 },
    { label: 'rebound', data: groups.rebound, backgroundColor: '#d33', pointRadius: 5 },
    { label: 'other', data: groups.other, backgroundColor: '#999', pointRadius: 5 },
    { label: 'window edge', data: edges, pointStyle: 'line', rotation: 90, pointRadius: 12,
      borderColor: '#000', borderWidth: 3, backgroundColor: '#000' },
  ];
  const chart = state.charts.map;
  if (chart) {
    chart.data.datasets = datasets;
    chart.options.scales.y.title.text = axis || '-';
    chart.update('none');
    return;
  }
  state.charts.map = new Chart(document.getElementById('map'), {
    type: 'scatter',
    data: { datasets },
    options: {
      animation: false,
      maintainAspectRatio: false,
      scales: {
        x: { title: { display: true, text: 'impact velocity (m/s)' } },
        y: { title: { display: true, text: axis || '-' } },
      },
      // The chart's current data, not this first call's: refreshes replace it.
      onClick: (ev, elements, chart) => {
        const hit = elements.find((e) => e.datasetIndex < 3);
        const point = hit && chart.data.datasets[hit.datasetIndex].data[hit.index];
        if (point && point.job) showJob(point.job.id);
      },
      plugins: {
        tooltip: {
          callbacks: {
            label: (ctx) => {
              const j = ctx.raw.job;
              return j ? `${fmt(j.velocity)} m/s: ${j.outcome || j.state}` : `edge ${fmt(ctx.raw.x)} m/s`;
            },
          },
        },
      },
    },
  });
}

// Charts of a job's histories, one per unit: velocities (m/s), energies (J),
// bonded area (m^2).
const HISTORY_CHARTS = [
  { canvas: 'chart-velocity', unit: 'm/s', title: 'velocities (m/s)' },
  { canvas: 'chart-energy', unit: 'J', title: 'energies (J)' },
  { canvas: 'chart-area', unit: 'm^2', title: 'bonded area (m^2)' },
];
const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#17becf', '#7f7f7f'];

async function showJob(id) {
  const job = await getJson(`/jobs/${id}`);
  document.getElementById('job-detail').hidden = false;
  const use = job.uses.find((u) => u.campaign_id === state.selected) || job.uses[0] || {};
  document.getElementById('job-title').textContent =
    `Job ${id.slice(0, 12)} at ${fmt(use.velocity)} m/s ${JSON.stringify(use.params || {})}`;
  document.getElementById('job-summary').textContent =
    `${job.state}; ${job.result ? `${job.result.outcome}: ${job.result.reason}` : job.exit_reason}; ` +
    `wall time ${seconds(job.wall_seconds)}` +
    (job.histories && job.histories.error ? `; no histories: ${job.histories.error}` : '');
  const link = document.getElementById('h5-link');
  link.hidden = !job.links.result_h5;
  if (job.links.result_h5) link.href = job.links.result_h5;
  const h = job.histories && job.histories.columns ? job.histories : null;
  for (const spec of HISTORY_CHARTS) {
    const old = state.charts[spec.canvas];
    if (old) old.destroy();
    const cols = h ? Object.keys(h.columns).filter((c) => c !== 'time' && h.units[c] === spec.unit) : [];
    const time = h ? h.columns.time : [];
    const datasets = cols.map((c, i) => ({
      label: c,
      data: h.columns[c].map((v, k) => ({ x: time[k], y: v })),
      borderColor: COLOURS[i % COLOURS.length],
      pointRadius: 0,
      borderWidth: 1.5,
    }));
    state.charts[spec.canvas] = new Chart(document.getElementById(spec.canvas), {
      type: 'line',
      data: { datasets },
      options: {
        animation: false,
        maintainAspectRatio: false,
        parsing: false,
        scales: { x: { type: 'linear', title: { display: true, text: 'time (s)' } } },
        plugins: { title: { display: true, text: datasets.length ? spec.title : `${spec.title}: none in this result` } },
      },
    });
  }
}

async function cancelSelected() {
  const r = await fetch(`${API}/campaigns/${state.selected}/cancel`, { method: 'POST', headers: authHeaders() });
  if (!r.ok) {
    const p = await r.json();
    alert(`${p.title}: ${p.detail}`);
  }
  await refreshCampaigns();
  await refreshDetail();
}

// ------------------------------------------------------------------ start --
async function main() {
  const token = document.getElementById('token');
  token.value = localStorage.getItem('splat-token') || '';
  token.addEventListener('change', () => localStorage.setItem('splat-token', token.value));
  document.getElementById('map-axis').addEventListener('change', renderMap);
  document.getElementById('cancel-campaign').addEventListener('click', cancelSelected);
  await setUpForm();
  await refreshCampaigns();
  setInterval(refreshCampaigns, 1000);
  setInterval(() => {
    if (state.selected !== null && state.selectedState === 'active') refreshDetail();
  }, 1500);
}

main();
