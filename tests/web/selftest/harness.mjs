#!/usr/bin/env node
// Checks of the harness itself: serve.mjs over raw HTTP (ranges, HEAD, gzip marking,
// types, traversal), and run_page.mjs's exit codes on failing pages.
// usage: node harness.mjs   (needs scripts/web-deps.sh to have run; prints "N passed, M failed")
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import http from 'node:http';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { startServer } from '../serve.mjs';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'globe-web-harness-'));
let passed = 0, failed = 0;
const check = (name, ok, detail = '') => {
  ok ? passed++ : failed++;
  console.error(`  ${ok ? 'ok ' : 'BAD'} ${name}${ok ? '' : ` ${detail}`}`);
};
// Raw request, so neither '..' nor gzip is touched on the way.
const get = (url, pathName, { method = 'GET', headers = {} } = {}) => new Promise((ok, fail) => {
  const { hostname, port } = new URL(url);
  const req = http.request({ hostname, port, path: pathName, method, headers }, (res) => {
    const parts = [];
    res.on('data', (d) => parts.push(d));
    res.on('end', () => ok({ status: res.statusCode, headers: res.headers, body: Buffer.concat(parts) }));
  });
  req.on('error', fail);
  req.end();
});

try {
  fs.writeFileSync(path.join(tmp, 'a.pmtiles'), '0123456789');
  fs.writeFileSync(path.join(tmp, 'gz.terrain'), Buffer.from([0x1f, 0x8b, 8, 0, 1, 2]));
  fs.writeFileSync(path.join(tmp, 'plain.pbf'), 'xy');
  const srv = await startServer({ mounts: { '/d': tmp } });
  let r = await get(srv.url, '/d/a.pmtiles', { headers: { Range: 'bytes=2-5' } });
  check('range 2-5 -> 206', r.status === 206 && r.body.toString() === '2345' &&
    r.headers['content-range'] === 'bytes 2-5/10' && r.headers['accept-ranges'] === 'bytes', JSON.stringify(r.headers));
  r = await get(srv.url, '/d/a.pmtiles', { headers: { Range: 'bytes=-3' } });
  check('suffix range -> last 3 bytes', r.status === 206 && r.body.toString() === '789');
  r = await get(srv.url, '/d/a.pmtiles', { headers: { Range: 'bytes=10-' } });
  check('range past the end -> 416', r.status === 416 && r.headers['content-range'] === 'bytes */10');
  r = await get(srv.url, '/d/a.pmtiles', { method: 'HEAD' });
  check('HEAD: length, no body', r.status === 200 && r.headers['content-length'] === '10' && r.body.length === 0);
  r = await get(srv.url, '/d/gz.terrain');
  check('gzipped .terrain -> Content-Encoding: gzip', r.headers['content-encoding'] === 'gzip' &&
    r.headers['content-type'] === 'application/vnd.quantized-mesh' && r.body.length === 6);
  r = await get(srv.url, '/d/plain.pbf');
  check('plain .pbf -> no Content-Encoding', r.status === 200 && !r.headers['content-encoding'] &&
    r.headers['access-control-allow-origin'] === '*');
  r = await get(srv.url, '/d/../../etc/passwd');
  check('path traversal -> 404', r.status === 404, r.status);
  await srv.close();

  // run_page exit codes: 3 uncaught exception, 4 ok:false, 2 timeout (with console errors).
  const pages = {
    'throws.html': '<script>throw new Error("boom")</script>',
    'notok.html': '<script>window.__result = {ok: false, why: "told to"}</script>',
    'silent.html': '<script>console.error("still waiting")</script>',
  };
  for (const [name, html] of Object.entries(pages)) fs.writeFileSync(path.join(tmp, name), html);
  const run = (page, timeout) => spawnSync(process.execPath, [path.join(web, 'run_page.mjs'), '--timeout', String(timeout),
    path.join(tmp, page)], { encoding: 'utf8' });
  r = run('throws.html', 20);
  check('page exception -> exit 3', r.status === 3 && /boom/.test(r.stderr), r.stderr);
  r = run('notok.html', 20);
  check('ok:false -> exit 4, result on stdout', r.status === 4 && JSON.parse(r.stdout).why === 'told to', r.stderr);
  r = run('silent.html', 2);
  check('no result -> exit 2, console errors reported', r.status === 2 && /console errors:\n\s+still waiting/.test(r.stderr), r.stderr);
} finally {
  fs.rmSync(tmp, { recursive: true, force: true });
}
console.log(`harness check: ${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
