#!/usr/bin/env python3
"""Runs the command blocks the README and docs/ mark as runnable, against
this build, and fails on a non-zero exit. A block is marked by its first
line, a comment that may say how to make it small:

    ```sh
    # runnable: 240x240 -> 32x32; --spp 96 -> --spp 2
    tessera-render builtin:cornell --size 240x240 --spp 96 --aperture 30 --focus-distance 880 --output dof.exr
    ```

Each "A -> B" replaces text A by B in the block before it runs. The block
runs with bash -e in a fresh folder that sees the repository's configs/
scripts/ and tests/, with the build's programs first on PATH.

    runnable_docs.py BIN_DIR REPO_DIR [PAGE ...]   (pages: only those, e.g. docs/viewer.md)
"""
import os
import re
import signal
import subprocess
import sys
import tempfile

from doc_pages import pages, report

MARK = re.compile(r"^#\s*runnable\b:?(.*)$")


def blocks(path):
    """(first line number, substitutions, text) of each marked fenced block.
    Raises ValueError for a fence that is never closed (the rest of the page
    would run as shell) and for a substitution that replaces nothing."""
    lines, found, i = open(path, encoding="utf-8").read().splitlines(), [], 0
    while i < len(lines):
        if not lines[i].strip().startswith("```"):
            i += 1
            continue
        end = i + 1
        while end < len(lines) and not lines[end].strip().startswith("```"):
            end += 1
        if end == len(lines):
            raise ValueError("line %d: a code fence that is never closed" % (i + 1))
        mark = MARK.match(lines[i + 1].strip()) if i + 1 < end else None
        if mark:
            rules = [r.split("->", 1) for r in mark.group(1).split(";") if "->" in r]
            rules = [(a.strip(), b.strip()) for a, b in rules]
            if any(not a for a, _ in rules):
                raise ValueError("line %d: a substitution with nothing to replace" % (i + 2))
            found.append((i + 2, rules, "\n".join(lines[i + 2:end])))
        i = end + 1
    return found


def run_block(text, work, env, timeout=120):
    """Exit status and output of the block. It runs in its own process
    group, killed when the block ends, so what a failed block started in
    the background (nodes) neither lingers nor holds the output open."""
    with open(os.path.join(work, ".output"), "w+") as out:
        p = subprocess.Popen(["bash", "-e", "-o", "pipefail", "-c", text], cwd=work, env=env, stdout=out, stderr=subprocess.STDOUT,
                             start_new_session=True)
        try:
            code = p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            code = -1
            print("timed out after %d s" % timeout, file=out)
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass  # the group is gone already
        p.wait()
        out.seek(0)
        return code, out.read()


def main():
    bin_dir, repo = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    chosen = [os.path.join(repo, p) for p in sys.argv[3:]] or pages(repo)
    # BUILD: the folder scripts/cluster-demo.sh takes its programs from.
    env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ.get("PATH", ""), BUILD=os.path.dirname(bin_dir))
    failed, ran = [], 0
    for page in chosen:
        try:
            marked = blocks(page)
        except ValueError as e:
            failed.append("%s: %s" % (os.path.relpath(page, repo), e))
            continue
        for line, rules, text in marked:
            for a, b in rules:
                if a not in text:
                    failed.append("%s:%d: the substitution '%s' finds nothing" % (os.path.relpath(page, repo), line, a))
                text = text.replace(a, b)
            with tempfile.TemporaryDirectory() as work:
                for folder in ("configs", "scripts", "tests"):
                    os.symlink(os.path.join(repo, folder), os.path.join(work, folder))
                code, output = run_block(text, work, env)
            ran += 1
            where = "%s:%d" % (os.path.relpath(page, repo), line)
            print("%s: exit %d" % (where, code))
            if code != 0:
                failed.append("%s failed (exit %d):\n%s\n%s" % (where, code, text, output))
    return report(failed, "%d runnable blocks run, %d failed" % (ran, len(failed)), ran)


if __name__ == "__main__":
    sys.exit(main())
