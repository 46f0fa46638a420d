#!/usr/bin/env node
// A Terrarium raster-dem tile set of a known analytic surface, written with
// node's zlib only, and the check of what MapLibre reports for it.
//   node terrarium.mjs write DIR [MAXZOOM=3]   -> DIR/{z}/{x}/{y}.png, 256 px, XYZ web mercator
//   node terrarium.mjs check < result.json     -> compares the page's elevations with height()
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { pathToFileURL } from 'node:url';

export const TILE = 256;
export const MAXZOOM = 3;
// Smooth everywhere, 500..1500 m; periods of 90 deg in lon and 120 deg in lat.
export const height = (lon, lat) => 1000 + 500 * Math.sin(lon * Math.PI / 45) * Math.cos(lat * Math.PI / 60);

const lonOf = (mx) => mx * 360 - 180; // mx, my: web mercator in [0, 1], y down
const latOf = (my) => Math.atan(Math.sinh(Math.PI * (1 - 2 * my))) * 180 / Math.PI;
const mercX = (lon) => (lon + 180) / 360;
const mercY = (lat) => (1 - Math.log(Math.tan(Math.PI / 4 + lat * Math.PI / 360)) / Math.PI) / 2;

const CRC = new Int32Array(256).map((_, n) => { let c = n; for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1; return c; });
const crc32 = (buf) => { let c = -1; for (const b of buf) c = CRC[(c ^ b) & 255] ^ (c >>> 8); return (c ^ -1) >>> 0; };
function chunk(type, data) {
  const len = Buffer.alloc(4); len.writeUInt32BE(data.length);
  const body = Buffer.concat([Buffer.from(type, 'latin1'), data]);
  const crc = Buffer.alloc(4); crc.writeUInt32BE(crc32(body));
  return Buffer.concat([len, body, crc]);
}
export function encodePng(width, height, rgb) { // 8-bit RGB, filter 0 on every row
  const raw = Buffer.alloc((width * 3 + 1) * height);
  for (let y = 0; y < height; y++) rgb.copy(raw, y * (width * 3 + 1) + 1, y * width * 3, (y + 1) * width * 3);
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0); ihdr.writeUInt32BE(height, 4); ihdr[8] = 8; ihdr[9] = 2; // depth 8, RGB
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
    chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}

// Terrarium: h = R*256 + G + B/256 - 32768. Pixels are sampled at their centres,
// which is where MapLibre places them (DEM_CELL_CENTER_OFFSET = -0.5).
export function writeTiles(dir, maxZoom = MAXZOOM) {
  let count = 0;
  for (let z = 0; z <= maxZoom; z++) {
    const n = 1 << z;
    for (let x = 0; x < n; x++) for (let y = 0; y < n; y++) {
      const rgb = Buffer.alloc(TILE * TILE * 3);
      for (let j = 0; j < TILE; j++) for (let i = 0; i < TILE; i++) {
        const v = Math.round((height(lonOf((x + (i + 0.5) / TILE) / n), latOf((y + (j + 0.5) / TILE) / n)) + 32768) * 256);
        rgb.set([v >> 16, (v >> 8) & 255, v & 255], (j * TILE + i) * 3);
      }
      fs.mkdirSync(path.join(dir, `${z}`, `${x}`), { recursive: true });
      fs.writeFileSync(path.join(dir, `${z}`, `${x}`, `${y}.png`), encodePng(TILE, TILE, rgb));
      count++;
    }
  }
  return count;
}

// Error bound at one point for bilinear interpolation of pixel-centre samples at
// zoom z: |e| <= (dx^2 max|h_xx| + dy^2 max|h_yy|) / 8 with dx = dy = one pixel in
// mercator units, the second derivatives taken numerically over the 2x2 pixel cell
// around the point; plus half a Terrarium step (1/512 m) for rounding.
export function tolerance(lon, lat, z) {
  const px = 1 / (TILE << z), mx = mercX(lon), my = mercY(lat);
  const hm = (u, v) => height(lonOf(u), latOf(v));
  let hxx = 0, hyy = 0;
  for (const du of [-px, 0, px]) for (const dv of [-px, 0, px]) {
    const u = mx + du, v = my + dv;
    hxx = Math.max(hxx, Math.abs(hm(u + px, v) - 2 * hm(u, v) + hm(u - px, v))); // = h_xx * px^2
    hyy = Math.max(hyy, Math.abs(hm(u, v + px) - 2 * hm(u, v) + hm(u, v - px)));
  }
  return (hxx + hyy) / 8 + 1 / 512;
}

if (process.argv[1] && import.meta.url === pathToFileURL(path.resolve(process.argv[1])).href) {
  const [cmd, dir, mz] = process.argv.slice(2);
  if (cmd === 'write' && dir) {
    const n = writeTiles(dir, mz ? Number(mz) : MAXZOOM);
    console.error(`terrarium: wrote ${n} tiles to ${dir}`);
  } else if (cmd === 'check') {
    // The page reports {points: [{lon, lat, elevation, elevation2}], exaggeration2, ramp, centerPixel}.
    const r = JSON.parse(fs.readFileSync(0, 'utf8'));
    let bad = 0;
    for (const p of r.points) {
      const want = height(p.lon, p.lat), tol = tolerance(p.lon, p.lat, MAXZOOM);
      const err = p.elevation - want, err2 = p.elevation2 / r.exaggeration2 - p.elevation;
      const ok = Math.abs(err) <= tol && Math.abs(err2) <= 1e-6 * want;
      bad += !ok;
      console.error(`  ${ok ? 'ok ' : 'BAD'} (${p.lon}, ${p.lat}): maplibre ${p.elevation.toFixed(4)} m, analytic ${want.toFixed(4)} m, ` +
        `error ${err.toFixed(4)} m (tolerance ${tol.toFixed(4)}); x${r.exaggeration2}: ${p.elevation2.toFixed(4)} m`);
    }
    // The centre pixel (points[0]) through the page's linear blue-to-red color-relief
    // ramp: +-3 of 255 covers 8-bit rounding in the ramp texture and the framebuffer.
    const [lo, hi] = r.ramp, t = (height(r.points[0].lon, r.points[0].lat) - lo) / (hi - lo);
    const want = [255 * t, 0, 255 * (1 - t)], pixOk = want.every((v, i) => Math.abs(v - r.centerPixel[i]) <= 3);
    bad += !pixOk;
    console.error(`  ${pixOk ? 'ok ' : 'BAD'} centre pixel rgb ${r.centerPixel.slice(0, 3)}, expected ${want.map((v) => v.toFixed(1))}`);
    console.log(`terrarium check: ${r.points.length + 1 - bad} passed, ${bad} failed`);
    process.exit(bad ? 1 : 0);
  } else {
    console.error('usage: terrarium.mjs write DIR [MAXZOOM] | check < result.json');
    process.exit(2);
  }
}
