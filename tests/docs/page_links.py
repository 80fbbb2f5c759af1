#!/usr/bin/env python3
"""Every relative link and image of the README and docs/ leads to a file of
the repository (or, with #anchor, to a heading of that page), so moving or
renaming a page breaks the build, not the reader.

    page_links.py REPO_DIR
"""
import os
import re
import sys

from doc_pages import pages, report

# [text](target), [text](<target>), [text](target "title")
LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def anchors(path):
    """GitHub's anchors of a page's headings (not of '#' lines inside code
    blocks); a repeated heading gets -1, -2, ..."""
    out, seen, fenced = set(), {}, False
    for line in open(path, encoding="utf-8"):
        if line.strip().startswith("```"):
            fenced = not fenced
        if fenced or not line.startswith("#"):
            continue
        text = line.lstrip("#").strip().lower()
        anchor = re.sub(r"[^\w\- ]", "", text).replace(" ", "-")
        count = seen.get(anchor, 0)
        seen[anchor] = count + 1
        out.add(anchor if count == 0 else "%s-%d" % (anchor, count))
    return out


def main():
    repo = os.path.abspath(sys.argv[1])
    broken, checked = [], 0
    for page in pages(repo):
        fenced = False
        for number, line in enumerate(open(page, encoding="utf-8"), 1):
            if line.strip().startswith("```"):
                fenced = not fenced
            if fenced or line.startswith("    "):  # code, fenced or indented
                continue
            for target in LINK.findall(line):
                if re.match(r"^[a-z]+:", target):
                    continue  # http:, mailto:: not ours to check here
                checked += 1
                path, _, anchor = target.partition("#")
                file = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
                where = "%s:%d" % (os.path.relpath(page, repo), number)
                if not os.path.exists(file):
                    broken.append("%s: %s leads nowhere" % (where, target))
                elif anchor and file.endswith(".md") and anchor not in anchors(file):
                    broken.append("%s: %s names no heading of %s" % (where, target, os.path.relpath(file, repo)))
    return report(broken, "%d links checked, %d broken" % (checked, len(broken)), checked)


if __name__ == "__main__":
    sys.exit(main())
