// Browser test of the dashboard (ctest label `browser`): starts a real
// `splat serve` on a port the OS picks over a fresh SQLite file, drives
// Debian's headless Chromium through playwright-core (from web/node_modules,
// `npm ci`), submits a small two-mass campaign through the form generated
// from the campaign schema, waits for it to finish, checks the window table
// against the closed-form edges, checks that the stick/rebound map and a
// job's history charts rendered, and saves a screenshot as a test artifact.
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
    for (const r of rows) {
      const G_c = JSON.parse(r[0]).G_c;
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

    const csvHref = await page.getAttribute('#csv-link', 'href');
    const csv = await page.evaluate(async (h) => (await fetch(h)).text(), csvHref);
    check(csv.split('\n').filter((l) => l).length === 3, 'CSV download has a header and two rows');

    await page.screenshot({ path: path.join(outDir, 'dashboard.png'), fullPage: true });
    console.log(`screenshot: ${path.join(outDir, 'dashboard.png')}`);
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
