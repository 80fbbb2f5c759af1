#!/usr/bin/env python3
"""Every option the README and docs/ show a program with exists: for each
command line in a code block (indented or fenced) that runs a tessera-*
program, each --option on it must be listed by that program's --help.
A renamed or dropped option breaks the test suite, not the reader.

    documented_options.py BIN_DIR REPO_DIR
"""
import os
import re
import subprocess
import sys

from doc_pages import pages, report

# (An option given as another's value, --node-arg=--present, is that program's business.)
OPTION = re.compile(r"(?<![\w=-])(--[a-z][a-z0-9-]*)")


def code_lines(path):
    """The lines of a Markdown file's code blocks, continuation lines joined."""
    lines, fenced, out = open(path, encoding="utf-8").read().splitlines(), False, []
    for line in lines:
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced or line.startswith("    "):
            out.append(line.strip())
    joined, buf = [], ""
    for line in out:
        buf += " " + line.rstrip("\\")
        if not line.endswith("\\"):
            joined.append(buf.strip())
            buf = ""
    return joined


PREFIXES = {"mpirun", "srun", "xvfb-run", "time", "env", "sudo"}


def commands(line):
    """(program, its arguments) for each tessera program the line runs: the
    first word, the first tessera word after a launcher (mpirun, srun,
    xvfb-run), or a word after `--`, `&&`, `;` or `|`."""
    words = [w for w in line.split() if not re.match(r"^[A-Z_][A-Z0-9_]*=", w)]  # VAR=value prefixes
    out, current, launcher = [], None, bool(words) and os.path.basename(words[0]) in PREFIXES
    for i, word in enumerate(words):
        name = os.path.basename(word)
        starts = i == 0 or words[i - 1] in ("--", "&&", ";", "|") or (launcher and current is None)
        if starts and re.fullmatch(r"tessera-[a-z]+", name):
            current = (name, [])
            out.append(current)
        elif current is not None and word not in ("--", "&&", ";", "|"):
            current[1].append(word)
        elif word in ("&&", ";", "|"):
            current = None
    return out


def main():
    bin_dir, repo = sys.argv[1], sys.argv[2]
    helps, missing, checked = {}, [], 0
    for page in pages(repo):
        for line in code_lines(page):
            line = line.split(" #", 1)[0]  # a comment after the command
            for program, arguments in commands(line):
                exe = os.path.join(bin_dir, program)
                if not os.path.exists(exe):
                    missing.append("%s: %s is not a program of this build (in: %s)" % (
                        os.path.relpath(page, repo), program, line))
                    continue
                if program not in helps:
                    helps[program] = subprocess.run([exe, "--help"], capture_output=True, text=True).stdout
                listed = set(OPTION.findall(helps[program]))
                for option in OPTION.findall(" ".join(arguments)):
                    checked += 1
                    if option not in listed:
                        missing.append("%s: %s has no option %s (in: %s)" % (os.path.relpath(page, repo), program,
                                                                             option, line))
    return report(missing, "%d options on %d programs' command lines checked, %d missing" % (
        checked, len(helps), len(missing)), checked)


if __name__ == "__main__":
    sys.exit(main())
