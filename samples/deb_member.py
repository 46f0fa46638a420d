#!/usr/bin/env python3
"""Streams one member of an ar archive (a Debian package) from stdin to stdout.

Usage: curl -s URL.deb | samples/deb_member.py data.tar.xz | xz -dc | tar -x -O ./PATH

Used by samples/fetch.sh to take one file out of a large package without
downloading all of it: the pipeline stops once tar has found the file.
"""
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: deb_member.py MEMBER < package.deb > member")
    name = sys.argv[1].encode()
    inp, out = sys.stdin.buffer, sys.stdout.buffer
    if inp.read(8) != b"!<arch>\n":
        sys.exit("deb_member.py: stdin is not an ar archive (a .deb)")
    while True:
        header = inp.read(60)
        if len(header) < 60:
            sys.exit("deb_member.py: no member %s" % sys.argv[1])
        member = header[0:16].strip().rstrip(b"/")
        size = int(header[48:58])
        if member == name:
            left = size
            try:
                while left:
                    block = inp.read(min(left, 1 << 20))
                    if not block:
                        sys.exit("deb_member.py: %s is truncated" % sys.argv[1])
                    out.write(block)
                    left -= len(block)
                out.flush()
            except BrokenPipeError:  # the reader has what it wanted
                pass
            return
        inp.read(size + (size & 1))


if __name__ == "__main__":
    main()
