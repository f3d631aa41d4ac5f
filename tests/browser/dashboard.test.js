// Browser test of the dashboard (ctest label `browser`): starts a real
// `splat serve` on a port the OS picks over a fresh SQLite file, drives
// Debian's headless Chromium through playwright-core (from web/node_modules,
// `npm ci`), submits a small two-mass campaign through the form generated
// from the campaign schema, waits for it to finish, checks the window table
// against the closed-form edges, checks that the stick/rebound map, a job's
// model and history charts and the window-of-deposition chart rendered (ticks
// readable, legends of at most 8 entries); submits the particle-impact
// template as shipped (accepted, then cancelled); runs a small FE resolution
// ladder and checks its per-level maps and window-of-deposition chart against
// the API's ladders; saves screenshots (dashboard.png, dashboard-ladder.png)
// as test artifacts.
// Every request the page makes must go to the server itself (no network).
//   node dashboard.test.js --splat BUILD/app/splat --web WEB_DIR --out ARTIFACT_DIR
'use strict';

const { spawn } = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');
const { createRequire } = require('module');

function arg(name) {
  const i = process.argv.indexOf(`--${name}`);
  if (i < 0 || i + 1 >= process.argv.length) throw new Error(`missing --${name}`);
  return process.argv[i + 1];
}

function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exitCode = 1;
  throw new Error(message);
}

function check(cond, message) {
  if (!cond) fail(message);
  console.log(`ok: ${message}`);
}

const splat = arg('splat');
const webDir = path.resolve(arg('web'));
const outDir = path.resolve(arg('out'));
const chromiumPath = process.env.SPLAT_CHROMIUM || '/usr/bin/chromium';

if (!fs.existsSync(path.join(webDir, 'node_modules', 'playwright-core'))) {
  fail(`no ${webDir}/node_modules: run \`npm ci\` in web/ (scripts/test.sh does)`);
}
if (!fs.existsSync(chromiumPath)) fail(`no ${chromiumPath}: apt-get install chromium (scripts/test.sh does)`);
const { chromium } = createRequire(path.join(webDir, 'package.json'))('playwright-core');

// Closed-form edge of the two-mass problem with k = 0: V0* = sqrt(2 G_c A (M + m) / (M m)).
const edge = (G_c) => Math.sqrt((2 * G_c * 1.0 * 3.0) / 2.0);

// The ladder campaign: FE axisymmetric Al/Al at 4, 6 and 8 elements across
// the radius, two particle radii, 800-1400 m/s; about 60 jobs of 0.1-2 s,
// some 20 s on 2 cores.
const LADDER = {
  from: '800', to: '1400', step: '100', tolerance: '25', extra: '24',
  fields: [
    { pointer: '/particle_impact/particle/elements_across', unit: '-', values: [4, 6, 8] },
    { pointer: '/particle_impact/particle/radius', unit: 'm', values: [1e-5, 1.5e-5] },
  ],
};

function startServer(db) {
  return new Promise((resolve, reject) => {
    const child = spawn(splat, ['serve', '--db', db, '--port', '0', '--workers', '2', '--web-dir', webDir],
      { stdio: ['ignore', 'pipe', 'inherit'] });
    let buf = '';
    const timer = setTimeout(() => reject(new Error('server did not start in 20 s')), 20000);
    child.stdout.on('data', (d) => {
      buf += d;
      const m = buf.match(/listening on (http:\/\/[^\s]+)/);
      if (m) {
        clearTimeout(timer);
        resolve({ child, url: m[1] });
      }
    });
    child.on('exit', (code) => reject(new Error(`server exited with ${code}`)));
  });
}

async function submitted(page) {
  await page.click('#submit-campaign');
  await page.waitForFunction(() => /accepted|:/.test(document.getElementById('submit-result').textContent),
    null, { timeout: 15000 });
  const text = await page.textContent('#submit-result');
  const errors = await page.$$eval('#form-errors li', (lis) => lis.map((li) => li.textContent));
  const m = text.match(/campaign (\d+) accepted \((\d+) jobs\)/);
  if (!m) fail(`campaign refused: ${text} ${errors.join('; ')}`);
  return { id: Number(m[1]), jobs: Number(m[2]) };
}

async function waitState(page, id, wanted, timeout) {
  await page.waitForFunction(([i, w]) => {
    const row = document.querySelector(`#campaigns tbody tr[data-id="${i}"]`);
    return row && w.includes(row.querySelector('.state').textContent) &&
      document.getElementById('detail-title').textContent.startsWith(`Campaign ${i}:`) &&
      new RegExp(`^(${w.join('|')})`).test(document.getElementById('detail-summary').textContent);
  }, [id, wanted], { timeout, polling: 250 });
}

// The Chart.js instances' axis ticks: at most 5 significant digits (not
// 1.00000000E-8), and legends of at most 8 entries.
async function checkReadableCharts(page, ids) {
  const charts = await page.evaluate((list) => list.map((id) => {
    const c = Chart.getChart(id);
    if (!c) return { id, missing: true };
    const ticks = Object.values(c.scales).flatMap((s) => s.ticks.map((t) => String(t.label)));
    const legend = c.legend && c.legend.legendItems ? c.legend.legendItems.length : 0;
    const titles = Object.values(c.scales).map((s) => (s.options.title && s.options.title.text) || '');
    return { id, ticks, legend, titles };
  }), ids);
  for (const c of charts) {
    if (c.missing) continue;
    const bad = c.ticks.filter((t) => t.replace(/e[-+]?\d+/i, '').replace(/[^0-9]/g, '').length > 5);
    check(bad.length === 0, `${c.id}: readable ticks (${c.ticks.slice(0, 4).join(' | ')}${bad.length ? `; bad: ${bad.join(' | ')}` : ''})`);
    check(c.legend <= 8, `${c.id}: legend of ${c.legend} entries (at most 8)`);
  }
}

async function depositionState(page) {
  return page.evaluate(() => {
    const c = Chart.getChart('deposition');
    const box = document.getElementById('deposition-box');
    if (!c || box.hidden) return { hidden: true, note: document.getElementById('deposition-note').textContent };
    return {
      hidden: false,
      field: document.getElementById('deposition-field').value,
      counts: c.data.datasets.map((d) => d.data.length),
      critical: c.data.datasets[0].data.map((p) => ({ x: p.x, y: p.y, err: p.err })),
      maximum: c.data.datasets[1].data.map((p) => ({ x: p.x, y: p.y, err: p.err })),
      fill: c.data.datasets[1].fill,
      errorBars: c.$errorBarsDrawn,
    };
  });
}

// The impact template, submitted exactly as the page fills it in, is
// accepted; the campaign is then cancelled (its jobs are not what this test
// is about), and the page says it has no second swept field.
async function impactTemplateAsShipped(page) {
  await page.selectOption('#scene-template', 'particle_impact');
  const { id, jobs } = await submitted(page);
  check(jobs > 0, `impact template accepted as shipped (campaign ${id}, ${jobs} jobs)`);
  const scene = JSON.parse(await page.inputValue('#base-scene'));
  check(scene.particle_impact.particle.discretization === 'fe' && scene.particle_impact.particle.elements_across > 0,
    'impact template names its model and resolution');
  await page.waitForFunction((i) => document.getElementById('detail-title').textContent.startsWith(`Campaign ${i}:`),
    id, { timeout: 15000 });
  await page.click('#cancel-campaign');
  await waitState(page, id, ['cancelled', 'finished'], 60000);
  check(true, `impact template campaign ${id} cancelled`);
  const dep = await depositionState(page);
  check(dep.hidden && /sweeps no field besides the velocity/.test(dep.note),
    `no second swept field: the page says so instead of an empty chart (${dep.note})`);
}

// A small resolution ladder (LADDER). Checks the per-level maps
// (one per radius, one row per level, every job of the level on its row, the
// edges per level and the estimates drawn) and the window-of-deposition chart
// against the radius (one critical and one maximum point per radius, error
// bars from the ladder), then a job's model and resolution.
async function ladderCampaign(page, url) {
  await page.selectOption('#scene-template', 'particle_impact');
  await page.fill('[data-pointer="/name"]', 'browser-ladder');
  await page.fill('[data-pointer="/velocity/range/from"]', LADDER.from);
  await page.fill('[data-pointer="/velocity/range/to"]', LADDER.to);
  await page.fill('[data-pointer="/velocity/range/step"]', LADDER.step);
  await page.fill('[data-pointer="/fields"]', JSON.stringify(LADDER.fields));
  await page.fill('[data-pointer="/refinement/tolerance"]', LADDER.tolerance);
  await page.fill('[data-pointer="/refinement/max_extra_jobs"]', LADDER.extra);
  const started = Date.now();
  const { id } = await submitted(page);
  check(true, `ladder campaign ${id} accepted through the form`);
  await page.waitForFunction((i) => document.getElementById('detail-title').textContent.startsWith(`Campaign ${i}:`),
    id, { timeout: 15000 });
  await waitState(page, id, ['finished'], 120000);
  console.log(`ladder campaign finished in ${((Date.now() - started) / 1000).toFixed(1)} s`);
  const api = await page.evaluate(async (i) => {
    const w = await (await fetch(`/api/v1/campaigns/${i}/windows`)).json();
    const jobs = await (await fetch(`/api/v1/campaigns/${i}/jobs?page_size=500`)).json();
    return { ladders: w.ladders, windows: w.windows, jobs: jobs.jobs };
  }, id);
  const levels = LADDER.fields[0].values;
  const radii = LADDER.fields[1].values;
  const models = await page.textContent('#detail-models');
  check(models === `Model: fe-axisym at ${levels.map((n) => `elements_across = ${n}`).join(', ')} (${api.jobs.length} jobs)`,
    `campaign names its model and resolutions: ${models}`);
  check(api.ladders.length === radii.length, `API: one ladder per radius (${api.ladders.length})`);

  // Two swept axes: the stick/rebound map gives each parameter set its row.
  const sets = await page.evaluate(() => ({
    axis: document.getElementById('map-axis').value,
    rows: Chart.getChart('map').scales.y.ticks.map((t) => t.label),
  }));
  check(sets.axis === '(each parameter set)' && sets.rows.length === levels.length * radii.length &&
    sets.rows.every((r) => /^elements_across = \d, radius = 1[05] µm$/.test(r)),
  `map: one row per parameter set (${sets.rows.join(' | ')})`);

  // The per-level maps, read from the DOM and the Chart.js instances.
  const maps = await page.evaluate(() => [...document.querySelectorAll('#ladders .ladder')].map((d) => {
    const canvas = d.querySelector('canvas');
    const c = Chart.getChart(canvas);
    const ds = c.data.datasets;
    const rows = new Set(ds.slice(0, 3).flatMap((x) => x.data.map((p) => p.y)));
    return {
      title: d.querySelector('h4').textContent,
      levels: Number(d.getAttribute('data-levels')),
      tableRows: d.querySelectorAll('tbody tr[data-level]').length,
      yTicks: c.scales.y.ticks.map((t) => t.label),
      xTitle: c.options.scales.x.title.text,
      jobs: ds.slice(0, 3).reduce((n, x) => n + x.data.length, 0),
      rows: rows.size,
      edgeMarks: ds[3].data.length,
      bands: c.$bandsDrawn,
      legend: c.legend.legendItems.length,
    };
  }));
  check(maps.length === radii.length, `one per-level map per parameter set (${maps.length})`);
  for (const [i, m] of maps.entries()) {
    const l = api.ladders[i];
    const wanted = levels.map((v) => `elements_across = ${v}`);
    check(m.levels === levels.length && m.tableRows === levels.length, `${m.title}: ${levels.length} levels in the table`);
    check(JSON.stringify(m.yTicks) === JSON.stringify(wanted), `${m.title}: rows labelled ${JSON.stringify(m.yTicks)}`);
    check(m.xTitle === 'impact velocity (m/s)', `${m.title}: velocity axis with its unit`);
    const jobs = api.jobs.filter((j) => j.params['/particle_impact/particle/radius'] === l.params['/particle_impact/particle/radius']);
    check(m.jobs === jobs.length && m.rows === levels.length, `${m.title}: all ${jobs.length} jobs on ${m.rows} rows`);
    const marks = ['critical', 'maximum'].reduce((n, k) => n + l[k].levels.filter((e) => e.estimate !== null).length, 0);
    const estimates = ['critical', 'maximum'].filter((k) => l[k].value !== null).length;
    check(marks > 0 && m.edgeMarks === marks, `${m.title}: ${marks} edges per level marked (${m.edgeMarks})`);
    check(m.bands === marks + 2 * estimates, `${m.title}: drew ${marks} brackets and ${estimates} estimates with error bands (${m.bands} shapes)`);
    check(m.legend <= 8, `${m.title}: legend of ${m.legend} entries`);
  }

  // The window of deposition against the radius.
  const dep = await depositionState(page);
  check(!dep.hidden && dep.field === '/particle_impact/particle/radius', `window of deposition against the radius (${dep.field})`);
  // A ladder's estimate, else the finest level's edge (an open one at its
  // outermost stick).
  const edgeOf = (l, k) => {
    if (l[k].value !== null) return true;
    const finest = api.windows.find((w) => w.params['/particle_impact/particle/radius'] === l.params['/particle_impact/particle/radius'] &&
      w.params[l.pointer] === l.levels[l.levels.length - 1]);
    const b = finest && finest[`${k}_bracket`];
    return Boolean(b) && (finest[`${k}_velocity`] !== null || b.rebound_velocity === null);
  };
  for (const [k, n] of [['critical', 0], ['maximum', 1]]) {
    const expected = api.ladders.filter((l) => edgeOf(l, k)).length;
    check(dep.counts[n] === expected, `deposition chart: ${expected} ${k} points (${dep.counts[n]})`);
  }
  check(dep.counts[0] > 0 && dep.counts[1] > 0 && dep.fill === '-1', 'deposition window shaded between critical and maximum velocity');
  const bars = [...dep.critical, ...dep.maximum].filter((p) => p.err !== null && p.err !== undefined).length;
  check(bars > 0 && dep.errorBars === bars, `deposition chart: ${bars} error bars drawn (${dep.errorBars})`);
  await checkReadableCharts(page, ['map', 'deposition', 'ladder-0']);

  // A job of the finest level: the job view says the model and resolution.
  const pos = await page.evaluate(() => {
    const c = Chart.getChart('ladder-0');
    c.canvas.scrollIntoView();
    const ds = [0, 1, 2].find((i) => c.data.datasets[i].data.length);
    const k = c.data.datasets[ds].data.findIndex((p) => p.y === c.data.datasets[ds].data.reduce((m, q) => Math.max(m, q.y), 0));
    const p = c.getDatasetMeta(ds).data[k];
    const r = c.canvas.getBoundingClientRect();
    return { x: r.left + p.x, y: r.top + p.y, level: c.data.datasets[ds].data[k].job.params['/particle_impact/particle/elements_across'] };
  });
  await page.mouse.click(pos.x, pos.y);
  await page.waitForFunction((lv) => new RegExp(`elements_across = ${lv}\\b`).test(document.getElementById('job-model').textContent),
    pos.level, { timeout: 15000 }).catch((e) => fail(`job view without its resolution (${e.message})`));
  const model = await page.textContent('#job-model');
  check(/model fe-axisym/.test(model) && new RegExp(`elements_across = ${pos.level}\\b`).test(model),
    `job view: ${model.slice(0, 120)}`);
  await checkReadableCharts(page, ['chart-velocity', 'chart-energy', 'chart-area']);
  await page.screenshot({ path: path.join(outDir, 'dashboard-ladder.png'), fullPage: true });
  console.log(`screenshot: ${path.join(outDir, 'dashboard-ladder.png')}`);
}

async function main() {
  fs.mkdirSync(outDir, { recursive: true });
  const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'splat_browser_'));
  const { child, url } = await startServer(path.join(tmp, 'store.db'));
  let browser;
  try {
    browser = await chromium.launch({ executablePath: chromiumPath, headless: true,
      args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage'] });
    const page = await browser.newPage({ viewport: { width: 1400, height: 1800 } });
    const foreign = [];
    page.on('request', (r) => { if (!r.url().startsWith(url)) foreign.push(r.url()); });
    const pageErrors = [];
    page.on('pageerror', (e) => pageErrors.push(e.message));

    await page.goto(url + '/');
    await page.waitForSelector('[data-pointer="/velocity/range/from"]', { timeout: 15000 });
    check(await page.evaluate(() => typeof Chart === 'function'), 'Chart.js loaded from the server');
    // The form is generated from the schema: units from its `unit` keyword.
    const unitText = await page.textContent('#schema-fields');
    check(unitText.includes('J/m^2') && unitText.includes('m/s'), 'form shows the schema units');

    // A small campaign: 8 velocities x 2 values of G_c, edges refined to 0.02 m/s.
    await page.fill('[data-pointer="/name"]', 'browser-test');
    await page.fill('[data-pointer="/velocity/range/from"]', '0.2');
    await page.fill('[data-pointer="/velocity/range/to"]', '1.6');
    await page.fill('[data-pointer="/velocity/range/step"]', '0.2');
    await page.fill('[data-pointer="/G_c/values"]', '0.1, 0.2');
    await page.fill('[data-pointer="/refinement/tolerance"]', '0.02');
    await page.fill('[data-pointer="/refinement/max_extra_jobs"]', '20');
    await page.click('#submit-campaign');
    await page.waitForFunction(() => /accepted/.test(document.getElementById('submit-result').textContent),
      null, { timeout: 15000 });
    check(true, 'campaign accepted through the form');

    await page.waitForFunction(() => {
      const row = document.querySelector('#campaigns tbody tr');
      return row && row.querySelector('.state').textContent === 'finished';
    }, null, { timeout: 120000, polling: 250 });
    check(true, 'campaign finished (progress polled in the list)');
    await page.waitForFunction(() => document.querySelectorAll('#windows tbody tr').length === 2 &&
      /finished/.test(document.getElementById('detail-summary').textContent), null, { timeout: 15000 });

    // The window table: two parameter sets, the maximum velocity within the
    // refinement tolerance of the closed form.
    const rows = await page.$$eval('#windows tbody tr', (trs) => trs.map((tr) => [...tr.children].map((td) => td.textContent)));
    check(rows.length === 2, 'window table has one row per parameter set');
    const params = await page.$$eval('#windows tbody tr td:first-child', (tds) => tds.map((td) => td.getAttribute('data-params')));
    for (const [i, r] of rows.entries()) {
      check(/G_c = 0\.[12] J\/m\^2/.test(r[0]), `window row labelled with its unit: ${r[0]}`);
      const G_c = JSON.parse(params[i]).G_c;
      const vmax = parseFloat(r[2]);
      check(Math.abs(vmax - edge(G_c)) <= 0.02, `G_c = ${G_c}: maximum velocity ${vmax} m/s vs closed form ${edge(G_c).toFixed(4)} m/s`);
    }

    // The stick/rebound map: every job a mark, edges drawn, canvas painted.
    const map = await page.evaluate(() => {
      const c = Chart.getChart('map');
      const counts = c.data.datasets.map((d) => d.data.length);
      const canvas = document.getElementById('map');
      const ctx = canvas.getContext('2d');
      const img = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
      let painted = 0;
      for (let i = 3; i < img.length; i += 4) if (img[i] > 0) painted++;
      return { counts, painted };
    });
    const jobs = await page.evaluate(async () => {
      const id = Number(document.querySelector('#campaigns tbody tr').getAttribute('data-id'));
      const r = await fetch(`/api/v1/campaigns/${id}`);
      return (await r.json()).jobs.total;
    });
    check(map.counts[0] > 0 && map.counts[1] > 0, `map has stick (${map.counts[0]}) and rebound (${map.counts[1]}) marks`);
    check(map.counts[0] + map.counts[1] + map.counts[2] === jobs, `map shows all ${jobs} jobs`);
    check(map.counts[3] === 2, 'map draws the two window edges');
    check(map.painted > 1000, `map canvas painted (${map.painted} pixels)`);

    // Click the first stick mark: its velocity and energy histories chart.
    const pos = await page.evaluate(() => {
      const c = Chart.getChart('map');
      c.canvas.scrollIntoView();
      const p = c.getDatasetMeta(0).data[0];
      const r = c.canvas.getBoundingClientRect();
      return { x: r.left + p.x, y: r.top + p.y };
    });
    await page.mouse.click(pos.x, pos.y);
    await page.waitForFunction(() => !document.getElementById('job-detail').hidden &&
      Chart.getChart('chart-velocity') && Chart.getChart('chart-velocity').data.datasets.length > 0,
    null, { timeout: 15000 }).catch(async (e) => {
      await page.screenshot({ path: path.join(outDir, 'dashboard-failed.png'), fullPage: true });
      fail(`no job charts after clicking a map mark (${e.message}; errors: ${pageErrors.join('; ')})`);
    });
    const hist = await page.evaluate(() => ({
      velocity: Chart.getChart('chart-velocity').data.datasets.map((d) => d.label),
      energy: Chart.getChart('chart-energy').data.datasets.map((d) => d.label),
    }));
    check(hist.velocity.includes('v_M') && hist.energy.includes('kinetic'), `job charts: ${JSON.stringify(hist)}`);
    await checkReadableCharts(page, ['map', 'chart-velocity', 'chart-energy', 'chart-area', 'deposition']);
    check(/model two-mass/.test(await page.textContent('#job-model')), 'job view names the two-mass model');
    const twoMassModels = await page.textContent('#detail-models');
    check(twoMassModels === `Model: two-mass (${jobs} jobs)`, `campaign names its model: ${twoMassModels}`);

    // Window of deposition against G_c: the maximum velocity (closed form)
    // at both values with its bracket as error bar; the critical velocity is
    // open (every low speed sticks) and drawn without one.
    const dep = await depositionState(page);
    check(dep.field === 'G_c' && !dep.hidden, `window-of-deposition chart against G_c (${dep.field})`);
    check(dep.counts[0] === 2 && dep.counts[1] === 2, `deposition chart: 2 critical and 2 maximum points (${dep.counts})`);
    for (const p of dep.maximum) {
      check(Math.abs(p.y - edge(p.x)) <= 0.02, `deposition maximum at G_c = ${p.x}: ${p.y} m/s vs ${edge(p.x).toFixed(4)}`);
    }
    check(dep.errorBars === 2, `deposition chart drew 2 error bars (${dep.errorBars})`);
    check(await page.$$eval('#ladders .ladder', (d) => d.length) === 0 &&
      /no resolution ladder/.test(await page.textContent('#ladders-note')), 'two-mass campaign: no ladder, and the page says so');

    const csvHref = await page.getAttribute('#csv-link', 'href');
    const csv = await page.evaluate(async (h) => (await fetch(h)).text(), csvHref);
    check(csv.split('\n').filter((l) => l).length === 3, 'CSV download has a header and two rows');

    await page.screenshot({ path: path.join(outDir, 'dashboard.png'), fullPage: true });
    console.log(`screenshot: ${path.join(outDir, 'dashboard.png')}`);

    await impactTemplateAsShipped(page);
    await ladderCampaign(page, url);
    check(foreign.length === 0, `no request left the server (${foreign.join(', ')})`);
    check(pageErrors.length === 0, `no script errors (${pageErrors.join('; ')})`);
  } finally {
    if (browser) await browser.close();
    child.kill('SIGTERM');
    fs.rmSync(tmp, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error(e.stack || e.message);
  process.exitCode = 1;
});
