#!/usr/bin/env node
// Opens one HTML page in headless Debian chromium (WebGL on SwiftShader) through
// playwright-core, waits for the page to set `window.__result`, and prints it as
// JSON on stdout. The page's console goes to stderr.
//
// usage: node run_page.mjs [options] PAGE
//   PAGE               a local .html file (its folder is served at /page/), a
//                      URL path on the server, e.g. /data/view.html, or a whole
//                      http:// URL (another server, e.g. globe-serve)
//   --mount /P=DIR     serve DIR at /P (repeatable); /lib is always the npm cache's
//                      node_modules (GLOBE_WEB_CACHE, default ~/.cache/globe-web)
//   --query STR        query string appended to the page URL (without '?')
//   --timeout S        seconds to wait for window.__result (default 30)
//   --screenshot F     save a PNG of the page after the result is set
//   --viewport WxH     page size in CSS pixels (default 800x600)
//   --allow-page-errors  keep waiting after an uncaught page exception
// env:   CHROMIUM (default /usr/bin/chromium), CHROMIUM_ARGS (replaces the flags below)
// exit: 0 result set (and result.ok !== false); 1 usage or launch failure;
//       2 timeout; 3 uncaught page error; 4 result.ok === false.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { startServer } from './serve.mjs';

// SwiftShader (CPU Vulkan under ANGLE): WebGL 1 and 2 with no GPU and no X server.
// Chromium >= 137 no longer falls back to it silently, hence the explicit flags.
const CHROMIUM_ARGS = ['--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist', '--disable-dev-shm-usage'];

function fail(code, msg) { console.error(`run_page: ${msg}`); process.exit(code); }

const args = process.argv.slice(2);
const opt = { mounts: {}, query: '', timeout: 30, screenshot: null, viewport: '800x600', allowErrors: false, page: null };
for (let i = 0; i < args.length; i++) {
  const a = args[i];
  if (a === '--mount') {
    const [prefix, ...dir] = (args[++i] ?? '').split('=');
    if (!prefix.startsWith('/') || !dir.length) fail(1, `bad --mount '${args[i]}', want /prefix=DIR`);
    opt.mounts[prefix] = dir.join('=');
  } else if (a === '--query') opt.query = args[++i];
  else if (a === '--timeout') opt.timeout = Number(args[++i]);
  else if (a === '--screenshot') opt.screenshot = args[++i];
  else if (a === '--viewport') opt.viewport = args[++i];
  else if (a === '--allow-page-errors') opt.allowErrors = true;
  else if (!a.startsWith('--') && !opt.page) opt.page = a;
  else fail(1, `unknown argument '${a}' (see the usage at the top of run_page.mjs)`);
}
if (!opt.page) fail(1, 'no PAGE given');

const cache = process.env.GLOBE_WEB_CACHE || path.join(os.homedir(), '.cache', 'globe-web');
const pwPath = path.join(cache, 'node_modules', 'playwright-core', 'index.mjs');
if (!fs.existsSync(pwPath)) fail(1, `${pwPath} missing: run scripts/web-deps.sh first`);
const { chromium } = await import(pathToFileURL(pwPath).href);

let pagePath = opt.page;
if (fs.existsSync(opt.page) && fs.statSync(opt.page).isFile()) {
  opt.mounts['/page'] = path.dirname(path.resolve(opt.page));
  pagePath = '/page/' + encodeURIComponent(path.basename(opt.page));
}
opt.mounts['/lib'] ??= path.join(cache, 'node_modules');

const t0 = Date.now();
const elapsed = () => ((Date.now() - t0) / 1000).toFixed(1) + 's';
const server = await startServer({ mounts: opt.mounts });
const url = (/^https?:\/\//.test(pagePath) ? pagePath : `${server.url}${pagePath}`) +
  (opt.query ? (pagePath.includes('?') ? '&' : '?') + opt.query : '');
const [w, h] = opt.viewport.split('x').map(Number);
let browser;
try {
  browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: process.env.CHROMIUM_ARGS?.split(/\s+/).filter(Boolean) ?? CHROMIUM_ARGS, timeout: 30000 });
} catch (e) { await server.close(); fail(1, `cannot launch chromium: ${e.message.split('\n')[0]}`); }

let code = 0;
const consoleErrors = [], pageErrors = [];
try {
  const page = await browser.newPage({ viewport: { width: w, height: h } });
  page.on('console', (m) => {
    console.error(`[page ${m.type()}] ${m.text()}`);
    if (m.type() === 'error') consoleErrors.push(m.text());
  });
  page.on('pageerror', (e) => { console.error(`[page exception] ${e.message}`); pageErrors.push(e.message); });
  page.on('requestfailed', (r) => console.error(`[page request failed] ${r.url()} ${r.failure()?.errorText}`));
  page.on('response', (r) => { if (r.status() >= 400) console.error(`[page http ${r.status()}] ${r.url()}`); });
  page.on('request', (r) => { if (!/^(http:\/\/127\.0\.0\.1[:/]|data:|blob:)/.test(r.url())) console.error(`[page external request] ${r.url()}`); });
  console.error(`run_page: chromium ${browser.version()} up at ${elapsed()}, opening ${url}`);
  const deadline = Date.now() + opt.timeout * 1000; // for the load and the result together
  await page.goto(url, { waitUntil: 'load', timeout: opt.timeout * 1000 });
  console.error(`run_page: page loaded at ${elapsed()}`);

  // Poll rather than waitForFunction so an uncaught exception ends the wait at once.
  let result;
  while ((result = await page.evaluate(() => window.__result)) === undefined) {
    if (pageErrors.length && !opt.allowErrors) { code = 3; break; }
    if (Date.now() > deadline) { code = 2; break; }
    await new Promise((r) => setTimeout(r, 100));
  }
  if (code === 0) console.error(`run_page: result at ${elapsed()}`);
  if (opt.screenshot) await page.screenshot({ path: opt.screenshot }).catch((e) => console.error(`run_page: no screenshot: ${e.message}`));
  if (code === 0) {
    console.log(JSON.stringify(result, null, 1));
    if (result && result.ok === false) code = 4;
  }
  if (code === 2) console.error(`run_page: timeout: no window.__result after ${opt.timeout}s`);
  if (code === 3) console.error(`run_page: page error: ${pageErrors[0]}`);
  if (code && consoleErrors.length) console.error(`run_page: console errors:\n  ${consoleErrors.join('\n  ')}`);
  if (code === 4) console.error('run_page: the page reported ok: false');
} catch (e) {
  code = e.name === 'TimeoutError' ? 2 : 1;
  console.error(`run_page: ${e.message.split('\n')[0]}`);
  if (consoleErrors.length) console.error(`run_page: console errors:\n  ${consoleErrors.join('\n  ')}`);
} finally {
  await browser.close();
  await server.close();
}
console.error(`run_page: done in ${elapsed()} (exit ${code})`);
process.exit(code);
