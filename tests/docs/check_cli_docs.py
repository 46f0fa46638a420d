#!/usr/bin/env python3
"""Checks docs/cli.md against the programs' --help, both ways.

    check_cli_docs.py --tiler PATH --vectorize PATH --view PATH --serve PATH
                      [--cli-md docs/cli.md]

Standard library only. Exit status: 0 the two agree, 1 at least one mismatch
(each printed on stdout, one per line) or a program whose --help fails,
2 usage error.

What --help says
  * `PROGRAM --help` lists the commands in its `commands:` block, one per line
    indented by two spaces (`  terrain INPUT... -o OUT.mbtiles  ...`). A program
    without that block (globe-view, globe-serve) is one command: itself.
  * `PROGRAM COMMAND --help` (or `PROGRAM --help`) lists the options in its
    `options:` block: lines indented by two spaces that start with `-`. The part
    before the first gap of two or more spaces is the option's spelling
    (`-j, --threads N`); its `-x` and `--name` words are one option, so the docs
    may name it by either (`-j` or `--threads`).
  * -h, --help and --version are in every command's --help and are not
    required per command (cli.md says once that every program has them).

What docs/cli.md says
  * A chapter is a `# PROGRAM command line` heading; text before the first
    chapter is not read.
  * Every heading inside a chapter starts a section. A section is a *command
    section* when its heading, without backticks, a trailing `options` and a
    trailing `(PROGRAM)`, is a list of the program's commands (`## terrain
    options`, `## info, validate, extract`, `## export (globe-vectorize)`). In a
    chapter of a program without commands the whole chapter is its section.
  * Options are read from code only: inline `code spans` (which may run over
    a line break) and fenced code blocks, whose lines starting with a program
    name begin a synopsis and whose other lines continue the one above.
    Words in prose outside backticks are not read.
  * Each span (or synopsis) belongs to a command:
      - `globe-X COMMAND ...`: that command of globe-X (`globe-X ...` for a
        program without commands);
      - `COMMAND ...`, a command of the chapter's program: that command
        (`extract --layer NAME` in the globe-tiler chapter);
      - anything else: the commands of the section it is in (none outside
        a command section: then it is not read).
  * A span *documents* its options when it is in a fenced code block (a
    chapter's synopsis) or its command is one of its section's commands
    (the section's own synopsis, tables and prose). Any other span naming a
    command is a cross-reference (`see globe-view --pick`, `as for
    globe-tiler terrain --shard`): its options must exist in that command's
    --help, but they do not document it.
  * A command section, or a span naming `globe-X word` where `word` looks
    like a command (lower case), that names a command --help does not have is
    a mismatch too.

Mismatches, one per line:
    docs/cli.md: globe-tiler export: --foo is not in --help (line N)
    globe-tiler export --help: --bar is not in docs/cli.md
    globe-tiler --help: merge has no section in docs/cli.md
    docs/cli.md: globe-tiler fuse is not a command in --help (line N)
"""

import argparse
import os
import re
import subprocess
import sys

PROGRAMS = ("globe-tiler", "globe-vectorize", "globe-view", "globe-serve")
UNIVERSAL = {"-h", "--help", "--version"}
# An option word: --name or -x, not part of a longer word (quantized-mesh,
# weight-1, gdalwarp's -et).
OPTION = re.compile(r"(?<![\w-])(--[a-z][a-z0-9_-]*[a-z0-9]|-[a-zA-Z])(?![\w-])")
HELP_TIMEOUT_S = 30


class UsageError(Exception):
    pass


# ---------------------------------------------------------------------------
# --help
# ---------------------------------------------------------------------------

def run_help(path, args):
    """Returns the text of PATH ARGS --help (stdout and stderr)."""
    shown = " ".join([os.path.basename(path)] + args + ["--help"])
    try:
        r = subprocess.run([path] + args + ["--help"], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, timeout=HELP_TIMEOUT_S)
    except OSError as e:
        raise RuntimeError(f"{shown}: cannot run: {e}")
    except subprocess.TimeoutExpired:
        raise RuntimeError(f"{shown}: no answer within {HELP_TIMEOUT_S} s")
    text = r.stdout.decode("utf-8", "replace")
    if r.returncode != 0 or "usage:" not in text:
        raise RuntimeError(f"{shown}: exit {r.returncode}, no usage text:\n{text}")
    return text


def block(text, title):
    """The lines of the block that starts with the line `title` and ends at
    the next blank or unindented line."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.strip() == title and not line.startswith(" "):
            out = []
            for l in lines[i + 1:]:
                if not l.strip() or not l.startswith(" "):
                    break
                out.append(l)
            return out
    return None


def help_commands(text):
    """The commands of a top-level --help, or None for a one-command program."""
    lines = block(text, "commands:")
    if lines is None:
        return None
    return [m.group(1) for m in (re.match(r"^  ([a-z][a-z0-9-]*)(?:\s|$)", l) for l in lines) if m]


def help_options(text):
    """The options of a command's --help: a list of sets of spellings."""
    lines = block(text, "options:")
    if lines is None:
        return []
    options = []
    for line in lines:
        if not re.match(r"^  -", line):
            continue  # a description's continuation line
        spec = re.split(r"\s{2,}", line.strip(), maxsplit=1)[0]
        names = {w.rstrip(",") for w in spec.split() if OPTION.fullmatch(w.rstrip(","))}
        if names:
            options.append(names)
    return options


def read_help(paths):
    """{program: {command: [set of spellings]}}; command None for a program
    without commands. Raises RuntimeError when a --help fails."""
    out = {}
    for program in PROGRAMS:
        path = paths[program]
        top = run_help(path, [])
        commands = help_commands(top)
        if commands is None:
            out[program] = {None: help_options(top)}
            continue
        if not commands:
            raise RuntimeError(f"{program} --help: an empty commands: block")
        out[program] = {c: help_options(run_help(path, [c])) for c in commands}
    return out


# ---------------------------------------------------------------------------
# docs/cli.md
# ---------------------------------------------------------------------------

class Span:
    def __init__(self, text, line, fenced):
        self.text = text
        self.line = line      # 1-based line of its start
        self.fenced = fenced  # in a fenced code block


class Section:
    def __init__(self, heading, line):
        self.heading = heading
        self.line = line
        self.lines = []  # (line number, text)


def split_chapters(md_lines):
    """[(program or None, heading line, [Section])]: `# ` headings start
    chapters, deeper ones sections; the chapter's text before its first
    section is a section with heading None."""
    chapters = []
    fenced = False
    for n, line in enumerate(md_lines, 1):
        if line.startswith("```"):
            fenced = not fenced
        if not fenced:
            m = re.match(r"^(#+)\s+(.*?)\s*$", line)
            if m and len(m.group(1)) == 1:
                c = re.match(r"^`?(globe-[a-z]+)`? command line$", m.group(2))
                chapters.append((c.group(1) if c else m.group(2), n, [Section(None, n)]))
                continue
            if m and chapters:
                chapters[-1][2].append(Section(m.group(2), n))
                continue
        if chapters:
            chapters[-1][2][-1].lines.append((n, line))
    return chapters


def spans_of(section):
    """The code spans and fenced synopses of a section, as Span."""
    spans = []
    prose = []  # (line number, text) outside fences
    fenced = False
    for n, line in section.lines:
        if line.startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            if line.strip().startswith("globe-") or not spans or not spans[-1].fenced:
                spans.append(Span(line.strip(), n, True))
            else:
                spans[-1].text += " " + line.strip()
        else:
            prose.append((n, line))
    # Inline spans may run over a line break: read the prose as one text.
    text = "\n".join(l for _, l in prose)
    starts = []
    offset = 0
    for n, l in prose:
        starts.append((offset, n))
        offset += len(l) + 1

    def line_at(pos):
        n = prose[0][0] if prose else section.line
        for off, ln in starts:
            if off > pos:
                break
            n = ln
        return n

    for m in re.finditer(r"(`+)(.+?)\1", text, re.S):
        spans.append(Span(" ".join(m.group(2).split()), line_at(m.start()), False))
    return spans


def section_commands(heading, program, commands):
    """(commands the heading names, unknown names) for a command section;
    (None, []) when it is not one."""
    h = heading.replace("`", "").strip()
    h = re.sub(r"\s*\(" + re.escape(program) + r"\)$", "", h)
    ends_in_options = bool(re.search(r"\s+options$", h))
    h = re.sub(r"\s+options$", "", h)
    parts = [p for p in re.split(r",\s*|\s+and\s+", h) if p]
    if not parts or not all(re.fullmatch(r"[a-z][a-z0-9-]*", p) for p in parts):
        return None, []
    known = [p for p in parts if p in commands]
    unknown = [p for p in parts if p not in commands]
    if not known and not ends_in_options:
        return None, []
    return known, unknown


def read_docs(md_path, help_of, shown):
    """Returns (documented, mentions, sections, problems):
    documented: {(program, command): set of option words} that document,
    mentions: [(program, command, option, line)] every option read,
    sections: set of (program, command) with a command section,
    problems: [str] mismatches found while reading."""
    with open(md_path, encoding="utf-8") as f:
        md_lines = f.read().splitlines()
    documented = {}
    mentions = []
    sections = set()
    problems = []

    def attribute(span, program, here):
        """The (program, command) a span belongs to, or None; records a
        command --help does not have as a problem."""
        words = span.text.replace("[", " ").replace("]", " ").split()
        if not words:
            return None
        if words[0] in PROGRAMS:
            p = words[0]
            cmds = help_of[p]
            if None in cmds:
                return (p, None)
            if len(words) > 1 and words[1] in cmds:
                return (p, words[1])
            if len(words) > 1 and re.fullmatch(r"[a-z][a-z0-9-]*", words[1]):
                problems.append(f"{shown}: {p} {words[1]} is not a command in --help "
                                f"(line {span.line})")
                return None
            return (p, "")  # the program itself: `globe-tiler COMMAND --help`
        if program in help_of and None not in help_of[program] and words[0] in help_of[program]:
            return (program, words[0])
        return here

    for program, line, secs in split_chapters(md_lines):
        if program not in PROGRAMS:
            if program.startswith("globe-"):
                problems.append(f"{shown}: {program} is not one of the programs checked "
                                f"(line {line})")
            continue
        cmds = help_of[program]
        single = None in cmds
        for sec in secs:
            if single:
                here = [(program, None)]
            elif sec.heading is None:
                here = []
            else:
                known, unknown = section_commands(sec.heading, program, cmds)
                for u in unknown:
                    problems.append(f"{shown}: {program} {u} is not a command in --help "
                                    f"(line {sec.line})")
                here = [(program, c) for c in (known or [])]
            sections.update(here)
            for span in spans_of(sec):
                options = OPTION.findall(span.text)
                if not options:
                    attribute(span, program, None)  # still checks command names
                    continue
                target = attribute(span, program, None)
                targets = [target] if target else here
                for t in targets:
                    docs = span.fenced or t in here
                    for o in options:
                        if o in UNIVERSAL:
                            continue
                        mentions.append((t[0], t[1], o, span.line))
                        if docs:
                            documented.setdefault(t, set()).add(o)
    return documented, mentions, sections, problems


# ---------------------------------------------------------------------------

def name(program, command):
    return program if not command else f"{program} {command}"


def check(help_of, md_path, shown):
    documented, mentions, sections, problems = read_docs(md_path, help_of, shown)
    out = list(problems)
    # Every option the docs name exists in that command's --help.
    for program, command, option, line in mentions:
        if command == "":
            out.append(f"{shown}: {program}: {option} is not in --help (line {line})")
            continue
        spellings = set().union(*help_of[program][command]) if help_of[program][command] else set()
        if option not in spellings:
            out.append(f"{shown}: {name(program, command)}: {option} is not in --help "
                       f"(line {line})")
    # Every command has a section, every option of its --help is documented.
    for program in PROGRAMS:
        for command, options in help_of[program].items():
            if (program, command) not in sections:
                if command is None:
                    out.append(f"{program} --help: {program} has no chapter "
                               f"'# {program} command line' in {shown}")
                else:
                    out.append(f"{program} --help: {command} has no section in {shown}")
            docs = documented.get((program, command), set())
            for spellings in options:
                if spellings & UNIVERSAL or spellings & docs:
                    continue
                shown_opt = ", ".join(sorted(spellings, key=len))
                out.append(f"{name(program, command)} --help: {shown_opt} is not in {shown}")
    # Unique, in the order found.
    seen = set()
    return [m for m in out if not (m in seen or seen.add(m))]


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    parser = argparse.ArgumentParser(
        description="Checks docs/cli.md against the programs' --help, both ways "
                    "(rules at the top of this script).")
    parser.add_argument("--tiler", required=True, help="the globe-tiler executable")
    parser.add_argument("--vectorize", required=True, help="the globe-vectorize executable")
    parser.add_argument("--view", required=True, help="the globe-view executable")
    parser.add_argument("--serve", required=True, help="the globe-serve executable")
    parser.add_argument("--cli-md", default=os.path.join(root, "docs", "cli.md"),
                        help="the document (default: docs/cli.md of this tree)")
    args = parser.parse_args(argv)  # exits 2 on a usage error
    paths = dict(zip(PROGRAMS, (args.tiler, args.vectorize, args.view, args.serve)))
    for program, path in paths.items():
        if not (os.path.isfile(path) and os.access(path, os.X_OK)):
            raise UsageError(f"{program}: {path} is not an executable file")
    if not os.path.isfile(args.cli_md):
        raise UsageError(f"{args.cli_md}: no such file")
    rel = os.path.relpath(os.path.abspath(args.cli_md), root)
    shown = rel if not rel.startswith("..") else args.cli_md
    try:
        help_of = read_help(paths)
    except RuntimeError as e:
        print(f"check_cli_docs: {e}", file=sys.stderr)
        return 1
    mismatches = check(help_of, args.cli_md, shown)
    for m in mismatches:
        print(m)
    commands = sum(len(c) for c in help_of.values())
    options = sum(len(o) for c in help_of.values() for o in c.values())
    if mismatches:
        print(f"check_cli_docs: {len(mismatches)} mismatches between {shown} and --help",
              file=sys.stderr)
        return 1
    print(f"check_cli_docs: {shown} matches --help: {len(PROGRAMS)} programs, "
          f"{commands} commands, {options} options")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except UsageError as e:
        print(f"check_cli_docs: {e}", file=sys.stderr)
        sys.exit(2)
