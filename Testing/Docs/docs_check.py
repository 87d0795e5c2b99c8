# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Keep the Markdown documentation honest: its code runs and its links resolve.

    docs_check.py links SOURCE_DIR
        Every relative link and image of every Markdown file in the tree
        (README.md, CHANGELOG.md, docs/, the data and fuzz notes) must name
        a file or folder that exists, and a #fragment a heading (GitHub's
        anchors) or an <a id/name> of the file it points into.

    docs_check.py python SOURCE_DIR SCRATCH_DIR [--python EXE]
        Every ```python block of README.md and docs/ runs in a fresh
        interpreter, in a scratch folder of its own that holds links to the
        tree's Testing, Examples, IO and scripts folders (so paths like
        Testing/Data/bunny.vtp work and outputs land in the scratch). A block
        whose info string is `python skip` is not run (pvpython, mpiexec, a
        GPU or data that is not in the tree). A block fails on a non-zero
        exit, a VTK error message or running past --timeout seconds.

    docs_check.py cpp SOURCE_DIR OUT_DIR
        Writes every ```cpp block of README.md and docs/ (except `cpp skip`)
        to OUT_DIR/<file>_L<line>.cxx, rewriting only what changed and
        removing what is gone, and prints their paths, one per line: CMake
        builds each as a program against the modules (Testing/Docs).

Exit status 1 and one line per problem, naming the file and line.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

SKIP_DIRS = {".git", "build", "node_modules"}
BROKEN = ("Testing", "Docs", "Broken")  # broken on purpose: its own tests
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([^\s`]*)\s*(.*)$")
LINK = re.compile(r"!?\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)", re.S)
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$")
HTML_ANCHOR = re.compile(r"<a\s+(?:id|name)=\"([^\"]+)\"", re.I)
HTML_SRC = re.compile(r"<(?:img|a)\s[^>]*(?:src|href)=\"([^\"]+)\"", re.I)
CODE_SPAN = re.compile(r"(`+).*?\1")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
VTK_ERROR = re.compile(r"^(ERROR|Generic Warning): In ", re.M)


def markdown_files(root, only_docs=False):
    """README.md and docs/ (only_docs), or every Markdown file of the tree."""
    if only_docs:
        found = [os.path.join(root, "README.md")]
        for base, dirs, files in os.walk(os.path.join(root, "docs")):
            dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS)
            found += [os.path.join(base, f) for f in sorted(files) if f.endswith(".md")]
        return [f for f in found if os.path.isfile(f)]
    found = []
    for base, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith(".")
                         and os.path.join(base, d) != os.path.join(root, *BROKEN))
        found += [os.path.join(base, f) for f in sorted(files) if f.endswith(".md")]
    return found


def blocks(path):
    """(line of the opening fence, language, flags, text) of each fenced block."""
    out = []
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, fence, language, flags = m.groups()
        start = i + 1
        body = []
        i += 1
        while i < len(lines):
            close = lines[i].strip()
            if close.startswith(fence[0] * len(fence)) and set(close) == {fence[0]}:
                break
            line = lines[i]
            body.append(line[len(indent):] if line.startswith(indent) else line.lstrip())
            i += 1
        out.append((start, language.lower(), flags.split(), "\n".join(body) + "\n"))
        i += 1
    return out


def prose_lines(path):
    """(line number, text) of the lines outside fenced code, code spans blanked."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    inside = None
    for number, line in enumerate(lines, 1):
        m = FENCE.match(line)
        if inside is None and m:
            inside = m.group(2)[0] * len(m.group(2))
            continue
        if inside is not None:
            if line.strip().startswith(inside) and set(line.strip()) == {inside[0]}:
                inside = None
            continue
        yield number, CODE_SPAN.sub(lambda s: " " * len(s.group(0)), line)


def slug(text):
    """GitHub's anchor for a heading."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links keep their text
    text = re.sub(r"<[^>]+>", "", text)  # inline HTML
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


_anchor_cache = {}


def anchors(path):
    if path not in _anchor_cache:
        seen, found = {}, set()
        for _, line in prose_lines(path):
            found.update(HTML_ANCHOR.findall(line))
            m = HEADING.match(line)
            if not m:
                continue
            base = slug(m.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else "%s-%d" % (base, count))
        _anchor_cache[path] = found
    return _anchor_cache[path]


def check_links(root):
    problems = []
    files = markdown_files(root)
    for path in files:
        rel = os.path.relpath(path, root)
        numbered = list(prose_lines(path))
        # Whole text, so that a link wrapped over two lines is found too.
        text = "\n".join(line for _, line in numbered)
        starts = [0]
        for _, line in numbered:
            starts.append(starts[-1] + len(line) + 1)
        found = [(m.start(), m.group(2)) for m in LINK.finditer(text)]
        found += [(m.start(), m.group(1)) for m in HTML_SRC.finditer(text)]
        for index, (_, line) in enumerate(numbered):
            m = REFERENCE.match(line)
            if m:
                found.append((starts[index], m.group(1)))
        for offset, target in sorted(found):
            problem = check_target(root, path, target)
            if problem:
                index = max(i for i, start in enumerate(starts) if start <= offset)
                problems.append("%s:%d: %s" % (rel, numbered[index][0], problem))
    return files, problems


def check_target(root, path, target):
    if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto: ...
        return None
    if target.startswith("/"):
        return "absolute link %r (use a path relative to this file)" % target
    where, _, fragment = target.partition("#")
    resolved = os.path.normpath(os.path.join(os.path.dirname(path), where)) if where else path
    inside = os.path.relpath(resolved, root)
    if inside.startswith(".."):
        return "link %r leaves the repository" % target
    if not os.path.exists(resolved):
        return "broken link %r: no %s" % (target, inside)
    if fragment and resolved.endswith(".md"):
        if fragment not in anchors(resolved):
            return "broken link %r: %s has no heading with the anchor #%s" % (
                target, inside, fragment)
    return None


def run_python(root, scratch, python, timeout):
    problems, ran, skipped = [], 0, 0
    os.makedirs(scratch, exist_ok=True)
    for path in markdown_files(root, only_docs=True):
        rel = os.path.relpath(path, root)
        for line, language, flags, text in blocks(path):
            if language not in ("python", "py", "python3"):
                continue
            if "skip" in flags:
                skipped += 1
                continue
            ran += 1
            name = "%s_L%d" % (re.sub(r"[^\w]", "_", rel), line)
            work = tempfile.mkdtemp(prefix=name + ".", dir=scratch)
            for folder in ("Testing", "Examples", "IO", "scripts"):
                os.symlink(os.path.join(root, folder), os.path.join(work, folder))
            script = os.path.join(work, "block.py")
            with open(script, "w", encoding="utf-8") as f:
                f.write(text)
            try:
                done = subprocess.run([python, script], cwd=work, stdout=subprocess.PIPE,
                                      stderr=subprocess.STDOUT, timeout=timeout)
                output = done.stdout.decode("utf-8", "replace")
                failed = done.returncode != 0 or VTK_ERROR.search(output)
                reason = "exit status %d" % done.returncode if done.returncode else "a VTK error"
            except subprocess.TimeoutExpired as e:
                output = (e.stdout or b"").decode("utf-8", "replace")
                failed, reason = True, "still running after %d s" % timeout
            print("%s %s:%d" % ("FAIL" if failed else "ok  ", rel, line), flush=True)
            if failed:
                problems.append("%s:%d: the python block fails (%s):\n%s" % (
                    rel, line, reason, "\n".join(output.splitlines()[-25:])))
    print("python blocks: %d run, %d marked skip" % (ran, skipped))
    if ran == 0:
        problems.append("no python block found in README.md and docs/: nothing was checked")
    return problems


def write_cpp(root, out):
    os.makedirs(out, exist_ok=True)
    written = set()
    for path in markdown_files(root, only_docs=True):
        rel = os.path.relpath(path, root)
        for line, language, flags, text in blocks(path):
            if language not in ("cpp", "c++", "cxx") or "skip" in flags:
                continue
            name = "%s_L%d.cxx" % (re.sub(r"[^\w]", "_", os.path.splitext(rel)[0]), line)
            target = os.path.join(out, name)
            content = "// From %s, line %d (Testing/Docs/docs_check.py cpp)\n#line %d \"%s\"\n%s" % (
                rel, line, line + 1, rel, text)
            old = None
            if os.path.exists(target):
                with open(target, encoding="utf-8") as f:
                    old = f.read()
            if old != content:
                with open(target, "w", encoding="utf-8") as f:
                    f.write(content)
            written.add(name)
            print(target)
    for stale in os.listdir(out):
        if stale.endswith(".cxx") and stale not in written:
            os.remove(os.path.join(out, stale))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mode", choices=("links", "python", "cpp"))
    parser.add_argument("source", help="the repository's top folder")
    parser.add_argument("scratch", nargs="?", help="python: scratch folder; cpp: output folder")
    parser.add_argument("--python", default=sys.executable)
    parser.add_argument("--timeout", type=int, default=180, help="python: seconds per block")
    args = parser.parse_args()
    root = os.path.realpath(args.source)
    if args.mode == "cpp":
        write_cpp(root, args.scratch)
        return 0
    if args.mode == "links":
        files, problems = check_links(root)
        print("links: %d Markdown files checked" % len(files))
    else:
        if not args.scratch:
            parser.error("python needs a scratch folder")
        problems = run_python(root, args.scratch, args.python, args.timeout)
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
