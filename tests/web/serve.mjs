#!/usr/bin/env node
// Tiny static HTTP server for the real-browser tests: no npm dependencies.
// Serves directories under URL prefixes on 127.0.0.1 (ephemeral port by default),
// with byte ranges (PMTiles), HEAD, CORS, and `Content-Encoding: gzip` for
// pre-gzipped tiles (files whose extension is in gzipExts and whose first two
// bytes are 1f 8b, as quantized-mesh .terrain and MVT .pbf tiles usually are).
//
// CLI:    node serve.mjs --mount /lib=DIR [--mount /data=DIR]... [--port N]
//                        [--gzip-ext .terrain,.pbf,.mvt]   (empty string: none)
//         prints its base URL (http://127.0.0.1:PORT) on stdout, serves until killed.
// Module: const {url, close} = await startServer({mounts: {'/lib': dir}, port, gzipExts});
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { pipeline } from 'node:stream';

export const MIME = {
  '.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8', '.cjs': 'text/javascript; charset=utf-8',
  '.json': 'application/json', '.map': 'application/json', '.css': 'text/css; charset=utf-8',
  '.txt': 'text/plain; charset=utf-8', '.xml': 'application/xml', '.svg': 'image/svg+xml',
  '.png': 'image/png', '.jpg': 'image/jpeg', '.jpeg': 'image/jpeg', '.webp': 'image/webp',
  '.gif': 'image/gif', '.ktx2': 'image/ktx2', '.pbf': 'application/x-protobuf',
  '.mvt': 'application/vnd.mapbox-vector-tile', '.terrain': 'application/vnd.quantized-mesh',
  '.pmtiles': 'application/octet-stream', '.wasm': 'application/wasm',
  '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json',
};
export const DEFAULT_GZIP_EXTS = ['.terrain', '.pbf', '.mvt'];

function isGzipped(file, fd) {
  const head = Buffer.alloc(2);
  return fs.readSync(fd, head, 0, 2, 0) === 2 && head[0] === 0x1f && head[1] === 0x8b;
}

// Parses a single "bytes=a-b" / "bytes=a-" / "bytes=-n" range. Returns
// null (ignore: serve whole file), 'bad' (416), or {start, end} inclusive.
function parseRange(header, size) {
  const m = /^bytes=(\d*)-(\d*)$/.exec(header.trim());
  if (!m || (m[1] === '' && m[2] === '')) return null; // multi-range or junk: RFC 9110 allows ignoring
  let start, end;
  if (m[1] === '') { start = Math.max(0, size - Number(m[2])); end = size - 1; if (Number(m[2]) === 0) return 'bad'; }
  else { start = Number(m[1]); end = m[2] === '' ? size - 1 : Math.min(Number(m[2]), size - 1); }
  if (start >= size || start > end) return 'bad';
  return { start, end };
}

export async function startServer({ mounts, port = 0, host = '127.0.0.1', gzipExts = DEFAULT_GZIP_EXTS, log = null }) {
  // Longest prefix first; prefixes normalised to "/name" (or "" for the root).
  const table = Object.entries(mounts)
    .map(([prefix, dir]) => [prefix.replace(/\/+$/, ''), path.resolve(dir)])
    .sort((a, b) => b[0].length - a[0].length);

  const resolve = (urlPath) => {
    for (const [prefix, dir] of table) {
      if (urlPath !== prefix && !urlPath.startsWith(prefix + '/')) continue;
      const file = path.join(dir, urlPath.slice(prefix.length));
      if (file !== dir && !file.startsWith(dir + path.sep)) return null; // traversal
      return file;
    }
    return null;
  };

  const server = http.createServer((req, res) => {
    const send = (status, headers, body) => { res.writeHead(status, headers); res.end(body); };
    res.setHeader('Access-Control-Allow-Origin', '*');
    res.setHeader('Access-Control-Expose-Headers', 'Content-Length, Content-Range, Content-Encoding, Accept-Ranges, ETag');
    res.setHeader('Cache-Control', 'no-store');
    if (log) res.on('finish', () => log(`${res.statusCode} ${req.method} ${req.url}`));
    if (req.method === 'OPTIONS') {
      return send(204, { 'Access-Control-Allow-Methods': 'GET, HEAD, OPTIONS',
        'Access-Control-Allow-Headers': req.headers['access-control-request-headers'] || '*' });
    }
    if (req.method !== 'GET' && req.method !== 'HEAD') return send(405, { Allow: 'GET, HEAD, OPTIONS' });
    let urlPath;
    try { urlPath = decodeURIComponent(new URL(req.url, 'http://x').pathname); } catch { return send(400, {}); }
    let file = resolve(urlPath);
    let st = file && fs.statSync(file, { throwIfNoEntry: false });
    if (st?.isDirectory()) { file = path.join(file, 'index.html'); st = fs.statSync(file, { throwIfNoEntry: false }); }
    if (!st?.isFile()) return send(404, { 'Content-Type': 'text/plain' }, `not found: ${urlPath}\n`);

    const ext = path.extname(file).toLowerCase();
    const headers = { 'Content-Type': MIME[ext] || 'application/octet-stream', 'Accept-Ranges': 'bytes',
      'Last-Modified': st.mtime.toUTCString() };
    let fd;
    try { fd = fs.openSync(file, 'r'); } catch { return send(403, {}); }
    if (gzipExts.includes(ext) && isGzipped(file, fd)) headers['Content-Encoding'] = 'gzip';
    let start = 0, end = st.size - 1, status = 200;
    const range = req.headers.range ? parseRange(req.headers.range, st.size) : null;
    if (range === 'bad') {
      fs.closeSync(fd);
      return send(416, { ...headers, 'Content-Range': `bytes */${st.size}` });
    }
    if (range) {
      ({ start, end } = range); status = 206;
      headers['Content-Range'] = `bytes ${start}-${end}/${st.size}`;
    }
    headers['Content-Length'] = String(st.size === 0 ? 0 : end - start + 1);
    res.writeHead(status, headers);
    if (req.method === 'HEAD' || st.size === 0) { fs.closeSync(fd); return res.end(); }
    pipeline(fs.createReadStream(file, { fd, start, end }), res, () => {});
  });

  await new Promise((ok, fail) => { server.once('error', fail); server.listen(port, host, ok); });
  const url = `http://${host}:${server.address().port}`;
  const close = () => new Promise((ok) => { server.closeAllConnections?.(); server.close(() => ok()); });
  return { url, close, server };
}

// CLI
if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const args = process.argv.slice(2);
  const mounts = {};
  let port = 0, gzipExts = DEFAULT_GZIP_EXTS, verbose = false;
  for (let i = 0; i < args.length; i++) {
    const a = args[i];
    if (a === '--mount') {
      const [prefix, ...dir] = (args[++i] ?? '').split('=');
      if (!prefix.startsWith('/') || !dir.length) { console.error(`serve: bad --mount '${args[i]}', want /prefix=DIR`); process.exit(2); }
      mounts[prefix] = dir.join('=');
    } else if (a === '--port') port = Number(args[++i]);
    else if (a === '--gzip-ext') gzipExts = args[++i].split(',').filter(Boolean);
    else if (a === '-v' || a === '--verbose') verbose = true;
    else { console.error('usage: serve.mjs --mount /prefix=DIR [--mount ...] [--port N] [--gzip-ext .a,.b] [-v]'); process.exit(2); }
  }
  if (!Object.keys(mounts).length) { console.error('serve: at least one --mount is needed'); process.exit(2); }
  const { url, close } = await startServer({ mounts, port, gzipExts, log: verbose ? (m) => console.error(m) : null });
  console.log(url);
  for (const sig of ['SIGINT', 'SIGTERM']) process.on(sig, () => close().then(() => process.exit(0)));
}
