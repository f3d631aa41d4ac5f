// The splat dashboard. Talks only to /api/v1 of the server that serves it.
// - Campaign list: polled every second (the browser revalidates with ETags).
// - New-campaign form: built from GET /api/v1/schemas/campaign; every field
//   shows its unit from the schema's `unit` keyword; empty fields are left out
//   so the server's defaults apply; errors come back as problem documents
//   whose JSON pointers are listed next to the form.
// - Campaign detail: window table, CSV download, stick/rebound map (Chart.js
//   scatter), per resolution ladder a map with one row per level and the edges
//   with their error from resolution, the window-of-deposition chart (critical
//   and maximum velocity against a second swept field), and per job its model,
//   resolution and histories grouped by unit (velocities, energies, area).
'use strict';

const API = '/api/v1';
const state = {
  selected: null,      // campaign id shown in the detail section
  selectedState: null, // its last known state
  campaigns: [],
  jobs: [],
  windows: [],
  ladders: [],         // resolution ladders of the selected campaign
  axisUnits: {},       // parameter axis name -> unit (campaign schema, spec's fields)
  campaignSchema: null,
  charts: {},
  series: {},          // history chart canvas -> the columns shown
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

// Numbers with their unit for ticks, tables and tooltips: SI prefixes on units
// that take one (1e-8 s -> "10 ns", 8.9e-6 J -> "8.9 µJ"), areas in mm^2 or
// µm^2, fixed precision on the rest (m/s, K, %, -), exponents only outside
// 1e-3..1e6 there.
const SI_PREFIXES = [[1e12, 'T'], [1e9, 'G'], [1e6, 'M'], [1e3, 'k'], [1, ''], [1e-3, 'm'],
  [1e-6, 'µ'], [1e-9, 'n'], [1e-12, 'p'], [1e-15, 'f']];
const PLAIN_UNITS = new Set(['', '-', 'm/s', 'K', '%', '1/s', 'm^3', 'J/m^2']);

function withUnit(s, unit) {
  return unit && unit !== '-' ? `${s} ${unit}` : s;
}

// `ref` picks the prefix (an axis's largest tick, so its ticks share one).
function siFormat(v, unit = '', digits = 3, ref = v) {
  if (v === null || v === undefined || !Number.isFinite(v)) return '-';
  const num = (x) => Number(x.toPrecision(digits)).toString();
  const a = Math.abs(Number.isFinite(ref) && ref !== 0 ? ref : v);
  if (a === 0) return withUnit('0', unit);
  if (unit === 'm^2') {
    const [f, u] = a >= 1e-2 ? [1, 'm^2'] : a >= 1e-7 ? [1e-6, 'mm^2'] : a >= 1e-13 ? [1e-12, 'µm^2'] : [1e-18, 'nm^2'];
    return `${num(v / f)} ${u}`;
  }
  if (PLAIN_UNITS.has(unit || '')) {
    return withUnit(a >= 1e-3 && a < 1e6 ? num(v) : Number(v.toPrecision(digits)).toExponential(), unit);
  }
  for (const [f, p] of SI_PREFIXES) {
    if (a >= f * (1 - 5e-4)) return `${num(v / f)} ${p}${unit}`;
  }
  return `${Number(v.toPrecision(digits)).toExponential()} ${unit}`;
}

// Tick labels: the unit only where a prefix changed it (the axis title has it).
function tickFormatter(unit) {
  const strip = PLAIN_UNITS.has(unit || '') && unit && unit !== '-';
  return (v, i, ticks) => {
    const ref = Math.max(...(ticks || []).map((t) => Math.abs(t.value)), 0);
    const s = siFormat(Number(v), unit, 3, ref || Number(v));
    return strip ? s.slice(0, -(unit.length + 1)) : s;
  };
}

// A parameter axis is named by its campaign key (G_c) or, for `fields`, by
// its JSON pointer; labels use the pointer's last part.
function axisShort(name) {
  return name.startsWith('/') ? name.split('/').pop() : name;
}

function axisUnit(name) {
  return state.axisUnits[name] || '';
}

function axisTitle(name) {
  const u = axisUnit(name);
  return `${axisShort(name)}${u && u !== '-' ? ` (${u})` : ''}`;
}

// Parameter set as key = value pairs with units.
function paramsText(params) {
  const keys = Object.keys(params).sort();
  if (!keys.length) return '(base scene)';
  return keys.map((k) => `${axisShort(k)} = ${typeof params[k] === 'number' ? siFormat(params[k], axisUnit(k)) :
    JSON.stringify(params[k])}`).join(', ');
}

// Same parameter set: key order does not matter.
function paramsKey(params) {
  return JSON.stringify(Object.keys(params).sort().map((k) => [k, params[k]]));
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
  // FE pinned (discretization fe: auto would switch to SPH above 500 m/s
  // within one sweep) at the resolution of scenes/impact_al_al.json, with its
  // bonding model (G_c = 30 J/m^2, thesis 3.5.3).
  particle_impact: () => {
    const p = document.getElementById('particle-material').value;
    const s = document.getElementById('substrate-material').value;
    return {
      name: 'impact',
      particle_impact: {
        particle: { material: p, radius: Number(document.getElementById('particle-radius').value),
          discretization: 'fe', elements_across: 8 },
        substrate: { material: s },
        velocity: 500,
        adhesion: { G_c: 30, sigma_c: 'flow-stress',
          activation: { rule: 'yield-drop', drop_percent: 30, sides: 'either' },
          averaging_length: 2e-6, D_adh_max: null },
      },
    };
  },
};

// The impact template's pair (scenes/impact_al_al.json's material).
const DEFAULT_MATERIAL = 'al-thesis-gf';

// Starting values of the form for the two-mass template (a small campaign).
const PREFILL = {
  two_mass: { '/name': 'two-mass-window', '/velocity/range/from': 0.1,
    '/velocity/range/to': 1.5, '/velocity/range/step': 0.1, '/G_c/values': '0.1, 0.2',
    '/job/time_limit': 60 },
  particle_impact: { '/name': 'impact-window', '/velocity/pointer': '/particle_impact/velocity',
    '/velocity/range/from': 300, '/velocity/range/to': 900, '/velocity/range/step': 100,
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
  state.campaignSchema = schema;
  state.materials = materials.materials.map((m) => m.name);
  for (const id of ['particle-material', 'substrate-material']) {
    const s = document.getElementById(id);
    for (const n of state.materials) s.append(el('option', { value: n, text: n }));
    if (state.materials.includes(DEFAULT_MATERIAL)) s.value = DEFAULT_MATERIAL;
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
  state.ladders = (w.ladders || []).filter((l) => l.campaign_id === id);
  state.jobs = jobs;
  state.axisUnits = axisUnits(c.spec || {});
  document.getElementById('detail-title').textContent = `Campaign ${c.id}: ${c.name}`;
  const j = c.jobs;
  document.getElementById('detail-summary').textContent =
    `${c.state}; ${j.total} jobs: ${j.succeeded} succeeded, ${j.failed} failed, ${j.timed_out} timed out, ` +
    `${j.cancelled} cancelled, ${j.running} running, ${j.queued} queued; ${c.refinement_jobs} from refinement` +
    (c.material_pair ? `; materials ${c.material_pair}` : '') + (c.description ? ` - ${c.description}` : '');
  const models = modelsOf(jobs);
  const m = document.getElementById('detail-models');
  m.textContent = models.length ? `${models.length > 1 ? 'Mixed models: ' : 'Model: '}` +
    models.map((x) => `${x.model}${x.resolutions.length ? ` at ${x.resolutions.join(', ')}` : ''} (${x.jobs} jobs)`)
      .join('; ') : '';
  m.classList.toggle('warning', models.length > 1);
  document.getElementById('cancel-campaign').disabled = !(c.state === 'active');
  document.getElementById('csv-link').href = `${API}/campaigns/${id}/windows?format=csv`;
  renderWindows();
  renderMapAxisChoice();
  renderMap();
  renderLadders();
  renderDepositionChoice();
  renderDeposition();
}

// A job row's resolution as text: elements_across = N or spacing = S.
function resolutionText(r) {
  if (!r) return 'no mesh';
  if (r.elements_across !== undefined) return `elements_across = ${r.elements_across}`;
  return `spacing = ${siFormat(r.spacing, 'm')}`;
}

// The models a campaign's jobs ran (or will run) with, each with its
// resolutions and number of jobs, so a sweep that changes model is seen.
function modelsOf(jobs) {
  const by = new Map();
  for (const j of jobs) {
    const name = j.model || '(scene bodies)';
    if (!by.has(name)) by.set(name, { model: name, resolutions: new Set(), jobs: 0 });
    const e = by.get(name);
    if (j.resolution) e.resolutions.add(resolutionText(j.resolution));
    e.jobs++;
  }
  return [...by.values()].map((e) => ({ ...e, resolutions: [...e.resolutions].sort((a, b) => a.localeCompare(b, 'en', { numeric: true })) }));
}

// Units of a campaign's parameter axes: the built-in ones (G_c, sigma_c, ...)
// from the campaign schema, `fields` from the spec (keyed by pointer).
function axisUnits(spec) {
  const units = {};
  const props = (state.campaignSchema && state.campaignSchema.properties) || {};
  for (const [k, v] of Object.entries(props)) {
    const values = v && v.properties && v.properties.values;
    if (values && values.unit) units[k] = values.unit;
  }
  for (const f of spec.fields || []) if (f.pointer) units[f.pointer] = f.unit;
  return units;
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
    tbody.append(el('tr', {},
      el('td', { text: paramsText(w.params), 'data-params': JSON.stringify(w.params) }),
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

// The map's second axis: one parameter axis, or one row per parameter set
// (the default when the campaign sweeps more than one axis, so sets never
// share a row).
const EACH_SET = '(each parameter set)';

function renderMapAxisChoice() {
  const s = document.getElementById('map-axis');
  const current = s.value;
  const axes = paramAxes();
  s.replaceChildren(...axes.map((a) => el('option', { value: a, text: axisTitle(a) })));
  if (axes.length > 1) s.prepend(el('option', { value: EACH_SET, text: 'one row per parameter set' }));
  if (!axes.length) s.append(el('option', { value: '', text: '(no parameter axis)' }));
  if ([...s.options].some((o) => o.value === current)) s.value = current;
  else s.selectedIndex = 0;
}

function mapSets() {
  const sets = new Map();
  for (const w of state.windows) sets.set(paramsKey(w.params), w.params);
  for (const j of state.jobs) if (!sets.has(paramsKey(j.params))) sets.set(paramsKey(j.params), j.params);
  return [...sets.entries()];
}

function renderMap() {
  const axis = document.getElementById('map-axis').value;
  const sets = axis === EACH_SET ? mapSets() : [];
  const yOf = (params) => {
    if (axis === EACH_SET) return sets.findIndex(([k]) => k === paramsKey(params));
    const v = axis ? params[axis] : 0;
    return typeof v === 'number' ? v : 0;
  };
  const groups = { stick: [], rebound: [], other: [] };
  for (const j of state.jobs) groups[outcomeKind(j)].push({ x: j.velocity, y: yOf(j.params), job: j });
  const edges = [];
  for (const w of state.windows) {
    for (const iv of w.intervals) {
      for (const e of [iv.lower, iv.upper]) {
        if (e && e.estimate !== null) edges.push({ x: e.estimate, y: yOf(w.params) });
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
  const y = axis === EACH_SET ? {
    min: -0.5, max: sets.length - 0.5,
    title: { display: true, text: 'parameter set' },
    afterBuildTicks: (scale) => { scale.ticks = sets.map((_, i) => ({ value: i })); },
    ticks: { callback: (v) => (sets[v] ? paramsText(sets[v][1]) : '') },
  } : {
    title: { display: true, text: axis ? axisTitle(axis) : '-' },
    ticks: { callback: tickFormatter(axis ? axisUnit(axis) : '') },
  };
  const old = state.charts.map;
  if (old) old.destroy();
  state.charts.map = new Chart(document.getElementById('map'), {
    type: 'scatter',
    data: { datasets },
    options: {
      animation: false,
      maintainAspectRatio: false,
      scales: {
        x: { title: { display: true, text: 'impact velocity (m/s)' }, ticks: { callback: tickFormatter('m/s') } },
        y,
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
              return j ? `${fmt(j.velocity)} m/s: ${j.outcome || j.state} (${paramsText(j.params)}; ` +
                `${j.model || 'scene bodies'}, ${resolutionText(j.resolution)})` :
                `edge ${fmt(ctx.raw.x)} m/s`;
            },
          },
        },
      },
    },
  });
}

// Shaded intervals and lines in data coordinates, drawn under the datasets:
// options.plugins.bands.items = [{x0, x1, y0, y1, fill, stroke, dash}]. The
// number drawn is kept on the chart ($bandsDrawn) for the browser test.
const bandsPlugin = {
  id: 'bands',
  beforeDatasetsDraw(chart, args, opts) {
    const { ctx, chartArea: a, scales: { x, y } } = chart;
    let drawn = 0;
    ctx.save();
    ctx.beginPath();
    ctx.rect(a.left, a.top, a.width, a.height);
    ctx.clip();
    for (const b of opts.items || []) {
      const px0 = x.getPixelForValue(b.x0);
      const px1 = x.getPixelForValue(b.x1);
      const py0 = y.getPixelForValue(b.y0);
      const py1 = y.getPixelForValue(b.y1);
      if (![px0, px1, py0, py1].every(Number.isFinite)) continue;
      if (b.fill) {
        ctx.fillStyle = b.fill;
        ctx.fillRect(Math.min(px0, px1), Math.min(py0, py1), Math.max(Math.abs(px1 - px0), 2), Math.abs(py1 - py0));
      }
      if (b.stroke) {
        ctx.strokeStyle = b.stroke;
        ctx.lineWidth = 2;
        ctx.setLineDash(b.dash || []);
        ctx.beginPath();
        ctx.moveTo(px0, py0);
        ctx.lineTo(px1, py1);
        ctx.stroke();
        ctx.setLineDash([]);
      }
      drawn++;
    }
    ctx.restore();
    chart.$bandsDrawn = drawn;
  },
};

// Vertical error bars on points that carry yMin and yMax; the number drawn is
// kept on the chart ($errorBarsDrawn).
const errorBarsPlugin = {
  id: 'errorBars',
  afterDatasetsDraw(chart) {
    const { ctx, scales: { y } } = chart;
    let drawn = 0;
    ctx.save();
    chart.data.datasets.forEach((ds, i) => {
      const meta = chart.getDatasetMeta(i);
      if (meta.hidden || !chart.isDatasetVisible(i)) return;
      ds.data.forEach((p, k) => {
        const point = meta.data[k];
        if (!point || p.yMin === undefined || p.yMax === undefined) return;
        const top = y.getPixelForValue(p.yMax);
        const bottom = y.getPixelForValue(p.yMin);
        ctx.strokeStyle = ds.borderColor;
        ctx.lineWidth = 1.5;
        ctx.beginPath();
        ctx.moveTo(point.x, top);
        ctx.lineTo(point.x, bottom);
        ctx.moveTo(point.x - 5, top);
        ctx.lineTo(point.x + 5, top);
        ctx.moveTo(point.x - 5, bottom);
        ctx.lineTo(point.x + 5, bottom);
        ctx.stroke();
        drawn++;
      });
    });
    ctx.restore();
    chart.$errorBarsDrawn = drawn;
  },
};

function outcomeKind(j) {
  return j.state === 'succeeded' && (j.outcome === 'stick' || j.outcome === 'rebound') ? j.outcome : 'other';
}

// ------------------------------------------------------ resolution ladders --
// One chart per ladder (a parameter set run at several resolutions): one row
// per level with its jobs, each edge's bracket at that level shaded, and the
// edge's estimate from all levels as a dashed line with its error band.
const EDGE_COLOURS = { critical: 'rgba(31, 95, 191, ', maximum: 'rgba(179, 38, 30, ' };

function levelLabel(l, i) {
  return `${axisShort(l.pointer)} = ${fmt(l.levels[i])}`;
}

function edgeSummary(e) {
  if (e.value === null) return `open (${e.status})`;
  return `${fmt(e.value)} ± ${fmt(e.error, 2)} m/s (${e.status}${e.order !== null ? `, order ${fmt(e.order, 2)}` : ''})`;
}

function levelEdgeText(e) {
  return e.estimate === null ? 'open' : `${fmt(e.estimate)} ± ${fmt(e.half_width, 2)}`;
}

function ladderTable(l) {
  const tbody = el('tbody');
  l.levels.forEach((v, i) => {
    const cost = l.cost[i] || { jobs: 0, job_seconds: 0 };
    tbody.append(el('tr', { 'data-level': i },
      el('td', { text: levelLabel(l, i) }),
      el('td', { text: levelEdgeText(l.critical.levels[i]) }),
      el('td', { text: levelEdgeText(l.maximum.levels[i]) }),
      el('td', { text: `${cost.jobs} jobs, ${seconds(cost.job_seconds)}` })));
  });
  tbody.append(el('tr', { class: 'estimate' },
    el('td', { text: 'estimate' }),
    el('td', { text: edgeSummary(l.critical) }),
    el('td', { text: edgeSummary(l.maximum) }),
    el('td', { text: '' })));
  return el('table', { class: 'ladder-table' },
    el('thead', {}, el('tr', {}, el('th', { text: 'level' }), el('th', { text: 'critical velocity (m/s)' }),
      el('th', { text: 'maximum velocity (m/s)' }), el('th', { text: 'cost (jobs, wall time)' }))),
    tbody);
}

function ladderJobs(l) {
  const key = paramsKey(l.params);
  const out = [];
  for (const j of state.jobs) {
    const rest = { ...j.params };
    const level = rest[l.pointer];
    delete rest[l.pointer];
    const row = l.levels.indexOf(level);
    if (row >= 0 && paramsKey(rest) === key) out.push({ job: j, row });
  }
  return out;
}

function ladderChart(canvas, l) {
  const n = l.levels.length;
  const groups = { stick: [], rebound: [], other: [] };
  for (const { job, row } of ladderJobs(l)) groups[outcomeKind(job)].push({ x: job.velocity, y: row, job });
  const marks = [];
  const items = [];
  for (const kind of ['critical', 'maximum']) {
    const e = l[kind];
    e.levels.forEach((le, i) => {
      if (le.estimate === null) return;
      marks.push({ x: le.estimate, y: i, edge: kind, level: i, half_width: le.half_width });
      items.push({ x0: le.estimate - le.half_width, x1: le.estimate + le.half_width, y0: i - 0.3, y1: i + 0.3,
        fill: `${EDGE_COLOURS[kind]}0.25)` });
    });
    if (e.value !== null) {
      items.push({ x0: e.value - e.error, x1: e.value + e.error, y0: -0.5, y1: n - 0.5, fill: `${EDGE_COLOURS[kind]}0.12)` });
      items.push({ x0: e.value, x1: e.value, y0: -0.5, y1: n - 0.5, stroke: `${EDGE_COLOURS[kind]}0.9)`, dash: [6, 4] });
    }
  }
  const xs = [...groups.stick, ...groups.rebound, ...groups.other].map((p) => p.x)
    .concat(items.flatMap((b) => [b.x0, b.x1]));
  const pad = xs.length ? Math.max(10, 0.05 * (Math.max(...xs) - Math.min(...xs))) : 10;

  const datasets = [
    { label: 'stick', data: groups.stick, backgroundColor: '#2a9d4b', pointRadius: 5 },
    { label: 'rebound', data: groups.rebound, backgroundColor: '#d33', pointRadius: 5 },
    { label: 'other', data: groups.other, backgroundColor: '#999', pointRadius: 5 },
    { label: 'edge per level (bracket shaded)', data: marks, pointStyle: 'line', rotation: 90, pointRadius: 10,
      borderColor: '#000', borderWidth: 3, backgroundColor: '#000' },
    { label: 'critical: estimate ± error', data: [], backgroundColor: `${EDGE_COLOURS.critical}0.35)`,
      borderColor: `${EDGE_COLOURS.critical}0.9)` },
    { label: 'maximum: estimate ± error', data: [], backgroundColor: `${EDGE_COLOURS.maximum}0.35)`,
      borderColor: `${EDGE_COLOURS.maximum}0.9)` },
  ];
  return new Chart(canvas, {
    type: 'scatter',
    data: { datasets },
    plugins: [bandsPlugin],
    options: {
      animation: false,
      maintainAspectRatio: false,
      scales: {
        x: { title: { display: true, text: 'impact velocity (m/s)' }, ticks: { callback: tickFormatter('m/s') },
          min: xs.length ? 50 * Math.floor((Math.min(...xs) - pad) / 50) : undefined,
          max: xs.length ? 50 * Math.ceil((Math.max(...xs) + pad) / 50) : undefined },
        y: { min: -0.5, max: n - 0.5, title: { display: true, text: `resolution level (${axisShort(l.pointer)})` },
          afterBuildTicks: (scale) => { scale.ticks = l.levels.map((_, i) => ({ value: i })); },
          ticks: { callback: (v) => (l.levels[v] !== undefined ? levelLabel(l, v) : '') } },
      },
      onClick: (ev, elements, chart) => {
        const hit = elements.find((e) => e.datasetIndex < 3);
        const point = hit && chart.data.datasets[hit.datasetIndex].data[hit.index];
        if (point && point.job) showJob(point.job.id);
      },
      plugins: {
        bands: { items },
        tooltip: {
          callbacks: {
            label: (ctx) => {
              const r = ctx.raw;
              if (r.job) {
                return `${fmt(r.job.velocity)} m/s, ${levelLabel(l, r.y)}: ${r.job.outcome || r.job.state} ` +
                  `(${r.job.model || 'scene bodies'})`;
              }
              return `${r.edge} velocity at ${levelLabel(l, r.level)}: ${fmt(r.x)} ± ${fmt(r.half_width, 2)} m/s`;
            },
          },
        },
      },
    },
  });
}

function renderLadders() {
  const box = document.getElementById('ladders');
  for (const k of Object.keys(state.charts)) {
    if (k.startsWith('ladder-')) {
      state.charts[k].destroy();
      delete state.charts[k];
    }
  }
  box.replaceChildren();
  document.getElementById('ladders-note').textContent = state.ladders.length ?
    'Per parameter set, one row per resolution level: its jobs, each edge at that level (bracket midpoint, ' +
    'bracket shaded) and the edge estimated from all levels (dashed) with its error from resolution (band).' :
    'This campaign has no resolution ladder (sweep /particle_impact/particle/elements_across over two or ' +
    'more values in `fields` for one).';
  state.ladders.forEach((l, i) => {
    const canvas = el('canvas', { id: `ladder-${i}` });
    box.append(el('div', { class: 'ladder', 'data-levels': l.levels.length },
      el('h4', { text: paramsText(l.params) }), ladderTable(l),
      el('div', { class: 'chart-box ladder-box' }, canvas)));
    state.charts[`ladder-${i}`] = ladderChart(canvas, l);
  });
}

// ------------------------------------------------- window of deposition --
// Critical and maximum velocity against a second swept field, the window
// shaded between them. Edges with an error from resolution where the campaign
// has ladders, else the bracket midpoints with half the bracket as error; an
// open edge is drawn at its outermost stick (triangle) without an error bar.

// A ladder's edge: its estimate and error from resolution, or, where the
// ladder has none (the edge is open at some level), the finest level's.
function ladderEdge(l, kind) {
  const e = l[kind];
  if (e.value !== null) return { y: e.value, err: e.error, status: e.status };
  const finest = { ...l.params, [l.pointer]: l.levels[l.levels.length - 1] };
  const w = state.windows.find((x) => paramsKey(x.params) === paramsKey(finest));
  const edge = w ? windowEdge(w[`${kind}_velocity`], w[`${kind}_bracket`]) : null;
  return edge && { ...edge, status: `${edge.status} at ${levelLabel(l, l.levels.length - 1)}` };
}

function windowEdge(v, b) {
  if (!b) return null;
  if (v !== null) return { y: v, err: b.width === null || b.width === undefined ? null : b.width / 2, status: 'bracket' };
  if (b.rebound_velocity === null) return { y: b.stick_velocity, err: null, status: 'open' };
  return null;
}

function depositionRows() {
  const resolution = new Set(state.ladders.map((l) => l.pointer));
  const inLadder = new Set();
  const rows = state.ladders.map((l) => ({ params: l.params, critical: ladderEdge(l, 'critical'), maximum: ladderEdge(l, 'maximum') }));
  for (const l of state.ladders) {
    for (const v of l.levels) inLadder.add(paramsKey({ ...l.params, [l.pointer]: v }));
  }
  for (const w of state.windows) {
    if (inLadder.has(paramsKey(w.params))) continue;
    const params = { ...w.params };
    for (const p of resolution) delete params[p];
    rows.push({ params, critical: windowEdge(w.critical_velocity, w.critical_bracket),
      maximum: windowEdge(w.maximum_velocity, w.maximum_bracket) });
  }
  return rows;
}

// Swept fields: numeric parameters with two or more values.
function sweptFields(rows) {
  const values = {};
  for (const r of rows) {
    for (const [k, v] of Object.entries(r.params)) {
      if (typeof v !== 'number') continue;
      (values[k] = values[k] || new Set()).add(v);
    }
  }
  return Object.keys(values).filter((k) => values[k].size > 1).sort();
}

function renderDepositionChoice() {
  const rows = depositionRows();
  const fields = sweptFields(rows);
  const s = document.getElementById('deposition-field');
  const current = s.value;
  s.replaceChildren(...fields.map((f) => el('option', { value: f, text: axisTitle(f) })));
  if (fields.includes(current)) s.value = current;
  renderDepositionOther(rows);
}

// The other parameters (all but the chosen field): one group shown at a time.
function depositionGroups(rows, field) {
  const groups = new Map();
  for (const r of rows) {
    if (typeof r.params[field] !== 'number') continue;
    const rest = { ...r.params };
    delete rest[field];
    const key = paramsKey(rest);
    if (!groups.has(key)) groups.set(key, { rest, rows: [] });
    groups.get(key).rows.push(r);
  }
  return [...groups.entries()];
}

function renderDepositionOther(rows) {
  const field = document.getElementById('deposition-field').value;
  const s = document.getElementById('deposition-other');
  const current = s.value;
  const groups = field ? depositionGroups(rows, field) : [];
  s.replaceChildren(...groups.map(([k, g]) => el('option', { value: k, text: paramsText(g.rest) })));
  if (groups.some(([k]) => k === current)) s.value = current;
  document.getElementById('deposition-other-label').hidden = groups.length < 2;
}

function renderDeposition() {
  const old = state.charts.deposition;
  if (old) old.destroy();
  delete state.charts.deposition;
  const rows = depositionRows();
  const field = document.getElementById('deposition-field').value;
  const note = document.getElementById('deposition-note');
  const box = document.getElementById('deposition-box');
  document.getElementById('deposition-controls').hidden = !field;
  if (!field) {
    box.hidden = true;
    note.textContent = 'No window-of-deposition chart: this campaign sweeps no field besides the velocity' +
      (state.ladders.length ? ' and the resolution' : '') +
      ' (add a second one, e.g. /particle_impact/particle/radius, to see the window against it).';
    return;
  }
  const groups = depositionGroups(rows, field);
  const chosen = groups.find(([k]) => k === document.getElementById('deposition-other').value) || groups[0];
  const points = (kind) => chosen[1].rows.filter((r) => r[kind]).map((r) => {
    const e = r[kind];
    const p = { x: r.params[field], y: e.y, status: e.status, err: e.err };
    if (e.err !== null && e.err !== undefined) Object.assign(p, { yMin: e.y - e.err, yMax: e.y + e.err });
    return p;
  }).sort((a, b) => a.x - b.x);
  const style = (data) => data.map((p) => (p.status.startsWith('open') ? 'triangle' : 'circle'));
  const critical = points('critical');
  const maximum = points('maximum');
  const bounds = [...critical, ...maximum].flatMap((p) => [p.y, p.yMin ?? p.y, p.yMax ?? p.y]);
  box.hidden = false;
  note.textContent = (state.ladders.length ?
    'Error bars: each edge\'s error from resolution (the ladders above).' :
    'Error bars: half the bracket between the nearest stick and rebound.') +
    ' Triangles: open edges (the outermost stick; the window reaches at least that far).';
  const unit = axisUnit(field);
  state.charts.deposition = new Chart(document.getElementById('deposition'), {
    type: 'line',
    data: {
      datasets: [
        { label: 'critical velocity', data: critical, borderColor: EDGE_COLOURS.critical + '1)',
          backgroundColor: EDGE_COLOURS.critical + '1)', pointStyle: style(critical), pointRadius: 5, fill: false },
        { label: 'maximum velocity (deposition window shaded)', data: maximum, borderColor: EDGE_COLOURS.maximum + '1)',
          backgroundColor: 'rgba(42, 157, 75, 0.2)', pointBackgroundColor: EDGE_COLOURS.maximum + '1)',
          pointStyle: style(maximum), pointRadius: 5, fill: '-1' },
      ],
    },
    plugins: [errorBarsPlugin],
    options: {
      animation: false,
      maintainAspectRatio: false,
      parsing: false,
      scales: {
        x: { type: 'linear', title: { display: true, text: axisTitle(field) }, ticks: { callback: tickFormatter(unit) } },
        // Room for the error bars.
        y: { title: { display: true, text: 'impact velocity (m/s)' }, ticks: { callback: tickFormatter('m/s') },
          suggestedMin: bounds.length ? Math.min(...bounds) : undefined,
          suggestedMax: bounds.length ? Math.max(...bounds) : undefined },
      },
      plugins: {
        tooltip: {
          callbacks: {
            label: (ctx) => {
              const p = ctx.raw;
              return `${ctx.dataset.label.split(' (')[0]} at ${axisShort(field)} = ${siFormat(p.x, unit)}: ` +
                `${fmt(p.y)} m/s` + (p.err !== null && p.err !== undefined ? ` ± ${fmt(p.err, 2)}` : '') + ` (${p.status})`;
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
  { canvas: 'chart-velocity', unit: 'm/s', title: 'velocities' },
  { canvas: 'chart-energy', unit: 'J', title: 'energies' },
  { canvas: 'chart-area', unit: 'm^2', title: 'bonded area' },
];
const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#17becf', '#7f7f7f'];

// The model (fidelity) and resolution a job ran with, and why that model:
// the expanded scene's particle_impact.model (or the result summary's), and
// the discretization of its particle body: elements across the radius (FE)
// or the particle spacing (SPH).
function modelText(job) {
  const scene = job.scene || {};
  const summary = job.result && job.result.summary ? job.result.summary : {};
  const pi = scene.particle_impact;
  const model = (pi && pi.model) || summary.model || null;
  if (!model) {
    return scene.two_mass ? 'model two-mass (two rigid masses joined by the adhesive link, thesis 3.5.1.1); ' +
      'resolution: none (no mesh)' : 'model: the bodies the scene lists (not a particle_impact scene)';
  }
  const particle = (scene.bodies || []).find((b) => b.name === 'particle');
  const d = particle && particle.discretization ? particle.discretization : null;
  const radius = particle && particle.geometry ? particle.geometry.radius : undefined;
  let resolution = 'none (rigid masses)';
  if (d && d.elements_across !== undefined) resolution = `elements_across = ${d.elements_across}`;
  else if (d && d.element_size !== undefined) {
    resolution = `spacing = ${siFormat(d.element_size, 'm')}` +
      (radius ? ` (${fmt(radius / d.element_size, 3)} across the radius)` : '');
  }
  const asked = pi && pi.fidelity ? pi.fidelity : 'auto';
  return `model ${model.name} (fidelity asked: ${asked}); resolution ${resolution}` +
    (model.why ? `; why: ${model.why}` : '');
}

// Time on the axis in the prefix that suits the run (ns for impacts).
function timeScale(time) {
  const t = Math.max(...time.filter(Number.isFinite).map(Math.abs), 0);
  for (const [f, p] of [[1e-9, 'n'], [1e-6, 'µ'], [1e-3, 'm']]) if (t > 0 && t < f * 1e4) return { f, unit: `${p}s` };
  return { f: 1, unit: 's' };
}

// At most MAX_SERIES lines per chart (a readable legend): the user picks
// which in the list under the chart; the first DEFAULT_SERIES are shown.
const MAX_SERIES = 8;
const DEFAULT_SERIES = 6;
// Shown first by default: the particle's motion and the main energies.
const PREFERRED_SERIES = ['v_M', 'v_m', 'particle_vz', 'substrate_vz', 'kinetic', 'internal', 'plastic_work',
  'adhesion', 'contact_work', 'hourglass', 'balance_error'];
const seriesRank = (c) => (PREFERRED_SERIES.includes(c) ? PREFERRED_SERIES.indexOf(c) : PREFERRED_SERIES.length);

function drawHistoryChart(spec, h) {
  const old = state.charts[spec.canvas];
  if (old) old.destroy();
  const cols = h ? Object.keys(h.columns).filter((c) => c !== 'time' && h.units[c] === spec.unit)
    .sort((a, b) => seriesRank(a) - seriesRank(b) || a.localeCompare(b)) : [];
  // A choice holds while the columns are the same (jobs of one kind).
  const key = cols.join(',');
  if (!state.series[spec.canvas] || state.series[spec.canvas].key !== key) {
    state.series[spec.canvas] = { key, chosen: cols.slice(0, DEFAULT_SERIES) };
  }
  const chosen = state.series[spec.canvas].chosen;
  const time = h ? h.columns.time : [];
  const ts = timeScale(time);
  const datasets = cols.filter((c) => chosen.includes(c)).map((c, i) => ({
    label: c,
    data: h.columns[c].map((v, k) => ({ x: time[k] / ts.f, y: v })),
    borderColor: COLOURS[i % COLOURS.length],
    backgroundColor: COLOURS[i % COLOURS.length],
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
      scales: {
        x: { type: 'linear', title: { display: true, text: `time (${ts.unit})` }, ticks: { callback: tickFormatter('-') } },
        y: { title: { display: true, text: spec.unit }, ticks: { callback: tickFormatter(spec.unit) } },
      },
      plugins: {
        title: { display: true, text: datasets.length ? spec.title : `${spec.title}: none in this result` },
        tooltip: { callbacks: { label: (ctx) => `${ctx.dataset.label}: ${siFormat(ctx.raw.y, spec.unit)}` } },
      },
    },
  });
  const details = document.getElementById(`series-${spec.canvas}`);
  const open = details.open;
  details.replaceChildren(el('summary', { text: `series: ${datasets.length} of ${cols.length} shown (at most ${MAX_SERIES})` }));
  details.hidden = cols.length <= datasets.length && cols.length <= DEFAULT_SERIES;
  details.open = open;
  for (const c of cols) {
    const box = el('input', { type: 'checkbox', value: c });
    box.checked = chosen.includes(c);
    box.disabled = !box.checked && chosen.length >= MAX_SERIES;
    box.addEventListener('change', () => {
      const list = state.series[spec.canvas].chosen;
      if (box.checked) list.push(c);
      else list.splice(list.indexOf(c), 1);
      if (!list.length) list.push(c === cols[0] ? cols[1] : cols[0]);
      drawHistoryChart(spec, h);
    });
    details.append(el('label', {}, box, ` ${c}`));
  }
}

async function showJob(id) {
  const job = await getJson(`/jobs/${id}`);
  document.getElementById('job-detail').hidden = false;
  const use = job.uses.find((u) => u.campaign_id === state.selected) || job.uses[0] || {};
  document.getElementById('job-title').textContent =
    `Job ${id.slice(0, 12)} at ${fmt(use.velocity)} m/s, ${paramsText(use.params || {})}`;
  document.getElementById('job-model').textContent = modelText(job);
  document.getElementById('job-summary').textContent =
    `${job.state}; ${job.result ? `${job.result.outcome}: ${job.result.reason}` : job.exit_reason}; ` +
    `wall time ${seconds(job.wall_seconds)}` +
    (job.histories && job.histories.error ? `; no histories: ${job.histories.error}` : '');
  const link = document.getElementById('h5-link');
  link.hidden = !job.links.result_h5;
  if (job.links.result_h5) link.href = job.links.result_h5;
  const h = job.histories && job.histories.columns ? job.histories : null;
  for (const spec of HISTORY_CHARTS) drawHistoryChart(spec, h);
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
  document.getElementById('deposition-field').addEventListener('change', () => {
    renderDepositionOther(depositionRows());
    renderDeposition();
  });
  document.getElementById('deposition-other').addEventListener('change', renderDeposition);
  document.getElementById('cancel-campaign').addEventListener('click', cancelSelected);
  await setUpForm();
  await refreshCampaigns();
  setInterval(refreshCampaigns, 1000);
  setInterval(() => {
    if (state.selected !== null && state.selectedState === 'active') refreshDetail();
  }, 1500);
}

main();
