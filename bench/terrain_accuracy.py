#!/usr/bin/env python3
# terrain_accuracy.py - independent accuracy checker for web terrain tiles.
#
# What: compares a terrain tileset against the GeoTIFF (or any GDAL raster)
# DEM it was made from, and reports
#   1. height error of the finest zoom's tiles against a bilinear brute force
#      of the source (n, max|e|, p99|e|, p50|e|, signed mean, RMSE, metres),
#      plus the same statistics against the source sampled half a source
#      pixel to the north-west ("shifted_half_pixel_se": small values there
#      mean the tileset is shifted half a pixel to the south-east);
#   2. for quantized-mesh: cracks between neighbouring tiles of the finest
#      zoom (vertex heights on a shared edge that disagree with the other
#      tile's edge polyline), T-junctions, uncovered edge stretches ("gaps");
#   3. for quantized-mesh: zero-area (in u,v) triangles (and how many of them
#      repeat a vertex index), clockwise triangles (the spec says CCW), holes
#      (sample points covered by no triangle), format problems (edge index
#      lists that differ from the boundary vertices, truncation, trailing
#      bytes, values outside 0..32767) and layer.json "available" vs files.
# Tileset formats: quantized-mesh-1.0 folders (layer.json, EPSG:4326 or
# EPSG:3857, tms or slippyMap rows, tiles gzipped or not), and raster DEM
# tiles in Terrarium or Mapbox Terrain-RGB encoding, as a z/x/y.png folder,
# an MBTiles file or a PMTiles v3 archive.
#
# Why: it is the reference for benchmarking this project's terrain output
# and that of a peer (cesium-terrain-builder), so it is written from the
# public specifications only (quantized-mesh-1.0, layer.json, TMS/XYZ tiling,
# Terrarium, Terrain-RGB, MBTiles 1.3, PMTiles v3) and shares no code with
# either tool.
#
# Usage:
#   python3 bench/terrain_accuracy.py SOURCE.tif TILESET
#       [--format qm|terrarium|terrain-rgb] [--zoom Z] [--points N]
#       [--seed S] [--crack-tiles PAIRS] [--scheme xyz|tms] [--json]
#   python3 bench/terrain_accuracy.py --self-test [--keep]
# TILESET: folder with layer.json (quantized-mesh), folder of z/x/y.png,
# file.mbtiles or file.pmtiles (raster DEM). --scheme only applies to raster
# folders (default xyz: y counts from the north). The format is guessed when
# --format is omitted: layer.json or *.terrain files mean quantized-mesh;
# for PNG tiles an "encoding" metadata entry is used, else the encoding that
# agrees better with the source.
# Output: a summary on stdout, or with --json one JSON object on one line:
#   error / shifted_half_pixel_se: {n, max_abs, p99_abs, p50_abs, mean, rmse}
#   points: {requested, sampled, compared, holes | tile_nodata,
#            bad_tile_points, source_nodata_skipped, drawn}
#   cracks: {pairs_total, pairs_checked, antimeridian_pairs,
#            edge_vertices_checked, cracked_vertices, pairs_with_cracks,
#            max_crack_m, t_junctions, gap_vertices, examples}
#   triangles: {tiles_decoded, triangles, degenerate,
#               degenerate_repeated_index, clockwise}
#   worst: the 5 largest errors (tile x, y rows as in worst_tile_rows).
# Exit status: 0 checked (whatever the numbers), 1 self-test failed,
# 2 unreadable input or nothing to compare, 3 missing Debian package.
#
# Conventions (how the specifications were read where they leave room):
# * Source values are samples at pixel centres (pixel-is-area geotransform),
#   interpolated bilinearly from the 4 surrounding centres; a point is only
#   used if it lies at least one source pixel inside the source's edges and
#   none of its 4 neighbours is nodata (or NaN). GDAL band scale/offset are
#   applied. A source that is not EPSG:4326 gets the points reprojected
#   (traditional lon/lat order); a geographic source whose longitudes run
#   past 180 (e.g. 20..380) is matched modulo 360.
# * Errors are tile minus source, in metres; heights are compared as stored
#   (no geoid/ellipsoid conversion).
# * quantized-mesh: u,v 0..32767 are linear in degrees (EPSG:4326) or in
#   mercator metres (EPSG:3857) across the tile; heights are linear in u,v
#   inside each triangle. Vertex count > 65536 means 32-bit indices. A point
#   on a triangle edge belongs to the first triangle that contains it
#   (barycentric tolerance 1e-9).
# * Raster DEM: a pixel value is the height at the pixel's centre; a pixel
#   with alpha 0 counts as tile nodata and is left out of the statistics.
# * Cracks compare finest-zoom neighbours only (east-west, wrapping across the
#   antimeridian, and north-south); the threshold is the larger of the two
#   tiles' height quantisation steps ((max-min)/32767) plus 1 mm. Edge
#   vertices are found from u,v (u==0/32767, v==0/32767), not from the edge
#   index lists; a vertex where the other tile has no edge vertices around
#   it is a "gap" and also counts as cracked. Edges are compared in integer
#   u (or v) positions, which both tiles of a pair share.
# * Sampling: quantized-mesh points are uniform in lon/lat over the union of
#   the finest zoom's tiles on disk (tile chosen with weight = its latitude
#   span, then a uniform point in it), kept if inside the source's valid
#   area; raster points are uniform over the tiles' pixels. Rejected draws
#   are replaced, so n reaches --points unless the overlap is tiny.
# * layer.json: "projection" and "scheme" default to EPSG:4326 and tms as in
#   the spec; cesium-terrain-builder's "schema" key is read as "scheme".
# * Interpreter: python3 on PATH may be one without Debian's modules (e.g.
#   pyenv); the script then re-runs itself under /usr/bin/python3.
import argparse
import gzip
import io
import json
import math
import os
import sqlite3
import struct
import subprocess
import sys
import tempfile
import time
import zlib


def _missing(package, module, err):
    """Import failed: re-run under Debian's python3 if we are another one
    (e.g. pyenv's), else name the Debian package to install."""
    debian_python = "/usr/bin/python3"
    if (os.path.realpath(sys.executable) != os.path.realpath(debian_python)
            and os.path.exists(debian_python)
            and not os.environ.get("TERRAIN_ACCURACY_REEXEC")):
        os.environ["TERRAIN_ACCURACY_REEXEC"] = "1"
        os.execv(debian_python, [debian_python] + sys.argv)
    sys.stderr.write("terrain_accuracy: cannot import %s (%s); install the "
                     "Debian package: apt-get install -y "
                     "--no-install-recommends %s\n" % (module, err, package))
    sys.exit(3)


try:
    import numpy as np
except ImportError as e:  # pragma: no cover
    _missing("python3-numpy", "numpy", e)
try:
    from osgeo import gdal, osr
except ImportError as e:  # pragma: no cover
    _missing("python3-gdal", "osgeo.gdal", e)


def _import_pil():
    """PIL is only needed for raster DEM tiles (and the self-test)."""
    try:
        from PIL import Image
    except ImportError as e:  # pragma: no cover
        _missing("python3-pil", "PIL", e)
    return Image


gdal.UseExceptions()
osr.UseExceptions()

QMAX = 32767                      # quantized-mesh u, v and height range
MERC_MAX_LAT = 85.0511287798066   # web mercator square's latitude limit
BARY_EPS = 1e-9                   # barycentric tolerance for point location


class InputError(Exception):
    """Unreadable or unusable input: reported with exit status 2."""


def die(msg, code=2):
    sys.stderr.write("terrain_accuracy: %s\n" % msg)
    sys.exit(code)


def error_stats(err):
    """n, max |e|, p99 |e|, p50 |e|, signed mean and RMSE of an error array."""
    err = np.asarray(err, dtype=np.float64)
    if err.size == 0:
        return {"n": 0, "max_abs": None, "p99_abs": None, "p50_abs": None,
                "mean": None, "rmse": None}
    a = np.abs(err)
    return {"n": int(err.size), "max_abs": float(a.max()),
            "p99_abs": float(np.percentile(a, 99)),
            "p50_abs": float(np.percentile(a, 50)),
            "mean": float(err.mean()),
            "rmse": float(math.sqrt(float(np.mean(err * err))))}


def maybe_gunzip(data):
    if data[:2] == b"\x1f\x8b":
        return gzip.decompress(data)
    return data


# --------------------------------------------------------------------------
# Source DEM: bilinear brute force at pixel centres
# --------------------------------------------------------------------------
class SourceDEM:
    """Band 1 of a GDAL raster, sampled bilinearly between pixel centres at
    lon/lat points (EPSG:4326, lon east, lat north)."""

    FULL_READ_LIMIT = 2 << 30     # bytes; bigger rasters are read per point

    def __init__(self, path):
        try:
            ds = gdal.Open(path)
        except RuntimeError as e:
            raise InputError("cannot open source %s: %s" % (path, e))
        if ds is None or ds.RasterCount < 1:
            raise InputError("cannot open source %s" % path)
        self.path = path
        self.ds = ds
        self.band = ds.GetRasterBand(1)
        self.W, self.H = ds.RasterXSize, ds.RasterYSize
        if self.W < 3 or self.H < 3:
            raise InputError("source %s is smaller than 3x3 pixels" % path)
        gt = ds.GetGeoTransform(can_return_null=True)
        if gt is None:
            raise InputError("source %s has no geotransform" % path)
        self.gt = gt
        self.inv = gdal.InvGeoTransform(gt)
        if self.inv is None:
            raise InputError("source %s has a singular geotransform" % path)
        self.nodata = self.band.GetNoDataValue()
        self.scale = self.band.GetScale() or 1.0
        self.offset = self.band.GetOffset() or 0.0
        self.notes = []
        srs = ds.GetSpatialRef()
        wgs = osr.SpatialReference()
        wgs.ImportFromEPSG(4326)
        wgs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        self.ct = None
        self.geographic = True
        if srs is None:
            self.notes.append("source has no CRS; assumed EPSG:4326")
        else:
            srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
            if not srs.IsSame(wgs):
                self.ct = osr.CoordinateTransformation(wgs, srs)
                self.inv_ct = osr.CoordinateTransformation(srs, wgs)
                self.geographic = False
                self.notes.append("source CRS %s is not EPSG:4326; points "
                                  "are reprojected into it" % srs.GetName())
        dt = gdal.GetDataTypeSize(self.band.DataType) // 8
        if self.W * self.H * dt <= self.FULL_READ_LIMIT:
            self.arr = self.band.ReadAsArray()
            if self.arr is None:
                raise InputError("cannot read source band of %s" % path)
        else:
            self.arr = None
        # Source pixel size in its own units (for the half-pixel diagnostic).
        self.dx = math.hypot(gt[1], gt[4])
        self.dy = math.hypot(gt[2], gt[5])
        self._valid_region()

    # Pixel "centre coordinates": px = 0 at the centre of column 0.
    def _to_pixel(self, x, y):
        inv = self.inv
        px = inv[0] + inv[1] * x + inv[2] * y - 0.5
        py = inv[3] + inv[4] * x + inv[5] * y - 0.5
        return px, py

    def _valid_region(self):
        """The lon/lat box holding the region one pixel inside the edges:
        self.lon_intervals (list of (w, e) in -180..180) and self.lat_range."""
        gt = self.gt
        k = 64
        t = np.linspace(0.0, 1.0, k + 1)
        c0, c1 = 1.0, self.W - 1.0     # pixel-corner coordinates
        r0, r1 = 1.0, self.H - 1.0
        cols = np.concatenate([c0 + (c1 - c0) * t, np.full(k + 1, c1),
                               c1 - (c1 - c0) * t, np.full(k + 1, c0)])
        rows = np.concatenate([np.full(k + 1, r0), r0 + (r1 - r0) * t,
                               np.full(k + 1, r1), r1 - (r1 - r0) * t])
        x = gt[0] + gt[1] * cols + gt[2] * rows
        y = gt[3] + gt[4] * cols + gt[5] * rows
        if self.ct is not None:
            lon, lat = self._transform(self.inv_ct, x, y)
            ok = np.isfinite(lon) & np.isfinite(lat)
            if not ok.any():
                raise InputError("cannot transform the source extent to "
                                 "EPSG:4326")
            lon, lat = lon[ok], lat[ok]
            self.lon_west = None
            self.lon_intervals = [(max(-180.0, float(lon.min())),
                                   min(180.0, float(lon.max())))]
            self.lat_range = (max(-90.0, float(lat.min())),
                              min(90.0, float(lat.max())))
            return
        a, b = float(x.min()), float(x.max())
        self.lat_range = (max(-90.0, float(y.min())),
                          min(90.0, float(y.max())))
        self.lon_west = a              # source longitudes are a + mod 360
        if b - a >= 360.0:
            self.lon_intervals = [(-180.0, 180.0)]
        else:
            s = (a + 180.0) % 360.0 - 180.0
            e = s + (b - a)
            if e <= 180.0:
                self.lon_intervals = [(s, e)]
            else:
                self.lon_intervals = [(s, 180.0), (-180.0, e - 360.0)]

    @staticmethod
    def _transform(ct, x, y):
        pts = ct.TransformPoints(list(zip(x.tolist(), y.tolist())))
        a = np.array([(p[0], p[1]) for p in pts], dtype=np.float64)
        a[~np.isfinite(a)] = np.nan
        return a[:, 0], a[:, 1]

    def pixel_coords(self, lon, lat):
        """lon/lat (degrees) -> source pixel-centre coordinates."""
        lon = np.asarray(lon, dtype=np.float64)
        lat = np.asarray(lat, dtype=np.float64)
        if self.ct is None:
            x = self.lon_west + np.mod(lon - self.lon_west, 360.0)
            return self._to_pixel(x, lat)
        if lon.size == 0:
            return lon.copy(), lat.copy()
        try:
            x, y = self._transform(self.ct, lon, lat)
        except RuntimeError:
            x = np.empty_like(lon)
            y = np.empty_like(lat)
            for i in range(lon.size):   # one by one: mark failures as NaN
                try:
                    p = self.ct.TransformPoint(float(lon[i]), float(lat[i]))
                    x[i], y[i] = p[0], p[1]
                except RuntimeError:
                    x[i] = y[i] = np.nan
        return self._to_pixel(x, y)

    def inside(self, px, py):
        """At least one source pixel inside the edges (centre coordinates
        0.5 .. size-1.5), so that also the half-pixel-shifted point has its
        4 neighbours inside."""
        with np.errstate(invalid="ignore"):
            return ((px >= 0.5) & (px <= self.W - 1.5) &
                    (py >= 0.5) & (py <= self.H - 1.5))

    def _gather(self, i, j):
        if self.arr is not None:
            return self.arr[j, i]
        out = np.empty(i.size, dtype=np.float64)
        for k in range(i.size):
            out[k] = self.band.ReadAsArray(int(i[k]), int(j[k]), 1, 1)[0, 0]
        return out

    def bilinear(self, px, py):
        """Values at pixel-centre coordinates; returns (values, ok) where ok
        is False where a neighbour is outside, nodata or NaN."""
        px = np.asarray(px, dtype=np.float64)
        py = np.asarray(py, dtype=np.float64)
        vals = np.full(px.shape, np.nan)
        with np.errstate(invalid="ignore"):
            inside = ((px >= 0) & (py >= 0) &
                      (px <= self.W - 1) & (py <= self.H - 1))
        if not inside.any():
            return vals, inside
        x, y = px[inside], py[inside]
        i0 = np.minimum(np.floor(x).astype(np.int64), self.W - 2)
        j0 = np.minimum(np.floor(y).astype(np.int64), self.H - 2)
        fx, fy = x - i0, y - j0
        corners = [self._gather(i0, j0), self._gather(i0 + 1, j0),
                   self._gather(i0, j0 + 1), self._gather(i0 + 1, j0 + 1)]
        bad = np.zeros(x.shape, dtype=bool)
        for c in corners:
            if self.nodata is not None:
                nd = np.array(self.nodata).astype(np.asarray(c).dtype)
                bad |= (c == nd)
            bad |= np.isnan(np.asarray(c, dtype=np.float64))
        c = [np.asarray(v, dtype=np.float64) for v in corners]
        v = ((1 - fx) * (1 - fy) * c[0] + fx * (1 - fy) * c[1] +
             (1 - fx) * fy * c[2] + fx * fy * c[3])
        v = v * self.scale + self.offset
        v[bad] = np.nan
        vals[inside] = v
        ok = inside.copy()
        ok[inside] = ~bad
        return vals, ok


# --------------------------------------------------------------------------
# Tiling schemes. Internally rows are TMS rows (y counts from the south).
# --------------------------------------------------------------------------
def merc_frac_from_lat(lat):
    """Latitude -> web mercator y as a fraction 0 (south) .. 1 (north)."""
    lat = np.radians(np.clip(lat, -MERC_MAX_LAT, MERC_MAX_LAT))
    return 0.5 + np.log(np.tan(np.pi / 4 + lat / 2)) / (2 * np.pi)


def lat_from_merc_frac(f):
    return np.degrees(np.arctan(np.sinh(np.pi * (2 * np.asarray(f) - 1))))


def grid_size(proj, z):
    """Columns, rows of a zoom level."""
    if proj == "EPSG:4326":
        return 2 << z, 1 << z
    return 1 << z, 1 << z


def tile_bounds(proj, z, x, y):
    """Vectorised west, south, east, north (degrees) of TMS tiles."""
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    if proj == "EPSG:4326":
        s = 180.0 / (1 << z)
        return -180 + x * s, -90 + y * s, -180 + (x + 1) * s, -90 + (y + 1) * s
    n = float(1 << z)
    return (x / n * 360 - 180, lat_from_merc_frac(y / n),
            (x + 1) / n * 360 - 180, lat_from_merc_frac((y + 1) / n))


def lonlat_to_uv(proj, z, x, y, lon, lat):
    """Continuous quantized-mesh u,v (0..32767) of points in TMS tile x,y."""
    if proj == "EPSG:4326":
        s = 180.0 / (1 << z)
        fu = (lon + 180.0) / s - x
        fv = (lat + 90.0) / s - y
    else:
        n = float(1 << z)
        fu = (lon + 180.0) / 360.0 * n - x
        fv = merc_frac_from_lat(lat) * n - y
    return fu * QMAX, fv * QMAX


def tiles_touching(proj, z, tiles, src):
    """Mask of tiles (K,2 TMS) whose box meets the source's valid box."""
    w, s, e, n = tile_bounds(proj, z, tiles[:, 0], tiles[:, 1])
    lat_ok = (n >= src.lat_range[0]) & (s <= src.lat_range[1])
    lon_ok = np.zeros(len(tiles), dtype=bool)
    for a, b in src.lon_intervals:
        lon_ok |= (e >= a) & (w <= b)
    return lat_ok & lon_ok


# --------------------------------------------------------------------------
# quantized-mesh-1.0 decoding
# --------------------------------------------------------------------------
class QMError(Exception):
    pass


class QMTile:
    """A decoded quantized-mesh tile: u, v, hq (int64 arrays), heights in
    metres, triangles (T,3 int64), edge index lists, extension ids and a list
    of format problems found while decoding."""
    __slots__ = ("u", "v", "hq", "h", "tris", "i0", "i1", "i2", "a2",
                 "edges", "minh", "maxh", "extensions", "problems")


def decode_quantized_mesh(data):
    data = maybe_gunzip(data)
    size = len(data)
    if size < 92:
        raise QMError("tile shorter than header + vertexCount (%d bytes)"
                      % size)
    hdr = struct.unpack_from("<3d2f4d3d", data, 0)
    t = QMTile()
    t.problems = []
    t.minh, t.maxh = float(hdr[3]), float(hdr[4])
    if not (math.isfinite(t.minh) and math.isfinite(t.maxh)):
        raise QMError("non-finite min/max height in header")
    if t.maxh < t.minh:
        t.problems.append("header max height < min height")
    vc = struct.unpack_from("<I", data, 88)[0]
    pos = 92
    if pos + 6 * vc > size:
        raise QMError("vertex data truncated (vertexCount %d)" % vc)
    raw = np.frombuffer(data, dtype="<u2", count=3 * vc, offset=pos)
    raw = raw.astype(np.int64).reshape(3, vc)
    dec = np.cumsum((raw >> 1) ^ (-(raw & 1)), axis=1)   # zig-zag deltas
    t.u, t.v, t.hq = dec[0], dec[1], dec[2]
    pos += 6 * vc
    if vc and (t.u.min() < 0 or t.u.max() > QMAX or t.v.min() < 0 or
               t.v.max() > QMAX):
        t.problems.append("u/v outside 0..32767")
    if vc and (t.hq.min() < 0 or t.hq.max() > QMAX):
        t.problems.append("quantized height outside 0..32767")
    t.h = t.minh + (t.maxh - t.minh) * t.hq.astype(np.float64) / QMAX
    wide = vc > 65536
    isz = 4 if wide else 2
    itype = "<u4" if wide else "<u2"
    if pos % isz:
        pos += isz - pos % isz                            # alignment padding
    if pos + 4 > size:
        raise QMError("index data truncated")
    tc = struct.unpack_from("<I", data, pos)[0]
    pos += 4
    if pos + 3 * tc * isz > size:
        raise QMError("triangle indices truncated (triangleCount %d)" % tc)
    codes = np.frombuffer(data, dtype=itype, count=3 * tc, offset=pos)
    codes = codes.astype(np.int64)
    pos += 3 * tc * isz
    # High-water-mark decoding: index = highest - code, where highest is the
    # number of zero codes seen before this one.
    highest = np.cumsum(codes == 0) - (codes == 0)
    idx = highest - codes
    if idx.size and (idx.min() < 0 or idx.max() >= vc):
        raise QMError("triangle index out of range (vertexCount %d)" % vc)
    t.tris = idx.reshape(-1, 3)
    # Corner index columns and twice the signed u,v area (> 0: CCW).
    t.i0, t.i1, t.i2 = idx[0::3].copy(), idx[1::3].copy(), idx[2::3].copy()
    u, v = t.u, t.v
    t.a2 = ((u[t.i1] - u[t.i0]) * (v[t.i2] - v[t.i0]) -
            (u[t.i2] - u[t.i0]) * (v[t.i1] - v[t.i0]))
    t.edges = []
    for name in ("west", "south", "east", "north"):
        if pos + 4 > size:
            raise QMError("%s edge index list truncated" % name)
        n = struct.unpack_from("<I", data, pos)[0]
        pos += 4
        if pos + n * isz > size:
            raise QMError("%s edge index list truncated" % name)
        e = np.frombuffer(data, dtype=itype, count=n, offset=pos)
        e = e.astype(np.int64)
        pos += n * isz
        if e.size and e.max() >= vc:
            raise QMError("%s edge index out of range" % name)
        t.edges.append(e)
    t.extensions = []
    while pos < size:
        if pos + 5 > size:
            t.problems.append("%d trailing bytes after extensions" %
                              (size - pos))
            break
        ext_id, ext_len = struct.unpack_from("<BI", data, pos)
        pos += 5
        if pos + ext_len > size:
            t.problems.append("extension %d truncated" % ext_id)
            break
        t.extensions.append(ext_id)
        pos += ext_len
    # Edge lists must list exactly the vertices on each boundary.
    bounds = ((t.u == 0), (t.v == 0), (t.u == QMAX), (t.v == QMAX))
    for name, lst, on in zip(("west", "south", "east", "north"),
                             t.edges, bounds):
        if not np.array_equal(np.unique(lst), np.flatnonzero(on)):
            t.problems.append("%s edge index list differs from the vertices "
                              "on that edge" % name)
    return t


class TileSummary:
    """What the crack and triangle checks need from a decoded tile."""
    __slots__ = ("step", "sides", "triangles", "degenerate", "repeated",
                 "clockwise", "problems", "extensions")


def summarize_tile(t):
    s = TileSummary()
    s.step = (t.maxh - t.minh) / QMAX
    # side -> (position along the edge, height), from the u,v values.
    s.sides = {}
    for side, on, along in (("W", t.u == 0, t.v), ("E", t.u == QMAX, t.v),
                            ("S", t.v == 0, t.u), ("N", t.v == QMAX, t.u)):
        s.sides[side] = (along[on].copy(), t.h[on].copy())
    s.triangles = int(t.a2.size)
    if s.triangles:
        a2 = t.a2
        s.degenerate = int(np.count_nonzero(a2 == 0))
        # Subset of those: a vertex index used twice (e.g. strip joins).
        s.repeated = int(np.count_nonzero((t.i0 == t.i1) | (t.i1 == t.i2) |
                                          (t.i0 == t.i2)))
        s.clockwise = int(np.count_nonzero(a2 < 0))
    else:
        s.degenerate = s.repeated = s.clockwise = 0
    s.problems = list(t.problems)
    s.extensions = list(t.extensions)
    return s


def interpolate_in_mesh(t, pu, pv):
    """Heights at continuous u,v points by linear interpolation inside the
    containing triangle; returns (heights, found)."""
    P = pu.size
    out = np.full(P, np.nan)
    found = np.zeros(P, dtype=bool)
    T = t.a2.size
    if P == 0 or T == 0:
        return out, found
    U = t.u.astype(np.float64)
    V = t.v.astype(np.float64)
    ax, ay, bx, by = U[t.i0], V[t.i0], U[t.i1], V[t.i1]
    cx, cy = U[t.i2], V[t.i2]
    with np.errstate(divide="ignore"):
        # Zero-area triangles get NaN weights and so never contain a point.
        inv = np.where(t.a2 != 0, 1.0 / t.a2, np.nan)

    def brute(pidx, sel):
        """Barycentric test of points pidx against triangles sel (None:
        all); weights are sub-triangle areas over the triangle's area."""
        if sel is None:
            d = (ax, ay, bx, by, cx, cy, inv, None)
        else:
            d = (ax[sel], ay[sel], bx[sel], by[sel], cx[sel], cy[sel],
                 inv[sel], sel)
        xa, ya, xb, yb, xc, yc, iv, tri_id = d
        nt = iv.size
        if nt == 0:
            return
        chunk = max(1, int(1_000_000 // nt))
        for c0 in range(0, pidx.size, chunk):
            ii = pidx[c0:c0 + chunk]
            px = pu[ii][:, None]
            py = pv[ii][:, None]
            with np.errstate(invalid="ignore"):
                l1 = ((xb - px) * (yc - py) - (xc - px) * (yb - py)) * iv
                l2 = ((xc - px) * (ya - py) - (xa - px) * (yc - py)) * iv
                l3 = 1.0 - l1 - l2
                inside = ((l1 >= -BARY_EPS) & (l2 >= -BARY_EPS) &
                          (l3 >= -BARY_EPS))
            has = inside.any(axis=1)
            if not has.any():
                continue
            k = inside.argmax(axis=1)[has]
            r = np.flatnonzero(has)
            tk = k if tri_id is None else tri_id[k]
            h = (l1[r, k] * t.h[t.i0[tk]] + l2[r, k] * t.h[t.i1[tk]] +
                 l3[r, k] * t.h[t.i2[tk]])
            out[ii[has]] = h
            found[ii[has]] = True

    if P * T <= 2_000_000:
        brute(np.arange(P), None)
        return out, found
    # Many points and triangles: bin points into a grid and test each cell's
    # points against the triangles whose bounding box meets the cell.
    g = int(min(64, max(4, math.ceil(math.sqrt(P)))))
    cw = (QMAX + 1.0) / g
    ci = np.clip((pu // cw).astype(np.int64), 0, g - 1)
    cj = np.clip((pv // cw).astype(np.int64), 0, g - 1)
    cell = ci * g + cj
    tx0 = np.minimum(np.minimum(ax, bx), cx)
    tx1 = np.maximum(np.maximum(ax, bx), cx)
    ty0 = np.minimum(np.minimum(ay, by), cy)
    ty1 = np.maximum(np.maximum(ay, by), cy)
    order = np.argsort(cell, kind="stable")
    cells, starts = np.unique(cell[order], return_index=True)
    ends = np.append(starts[1:], P)
    for c, s0, s1 in zip(cells, starts, ends):
        pidx = order[s0:s1]
        x0 = pu[pidx].min() - 1
        x1 = pu[pidx].max() + 1
        y0 = pv[pidx].min() - 1
        y1 = pv[pidx].max() + 1
        sel = np.flatnonzero((tx1 >= x0) & (tx0 <= x1) &
                             (ty1 >= y0) & (ty0 <= y1))
        brute(pidx, sel)
    return out, found


# --------------------------------------------------------------------------
# quantized-mesh tileset folder
# --------------------------------------------------------------------------
class QMTileset:
    def __init__(self, root):
        self.root = root
        self.notes = []
        self.layer = {}
        lj = os.path.join(root, "layer.json")
        if os.path.exists(lj):
            try:
                with open(lj, "rb") as f:
                    self.layer = json.loads(f.read().decode("utf-8"))
            except (OSError, ValueError) as e:
                raise InputError("cannot read %s: %s" % (lj, e))
        else:
            self.notes.append("no layer.json; spec defaults EPSG:4326, tms")
        self.proj = self.layer.get("projection", "EPSG:4326")
        if self.proj not in ("EPSG:4326", "EPSG:3857"):
            raise InputError("unsupported projection %r in layer.json"
                             % self.proj)
        self.scheme = self.layer.get("scheme")
        if self.scheme is None and "schema" in self.layer:
            # cesium-terrain-builder writes "schema"; read it as "scheme".
            self.scheme = self.layer["schema"]
            self.notes.append('layer.json has "schema" (not "scheme"): '
                              'read as the scheme')
        if self.scheme is None:
            self.scheme = "tms"
        if self.scheme not in ("tms", "slippyMap"):
            raise InputError("unsupported scheme %r in layer.json"
                             % self.scheme)
        tmpl = (self.layer.get("tiles") or ["{z}/{x}/{y}.terrain"])[0]
        tmpl = tmpl.split("?")[0]
        if not tmpl.startswith("{z}/{x}/{y}"):
            self.notes.append("tiles template %r is not {z}/{x}/{y}<ext>; "
                              "assumed {z}/{x}/{y}.terrain" % tmpl)
            tmpl = "{z}/{x}/{y}.terrain"
        self.ext = tmpl[len("{z}/{x}/{y}"):]
        self._listing = {}

    def finest_zoom(self):
        """Highest zoom folder that holds at least one tile, or None."""
        try:
            names = os.listdir(self.root)
        except OSError as e:
            raise InputError("cannot list %s: %s" % (self.root, e))
        zs = sorted((int(n) for n in names if n.isdigit() and
                     os.path.isdir(os.path.join(self.root, n))), reverse=True)
        for z in zs:
            if len(self.tiles_at(z)):
                return z
        return None

    def tiles_at(self, z):
        """Tiles present on disk at zoom z: (K,2) int64 array of x, TMS y."""
        if z in self._listing:
            return self._listing[z]
        out = []
        zdir = os.path.join(self.root, str(z))
        ncols, nrows = grid_size(self.proj, z)
        if os.path.isdir(zdir):
            for xs in os.listdir(zdir):
                if not xs.isdigit():
                    continue
                try:
                    ents = os.listdir(os.path.join(zdir, xs))
                except OSError:
                    continue
                x = int(xs)
                for fn in ents:
                    if not fn.endswith(self.ext):
                        continue
                    ys = fn[:len(fn) - len(self.ext)] if self.ext else fn
                    if ys.isdigit() and x < ncols and int(ys) < nrows:
                        out.append((x, int(ys)))
        a = np.array(sorted(out), dtype=np.int64).reshape(-1, 2)
        if self.scheme == "slippyMap" and a.size:
            a[:, 1] = nrows - 1 - a[:, 1]
        self._listing[z] = a
        return a

    def path(self, z, x, y_tms):
        y = y_tms
        if self.scheme == "slippyMap":
            y = grid_size(self.proj, z)[1] - 1 - y_tms
        return os.path.join(self.root, str(z), str(x), "%d%s" % (y, self.ext))

    def available_check(self, z, tiles):
        """Compare layer.json's "available" rectangles at z with the files."""
        av = self.layer.get("available")
        if not isinstance(av, list):
            return None
        if z >= len(av):
            return {"listed": 0, "on_disk_not_listed": int(len(tiles)),
                    "listed_not_on_disk": 0}
        rects = av[z] or []
        listed = 0
        inrect = np.zeros(len(tiles), dtype=bool)
        if len(rects) * len(tiles) > 50_000_000:
            return {"skipped": "too many rectangles x tiles"}
        nrows = grid_size(self.proj, z)[1]
        for r in rects:
            try:
                sx, sy, ex, ey = (int(r["startX"]), int(r["startY"]),
                                  int(r["endX"]), int(r["endY"]))
            except (KeyError, TypeError, ValueError):
                continue
            if self.scheme == "slippyMap":
                sy, ey = nrows - 1 - ey, nrows - 1 - sy
            listed += (ex - sx + 1) * (ey - sy + 1)
            if len(tiles):
                inrect |= ((tiles[:, 0] >= sx) & (tiles[:, 0] <= ex) &
                           (tiles[:, 1] >= sy) & (tiles[:, 1] <= ey))
        on_listed = int(inrect.sum())
        return {"listed": int(listed),
                "on_disk_not_listed": int(len(tiles) - on_listed),
                "listed_not_on_disk": int(max(0, listed - on_listed))}


class QMCache:
    """Decodes tiles on demand; keeps a small LRU of full meshes and the
    summary of every tile decoded so far."""

    def __init__(self, ts, z, lru=32):
        self.ts, self.z, self.lru = ts, z, lru
        self.meshes = {}
        self.summaries = {}
        self.bad = {}

    def mesh(self, x, y):
        key = (x, y)
        if key in self.bad:
            return None
        m = self.meshes.pop(key, None)
        if m is None:
            try:
                with open(self.ts.path(self.z, x, y), "rb") as f:
                    data = f.read()
                m = decode_quantized_mesh(data)
            except (OSError, QMError, EOFError, zlib.error,
                    gzip.BadGzipFile) as e:
                self.bad[key] = str(e)
                return None
            if key not in self.summaries:
                self.summaries[key] = summarize_tile(m)
        self.meshes[key] = m
        while len(self.meshes) > self.lru:
            self.meshes.pop(next(iter(self.meshes)))
        return m

    def summary(self, x, y):
        key = (x, y)
        if key not in self.summaries and key not in self.bad:
            self.mesh(x, y)
        return self.summaries.get(key)


def edge_compare(pa, ha, pb, hb, thr):
    """Vertices of side A against side B's edge polyline. Returns counts
    (vertices, cracked, t_junctions, gaps) and the largest height difference
    where B covers A's position."""
    n = int(pa.size)
    if n == 0:
        return 0, 0, 0, 0, 0.0
    if pb.size == 0:
        return n, n, n, n, 0.0
    o = np.argsort(pb, kind="stable")
    pb, hb = pb[o].astype(np.float64), hb[o]
    pa = pa.astype(np.float64)
    covered = (pa >= pb[0]) & (pa <= pb[-1])
    diff = np.abs(ha - np.interp(pa, pb, hb))
    cracked = (~covered) | (diff > thr)
    tj = ~np.isin(pa, pb)
    mx = float(diff[covered].max()) if covered.any() else 0.0
    return (n, int(cracked.sum()), int(tj.sum()), int((~covered).sum()), mx)


def sample_points_in_tiles(rng, proj, z, tiles, src, n_points):
    """N points uniform in lon/lat over the union of the given TMS tiles,
    restricted to the source's valid region and nodata-free neighbourhoods.
    Returns (tile index, lon, lat, px, py, source value, counters)."""
    w, s, e, n = tile_bounds(proj, z, tiles[:, 0], tiles[:, 1])
    # Equal lon widths; weight by lat height so that lat is uniform (3857).
    wt = (n - s) / (n - s).sum()
    acc = {k: [] for k in ("ti", "lon", "lat", "px", "py", "val")}
    drawn = nodata = got = 0
    max_draw = max(200 * n_points, 100_000)
    while got < n_points and drawn < max_draw:
        b = min(max(2 * (n_points - got), 1024), max_draw - drawn)
        ti = rng.choice(len(tiles), size=b, p=wt)
        lon = w[ti] + rng.random(b) * (e[ti] - w[ti])
        lat = s[ti] + rng.random(b) * (n[ti] - s[ti])
        drawn += b
        px, py = src.pixel_coords(lon, lat)
        m = src.inside(px, py)
        val, ok = src.bilinear(px[m], py[m])
        nodata += int((~ok).sum())
        sel = np.flatnonzero(m)[ok][:n_points - got]
        val = val[ok][:n_points - got]
        for k, a in (("ti", ti), ("lon", lon), ("lat", lat), ("px", px),
                     ("py", py)):
            acc[k].append(a[sel])
        acc["val"].append(val)
        got += sel.size
    out = {k: (np.concatenate(v) if v else np.zeros(0))
           for k, v in acc.items()}
    out["ti"] = out["ti"].astype(np.int64)
    return out, {"drawn": drawn, "source_nodata_skipped": nodata}


def worst_points(err, lon, lat, tile_xy, got, want, k=5):
    if err.size == 0:
        return []
    idx = np.argsort(-np.abs(err))[:k]
    return [{"lon": round(float(lon[i]), 7), "lat": round(float(lat[i]), 7),
             "tile": [int(tile_xy[i][0]), int(tile_xy[i][1])],
             "tile_height": float(got[i]), "source_height": float(want[i]),
             "error": float(err[i])} for i in idx]


def check_quantized_mesh(src, ts, args):
    t_start = time.time()
    z = args.zoom if args.zoom is not None else ts.finest_zoom()
    if z is None:
        raise InputError("no %s tiles under %s" % (ts.ext or "tile", ts.root))
    tiles = ts.tiles_at(z)
    if not len(tiles):
        raise InputError("no tiles at zoom %d under %s" % (z, ts.root))
    ncols, nrows = grid_size(ts.proj, z)
    res = {"format": "qm", "container": "folder",
           "projection": ts.proj, "scheme": ts.scheme, "zoom": z,
           "tiles_at_zoom": int(len(tiles)),
           "notes": list(ts.notes) + list(src.notes)}
    av = ts.available_check(z, tiles)
    if av is not None:
        res["layer_available"] = av
    rng = np.random.default_rng(args.seed)
    cand = tiles[tiles_touching(ts.proj, z, tiles, src)]
    cache = QMCache(ts, z)
    if len(cand):
        pts, cnt = sample_points_in_tiles(rng, ts.proj, z, cand, src,
                                          args.points)
    else:
        pts, cnt = {k: np.zeros(0) for k in ("lon", "lat", "px", "py",
                                             "val")}, {"drawn": 0,
                                                       "source_nodata_skipped":
                                                       0}
        pts["ti"] = np.zeros(0, dtype=np.int64)
    npts = pts["ti"].size
    tile_h = np.full(npts, np.nan)
    hole = np.zeros(npts, dtype=bool)
    badpt = np.zeros(npts, dtype=bool)
    # Decode each needed tile once, for all of its points.
    order = np.argsort(pts["ti"], kind="stable")
    uniq, starts = np.unique(pts["ti"][order], return_index=True)
    ends = np.append(starts[1:], npts)
    for ti, s0, s1 in zip(uniq, starts, ends):
        idx = order[s0:s1]
        x, y = int(cand[ti, 0]), int(cand[ti, 1])
        mesh = cache.mesh(x, y)
        if mesh is None:
            badpt[idx] = True
            continue
        pu, pv = lonlat_to_uv(ts.proj, z, x, y, pts["lon"][idx],
                              pts["lat"][idx])
        h, found = interpolate_in_mesh(mesh, np.clip(pu, 0, QMAX),
                                       np.clip(pv, 0, QMAX))
        tile_h[idx] = h
        hole[idx[~found]] = True
    good = ~hole & ~badpt
    err = tile_h[good] - pts["val"][good]
    sval, sok = src.bilinear(pts["px"][good] - 0.5, pts["py"][good] - 0.5)
    serr = tile_h[good][sok] - sval[sok]
    txy = cand[pts["ti"][good]] if npts else np.zeros((0, 2), np.int64)
    res["points"] = {"requested": args.points, "seed": args.seed,
                     "sampled": int(npts), "compared": int(good.sum()),
                     "holes": int(hole.sum()),
                     "bad_tile_points": int(badpt.sum()),
                     "source_nodata_skipped": cnt["source_nodata_skipped"],
                     "drawn": cnt["drawn"]}
    res["error"] = error_stats(err)
    res["shifted_half_pixel_se"] = error_stats(serr)
    res["worst"] = worst_points(err, pts["lon"][good], pts["lat"][good], txy,
                                tile_h[good], pts["val"][good])
    res["worst_tile_rows"] = "tms"
    if hole.any():
        hi = np.flatnonzero(hole)[:5]
        res["hole_examples"] = [{"lon": round(float(pts["lon"][i]), 7),
                                 "lat": round(float(pts["lat"][i]), 7),
                                 "tile": [int(cand[pts["ti"][i], 0]),
                                          int(cand[pts["ti"][i], 1])]}
                                for i in hi]

    # Cracks between finest-zoom neighbours (sampled pairs).
    keys = tiles[:, 0] * nrows + tiles[:, 1]
    ks = np.sort(keys)

    def exists(xx, yy):
        k = xx * nrows + yy
        p = np.clip(np.searchsorted(ks, k), 0, len(ks) - 1)
        return ks[p] == k

    ex = (tiles[:, 0] + 1) % ncols                  # east, across 180 too
    em = exists(ex, tiles[:, 1]) & (ex != tiles[:, 0])
    nm = (tiles[:, 1] + 1 < nrows)
    nm &= exists(tiles[:, 0], np.minimum(tiles[:, 1] + 1, nrows - 1))
    pairs = ([("EW", int(a[0]), int(a[1]), int(b), int(a[1]))
              for a, b in zip(tiles[em], ex[em])] +
             [("NS", int(a[0]), int(a[1]), int(a[0]), int(a[1]) + 1)
              for a in tiles[nm]])
    total_pairs = len(pairs)
    prng = np.random.default_rng([args.seed, 1])
    if total_pairs > args.crack_tiles:
        pick = np.sort(prng.choice(total_pairs, size=args.crack_tiles,
                                   replace=False))
        pairs = [pairs[i] for i in pick]
    c = {"pairs_total": total_pairs, "pairs_checked": 0,
         "pairs_skipped_bad_tile": 0, "edge_vertices_checked": 0,
         "cracked_vertices": 0, "pairs_with_cracks": 0, "max_crack_m": 0.0,
         "t_junctions": 0, "gap_vertices": 0, "antimeridian_pairs": 0,
         "examples": []}
    for kind, x0, y0, x1, y1 in pairs:
        a = cache.summary(x0, y0)
        b = cache.summary(x1, y1)
        if a is None or b is None:
            c["pairs_skipped_bad_tile"] += 1
            continue
        sa, sb = ("E", "W") if kind == "EW" else ("N", "S")
        thr = max(a.step, b.step) + 1e-3
        (pa, ha), (pb, hb) = a.sides[sa], b.sides[sb]
        r1 = edge_compare(pa, ha, pb, hb, thr)
        r2 = edge_compare(pb, hb, pa, ha, thr)
        c["pairs_checked"] += 1
        if kind == "EW" and x1 < x0:
            c["antimeridian_pairs"] += 1
        c["edge_vertices_checked"] += r1[0] + r2[0]
        cr = r1[1] + r2[1]
        c["cracked_vertices"] += cr
        c["t_junctions"] += r1[2] + r2[2]
        c["gap_vertices"] += r1[3] + r2[3]
        # Largest height disagreement seen where both sides cover the edge.
        mx = max(r1[4], r2[4])
        if cr:
            c["pairs_with_cracks"] += 1
            c["max_crack_m"] = max(c["max_crack_m"], mx)
            if len(c["examples"]) < 5:
                c["examples"].append({"pair": kind, "tiles": [[x0, y0],
                                                              [x1, y1]],
                                      "cracked_vertices": cr,
                                      "max_diff_m": mx})
    res["cracks"] = c

    # Triangle and format statistics over every tile decoded above.
    tri = {"tiles_decoded": len(cache.summaries), "triangles": 0,
           "degenerate": 0, "degenerate_repeated_index": 0, "clockwise": 0}
    problems = {}
    exts = {}
    for s in cache.summaries.values():
        tri["triangles"] += s.triangles
        tri["degenerate"] += s.degenerate
        tri["degenerate_repeated_index"] += s.repeated
        tri["clockwise"] += s.clockwise
        for p in s.problems:
            problems[p] = problems.get(p, 0) + 1
        for e in s.extensions:
            exts[str(e)] = exts.get(str(e), 0) + 1
    res["triangles"] = tri
    res["tile_problems"] = problems
    res["extensions_seen"] = exts
    res["bad_tiles"] = len(cache.bad)
    res["bad_tile_examples"] = ["%d/%d/%d: %s" % (z, k[0], k[1], v)
                                for k, v in list(cache.bad.items())[:5]]
    res["seconds"] = round(time.time() - t_start, 3)
    return res


# --------------------------------------------------------------------------
# Raster DEM containers (rows returned as TMS rows, like everything else)
# --------------------------------------------------------------------------
def read_varint(buf, pos):
    result = shift = 0
    while True:
        if pos >= len(buf):
            raise InputError("PMTiles directory truncated (varint)")
        b = buf[pos]
        pos += 1
        result |= (b & 0x7F) << shift
        if not b & 0x80:
            return result, pos
        shift += 7


def pmtiles_zxy_to_id(z, x, y):
    """PMTiles v3 tile id: tiles of lower zooms first, then the position
    on the zoom's Hilbert curve (x, y in XYZ rows)."""
    acc = ((1 << (2 * z)) - 1) // 3
    n = 1 << z
    d = 0
    s = n >> 1
    while s > 0:
        rx = 1 if x & s else 0
        ry = 1 if y & s else 0
        d += s * s * ((3 * rx) ^ ry)
        if ry == 0:                        # rotate the quadrant
            if rx == 1:
                x = n - 1 - x
                y = n - 1 - y
            x, y = y, x
        s >>= 1
    return acc + d


def pmtiles_ids_to_xy(z, ids):
    """Vectorised inverse of pmtiles_zxy_to_id for ids of one zoom."""
    t = np.asarray(ids, dtype=np.int64) - ((1 << (2 * z)) - 1) // 3
    x = np.zeros_like(t)
    y = np.zeros_like(t)
    s = 1
    while s < (1 << z):
        rx = 1 & (t // 2)
        ry = 1 & (t ^ rx)
        rot = ry == 0
        flip = rot & (rx == 1)
        x = np.where(flip, s - 1 - x, x)
        y = np.where(flip, s - 1 - y, y)
        x, y = np.where(rot, y, x), np.where(rot, x, y)
        x = x + s * rx
        y = y + s * ry
        t = t // 4
        s *= 2
    return x, y


class PMTilesTiles:
    COMPRESSION = {0: "unknown", 1: "none", 2: "gzip", 3: "brotli", 4: "zstd"}

    def __init__(self, path):
        self.path = path
        self.kind = "pmtiles"
        try:
            self.f = open(path, "rb")
            hdr = self.f.read(127)
        except OSError as e:
            raise InputError("cannot read %s: %s" % (path, e))
        if len(hdr) < 127 or hdr[:7] != b"PMTiles":
            raise InputError("%s is not a PMTiles archive" % path)
        if hdr[7] != 3:
            raise InputError("%s: PMTiles version %d, only 3 is supported"
                             % (path, hdr[7]))
        (self.root_off, self.root_len, self.meta_off, self.meta_len,
         self.leaf_off, self.leaf_len, self.data_off, self.data_len,
         _, _, _) = struct.unpack_from("<11Q", hdr, 8)
        (_, self.internal_comp, self.tile_comp, self.tile_type,
         self.min_zoom, self.max_zoom) = struct.unpack_from("<6B", hdr, 96)
        self._index = {}

    def _read(self, off, length):
        self.f.seek(off)
        b = self.f.read(length)
        if len(b) != length:
            raise InputError("%s truncated" % self.path)
        return b

    def _decompress(self, b, comp):
        if comp in (0, 1) and b[:2] != b"\x1f\x8b":
            return b
        if comp == 2 or b[:2] == b"\x1f\x8b":
            return gzip.decompress(b)
        if comp == 3:
            try:
                import brotli
            except ImportError as e:
                _missing("python3-brotli", "brotli", e)
            return brotli.decompress(b)
        if comp == 4:
            try:
                import zstandard
            except ImportError as e:
                _missing("python3-zstandard", "zstandard", e)
            return zstandard.ZstdDecompressor().decompress(b)
        raise InputError("unknown PMTiles compression %d" % comp)

    def _directory(self, off, length):
        buf = self._decompress(self._read(off, length), self.internal_comp)
        n, pos = read_varint(buf, 0)
        ids, runs, lens, offs = [], [], [], []
        last = 0
        for _ in range(n):
            v, pos = read_varint(buf, pos)
            last += v
            ids.append(last)
        for _ in range(n):
            v, pos = read_varint(buf, pos)
            runs.append(v)
        for _ in range(n):
            v, pos = read_varint(buf, pos)
            lens.append(v)
        for i in range(n):
            v, pos = read_varint(buf, pos)
            if v == 0 and i > 0:
                offs.append(offs[-1] + lens[i - 1])
            else:
                offs.append(v - 1)
        return list(zip(ids, runs, lens, offs))

    def _tiles_of_zoom(self, z):
        """Index of zoom z: sorted tile ids with data offset and length."""
        if z in self._index:
            return self._index[z]
        lo = ((1 << (2 * z)) - 1) // 3
        hi = ((1 << (2 * (z + 1))) - 1) // 3         # exclusive
        ids, offs, lens = [], [], []

        def walk(off, length, depth):
            if depth > 8:
                raise InputError("PMTiles leaf directories nested too deep")
            ents = self._directory(off, length)
            for i, (tid, run, ln, of) in enumerate(ents):
                nxt = ents[i + 1][0] if i + 1 < len(ents) else None
                if run == 0:                        # leaf directory
                    if tid < hi and (nxt is None or nxt > lo):
                        walk(self.leaf_off + of, ln, depth + 1)
                    continue
                for t in range(max(tid, lo), min(tid + run, hi)):
                    ids.append(t)
                    offs.append(of)
                    lens.append(ln)

        walk(self.root_off, self.root_len, 0)
        o = np.argsort(np.array(ids, dtype=np.int64), kind="stable")
        r = (np.array(ids, dtype=np.int64)[o], np.array(offs, np.int64)[o],
             np.array(lens, np.int64)[o])
        self._index[z] = r
        return r

    def zooms(self):
        """The finest zoom holding tiles (header max zoom downwards)."""
        for z in range(self.max_zoom, -1, -1):
            if len(self._tiles_of_zoom(z)[0]):
                return [z]
        return []

    def tiles_at(self, z):
        ids = self._tiles_of_zoom(z)[0]
        x, y = pmtiles_ids_to_xy(z, ids)
        return np.stack([x, (1 << z) - 1 - y], axis=1).reshape(-1, 2)

    def read(self, z, x, y_tms):
        ids, offs, lens = self._tiles_of_zoom(z)
        t = pmtiles_zxy_to_id(z, x, (1 << z) - 1 - y_tms)
        p = np.searchsorted(ids, t)
        if p >= len(ids) or ids[p] != t:
            return None
        b = self._read(self.data_off + int(offs[p]), int(lens[p]))
        return self._decompress(b, self.tile_comp)

    def metadata(self):
        if not self.meta_len:
            return {}
        try:
            b = self._decompress(self._read(self.meta_off, self.meta_len),
                                 self.internal_comp)
            m = json.loads(b.decode("utf-8"))
            return m if isinstance(m, dict) else {}
        except (ValueError, OSError, zlib.error):
            return {}


class MBTilesTiles:
    def __init__(self, path):
        self.path = path
        self.kind = "mbtiles"
        try:
            self.db = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
            self.db.execute("SELECT zoom_level, tile_column, tile_row, "
                            "tile_data FROM tiles LIMIT 1").fetchall()
        except sqlite3.Error as e:
            raise InputError("cannot read MBTiles %s: %s" % (path, e))

    def zooms(self):
        return [r[0] for r in self.db.execute(
            "SELECT DISTINCT zoom_level FROM tiles ORDER BY zoom_level")]

    def tiles_at(self, z):
        rows = self.db.execute("SELECT tile_column, tile_row FROM tiles "
                               "WHERE zoom_level=?", (z,)).fetchall()
        return np.array(rows, dtype=np.int64).reshape(-1, 2)   # TMS rows

    def read(self, z, x, y_tms):
        r = self.db.execute("SELECT tile_data FROM tiles WHERE zoom_level=? "
                            "AND tile_column=? AND tile_row=?",
                            (z, x, y_tms)).fetchone()
        return maybe_gunzip(bytes(r[0])) if r else None

    def metadata(self):
        try:
            return dict(self.db.execute("SELECT name, value FROM metadata"))
        except sqlite3.Error:
            return {}


class FolderTiles:
    EXTS = (".png", ".webp")

    def __init__(self, root, scheme):
        self.root = root
        self.kind = "folder"
        self.scheme = scheme
        self._paths = {}

    def zooms(self):
        return sorted(int(d) for d in os.listdir(self.root)
                      if d.isdigit() and len(self.tiles_at(int(d))))

    def tiles_at(self, z):
        out = []
        zdir = os.path.join(self.root, str(z))
        if os.path.isdir(zdir):
            for xs in os.listdir(zdir):
                if not xs.isdigit() or not os.path.isdir(os.path.join(zdir,
                                                                      xs)):
                    continue
                for fn in os.listdir(os.path.join(zdir, xs)):
                    stem, ext = os.path.splitext(fn)
                    if ext.lower() in self.EXTS and stem.isdigit():
                        y = int(stem)
                        if y >= (1 << z) or int(xs) >= (1 << z):
                            continue
                        if self.scheme == "xyz":
                            y = (1 << z) - 1 - y
                        out.append((int(xs), y))
                        self._paths[(z, int(xs), y)] = os.path.join(zdir, xs,
                                                                    fn)
        return np.array(sorted(out), dtype=np.int64).reshape(-1, 2)

    def read(self, z, x, y_tms):
        p = self._paths.get((z, x, y_tms))
        if p is None:
            return None
        with open(p, "rb") as f:
            return maybe_gunzip(f.read())

    def metadata(self):
        for name in ("metadata.json", "tiles.json", "tilejson.json"):
            p = os.path.join(self.root, name)
            if os.path.exists(p):
                try:
                    with open(p, "rb") as f:
                        m = json.loads(f.read().decode("utf-8"))
                    if isinstance(m, dict):
                        return m
                except (OSError, ValueError):
                    pass
        return {}


def decode_rgb_heights(rgb, encoding):
    r, g, b = (rgb[..., k].astype(np.float64) for k in range(3))
    if encoding == "terrarium":
        return r * 256.0 + g + b / 256.0 - 32768.0
    return -10000.0 + (r * 65536.0 + g * 256.0 + b) * 0.1


def encoding_from_metadata(meta):
    for key in ("encoding", "raster_encoding", "dem_encoding"):
        v = str(meta.get(key, "")).lower().replace("_", "-")
        if v in ("terrarium",):
            return "terrarium"
        if v in ("mapbox", "terrain-rgb", "terrainrgb", "mapbox-terrain-rgb"):
            return "terrain-rgb"
    return None


def check_raster(src, cont, args):
    t_start = time.time()
    Image = _import_pil()
    zooms = cont.zooms()
    if not zooms:
        raise InputError("no tiles in %s" % cont.path if hasattr(cont, "path")
                         else "no tiles")
    z = args.zoom if args.zoom is not None else zooms[-1]
    tiles = cont.tiles_at(z)
    if not len(tiles):
        raise InputError("no tiles at zoom %d" % z)
    res = {"container": cont.kind, "projection": "EPSG:3857", "zoom": z,
           "tiles_at_zoom": int(len(tiles)), "notes": list(src.notes)}
    cand = tiles[tiles_touching("EPSG:3857", z, tiles, src)]
    if not len(cand):
        raise InputError("no tile at zoom %d overlaps the source" % z)
    # Tile pixel size, from the first readable tile.
    size = None
    for x, y in cand[:16]:
        data = cont.read(z, int(x), int(y))
        if data:
            try:
                size = Image.open(io.BytesIO(data)).size
                break
            except OSError:
                continue
    if size is None:
        raise InputError("cannot decode any tile image at zoom %d" % z)
    TW, TH = size
    res["tile_size"] = [TW, TH]
    n = float(1 << z)
    rng = np.random.default_rng(args.seed)
    acc = {k: [] for k in ("ti", "i", "j", "lon", "lat", "px", "py", "val")}
    drawn = nodata = got = 0
    N = args.points
    max_draw = max(200 * N, 100_000)
    while got < N and drawn < max_draw:
        b = min(max(2 * (N - got), 1024), max_draw - drawn)
        ti = rng.integers(len(cand), size=b)
        i = rng.integers(TW, size=b)
        j = rng.integers(TH, size=b)         # j = 0 is the tile's top row
        drawn += b
        gx = cand[ti, 0] + (i + 0.5) / TW
        gy_s = cand[ti, 1] + 1 - (j + 0.5) / TH      # from the south
        lon = gx / n * 360.0 - 180.0
        lat = lat_from_merc_frac(gy_s / n)
        px, py = src.pixel_coords(lon, lat)
        m = src.inside(px, py)
        val, ok = src.bilinear(px[m], py[m])
        nodata += int((~ok).sum())
        sel = np.flatnonzero(m)[ok][:N - got]
        for k, a in (("ti", ti), ("i", i), ("j", j), ("lon", lon),
                     ("lat", lat), ("px", px), ("py", py)):
            acc[k].append(a[sel])
        acc["val"].append(val[ok][:N - got])
        got += sel.size
    pts = {k: np.concatenate(v) for k, v in acc.items()}
    for k in ("ti", "i", "j"):
        pts[k] = pts[k].astype(np.int64)
    npts = pts["ti"].size
    rgba = np.zeros((npts, 4), dtype=np.uint8)
    badpt = np.zeros(npts, dtype=bool)
    bad = {}
    order = np.argsort(pts["ti"], kind="stable")
    uniq, starts = np.unique(pts["ti"][order], return_index=True)
    ends = np.append(starts[1:], npts)
    for ti, s0, s1 in zip(uniq, starts, ends):
        idx = order[s0:s1]
        x, y = int(cand[ti, 0]), int(cand[ti, 1])
        try:
            data = cont.read(z, x, y)
            if data is None:
                raise OSError("tile missing")
            img = Image.open(io.BytesIO(data))
            if img.size != (TW, TH):
                raise OSError("tile size %s differs from %s" % (img.size,
                                                                 (TW, TH)))
            a = np.asarray(img.convert("RGBA"))
        except (OSError, ValueError, zlib.error) as e:
            bad[(x, y)] = str(e)
            badpt[idx] = True
            continue
        rgba[idx] = a[pts["j"][idx], pts["i"][idx]]
    tile_nodata = (rgba[:, 3] == 0) & ~badpt
    good = ~badpt & ~tile_nodata
    enc = args.format
    if enc:
        res["format_from"] = "--format"
    else:
        enc = encoding_from_metadata(cont.metadata())
        if enc:
            res["format_from"] = "metadata encoding"
        else:
            # No metadata: pick the encoding that agrees with the source.
            e1 = np.median(np.abs(decode_rgb_heights(rgba[good], "terrarium")
                                  - pts["val"][good])) if good.any() else 0
            e2 = np.median(np.abs(decode_rgb_heights(rgba[good],
                                                     "terrain-rgb")
                                  - pts["val"][good])) if good.any() else 1
            enc = "terrarium" if e1 <= e2 else "terrain-rgb"
            res["format_from"] = "guessed: better agreement with the source"
    res["format"] = enc
    res["height_quantum_m"] = 1.0 / 256 if enc == "terrarium" else 0.1
    th = decode_rgb_heights(rgba, enc)
    err = th[good] - pts["val"][good]
    sval, sok = src.bilinear(pts["px"][good] - 0.5, pts["py"][good] - 0.5)
    serr = th[good][sok] - sval[sok]
    res["points"] = {"requested": N, "seed": args.seed, "sampled": int(npts),
                     "compared": int(good.sum()),
                     "tile_nodata": int(tile_nodata.sum()),
                     "bad_tile_points": int(badpt.sum()),
                     "source_nodata_skipped": nodata, "drawn": drawn}
    res["error"] = error_stats(err)
    res["shifted_half_pixel_se"] = error_stats(serr)
    txy = cand[pts["ti"][good]]
    txy_xyz = np.stack([txy[:, 0], (1 << z) - 1 - txy[:, 1]], axis=1)
    res["worst"] = worst_points(err, pts["lon"][good], pts["lat"][good],
                                txy_xyz, th[good], pts["val"][good])
    res["worst_tile_rows"] = "xyz"
    res["bad_tiles"] = len(bad)
    res["bad_tile_examples"] = ["%d/%d/%d(tms): %s" % (z, k[0], k[1], v)
                                for k, v in list(bad.items())[:5]]
    res["seconds"] = round(time.time() - t_start, 3)
    return res


# --------------------------------------------------------------------------
# Driver
# --------------------------------------------------------------------------
def open_tileset(path, fmt, scheme):
    """-> ("qm", QMTileset) or ("raster", container)."""
    if os.path.isdir(path):
        if fmt == "qm" or os.path.exists(os.path.join(path, "layer.json")):
            return "qm", QMTileset(path)
        for dp, dn, fn in os.walk(path):
            if any(f.endswith(".terrain") for f in fn):
                return "qm", QMTileset(path)
            if dp.count(os.sep) - path.count(os.sep) > 3:
                break
        return "raster", FolderTiles(path, scheme)
    try:
        with open(path, "rb") as f:
            head = f.read(16)
    except OSError as e:
        raise InputError("cannot read tileset %s: %s" % (path, e))
    if head[:7] == b"PMTiles":
        return "raster", PMTilesTiles(path)
    if head[:16] == b"SQLite format 3\x00":
        return "raster", MBTilesTiles(path)
    raise InputError("%s is neither a folder, an MBTiles nor a PMTiles file"
                     % path)


def run_check(args):
    src = SourceDEM(args.source)
    kind, ts = open_tileset(args.tileset, args.format, args.scheme)
    if kind == "qm":
        if args.format not in (None, "qm"):
            raise InputError("%s is a quantized-mesh tileset" % args.tileset)
        res = check_quantized_mesh(src, ts, args)
        res["format_from"] = ("--format" if args.format
                              else "layer.json/.terrain")
    else:
        if args.format == "qm":
            raise InputError("%s is not a quantized-mesh folder"
                             % args.tileset)
        res = check_raster(src, ts, args)
    out = {"tool": "terrain_accuracy", "source": args.source,
           "tileset": args.tileset}
    out.update(res)
    return out


def _f(v, nd=4):
    return "-" if v is None else ("%.*f" % (nd, v))


def format_summary(r):
    L = []
    L.append("terrain_accuracy: %s  vs  %s" % (r["source"], r["tileset"]))
    L.append("  tileset: %s (%s, format from %s), %s, zoom %d, %d tiles%s"
             % (r["format"], r["container"], r.get("format_from", "?"),
                r["projection"], r["zoom"], r["tiles_at_zoom"],
                (", tile %dx%d px" % tuple(r["tile_size"]))
                if "tile_size" in r else ""))
    p = r["points"]
    extra = []
    if "holes" in p:
        extra.append("holes %d" % p["holes"])
    if "tile_nodata" in p:
        extra.append("tile nodata %d" % p["tile_nodata"])
    extra.append("in bad tiles %d" % p["bad_tile_points"])
    extra.append("source-nodata points skipped %d" %
                 p["source_nodata_skipped"])
    L.append("  points: %d compared of %d sampled (%d requested, seed %d); %s"
             % (p["compared"], p["sampled"], p["requested"], p["seed"],
                ", ".join(extra)))
    for label, key in (("height error (tile - source bilinear), m",
                        "error"),
                       ("vs source shifted half a pixel (tiles shifted SE?)",
                        "shifted_half_pixel_se")):
        s = r[key]
        L.append("  %s:" % label)
        L.append("    n %d  max|e| %s  p99|e| %s  p50|e| %s  mean %s  "
                 "rmse %s" % (s["n"], _f(s["max_abs"]), _f(s["p99_abs"]),
                              _f(s["p50_abs"]), _f(s["mean"]),
                              _f(s["rmse"])))
    if "height_quantum_m" in r:
        L.append("  encoding quantum %.4f m" % r["height_quantum_m"])
    if r.get("worst"):
        w = r["worst"][0]
        L.append("  worst: lon %.6f lat %.6f tile %d/%d: tile %.3f source "
                 "%.3f error %+.3f" % (w["lon"], w["lat"], w["tile"][0],
                                       w["tile"][1], w["tile_height"],
                                       w["source_height"], w["error"]))
    if "cracks" in r:
        c = r["cracks"]
        L.append("  cracks: %d neighbour pairs checked of %d (%d across "
                 "the antimeridian), %d edge vertices" %
                 (c["pairs_checked"], c["pairs_total"],
                  c["antimeridian_pairs"], c["edge_vertices_checked"]))
        L.append("    cracked vertices %d in %d pairs (max %.4f m), "
                 "T-junctions %d, vertices where the other side has no "
                 "edge %d" % (c["cracked_vertices"], c["pairs_with_cracks"],
                              c["max_crack_m"], c["t_junctions"],
                              c["gap_vertices"]))
    if "triangles" in r:
        t = r["triangles"]
        L.append("  triangles: %d tiles decoded, %d triangles, %d zero-area "
                 "in u,v (%d of them with a repeated vertex index), %d "
                 "clockwise" % (t["tiles_decoded"], t["triangles"],
                                t["degenerate"],
                                t["degenerate_repeated_index"],
                                t["clockwise"]))
    if r.get("extensions_seen"):
        L.append("  extensions (id: tiles): %s" % ", ".join(
            "%s: %d" % kv for kv in sorted(r["extensions_seen"].items())))
    if r.get("tile_problems"):
        for k, v in sorted(r["tile_problems"].items()):
            L.append("  tile problem: %s (%d tiles)" % (k, v))
    if "layer_available" in r:
        L.append("  layer.json available at this zoom: %s" %
                 json.dumps(r["layer_available"]))
    if r.get("bad_tiles"):
        L.append("  unreadable tiles: %d, e.g. %s" %
                 (r["bad_tiles"], "; ".join(r["bad_tile_examples"][:2])))
    for n in r.get("notes", []):
        L.append("  note: %s" % n)
    L.append("  (%.2f s)" % r.get("seconds", 0))
    return "\n".join(L)


# --------------------------------------------------------------------------
# Self-test: writers for synthetic tilesets (quantized-mesh, Terrarium,
# Terrain-RGB in a folder, MBTiles and PMTiles) and checks on them.
# --------------------------------------------------------------------------
def _st_geotiff(path, lon0, lat1, d, W, H, fn, nodata_block=None):
    """Float32 EPSG:4326 GeoTIFF with fn(lon, lat) at pixel centres."""
    drv = gdal.GetDriverByName("GTiff")
    ds = drv.Create(path, W, H, 1, gdal.GDT_Float32)
    ds.SetGeoTransform([lon0, d, 0, lat1, 0, -d])
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(4326)
    ds.SetProjection(srs.ExportToWkt())
    lon = lon0 + (np.arange(W) + 0.5) * d
    lat = lat1 - (np.arange(H) + 0.5) * d
    a = fn(lon[None, :], lat[:, None]).astype(np.float32)
    b = ds.GetRasterBand(1)
    if nodata_block is not None:
        c0, r0, c1, r1 = nodata_block
        a[r0:r1, c0:c1] = -9999
        b.SetNoDataValue(-9999)
    b.WriteArray(a)
    ds = None


def _st_grid_mesh(k, jitter=0, rng=None):
    """k x k vertex grid over the tile in u,v with two CCW triangles per
    cell; interior vertices optionally jittered."""
    g = np.rint(np.linspace(0, QMAX, k)).astype(np.int64)
    U, V = np.meshgrid(g, g, indexing="ij")           # U[i, j]: i along u
    if jitter and k > 2:
        cell = QMAX / (k - 1)
        J = int(cell * jitter)
        U[1:-1, 1:-1] += rng.integers(-J, J + 1, size=(k - 2, k - 2))
        V[1:-1, 1:-1] += rng.integers(-J, J + 1, size=(k - 2, k - 2))
    vid = np.arange(k * k).reshape(k, k)
    a, b = vid[:-1, :-1].ravel(), vid[1:, :-1].ravel()
    c, d = vid[1:, 1:].ravel(), vid[:-1, 1:].ravel()
    tris = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return U.ravel(), V.ravel(), tris


def _st_uv_lonlat(proj, z, x, y, u, v):
    w, s, e, n = tile_bounds(proj, z, x, y)
    lon = w + (e - w) * u / QMAX
    if proj == "EPSG:4326":
        lat = s + (n - s) * v / QMAX
    else:
        nn = float(1 << z)
        lat = lat_from_merc_frac((y + v / QMAX) / nn)
    return lon, lat


def _st_encode_qm(u, v, h, tris, gz=False, extensions=()):
    """quantized-mesh-1.0 bytes for integer u,v, heights h (metres) and
    triangles (vertex indices). Vertices are renumbered in order of first use
    so that high-water-mark encoding applies."""
    u, v, tris = np.asarray(u), np.asarray(v), np.asarray(tris)
    used = np.zeros(u.size, dtype=bool)
    first = []
    for i in tris.ravel():
        if not used[i]:
            used[i] = True
            first.append(i)
    first += [i for i in range(u.size) if not used[i]]
    perm = np.array(first, dtype=np.int64)
    new = np.empty_like(perm)
    new[perm] = np.arange(perm.size)
    u, v, h, tris = u[perm], v[perm], np.asarray(h)[perm], new[tris]
    hmin, hmax = float(np.float32(h.min())), float(np.float32(h.max()))
    if hmax <= hmin:
        hmax = hmin + 1.0
    hq = np.rint((h - hmin) / (hmax - hmin) * QMAX).astype(np.int64)
    hq = np.clip(hq, 0, QMAX)

    def zz(a):
        d = np.diff(np.concatenate([[0], a]))
        return np.where(d >= 0, 2 * d, -2 * d - 1).astype("<u2")

    vc = u.size
    out = bytearray()
    out += struct.pack("<3d2f4d3d", 6378137.0, 0, 0, hmin, hmax,
                       6378137.0, 0, 0, 1e5, 1, 0, 0)
    out += struct.pack("<I", vc)
    out += zz(u).tobytes() + zz(v).tobytes() + zz(hq).tobytes()
    wide = vc > 65536
    isz, itype = (4, "<u4") if wide else (2, "<u2")
    while len(out) % isz:
        out += b"\0"
    idx = tris.ravel().astype(np.int64)
    highest = np.concatenate([[0], np.maximum.accumulate(idx)[:-1] + 1])
    highest[0] = 0
    out += struct.pack("<I", tris.shape[0])
    out += (highest - idx).astype(itype).tobytes()
    for on in (u == 0, v == 0, u == QMAX, v == QMAX):
        e = np.flatnonzero(on)
        out += struct.pack("<I", e.size) + e.astype(itype).tobytes()
    for ext_id, payload in extensions:
        out += struct.pack("<BI", ext_id, len(payload)) + payload
    data = bytes(out)
    return gzip.compress(data) if gz else data


def _st_write_qm_set(root, proj, z, tiles, fn, gz=False, perturb=None,
                     drop=None):
    """tiles: {(x, y_tms): (grid k, jitter)}; fn(lon, lat) -> height."""
    os.makedirs(root, exist_ok=True)
    ncols, nrows = grid_size(proj, z)
    avail = [[] for _ in range(z + 1)]
    rng = np.random.default_rng(7)
    for (x, y), (k, jit) in sorted(tiles.items()):
        u, v, tris = _st_grid_mesh(k, jit, rng)
        lon, lat = _st_uv_lonlat(proj, z, x, y, u, v)
        h = fn(lon, lat)
        if perturb and perturb[0] == (x, y):
            side, dh = perturb[1], perturb[2]
            on = {"W": u == 0, "E": u == QMAX, "S": v == 0,
                  "N": v == QMAX}[side]
            mid = np.flatnonzero(on & (u > 0) & (u < QMAX) |
                                 on & (v > 0) & (v < QMAX))
            h = h.copy()
            h[mid[len(mid) // 2]] += dh
        if drop and drop == (x, y):
            # One triangle less (a hole), plus a repeated-index and a
            # collinear (west edge) zero-area triangle.
            tris = np.delete(tris, len(tris) // 4, axis=0)
            tris = np.concatenate([tris, [[0, 0, 1], [0, 1, 2]]])
        ext = [(1, bytes(2 * u.size))]         # octvertexnormals payload
        d = os.path.join(root, str(z), str(x))
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "%d.terrain" % y), "wb") as f:
            f.write(_st_encode_qm(u, v, h, tris, gz=gz, extensions=ext))
        avail[z].append({"startX": x, "startY": y, "endX": x, "endY": y})
    layer = {"tilejson": "2.1.0", "format": "quantized-mesh-1.0",
             "version": "1.0.0", "scheme": "tms", "projection": proj,
             "tiles": ["{z}/{x}/{y}.terrain?v={version}"],
             "available": avail}
    with open(os.path.join(root, "layer.json"), "w") as f:
        json.dump(layer, f)


def _st_png_tiles(z, tiles_xyz, fn, encoding, size=256):
    """{(x, y_xyz): png bytes} of fn sampled at pixel centres."""
    Image = _import_pil()
    out = {}
    n = float(1 << z)
    for x, y in tiles_xyz:
        i = np.arange(size) + 0.5
        lon = (x + i / size) / n * 360 - 180
        lat = lat_from_merc_frac(1 - (y + i / size) / n)
        h = fn(lon[None, :], lat[:, None])
        if encoding == "terrarium":
            q = np.rint((h + 32768.0) * 256).astype(np.int64)
            rgb = np.stack([q >> 16, (q >> 8) & 255, q & 255], axis=-1)
        else:
            q = np.rint((h + 10000.0) * 10).astype(np.int64)
            rgb = np.stack([q >> 16, (q >> 8) & 255, q & 255], axis=-1)
        buf = io.BytesIO()
        Image.fromarray(rgb.astype(np.uint8), "RGB").save(buf, "PNG")
        out[(x, y)] = buf.getvalue()
    return out


def _st_write_folder(root, z, pngs, tms=False):
    for (x, y), data in pngs.items():
        if tms:
            y = (1 << z) - 1 - y
        d = os.path.join(root, str(z), str(x))
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "%d.png" % y), "wb") as f:
            f.write(data)


def _st_write_mbtiles(path, z, pngs, encoding=None):
    if os.path.exists(path):
        os.remove(path)
    db = sqlite3.connect(path)
    db.execute("CREATE TABLE metadata (name text, value text)")
    db.execute("CREATE TABLE tiles (zoom_level integer, tile_column integer, "
               "tile_row integer, tile_data blob)")
    db.execute("INSERT INTO metadata VALUES ('format', 'png')")
    if encoding:
        db.execute("INSERT INTO metadata VALUES ('encoding', ?)", (encoding,))
    for (x, y), data in pngs.items():
        db.execute("INSERT INTO tiles VALUES (?, ?, ?, ?)",
                   (z, x, (1 << z) - 1 - y, data))
    db.commit()
    db.close()


def _st_varint(v):
    out = bytearray()
    while True:
        b = v & 0x7F
        v >>= 7
        if v:
            out.append(b | 0x80)
        else:
            out.append(b)
            return bytes(out)


def _st_pm_dir(entries):
    """Serialise (tile_id, offset, length, run_length) entries."""
    out = bytearray(_st_varint(len(entries)))
    last = 0
    for e in entries:
        out += _st_varint(e[0] - last)
        last = e[0]
    for e in entries:
        out += _st_varint(e[3])
    for e in entries:
        out += _st_varint(e[2])
    for i, e in enumerate(entries):
        if i > 0 and e[1] == entries[i - 1][1] + entries[i - 1][2]:
            out += _st_varint(0)
        else:
            out += _st_varint(e[1] + 1)
    return bytes(out)


def _st_write_pmtiles(path, z, pngs, meta, leaf=False, gz=False):
    """Minimal PMTiles v3 writer: tiles in tile-id order, one root directory
    (or a root pointing at one leaf directory), optional gzip of the
    directories and metadata."""
    items = sorted((pmtiles_zxy_to_id(z, x, y), d) for (x, y), d in
                   pngs.items())
    data = bytearray()
    entries = []
    for tid, d in items:
        entries.append((tid, len(data), len(d), 1))
        data += d
    comp = (lambda b: gzip.compress(b)) if gz else (lambda b: b)
    if leaf:
        leafb = comp(_st_pm_dir(entries))
        root = comp(_st_pm_dir([(entries[0][0], 0, len(leafb), 0)]))
    else:
        leafb = b""
        root = comp(_st_pm_dir(entries))
    metab = comp(json.dumps(meta).encode())
    root_off = 127
    meta_off = root_off + len(root)
    leaf_off = meta_off + len(metab)
    data_off = leaf_off + len(leafb)
    hdr = b"PMTiles" + struct.pack(
        "<B11Q6B4iB2i", 3, root_off, len(root), meta_off, len(metab),
        leaf_off, len(leafb), data_off, len(data), len(items), len(items),
        len(items), 1, 2 if gz else 1, 1, 2, z, z, 0, 0, 0, 0, z, 0, 0)
    assert len(hdr) == 127
    with open(path, "wb") as f:
        f.write(hdr + root + metab + leafb + bytes(data))


def self_test(keep=False):
    tmp = tempfile.mkdtemp(prefix="terrain_accuracy_", dir="/tmp")
    failures = []
    lines = []

    def check(name, cond, detail=""):
        lines.append("%s %s%s" % ("ok  " if cond else "FAIL", name,
                                  (": " + detail) if detail else ""))
        if not cond:
            failures.append(name)

    def run(src, ts, **kw):
        a = argparse.Namespace(source=src, tileset=ts, format=kw.get("fmt"),
                               zoom=kw.get("zoom"), points=kw.get("points",
                                                                  4000),
                               seed=1, crack_tiles=kw.get("crack", 2000),
                               scheme=kw.get("scheme", "xyz"), json=True)
        return run_check(a)

    def s(r):
        e = r["error"]
        return "n=%d max=%.5f mean=%+.5f rmse=%.5f" % (
            e["n"], e["max_abs"] or 0, e["mean"] or 0, e["rmse"] or 0)

    # PMTiles tile ids: values from the spec's reference implementations.
    ids = [pmtiles_zxy_to_id(0, 0, 0), pmtiles_zxy_to_id(1, 1, 0),
           pmtiles_zxy_to_id(2, 1, 3), pmtiles_zxy_to_id(3, 3, 0)]
    check("pmtiles tile ids", ids == [0, 4, 11, 26], str(ids))
    rt = True
    for z in range(0, 6):
        xs, ys = np.meshgrid(np.arange(1 << z), np.arange(1 << z))
        tid = [pmtiles_zxy_to_id(z, int(x), int(y))
               for x, y in zip(xs.ravel(), ys.ravel())]
        bx, by = pmtiles_ids_to_xy(z, tid)
        rt &= bool(np.array_equal(bx, xs.ravel()) and
                   np.array_equal(by, ys.ravel()))
    check("pmtiles id <-> z/x/y round trip (z 0..5)", rt)

    # Source: plane over lon -2..2, lat 43..47, 0.01 deg pixels, with a
    # nodata block; heights in metres.
    A, B, C = 150.0, -80.0, 5000.0

    def plane(lon, lat):
        return A * lon + B * lat + C

    src = os.path.join(tmp, "plane.tif")
    _st_geotiff(src, -2.0, 47.0, 0.01, 400, 400, plane,
                nodata_block=(180, 170, 220, 210))

    # quantized-mesh EPSG:4326, zoom 9: a 2x2 block of tiles around (0, 45):
    # grids of different density (T-junctions), a jittered grid, and one
    # tile with > 65536 vertices (32-bit indices).
    z = 9
    qt = {(511, 383): (17, 0.2), (512, 383): (9, 0),
          (511, 384): (257, 0), (512, 384): (5, 0)}
    for gz in (False, True):
        d = os.path.join(tmp, "qm4326" + ("_gz" if gz else ""))
        _st_write_qm_set(d, "EPSG:4326", z, qt, plane, gz=gz)
        r = run(src, d)
        e, c, t = r["error"], r["cracks"], r["triangles"]
        tag = "qm 4326 %s" % ("gzip" if gz else "plain")
        check(tag + " errors ~ 0", e["n"] > 3000 and e["max_abs"] < 0.01,
              s(r))
        check(tag + " no holes, nodata skipped",
              r["points"]["holes"] == 0 and
              r["points"]["source_nodata_skipped"] > 0,
              "holes %d, nodata skipped %d" % (
                  r["points"]["holes"], r["points"]["source_nodata_skipped"]))
        check(tag + " 4 pairs, 0 cracks, T-junctions > 0",
              c["pairs_checked"] == 4 and c["cracked_vertices"] == 0 and
              c["t_junctions"] > 0 and c["gap_vertices"] == 0,
              "pairs %d cracked %d tj %d gaps %d" % (
                  c["pairs_checked"], c["cracked_vertices"],
                  c["t_junctions"], c["gap_vertices"]))
        check(tag + " triangles", t["tiles_decoded"] == 4 and
              t["degenerate"] == 0 and t["clockwise"] == 0 and
              t["triangles"] == 2 * (16 * 16 + 8 * 8 + 256 * 256 + 4 * 4),
              json.dumps(t))
        check(tag + " no format problems", not r["tile_problems"] and
              r["extensions_seen"] == {"1": 4} and r["bad_tiles"] == 0,
              json.dumps(r["tile_problems"]))
        check(tag + " layer.json available agrees",
              r["layer_available"] == {"listed": 4, "on_disk_not_listed": 0,
                                       "listed_not_on_disk": 0})

    # The same with one west-edge vertex of tile 512/383 raised by 50 m.
    d = os.path.join(tmp, "qm4326_crack")
    _st_write_qm_set(d, "EPSG:4326", z, qt, plane, perturb=((512, 383), "W",
                                                            50.0))
    r = run(src, d)
    c = r["cracks"]
    check("qm perturbed edge vertex -> crack",
          c["cracked_vertices"] >= 1 and c["pairs_with_cracks"] == 1 and
          45 < c["max_crack_m"] < 55,
          "cracked %d in %d pairs, max %.3f m" % (
              c["cracked_vertices"], c["pairs_with_cracks"], c["max_crack_m"]))

    # A missing triangle -> holes.
    d = os.path.join(tmp, "qm4326_hole")
    _st_write_qm_set(d, "EPSG:4326", z, qt, plane, drop=(512, 384))
    r = run(src, d)
    t = r["triangles"]
    check("qm missing triangle -> holes", r["points"]["holes"] > 0 and
          r["error"]["max_abs"] < 0.01 and r["cracks"]["cracked_vertices"]
          == 0, "holes %d" % r["points"]["holes"])
    check("qm zero-area triangles counted", t["degenerate"] == 2 and
          t["degenerate_repeated_index"] == 1, json.dumps(t))

    # quantized-mesh EPSG:3857 (u,v linear in mercator; plane in lon only so
    # that linear interpolation is exact).
    def plane_lon(lon, lat):
        return 300.0 * lon + 1000.0 + 0 * lat

    src2 = os.path.join(tmp, "plane_lon.tif")
    _st_geotiff(src2, -2.0, 47.0, 0.01, 400, 400, plane_lon)
    z3 = 9
    fx = merc_frac_from_lat(45.0) * (1 << z3)
    y3 = int(fx)
    d = os.path.join(tmp, "qm3857")
    _st_write_qm_set(d, "EPSG:3857", z3, {(255, y3): (33, 0.2),
                                          (256, y3): (17, 0),
                                          (255, y3 + 1): (9, 0)}, plane_lon,
                     gz=True)
    r = run(src2, d)
    check("qm 3857 errors ~ 0, 2 pairs, 0 cracks",
          r["error"]["n"] > 3000 and r["error"]["max_abs"] < 0.01 and
          r["cracks"]["pairs_checked"] == 2 and
          r["cracks"]["cracked_vertices"] == 0, s(r))

    # Global EPSG:4326 zoom 0 (two tiles): the east-west pair across the
    # antimeridian must be checked; a plane in latitude has no crack there,
    # one in longitude must show cracks.
    srcg = os.path.join(tmp, "global_lat.tif")
    _st_geotiff(srcg, -180.0, 90.0, 1.0, 360, 180,
                lambda lon, lat: 2.0 * lat + 0 * lon)
    d = os.path.join(tmp, "qm_global")
    _st_write_qm_set(d, "EPSG:4326", 0, {(0, 0): (33, 0), (1, 0): (17, 0)},
                     lambda lon, lat: 2.0 * lat + 0 * lon)
    r = run(srcg, d)
    c = r["cracks"]
    check("qm global: antimeridian pair, no cracks",
          c["pairs_total"] == 2 and c["antimeridian_pairs"] == 1 and
          c["cracked_vertices"] == 0 and r["error"]["max_abs"] < 0.02,
          "pairs %d (antimeridian %d) cracked %d; %s" % (
              c["pairs_total"], c["antimeridian_pairs"],
              c["cracked_vertices"], s(r)))
    srcg2 = os.path.join(tmp, "global_lon.tif")
    _st_geotiff(srcg2, -180.0, 90.0, 1.0, 360, 180,
                lambda lon, lat: 1.0 * lon + 0 * lat)
    d = os.path.join(tmp, "qm_global_lon")
    _st_write_qm_set(d, "EPSG:4326", 0, {(0, 0): (33, 0), (1, 0): (17, 0)},
                     lambda lon, lat: 1.0 * lon + 0 * lat)
    r = run(srcg2, d)
    c = r["cracks"]
    check("qm global lon plane: cracks only across the antimeridian",
          c["pairs_with_cracks"] == 1 and c["cracked_vertices"] > 0 and
          c["examples"][0]["tiles"] == [[1, 0], [0, 0]] and
          r["error"]["max_abs"] < 0.02,
          "cracked %d in %d pairs, %s" % (c["cracked_vertices"],
                                          c["pairs_with_cracks"],
                                          c["examples"][:1]))
    # A source whose longitudes run 0..360 (matched modulo 360).
    srcg3 = os.path.join(tmp, "global_lat_0_360.tif")
    _st_geotiff(srcg3, 0.0, 90.0, 1.0, 360, 180,
                lambda lon, lat: 2.0 * lat + 0 * lon)
    r = run(srcg3, os.path.join(tmp, "qm_global"))
    check("source with longitudes 0..360", r["error"]["n"] > 3000 and
          r["error"]["max_abs"] < 0.02, s(r))

    # Raster DEM: Terrarium and Terrain-RGB, zoom 10, 2x2 tiles around
    # (0, 45) in XYZ rows; folder, MBTiles, PMTiles.
    zr = 10
    yr = int((1 - merc_frac_from_lat(45.0)) * (1 << zr))
    txyz = [(511, yr), (512, yr), (511, yr + 1), (512, yr + 1)]
    quant = {"terrarium": 1.0 / 256, "terrain-rgb": 0.1}
    for enc in ("terrarium", "terrain-rgb"):
        pngs = _st_png_tiles(zr, txyz, plane, enc)
        q = quant[enc]
        meta_enc = "terrarium" if enc == "terrarium" else "mapbox"
        outs = []
        d = os.path.join(tmp, "folder_" + enc)
        _st_write_folder(d, zr, pngs)
        outs.append(("folder (format guessed)", run(src, d)))
        d2 = os.path.join(tmp, "folder_tms_" + enc)
        _st_write_folder(d2, zr, pngs, tms=True)
        outs.append(("folder tms", run(src, d2, fmt=enc, scheme="tms")))
        p = os.path.join(tmp, enc + ".mbtiles")
        _st_write_mbtiles(p, zr, pngs, encoding=meta_enc)
        outs.append(("mbtiles", run(src, p)))
        p = os.path.join(tmp, enc + ".pmtiles")
        _st_write_pmtiles(p, zr, pngs, {"encoding": meta_enc})
        outs.append(("pmtiles", run(src, p)))
        p = os.path.join(tmp, enc + "_leaf_gz.pmtiles")
        _st_write_pmtiles(p, zr, pngs, {"encoding": meta_enc}, leaf=True,
                          gz=True)
        outs.append(("pmtiles leaf+gzip", run(src, p)))
        for name, r in outs:
            check("%s %s within quantum/2" % (enc, name),
                  r["format"] == enc and r["error"]["n"] == 4000 and
                  r["error"]["max_abs"] <= q / 2 + 1e-3 and
                  r["points"]["source_nodata_skipped"] > 0, s(r))

    # Half-pixel south-east shift (a known peer defect): the tileset holds
    # the source at (lon - dx/2, lat + dy/2).
    dx = 0.01
    pngs = _st_png_tiles(zr, txyz, lambda lon, lat: plane(lon - dx / 2,
                                                          lat + dx / 2),
                         "terrarium")
    d = os.path.join(tmp, "folder_shifted")
    _st_write_folder(d, zr, pngs)
    r = run(src, d, fmt="terrarium")
    want = A * (-dx / 2) + B * (dx / 2)
    sh = r["shifted_half_pixel_se"]
    check("half-pixel SE shift detected",
          abs(r["error"]["mean"] - want) < 0.01 and sh["max_abs"] < 0.005,
          "mean %+.4f (expected %+.4f), shifted max %.5f" % (
              r["error"]["mean"], want, sh["max_abs"]))

    # Command line: JSON on one line, exit 2 on unreadable input.
    me = os.path.abspath(__file__)
    p = subprocess.run([sys.executable, me, src,
                        os.path.join(tmp, "qm4326_gz"), "--json",
                        "--points", "500"], capture_output=True, text=True)
    ok = p.returncode == 0 and len(p.stdout.strip().splitlines()) == 1
    try:
        j = json.loads(p.stdout)
        ok &= j["error"]["n"] == 500
    except ValueError:
        ok = False
    check("cli --json", ok, p.stderr.strip()[:200])
    p = subprocess.run([sys.executable, me, src,
                        os.path.join(tmp, "qm4326")],
                       capture_output=True, text=True)
    check("cli text summary", p.returncode == 0 and "cracks:" in p.stdout,
          p.stderr.strip()[:200])
    bogus = os.path.join(tmp, "bogus.tif")
    with open(bogus, "wb") as f:
        f.write(b"not a tiff")
    for args_ in ([bogus, os.path.join(tmp, "qm4326")],
                  [src, os.path.join(tmp, "does_not_exist")],
                  [src, bogus]):
        p = subprocess.run([sys.executable, me] + args_, capture_output=True,
                           text=True)
        check("cli exit 2 for %s" % os.path.basename(args_[-1] if
                                                     args_[0] == src
                                                     else args_[0]),
              p.returncode == 2 and "terrain_accuracy:" in p.stderr,
              "rc %d %s" % (p.returncode, p.stderr.strip()[:120]))

    # Performance: 4000 points and 2000 crack pairs on a 10,000-tile set.
    d = os.path.join(tmp, "qm_perf")
    zp = 11
    x0, y0 = 2040, 1525          # 100 x 100 tiles near (-1.4, 44.0)
    tiles = {(x0 + i, y0 + j): (9, 0) for i in range(100) for j in range(100)}
    wsrc = os.path.join(tmp, "plane_wide.tif")
    _st_geotiff(wsrc, -2.5, 53.0, 0.02, 600, 550, plane)
    _st_write_qm_set(d, "EPSG:4326", zp, tiles, plane, gz=True)
    t0 = time.time()
    r = run(wsrc, d)
    dt = time.time() - t0
    check("10,000-tile set: 4000 points + 2000 pairs in < 60 s",
          dt < 60 and r["error"]["n"] == 4000 and
          r["cracks"]["pairs_checked"] == 2000 and
          r["cracks"]["cracked_vertices"] == 0 and
          r["error"]["max_abs"] < 0.01,
          "%.1f s, %s, %d tiles decoded" % (dt, s(r),
                                            r["triangles"]["tiles_decoded"]))

    print("\n".join(lines))
    print("self-test: %d checks, %d failed; files in %s" % (
        len(lines), len(failures), tmp if keep else "(removed)"))
    if not keep:
        import shutil
        shutil.rmtree(tmp, ignore_errors=True)
    return 1 if failures else 0


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Independent accuracy checker for web terrain tiles "
                    "(quantized-mesh, Terrarium, Terrain-RGB) against their "
                    "source DEM.")
    ap.add_argument("source", nargs="?", help="source DEM (GeoTIFF or any "
                    "GDAL raster; band 1, metres)")
    ap.add_argument("tileset", nargs="?", help="quantized-mesh folder with "
                    "layer.json, PNG tile folder, .mbtiles or .pmtiles")
    ap.add_argument("--format", choices=("qm", "terrarium", "terrain-rgb"))
    ap.add_argument("--zoom", type=int, help="zoom to check (default: finest)")
    ap.add_argument("--points", type=int, default=4000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--crack-tiles", type=int, default=2000,
                    help="at most this many neighbour tile pairs are "
                         "checked for cracks (random sample)")
    ap.add_argument("--scheme", choices=("xyz", "tms"), default="xyz",
                    help="row order of a raster tile folder (default xyz)")
    ap.add_argument("--json", action="store_true",
                    help="print one JSON object on one line")
    ap.add_argument("--self-test", action="store_true",
                    help="build synthetic tilesets under /tmp and check them")
    ap.add_argument("--keep", action="store_true",
                    help="with --self-test: keep the files")
    args = ap.parse_args(argv)
    if args.self_test:
        return self_test(args.keep)
    if not args.source or not args.tileset:
        ap.print_usage(sys.stderr)
        die("SOURCE and TILESET are required")
    if args.points < 1 or args.crack_tiles < 0:
        die("--points must be >= 1 and --crack-tiles >= 0")
    if not os.path.exists(args.tileset):
        die("tileset %s does not exist" % args.tileset)
    try:
        res = run_check(args)
    except InputError as e:
        die(str(e))
    if res["error"]["n"] == 0:
        msg = ("no comparable points (does the tileset overlap the "
               "source's valid area?)")
        res.setdefault("notes", []).append(msg)
    try:
        if args.json:
            print(json.dumps(res, separators=(",", ":")))
        else:
            print(format_summary(res))
        sys.stdout.flush()
    except BrokenPipeError:               # e.g. piped into head
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    if res["error"]["n"] == 0:
        die(msg)
    return 0


if __name__ == "__main__":
    sys.exit(main())
