#!/usr/bin/env python3
"""Black-box HTTP/1.1 conformance checker for a static tile server.

Written from RFC 9110 (HTTP semantics), RFC 9111 (caching, for 304) and
RFC 9112 (HTTP/1.1 message framing) alone; standard library only.

    check_http.py --base http://127.0.0.1:PORT [options] RESOURCE...

RESOURCE is PATH or PATH=FILE.  See README.md next to this file for the
cases and the RFC sections behind each.  Exit status: 0 all passed,
1 at least one case failed, 2 usage error.
"""

import argparse
import gzip
import json
import os
import re
import shutil
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.parse
import urllib.request
import zlib
import http.client

# ---------------------------------------------------------------------------
# A small raw HTTP/1.1 client: exact status line, header fields and body
# bytes, framed by Content-Length / chunked / close (RFC 9112 section 6.3),
# every read bounded by one per-request deadline.
# ---------------------------------------------------------------------------

MAX_HEAD = 256 * 1024
CLOSE_GRACE_S = 1.0   # how long to wait for the server to close after the body


class Response:
    """One parsed response.  `error` describes a framing problem (short body,
    timeout, garbled status line); `extra` holds bytes that came after the
    framed body on a connection that should have ended there."""

    def __init__(self):
        self.version = None
        self.status = None
        self.reason = ''
        self.headers = []          # [(name, value)] in arrival order
        self.body = b''
        self.extra = b''
        self.error = None
        self.framing = ''
        self.server_closed = None  # after a close-delimited exchange: did it close?

    def get(self, name):
        vals = [v for n, v in self.headers if n.lower() == name.lower()]
        return ', '.join(vals) if vals else None

    def has(self, name):
        return any(n.lower() == name.lower() for n, _ in self.headers)

    def tokens(self, name):
        v = self.get(name)
        return [t.strip().lower() for t in v.split(',') if t.strip()] if v else []


class RawConnection:
    def __init__(self, target, timeout):
        self.target = target
        self.timeout = timeout
        self.buf = b''
        self.eof = False
        self.sock = socket.create_connection((target.host, target.port), timeout=timeout)

    def close(self):
        try:
            self.sock.close()
        except OSError:
            pass

    def send(self, method, path, headers=(), close=True):
        lines = ['%s %s HTTP/1.1' % (method, self.target.prefix + path),
                 'Host: %s' % self.target.hostport,
                 'User-Agent: check_http/1']
        lines += ['%s: %s' % (n, v) for n, v in headers]
        if close:
            lines.append('Connection: close')
        self.sock.sendall(('\r\n'.join(lines) + '\r\n\r\n').encode('latin-1'))

    def _fill(self, deadline):
        """Read more bytes into buf; False at EOF; socket.timeout past deadline."""
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            raise socket.timeout()
        self.sock.settimeout(remaining)
        data = self.sock.recv(65536)
        if not data:
            self.eof = True
            return False
        self.buf += data
        return True

    def _take(self, n):
        out, self.buf = self.buf[:n], self.buf[n:]
        return out

    def _read_line(self, deadline):
        while b'\n' not in self.buf:
            if len(self.buf) > MAX_HEAD or not self._fill(deadline):
                raise EOFError('connection closed in the middle of a line')
        i = self.buf.index(b'\n')
        return self._take(i + 1).rstrip(b'\r\n')

    def _read_head(self, resp, deadline):
        while True:
            m = re.search(b'\r?\n\r?\n', self.buf)
            if m:
                head = self._take(m.end())
                break
            if len(self.buf) > MAX_HEAD:
                raise ValueError('header section larger than %d bytes' % MAX_HEAD)
            if not self._fill(deadline):
                if not self.buf:
                    raise EOFError('connection closed without any response')
                raise EOFError('connection closed inside the header section (%d bytes: %r)'
                               % (len(self.buf), self.buf[:80]))
        lines = head.decode('latin-1').split('\n')
        lines = [l.rstrip('\r') for l in lines]
        m = re.match(r'HTTP/(\d\.\d) (\d{3})(?: (.*))?$', lines[0])
        if not m:
            raise ValueError('garbled status line %r' % lines[0][:80])
        resp.version, resp.status, resp.reason = m.group(1), int(m.group(2)), m.group(3) or ''
        resp.headers = []
        for line in lines[1:]:
            if not line:
                continue
            if line[0] in ' \t' and resp.headers:          # obs-fold
                n, v = resp.headers[-1]
                resp.headers[-1] = (n, v + ' ' + line.strip())
                continue
            name, sep, value = line.partition(':')
            if not sep or not name or name != name.strip():
                raise ValueError('malformed header line %r' % line[:80])
            resp.headers.append((name, value.strip()))

    def _read_exact(self, n, deadline):
        while len(self.buf) < n:
            if not self._fill(deadline):
                break
        return self._take(n)

    def _read_chunked(self, deadline):
        body = b''
        while True:
            line = self._read_line(deadline)
            size_txt = line.split(b';')[0].strip()
            if not re.fullmatch(rb'[0-9A-Fa-f]+', size_txt):
                raise ValueError('bad chunk size line %r' % line[:40])
            size = int(size_txt, 16)
            if size == 0:
                while self._read_line(deadline):   # trailer section
                    pass
                return body
            chunk = self._read_exact(size, deadline)
            body += chunk
            if len(chunk) < size:
                raise EOFError('connection closed inside a chunk (%d of %d bytes)' % (len(chunk), size))
            if self._read_line(deadline) != b'':
                raise ValueError('chunk not followed by CRLF')

    def read_response(self, method, close=True):
        """Read one final response (1xx skipped).  With close=True the rest of
        the connection is drained (briefly) into resp.extra."""
        resp = Response()
        deadline = time.monotonic() + self.timeout
        try:
            while True:
                self._read_head(resp, deadline)
                if not 100 <= resp.status < 200:
                    break
            te = resp.tokens('transfer-encoding')
            cl = resp.get('content-length')
            if method == 'HEAD' or resp.status in (204, 304):
                resp.framing = 'none'
            elif te:
                if te[-1] != 'chunked':
                    resp.framing = 'close'
                    resp.body = self._read_to_eof(deadline, strict=True)
                else:
                    resp.framing = 'chunked'
                    if cl is not None:
                        resp.error = 'both Transfer-Encoding and Content-Length sent (RFC 9112 6.1)'
                    resp.body = self._read_chunked(deadline)
            elif cl is not None:
                vals = {v.strip() for v in cl.split(',')}
                if len(vals) != 1 or not re.fullmatch(r'\d+', next(iter(vals))):
                    raise ValueError('invalid Content-Length %r' % cl)
                n = int(next(iter(vals)))
                resp.framing = 'length'
                try:
                    resp.body = self._read_exact(n, deadline)
                except socket.timeout:
                    resp.body = self._take(len(self.buf))
                    resp.error = ('short body: %d of Content-Length %d bytes, then nothing for the '
                                  'rest of the %gs timeout' % (len(resp.body), n, self.timeout))
                    return resp
                if len(resp.body) < n:
                    resp.error = ('short body: connection closed after %d of Content-Length %d bytes'
                                  % (len(resp.body), n))
                    return resp
            else:
                resp.framing = 'close'
                resp.body = self._read_to_eof(deadline, strict=True)
            if close or 'close' in resp.tokens('connection') or resp.framing == 'close':
                grace = min(deadline, time.monotonic() + CLOSE_GRACE_S)
                resp.extra = self._read_to_eof(grace, strict=False)
                resp.server_closed = self.eof
        except socket.timeout:
            resp.error = 'timed out after %gs (no complete response)' % self.timeout
            if resp.status is not None:
                resp.body += self._take(len(self.buf))
        except (EOFError, ValueError) as e:
            resp.error = str(e)
        except OSError as e:
            resp.error = 'socket error: %s' % e
        return resp

    def _read_to_eof(self, deadline, strict):
        try:
            while self._fill(deadline):
                pass
        except socket.timeout:
            if strict:
                raise
        return self._take(len(self.buf))


class Target:
    def __init__(self, base):
        u = urllib.parse.urlsplit(base)
        if u.scheme != 'http' or not u.hostname:
            raise ValueError('--base must be an http:// URL, got %r' % base)
        self.base = base.rstrip('/')
        self.host = u.hostname
        self.port = u.port or 80
        self.hostport = u.netloc.rsplit('@', 1)[-1]
        self.prefix = u.path.rstrip('/')

    def url(self, path):
        return self.base + path


def raw_request(target, timeout, method, path, headers=()):
    """One request on a fresh connection with Connection: close."""
    try:
        conn = RawConnection(target, timeout)
    except OSError as e:
        r = Response()
        r.error = 'connection failed: %s' % e
        return r
    try:
        conn.send(method, path, headers, close=True)
        return conn.read_response(method, close=True)
    except OSError as e:
        r = Response()
        r.error = 'socket error: %s' % e
        return r
    finally:
        conn.close()


# ---------------------------------------------------------------------------
# Reporting
# ---------------------------------------------------------------------------

SHOWN_HEADERS = ('Content-Range', 'Content-Length', 'Content-Type', 'Content-Encoding',
                 'Transfer-Encoding', 'ETag', 'Vary', 'Accept-Ranges')


def desc(resp):
    """What came: status, relevant headers, body length, framing problems."""
    if resp.status is None:
        return 'no response (%s)' % resp.error
    parts = ['status %d' % resp.status]
    for h in SHOWN_HEADERS:
        v = resp.get(h)
        if v is not None:
            parts.append('%s: %s' % (h, v))
    parts.append('body %d bytes' % len(resp.body))
    if resp.extra:
        parts.append('%d more bytes after the framed body' % len(resp.extra))
    if resp.error:
        parts.append(resp.error)
    return ', '.join(parts)


class Skip(Exception):
    pass


class Case:
    def __init__(self, name):
        self.name = name
        self.problems = []
        self.notes = []
        self.skipped = None

    def fail(self, msg):
        self.problems.append(msg)

    def note(self, msg):
        self.notes.append(msg)

    @property
    def status(self):
        return 'skip' if self.skipped is not None else ('fail' if self.problems else 'pass')


class Runner:
    def __init__(self):
        self.cases = []

    def run(self, name, fn, *args):
        case = Case(name)
        try:
            fn(case, *args)
        except Skip as e:
            case.skipped = str(e)
        except Exception as e:      # a checker bug or a very odd answer: a failing case, no traceback
            case.fail('checker error %s: %s' % (type(e).__name__, e))
        if case.status == 'skip':
            print('SKIP %s: %s' % (name, case.skipped))
        elif case.status == 'fail':
            print('FAIL %s: %s' % (name, '; '.join(case.problems)))
        else:
            print('PASS %s' % name)
        for n in case.notes:
            print('#   %s' % n)
        sys.stdout.flush()
        self.cases.append(case)
        return case

    def counts(self):
        c = {'pass': 0, 'fail': 0, 'skip': 0}
        for case in self.cases:
            c[case.status] += 1
        return c


# ---------------------------------------------------------------------------
# Shared expectations
# ---------------------------------------------------------------------------

class Resource:
    def __init__(self, path, file_bytes):
        self.path = path
        self.file = file_bytes
        self.ref = file_bytes        # reference representation bytes (as sent without Accept-Encoding)
        self.plain = None            # the plain GET Response
        self.etag = None
        self.decoded = None          # ref with the plain answer's content coding removed

    @property
    def size(self):
        return len(self.ref)


class Ctx:
    def __init__(self, target, timeout):
        self.target = target
        self.timeout = timeout

    def req(self, method, path, headers=()):
        return raw_request(self.target, self.timeout, method, path, headers)


def need_ref(R):
    if R.ref is None:
        raise Skip('no reference bytes (the plain GET failed and no FILE was given)')


def need_size(R, minimum=1):
    need_ref(R)
    if R.size < minimum:
        raise Skip('resource has %d bytes, this case needs at least %d' % (R.size, minimum))


def check_framing(case, resp, what='response'):
    if resp.status is None:
        case.fail('expected a %s, got %s' % (what, desc(resp)))
        return False
    if resp.error:
        case.fail('%s is broken: %s' % (what, desc(resp)))
        return False
    if resp.extra:
        case.fail('%d bytes after the end of the framed body (Content-Length lies?): %s'
                  % (len(resp.extra), desc(resp)))
        return False
    return True


# Fields a 206/304 MUST carry when the 200 would have (RFC 9110 15.3.7, 15.4.5).
REPEATED_206 = ('Date', 'Cache-Control', 'ETag', 'Expires', 'Content-Location', 'Vary')
REPEATED_304 = ('Content-Location', 'Date', 'ETag', 'Vary', 'Cache-Control', 'Expires')


def check_repeated(case, R, resp, names, section):
    """ETag must come back unchanged (FAIL); the other listed fields missing or changed are reported
    as warnings only (nginx 1.22, the reference, drops Vary on its 304s)."""
    if R.plain is None or R.plain.status != 200:
        return
    for n in names:
        want = R.plain.get(n)
        if want is None:
            continue
        got = resp.get(n)
        report = case.fail if n == 'ETag' else (lambda m: case.note('warning: ' + m))
        if got is None:
            report('%s missing on %d though the 200 has it (RFC 9110 %s)' % (n, resp.status, section))
        elif n in ('ETag', 'Vary', 'Cache-Control', 'Content-Location') and got != want:
            report('%s on %d is %r, the 200 has %r (RFC 9110 %s)' % (n, resp.status, got, want, section))


def expect_whole_200(case, R, resp, why):
    if not check_framing(case, resp):
        return
    if resp.status != 200:
        case.fail('expected 200 with the whole body (%s), got %s' % (why, desc(resp)))
        return
    if resp.body != R.ref:
        case.fail('200 body differs from the reference (%d bytes expected): %s' % (R.size, desc(resp)))


CR_RE = re.compile(r'bytes (\d+)-(\d+)/(\d+|\*)$')


def expect_206(case, R, resp, first, last):
    want = 'bytes %d-%d/%d' % (first, last, R.size)
    if resp.status != 206:
        case.fail('expected 206 with Content-Range: %s, got %s' % (want, desc(resp)))
        return
    described = False           # desc() already shows the framing error
    cr = resp.get('Content-Range')
    if cr != want:
        case.fail('expected Content-Range: %s, got %s' % (want, desc(resp)))
        described = True
    cl = resp.get('Content-Length')
    if cl is not None and cl != str(last - first + 1):
        case.fail('expected Content-Length: %d, got %s' % (last - first + 1, cl))
    if resp.error or resp.extra:
        if not described:
            check_framing(case, resp)
        return
    if resp.body != R.ref[first:last + 1]:
        case.fail('206 body (%d bytes) is not the reference bytes %d-%d (%d bytes)'
                  % (len(resp.body), first, last, last - first + 1))
    check_repeated(case, R, resp, REPEATED_206, '15.3.7')


def expect_416(case, R, resp):
    want = 'bytes */%d' % R.size
    if resp.status != 416:
        case.fail('expected 416 with Content-Range: %s, got %s' % (want, desc(resp)))
        return
    if resp.get('Content-Range') != want:
        case.fail('expected Content-Range: %s on the 416, got %s' % (want, desc(resp)))
    check_framing(case, resp)


def clamp(R, first, last):
    return first, min(last, R.size - 1)


# ---------------------------------------------------------------------------
# Cases over the raw client, one function each
# ---------------------------------------------------------------------------

def case_get(case, ctx, R):
    """1. Plain GET: 200, Content-Length == SIZE, body == reference, ETag."""
    resp = ctx.req('GET', R.path)
    R.plain = resp
    if not check_framing(case, resp, 'plain GET response'):
        return
    if resp.status != 200:
        case.fail('expected 200, got %s' % desc(resp))
        return
    if R.file is None:
        R.ref = resp.body
    elif resp.body != R.file:
        case.fail('body differs from FILE (%d bytes expected): %s' % (len(R.file), desc(resp)))
    cl = resp.get('Content-Length')
    if cl is None:
        case.fail('no Content-Length on the 200 (clients such as GDAL need the size): %s' % desc(resp))
    elif cl != str(len(resp.body)):
        case.fail('Content-Length %s but %d body bytes' % (cl, len(resp.body)))
    etag = resp.get('ETag')
    if etag is None:
        case.fail('no ETag (RFC 9110 8.8.3: SHOULD; If-Range/If-None-Match cases need it): %s' % desc(resp))
    elif not re.fullmatch(r'(W/)?"[^"]*"', etag):
        case.fail('ETag %r is not an entity-tag (RFC 9110 8.8.3)' % etag)
    else:
        R.etag = etag
        case.note('ETag %s (%s)' % (etag, 'weak' if etag.startswith('W/') else 'strong'))
    case.note('Accept-Ranges: %s; Content-Encoding: %s; Vary: %s; %d bytes'
              % (resp.get('Accept-Ranges') or '-', resp.get('Content-Encoding') or '-',
                 resp.get('Vary') or '-', len(resp.body)))
    try:
        R.decoded = decode_body(resp.tokens('content-encoding'), R.ref)[0]
    except (OSError, EOFError, zlib.error) as e:
        case.fail('Content-Encoding: %s but the body does not decode: %s' % (resp.get('Content-Encoding'), e))


HEAD_COMPARED = ('Content-Type', 'Content-Length', 'ETag', 'Accept-Ranges', 'Cache-Control',
                 'Content-Encoding', 'Vary', 'Access-Control-Allow-Origin')


def case_head(case, ctx, R):
    """2. HEAD: same status and header fields as GET, no body bytes (RFC 9110 9.3.2, 8.6)."""
    if R.plain is None or R.plain.status is None:
        raise Skip('no plain GET answer to compare with')
    resp = ctx.req('HEAD', R.path)
    if resp.status is None or resp.error:
        case.fail('expected a HEAD response, got %s' % desc(resp))
        return
    if resp.status != R.plain.status:
        case.fail('HEAD status %d, GET status %d' % (resp.status, R.plain.status))
    for n in HEAD_COMPARED:
        g, h = R.plain.get(n), resp.get(n)
        if g != h:
            case.fail('%s: GET has %r, HEAD has %r' % (n, g, h))
    if resp.extra:
        case.fail('HEAD answer carried %d body bytes (must have none)' % len(resp.extra))


def case_range(case, ctx, R, spec, first, last):
    """3/4. A satisfiable single range: 206, exact Content-Range and bytes (RFC 9110 14.4, 15.3.7)."""
    need_size(R)
    expect_206(case, R, ctx.req('GET', R.path, [('Range', spec)]), first, last)


def case_416(case, ctx, R, spec):
    """5. First byte at/after the end: 416, Content-Range: bytes */SIZE (RFC 9110 14.1.2, 15.5.17)."""
    need_size(R)
    expect_416(case, R, ctx.req('GET', R.path, [('Range', spec)]))


def parse_multipart(body, boundary):
    """Split a multipart/byteranges body into [(headers dict, bytes)] (RFC 9110 14.6, RFC 2046 5.1)."""
    delim = b'--' + boundary.encode('latin-1')
    if body.startswith(delim):
        body = b'\r\n' + body
    pieces = body.split(b'\r\n' + delim)
    if len(pieces) < 3:
        raise ValueError('fewer than one part between boundaries')
    parts = []
    for piece in pieces[1:]:
        if piece.startswith(b'--'):
            return parts            # close-delimiter
        line_end = piece.find(b'\r\n')
        if line_end < 0 or piece[:line_end].strip(b' \t'):
            raise ValueError('junk after a boundary: %r' % piece[:40])
        piece = piece[line_end + 2:]
        sep = piece.find(b'\r\n\r\n')
        if sep < 0:
            if piece.startswith(b'\r\n'):
                head, data = b'', piece[2:]
            else:
                raise ValueError('part without a header/body separator')
        else:
            head, data = piece[:sep], piece[sep + 4:]
        hdrs = {}
        for line in head.decode('latin-1').split('\r\n'):
            if line:
                n, _, v = line.partition(':')
                hdrs[n.strip().lower()] = v.strip()
        parts.append((hdrs, data))
    raise ValueError('no close-delimiter (--%s--)' % boundary)


def case_multi(case, ctx, R, ranges):
    """6. Several ranges: 206 multipart/byteranges with correct parts, or 200 whole (RFC 9110 14.2, 14.6)."""
    need_size(R, max(b for _, b in ranges) + 1)
    spec = 'bytes=' + ','.join('%d-%d' % r for r in ranges)
    resp = ctx.req('GET', R.path, [('Range', spec)])
    if not check_framing(case, resp):
        return
    if resp.status == 200:
        expect_whole_200(case, R, resp, 'multiple ranges ignored')
        case.note('200 whole body (ranges ignored, allowed)')
        return
    if resp.status != 206:
        case.fail('expected 206 multipart/byteranges or 200 whole, got %s' % desc(resp))
        return
    check_repeated(case, R, resp, REPEATED_206, '15.3.7')
    wanted = set()
    for a, b in ranges:
        wanted.update(range(a, b + 1))
    got = set()
    ctype = resp.get('Content-Type') or ''
    if not ctype.lower().startswith('multipart/byteranges'):
        # one coalesced range is allowed (RFC 9110 14.2 "MAY coalesce"; 15.3.7.1)
        m = CR_RE.match(resp.get('Content-Range') or '')
        if not m or m.group(3) != str(R.size):
            case.fail('206 that is neither multipart/byteranges nor a valid single part: %s' % desc(resp))
            return
        a, b = int(m.group(1)), int(m.group(2))
        if resp.body != R.ref[a:b + 1]:
            case.fail('single coalesced part bytes %d-%d differ from the reference' % (a, b))
        got.update(range(a, b + 1))
        case.note('answered with one coalesced part bytes %d-%d' % (a, b))
    else:
        m = re.search(r';\s*boundary=("([^"]+)"|[^;\s]+)', ctype, re.I)
        if not m:
            case.fail('multipart/byteranges without a boundary parameter: %s' % desc(resp))
            return
        boundary = m.group(2) or m.group(1)
        if resp.has('Content-Range'):
            case.fail('multipart 206 must not carry a Content-Range header field (RFC 9110 14.6)')
        try:
            parts = parse_multipart(resp.body, boundary)
        except ValueError as e:
            case.fail('multipart body unparseable: %s' % e)
            return
        if len(parts) < 2:
            case.note('multipart with %d part(s)' % len(parts))
        for i, (hdrs, data) in enumerate(parts):
            cr = hdrs.get('content-range', '')
            pm = CR_RE.match(cr)
            if not pm or pm.group(3) == '*':
                case.fail('part %d: bad Content-Range %r' % (i, cr))
                continue
            a, b, total = int(pm.group(1)), int(pm.group(2)), int(pm.group(3))
            if total != R.size:
                case.fail('part %d: Content-Range %r, complete length must be %d' % (i, cr, R.size))
            if b < a or b >= R.size:
                case.fail('part %d: Content-Range %r outside 0-%d' % (i, cr, R.size - 1))
                continue
            if data != R.ref[a:b + 1]:
                case.fail('part %d (%s): %d bytes, not the reference slice of %d bytes'
                          % (i, cr, len(data), b - a + 1))
            got.update(range(a, b + 1))
        case.note('multipart/byteranges, %d parts' % len(parts))
    if not wanted <= got:
        case.fail('parts do not cover all requested bytes (%d missing)' % len(wanted - got))


def case_invalid_range(case, ctx, R, spec, may_reject):
    """7. Invalid Range: ignored, i.e. 200 whole (RFC 9110 14.2).  For an invalid ranges-specifier
    in the bytes unit the RFC also allows 'reject' (416 bytes */SIZE); an unknown unit MUST be ignored."""
    need_ref(R)
    resp = ctx.req('GET', R.path, [('Range', spec)])
    if may_reject and resp.status == 416:
        expect_416(case, R, resp)
        case.note('rejected with 416 (RFC 9110 14.2 allows ignore or reject)')
        return
    expect_whole_200(case, R, resp, 'an invalid Range is ignored')


def case_if_range(case, ctx, R, validator, kind):
    """8. If-Range (RFC 9110 13.1.5): a strong-matching ETag lets the Range through, anything else
    (stale tag, weak tag, a date that is not exactly Last-Modified) makes the server ignore Range."""
    need_size(R, 10)
    if kind == 'current':
        if R.etag is None:
            raise Skip('no ETag on the plain GET')
        validator = R.etag
    if kind == 'date' and R.plain is not None and R.plain.get('Last-Modified') == validator:
        raise Skip('Last-Modified equals the test date')
    if kind == 'stale' and R.etag == validator:
        raise Skip('the current ETag happens to be %s' % validator)
    resp = ctx.req('GET', R.path, [('Range', 'bytes=0-9'), ('If-Range', validator)])
    if kind == 'current' and not validator.startswith('W/'):
        expect_206(case, R, resp, 0, 9)
    else:
        why = {'current': 'a weak ETag never matches in If-Range (strong comparison)',
               'stale': 'the If-Range ETag does not match',
               'date': 'the If-Range date is not the Last-Modified'}[kind]
        expect_whole_200(case, R, resp, why)


def case_inm(case, ctx, R, kind):
    """9. If-None-Match (RFC 9110 13.1.2, 15.4.5, 8.6; RFC 9111 4.3.4)."""
    need_ref(R)
    if kind in ('current', 'list') and R.etag is None:
        raise Skip('no ETag on the plain GET')
    value = {'current': R.etag, 'list': '"x-no-such-tag", %s, "y-no-such-tag"' % R.etag,
             'star': '*', 'other': '"nomatch-check-http"'}[kind]
    resp = ctx.req('GET', R.path, [('If-None-Match', value)])
    if kind == 'other':
        expect_whole_200(case, R, resp, 'the If-None-Match tag does not match')
        return
    if resp.status != 304:
        case.fail('expected 304 for If-None-Match: %s, got %s' % (value, desc(resp)))
        return
    check_framing(case, resp)
    cl = resp.get('Content-Length')
    if cl is not None and cl != str(R.size):
        case.fail('304 with Content-Length: %s; if sent it must be %d, what the 200 would send '
                  '(RFC 9110 8.6)' % (cl, R.size))
    if R.etag is not None and resp.get('ETag') != R.etag:
        case.fail('304 must repeat ETag %s, got %r (RFC 9110 15.4.5)' % (R.etag, resp.get('ETag')))
    check_repeated(case, R, resp, REPEATED_304, '15.4.5')


GZIP_NAMES = ('gzip', 'x-gzip')


def decode_body(codings, data):
    """Undo content codings (last applied first). Returns (bytes or None, note)."""
    for c in reversed([c for c in codings if c != 'identity']):
        if c in GZIP_NAMES:
            data = gzip.decompress(data)
        elif c == 'deflate':
            try:
                data = zlib.decompress(data)
            except zlib.error:
                data = zlib.decompress(data, -15)
        elif c == 'br':
            try:
                import brotli          # optional, not in the standard library
            except ImportError:
                return None, 'br body not verified (no brotli module)'
            data = brotli.decompress(data)
        else:
            return None, 'unknown coding %r' % c
    return data, ''


def case_encoding(case, ctx, R, accept, allowed):
    """10. Content negotiation of the coding (RFC 9110 8.4, 12.5.3, 12.5.5, 8.8.3)."""
    need_ref(R)
    resp = ctx.req('GET', R.path, [('Accept-Encoding', accept)])
    if not check_framing(case, resp):
        return
    if resp.status != 200:
        case.fail('expected 200, got %s' % desc(resp))
        return
    codings = resp.tokens('content-encoding')
    plain_codings = R.plain.tokens('content-encoding') if R.plain is not None else []
    real = [c for c in codings if c != 'identity']
    if len(real) > 1:
        case.fail('Content-Encoding: %s is %d codings; expected at most one'
                  % (resp.get('Content-Encoding'), len(real)))
    if any(c not in allowed for c in real):
        case.fail('Content-Encoding: %s not acceptable for Accept-Encoding: %s'
                  % (resp.get('Content-Encoding'), accept))
    try:
        decoded, why = decode_body(codings, resp.body)
    except (OSError, EOFError, zlib.error) as e:
        case.fail('body does not decode as Content-Encoding %s: %s' % (resp.get('Content-Encoding'), e))
        return
    if decoded is None:
        case.note(why)
    elif R.decoded is not None and decoded != R.decoded:
        extra = ''
        if decoded[:2] == b'\x1f\x8b':
            try:
                if gzip.decompress(decoded) == R.decoded:
                    extra = ' (it is gzipped twice)'
            except (OSError, EOFError, zlib.error):
                pass
        case.fail('decoded body (%d bytes) differs from the reference (%d bytes)%s'
                  % (len(decoded), len(R.decoded), extra))
    if codings != plain_codings:
        vary = resp.tokens('vary')
        if resp.get('ETag') is not None and resp.get('ETag') == R.etag and \
                'accept-encoding' not in vary and '*' not in vary:
            case.fail('%s answer has the identity ETag %s and no Vary: Accept-Encoding'
                      % (resp.get('Content-Encoding') or 'identity', R.etag))
        elif resp.get('ETag') is not None and resp.get('ETag') == R.etag and not R.etag.startswith('W/'):
            case.note('same strong ETag for two codings (RFC 9110 8.8.3 wants distinct tags); '
                      'Vary: Accept-Encoding present')
    case.note('Content-Encoding: %s, ETag: %s, Vary: %s'
              % (resp.get('Content-Encoding'), resp.get('ETag'), resp.get('Vary')))


def case_keepalive(case, ctx, R, first):
    """11. Two requests in sequence on one persistent connection (RFC 9112 6.3, 9.3, 9.6)."""
    need_size(R)
    if first == '304' and R.etag is None:
        raise Skip('no ETag on the plain GET')
    a, b = max(0, R.size - 10), R.size + 100     # last-byte-pos past the end: where lying lengths hide
    method, hdrs = {'range': ('GET', [('Range', 'bytes=%d-%d' % (a, b))]),
                    'HEAD': ('HEAD', []),
                    '304': ('GET', [('If-None-Match', R.etag or '')])}[first]
    try:
        conn = RawConnection(ctx.target, ctx.timeout)
    except OSError as e:
        case.fail('connection failed: %s' % e)
        return
    try:
        conn.send(method, R.path, hdrs, close=False)
        r1 = conn.read_response(method, close=False)
        if r1.status is None or r1.error:
            case.fail('first answer broken: %s' % desc(r1))
            return
        if first == 'range':
            expect_206(case, R, r1, a, R.size - 1)
        elif first == '304' and r1.status != 304:
            case.fail('first answer: expected 304, got %s' % desc(r1))
        elif first == 'HEAD' and r1.status != 200:
            case.fail('first answer: expected 200, got %s' % desc(r1))
        if 'close' in r1.tokens('connection') or \
                (r1.version == '1.0' and 'keep-alive' not in r1.tokens('connection')):
            case.note('server ends the connection after the first answer and says so (allowed)')
            if r1.extra:
                case.fail('%d bytes after the first answer' % len(r1.extra))
            return
        try:
            conn.send('GET', R.path, [], close=True)
        except OSError as e:
            case.fail('second request could not be sent (%s): the server dropped the connection '
                      'without Connection: close (RFC 9112 9.6)' % e)
            return
        r2 = conn.read_response('GET', close=True)
        if r2.status is None and conn.eof and not r2.headers:
            case.fail('server closed the connection after the first answer without Connection: close '
                      '(RFC 9112 9.6): %s' % r2.error)
            return
        if r2.status is None:
            case.fail('second answer garbled (the first one\'s framing was wrong?): %s' % r2.error)
            return
        expect_whole_200(case, R, r2, 'second request, plain GET')
    finally:
        conn.close()


def case_options(case, ctx, R):
    """12. OPTIONS / CORS preflight: reported; only a 5xx or no answer fails."""
    resp = ctx.req('OPTIONS', R.path, [('Origin', 'http://example.test'),
                                       ('Access-Control-Request-Method', 'GET'),
                                       ('Access-Control-Request-Headers', 'range')])
    if resp.status is None:
        case.fail('no answer: %s' % desc(resp))
        return
    if resp.status >= 500:
        case.fail('server error: %s' % desc(resp))
        return
    case.note('OPTIONS -> %d; Allow: %s; Access-Control-Allow-Origin: %s; -Methods: %s; -Headers: %s'
              % (resp.status, resp.get('Allow'), resp.get('Access-Control-Allow-Origin'),
                 resp.get('Access-Control-Allow-Methods'), resp.get('Access-Control-Allow-Headers')))


def raw_cases(run, ctx, R):
    p = R.path
    run.run('%s GET' % p, case_get, ctx, R)
    if R.ref is None:
        return
    S = R.size
    run.run('%s HEAD' % p, case_head, ctx, R)
    singles = [('first byte', 0, 0), ('first 100', 0, 99),
               ('middle', S // 3, S // 3 + min(1000, S - S // 3) - 1),
               ('last-byte-pos past the end', max(0, S - 10), S + 100),
               ('pmtiles header', 0, 16383)]
    for label, a, b in singles:
        a2, b2 = clamp(R, a, b)
        run.run('%s range bytes=%d-%d (%s)' % (p, a, b, label), case_range, ctx, R,
                'bytes=%d-%d' % (a, b), a2, b2)
    for n in (500, S + 50):
        run.run('%s range bytes=-%d (suffix)' % (p, n), case_range, ctx, R,
                'bytes=-%d' % n, max(0, S - n), S - 1)
    first = 100 if S > 100 else S // 2
    run.run('%s range bytes=%d- (open)' % (p, first), case_range, ctx, R, 'bytes=%d-' % first, first, S - 1)
    for spec in ('bytes=%d-' % S, 'bytes=%d-%d' % (S + 5, S + 10)):
        run.run('%s range %s (416)' % (p, spec), case_416, ctx, R, spec)
    if S >= 30:
        sets = [[(0, 9), (20, 29)], [(20, 29), (0, 9)], [(0, 9), (5, 14)]]
    else:
        sets = [[(0, 0), (2, 2)], [(2, 2), (0, 0)], [(0, 1), (1, 2)]]
    for label, rs in zip(('two', 'unsorted', 'overlapping'), sets):
        run.run('%s range bytes=%s (multiple, %s)' % (p, ','.join('%d-%d' % r for r in rs), label),
                case_multi, ctx, R, rs)
    for spec, may_reject in (('bytes=5-2', True), ('bytes=abc', True), ('items=0-5', False)):
        run.run('%s range %s (invalid)' % (p, spec), case_invalid_range, ctx, R, spec, may_reject)
    run.run('%s If-Range current ETag' % p, case_if_range, ctx, R, None, 'current')
    run.run('%s If-Range stale ETag' % p, case_if_range, ctx, R, '"stale"', 'stale')
    run.run('%s If-Range old date' % p, case_if_range, ctx, R, 'Thu, 01 Jan 1970 00:00:00 GMT', 'date')
    run.run('%s If-None-Match current ETag' % p, case_inm, ctx, R, 'current')
    run.run('%s If-None-Match list' % p, case_inm, ctx, R, 'list')
    run.run('%s If-None-Match *' % p, case_inm, ctx, R, 'star')
    run.run('%s If-None-Match other tag' % p, case_inm, ctx, R, 'other')
    run.run('%s Accept-Encoding gzip' % p, case_encoding, ctx, R, 'gzip', GZIP_NAMES)
    run.run('%s Accept-Encoding gzip;q=0' % p, case_encoding, ctx, R, 'gzip;q=0', ())
    run.run('%s Accept-Encoding "gzip, br"' % p, case_encoding, ctx, R, 'gzip, br', GZIP_NAMES + ('br',))
    for first in ('range', 'HEAD', '304'):
        run.run('%s keep-alive %s then GET' % (p, first), case_keepalive, ctx, R, first)
    run.run('%s OPTIONS' % p, case_options, ctx, R)


def fetch_reference(ctx, R):
    """When the raw cases are not selected, still learn the reference bytes."""
    resp = ctx.req('GET', R.path)
    R.plain = resp
    if resp.status == 200 and not resp.error:
        if R.file is None:
            R.ref = resp.body
        R.etag = resp.get('ETag')
        try:
            R.decoded = decode_body(resp.tokens('content-encoding'), R.ref)[0]
        except (OSError, EOFError, zlib.error):
            R.decoded = None


# ---------------------------------------------------------------------------
# Real clients
# ---------------------------------------------------------------------------

def clean_env(extra=None):
    env = {k: v for k, v in os.environ.items() if 'proxy' not in k.lower()}
    env['no_proxy'] = env['NO_PROXY'] = '*'
    env.update(extra or {})
    return env


def run_prog(argv, timeout, env=None):
    """(rc, stdout, stderr) or raises Skip/returns rc None on timeout."""
    try:
        p = subprocess.run(argv, stdin=subprocess.DEVNULL, capture_output=True,
                           timeout=timeout, env=env or clean_env())
        return p.returncode, p.stdout, p.stderr.decode('utf-8', 'replace')
    except subprocess.TimeoutExpired as e:
        return None, e.stdout or b'', 'killed after %gs (hung)' % timeout


def cmd_text(argv):
    return ' '.join(a if re.fullmatch(r'[\w./:=,@%+-]+', a) else "'%s'" % a for a in argv)


EXIT_MEANING = {'curl': {18: 'partial file', 28: 'timed out', 61: 'bad content encoding'},
                'wget': {4: 'network failure', 8: 'server error response'}}


def compare_output(case, argv, rc, out, err, want, what):
    if rc is None:
        case.fail('%s: %s' % (cmd_text(argv), err))
        return
    if rc != 0:
        meaning = EXIT_MEANING.get(os.path.basename(argv[0]), {}).get(rc)
        case.fail('%s exited %d%s: %s' % (cmd_text(argv), rc, ' (%s)' % meaning if meaning else '',
                                          err.strip()[-300:]))
    if want is not None and out != want:
        case.fail('%s gave %d bytes, expected %s (%d bytes)' % (cmd_text(argv), len(out), what, len(want)))


def case_curl(case, ctx, R, kind):
    need_size(R)
    url = ctx.target.url(R.path)
    base = ['curl', '-q', '-sS', '-g', '--noproxy', '*', '--max-time', '%g' % ctx.timeout]
    S = R.size
    if kind == 'past-end':
        a, b = max(0, S - 10), S + 100
        argv = base + ['-r', '%d-%d' % (a, b), url]
        want, what = R.ref[a:], 'bytes %d-%d' % (a, S - 1)
    elif kind == 'suffix':
        argv = base + ['-r', '-500', url]
        want, what = R.ref[max(0, S - 500):], 'the last %d bytes' % min(500, S)
    elif kind == 'compressed':
        if R.decoded is None:
            raise Skip('reference content coding could not be decoded')
        argv = base + ['--compressed', url]
        want, what = R.decoded, 'the decoded reference'
    else:
        argv = base + ['-I', url]
        want, what = None, ''
    rc, out, err = run_prog(argv, ctx.timeout + 5)
    compare_output(case, argv, rc, out, err, want, what)
    if kind == 'head' and rc == 0:
        first = out.split(b'\r\n', 1)[0].decode('latin-1')
        if not re.match(r'HTTP/\S+ 200\b', first):
            case.fail('curl -I status line %r, expected 200' % first)


def case_wget(case, ctx, R, kind):
    """wget refuses a 206 whose first byte is not where it asked to resume (it gives up with exit 4
    even on a correct server), so the past-the-end range starts at 0 and the resume offset comes
    from --start-pos."""
    need_size(R)
    url = ctx.target.url(R.path)
    argv = ['wget', '--no-config', '-q', '-O', '-', '--no-proxy', '--tries=1',
            '--timeout=%g' % ctx.timeout]
    S = R.size
    if kind == 'past-end':
        argv += ['--header', 'Range: bytes=0-%d' % (S + 100), url]
        want, what = R.ref, 'bytes 0-%d (the whole file)' % (S - 1)
    elif kind == 'start-pos':
        a = max(0, S - 10)
        argv += ['--start-pos=%d' % a, url]
        want, what = R.ref[a:], 'bytes %d-%d' % (a, S - 1)
    else:
        argv += [url]
        want, what = R.ref, 'the reference'
    rc, out, err = run_prog(argv, ctx.timeout + 5)
    compare_output(case, argv, rc, out, err, want, what)


def case_urllib(case, ctx, R):
    need_size(R)
    S = R.size
    a, b = max(0, S - 10), S + 100
    req = urllib.request.Request(ctx.target.url(R.path), headers={'Range': 'bytes=%d-%d' % (a, b)})
    opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))
    try:
        with opener.open(req, timeout=ctx.timeout) as r:
            status = r.status
            data = r.read()
    except http.client.IncompleteRead as e:
        case.fail('urllib read() raised IncompleteRead (%d bytes read, %s more expected)'
                  % (len(e.partial), e.expected))
        return
    except urllib.error.HTTPError as e:
        case.fail('urllib got HTTP %d' % e.code)
        return
    except (urllib.error.URLError, OSError, http.client.HTTPException) as e:
        case.fail('urllib failed: %s: %s' % (type(e).__name__, e))
        return
    if status != 206:
        case.fail('urllib status %d, expected 206' % status)
    if data != R.ref[a:]:
        case.fail('urllib read() returned %d bytes, expected bytes %d-%d (%d bytes)'
                  % (len(data), a, S - 1, S - a))


GDAL_READ_SCRIPT = r'''
import sys
from osgeo import gdal
gdal.UseExceptions()
url = sys.argv[1]
st = gdal.VSIStatL(url)
if st is None:
    sys.stderr.write("VSIStatL failed\n"); sys.exit(3)
sys.stderr.write("SIZE %d\n" % st.size)
f = gdal.VSIFOpenL(url, "rb")
if f is None:
    sys.stderr.write("VSIFOpenL failed\n"); sys.exit(4)
out = []
while True:
    b = gdal.VSIFReadL(1, 65536, f)
    if not b:
        break
    out.append(b)
gdal.VSIFCloseL(f)
sys.stdout.buffer.write(b"".join(out))
'''


def gdal_env(timeout):
    return clean_env({'GDAL_HTTP_TIMEOUT': '%d' % max(1, int(timeout)),
                      'GDAL_HTTP_CONNECTTIMEOUT': '%d' % max(1, int(timeout)),
                      'GDAL_HTTP_MAX_RETRY': '0',
                      'GDAL_DISABLE_READDIR_ON_OPEN': 'EMPTY_DIR',
                      'CPL_VSIL_CURL_NON_CACHED': '/vsicurl/'})


def find_gdal_python(explicit):
    cands = [explicit] if explicit else [sys.executable, '/usr/bin/python3', shutil.which('python3')]
    for c in cands:
        if not c:
            continue
        try:
            p = subprocess.run([c, '-c', 'from osgeo import gdal'], capture_output=True, timeout=30)
            if p.returncode == 0:
                return c
        except (OSError, subprocess.TimeoutExpired):
            pass
    return None


def case_gdalinfo(case, ctx, path):
    argv = ['gdalinfo', '/vsicurl/' + ctx.target.url(path)]
    rc, out, err = run_prog(argv, 3 * ctx.timeout + 10, gdal_env(ctx.timeout))
    if rc is None:
        case.fail('%s: %s' % (cmd_text(argv), err))
        return
    text = out.decode('utf-8', 'replace')
    if rc != 0:
        case.fail('%s exited %d: %s' % (cmd_text(argv), rc, err.strip()[-300:]))
    drv = re.search(r"^Driver: (.+)$", text, re.M)
    size = re.search(r'^Size is (\d+), (\d+)', text, re.M)
    if not drv:
        case.fail('no "Driver:" line in gdalinfo output')
    if not size:
        case.fail('no "Size is" line in gdalinfo output')
    if drv and size:
        case.note('Driver: %s, Size %s x %s' % (drv.group(1), size.group(1), size.group(2)))


def case_gdal_read(case, ctx, path, want, gdal_python):
    argv = [gdal_python, '-c', GDAL_READ_SCRIPT, '/vsicurl/' + ctx.target.url(path)]
    rc, out, err = run_prog(argv, 3 * ctx.timeout + 10, gdal_env(ctx.timeout))
    shown = ['python3', '-c', '<VSIStatL+VSIFReadL>'] + argv[3:]
    if rc is None:
        case.fail('%s: %s' % (cmd_text(shown), err))
        return
    if rc != 0:
        case.fail('%s exited %d: %s' % (cmd_text(shown), rc, err.strip()[-300:]))
        return
    m = re.search(r'^SIZE (\d+)$', err, re.M)
    if not m or int(m.group(1)) != len(want):
        case.fail('VSIStatL size %s, expected %d' % (m.group(1) if m else '?', len(want)))
    if out != want:
        case.fail('VSIFReadL gave %d bytes, expected FILE (%d bytes)%s'
                  % (len(out), len(want), '' if len(out) != len(want) else ', same length but different bytes'))


# ---------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------

CLIENTS = ('raw', 'curl', 'wget', 'urllib', 'gdal')


def skip_case(case, msg):
    raise Skip(msg)


def fail_case(case, msg):
    case.fail(msg)


def split_resource(spec):
    """PATH or PATH=FILE; PATH may have a query string with '=', so take the first '=' whose
    right side is an existing file."""
    if not spec.startswith('/'):
        raise ValueError('RESOURCE must start with /: %r' % spec)
    for m in re.finditer('=', spec):
        path, f = spec[:m.start()], spec[m.end():]
        if os.path.isfile(f):
            return path, f
    if '=' in spec and '?' not in spec.split('=', 1)[0]:
        raise ValueError('FILE in %r does not exist' % spec)
    return spec, None


def read_file(f):
    with open(f, 'rb') as fh:
        return fh.read()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--base', required=True, help='http://HOST:PORT[/prefix]')
    ap.add_argument('--clients', default=None,
                    help='comma list of %s (default: all; missing programs are skipped)' % ','.join(CLIENTS))
    ap.add_argument('--gdalinfo', action='append', default=[], metavar='PATH')
    ap.add_argument('--gdal-read', action='append', default=[], metavar='PATH=FILE')
    ap.add_argument('--gdal-python', default=None, help='python with osgeo (default: auto)')
    ap.add_argument('--json', metavar='OUT')
    ap.add_argument('--timeout', type=float, default=10.0, help='seconds per request (default 10)')
    ap.add_argument('resources', nargs='*', metavar='RESOURCE')
    args = ap.parse_args(argv)

    def usage(msg):
        ap.print_usage(sys.stderr)
        print('%s: error: %s' % (ap.prog, msg), file=sys.stderr)
        return 2

    try:
        target = Target(args.base)
    except ValueError as e:
        return usage(str(e))
    if args.timeout <= 0:
        return usage('--timeout must be positive')
    explicit = args.clients is not None
    clients = [c.strip() for c in (args.clients or ','.join(CLIENTS)).split(',') if c.strip()]
    bad = [c for c in clients if c not in CLIENTS]
    if bad or not clients:
        return usage('unknown client(s) %s; choose from %s' % (','.join(bad), ','.join(CLIENTS)))
    if not args.resources and not args.gdalinfo and not args.gdal_read:
        return usage('nothing to check: give RESOURCE, --gdalinfo or --gdal-read')
    resources, gdal_reads = [], []
    try:
        for spec in args.resources:
            path, f = split_resource(spec)
            resources.append(Resource(path, read_file(f) if f else None))
        for spec in args.gdal_read:
            path, f = split_resource(spec)
            if f is None:
                raise ValueError('--gdal-read needs PATH=FILE, got %r' % spec)
            gdal_reads.append((path, read_file(f)))
        for p in args.gdalinfo:
            if not p.startswith('/'):
                raise ValueError('--gdalinfo PATH must start with /: %r' % p)
    except (ValueError, OSError) as e:
        return usage(str(e))

    run = Runner()
    ctx = Ctx(target, args.timeout)

    def client_missing(client, msg):
        """A missing program: SKIP when running all clients, FAIL when it was asked for."""
        if explicit:
            run.run('client %s' % client, fail_case, msg + ' (explicitly requested)')
        else:
            run.run('client %s' % client, skip_case, msg)

    def available(client, programs):
        missing = [p for p in programs if shutil.which(p) is None]
        if missing:
            client_missing(client, 'program %s not found' % ', '.join(missing))
        return not missing

    use = {c: c in clients for c in CLIENTS}
    if use['curl']:
        use['curl'] = available('curl', ['curl'])
    if use['wget']:
        use['wget'] = available('wget', ['wget'])
    gdal_info_ok, gdal_python = False, None
    if use['gdal']:
        if not args.gdalinfo and not gdal_reads:
            if explicit:
                run.run('client gdal', skip_case, 'no --gdalinfo/--gdal-read given')
        if args.gdalinfo:
            gdal_info_ok = available('gdal', ['gdalinfo'])
        if gdal_reads:
            gdal_python = find_gdal_python(args.gdal_python)
            if gdal_python is None:
                client_missing('gdal', 'no python with osgeo (package python3-gdal) found')

    for R in resources:
        if use['raw']:
            raw_cases(run, ctx, R)
        else:
            fetch_reference(ctx, R)
        if R.ref is None:
            if not use['raw']:
                run.run('%s reference' % R.path, fail_case, 'plain GET failed: %s' % desc(R.plain))
            continue
        p = R.path
        if use['curl']:
            S = R.size
            run.run('%s curl -r %d-%d (past the end)' % (p, max(0, S - 10), S + 100), case_curl, ctx, R, 'past-end')
            run.run('%s curl -r -500' % p, case_curl, ctx, R, 'suffix')
            run.run('%s curl --compressed' % p, case_curl, ctx, R, 'compressed')
            run.run('%s curl -I' % p, case_curl, ctx, R, 'head')
        if use['wget']:
            run.run('%s wget Range bytes=0-%d (past the end)' % (p, R.size + 100), case_wget, ctx, R, 'past-end')
            run.run('%s wget --start-pos=%d' % (p, max(0, R.size - 10)), case_wget, ctx, R, 'start-pos')
            run.run('%s wget plain' % p, case_wget, ctx, R, 'plain')
        if use['urllib']:
            run.run('%s urllib Range past the end' % p, case_urllib, ctx, R)
    for p in args.gdalinfo if gdal_info_ok else ():
        run.run('%s gdalinfo /vsicurl/' % p, case_gdalinfo, ctx, p)
    for p, want in gdal_reads if gdal_python else ():
        run.run('%s gdal VSIFReadL /vsicurl/' % p, case_gdal_read, ctx, p, want, gdal_python)

    c = run.counts()
    if c['skip']:
        print('# %d skipped' % c['skip'])
    print('%d passed, %d failed' % (c['pass'], c['fail']))
    if args.json:
        report = {'base': args.base, 'clients': clients, 'timeout': args.timeout,
                  'passed': c['pass'], 'failed': c['fail'], 'skipped': c['skip'],
                  'cases': [{'name': k.name, 'status': k.status, 'problems': k.problems,
                             'notes': k.notes, 'skip_reason': k.skipped} for k in run.cases]}
        try:
            with open(args.json, 'w') as fh:
                json.dump(report, fh, indent=1)
        except OSError as e:
            print('cannot write %s: %s' % (args.json, e), file=sys.stderr)
            return 2
    return 1 if c['fail'] else 0


if __name__ == '__main__':
    sys.exit(main())
