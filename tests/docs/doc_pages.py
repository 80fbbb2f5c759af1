"""What the docs checks share: which pages they read, and how they end."""
import glob
import os


def pages(repo):
    """The README and every page of docs/."""
    return [os.path.join(repo, "README.md")] + sorted(glob.glob(os.path.join(repo, "docs", "*.md")))


def report(problems, summary, count):
    """Prints each problem and the summary; the exit status: 1 when there are
    problems or nothing was checked (a check that found nothing to check
    would pass forever)."""
    for p in problems:
        print(p)
    print(summary)
    return 1 if problems or count == 0 else 0
