"""Every Python snippet of the README and of the book runs as shown.

Each page's ```python blocks are run in order, in one namespace (as a reader would type them into
one session), in a scratch directory that holds links to the repository's `models/` and
`validation/`, so that the snippets name the repository's files as they are named at the root of
a clone. A failure names the page and the line of the snippet.
"""

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def documents():
    return [ROOT / "README.md"] + sorted((ROOT / "book" / "src").rglob("*.md"))


def snippets(text):
    """The ```python blocks of a page: (line number of the first code line, code)."""
    lines = text.splitlines()
    found = []
    i = 0
    while i < len(lines):
        fence = lines[i].strip()
        if fence.startswith("```"):
            end = i + 1
            while end < len(lines) and not lines[end].strip().startswith("```"):
                end += 1
            if fence[3:].strip().split(",")[0] == "python":
                found.append((i + 2, "\n".join(lines[i + 1:end])))
            i = end + 1
        else:
            i += 1
    return found


PAGES = [p for p in documents() if snippets(p.read_text())]


def test_snippets_are_found():
    assert snippets("text\n```python\nx = 1\n```\n```sh\nls\n```\n```python\ny = 2\n```\n") == [
        (3, "x = 1"),
        (9, "y = 2"),
    ]
    names = {p.relative_to(ROOT).as_posix() for p in PAGES}
    assert "README.md" in names, names
    assert "book/src/getting-started/python.md" in names, names


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_the_snippets_of_a_page_run(page, tmp_path, monkeypatch):
    for linked in ["models", "validation"]:
        os.symlink(ROOT / linked, tmp_path / linked)
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__main__"}
    name = page.relative_to(ROOT).as_posix()
    for line, code in snippets(page.read_text()):
        # Padded so that a traceback gives the line of the page.
        exec(compile("\n" * (line - 1) + code, name, "exec"), namespace)
