"""The documentation's Python examples, run: every ```python block in README.md and docs/**/*.md
(and python/README.md)
is run in a scratch directory and, where a ```text block follows it, must print those lines
(trailing spaces ignored). A block that is a fragment (it cannot run alone) carries
`<!-- check: skip (REASON) -->` on the line before its fence, as the shell examples do
(tests/suite/docs_examples.rs)."""

import pathlib
import re
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def documents():
    return [ROOT / "README.md", ROOT / "python" / "README.md"] + sorted(
        (ROOT / "docs").rglob("*.md")
    )


def python_blocks(path):
    """(line, code, shown output or None, skip reason or None) for each python block."""
    lines = path.read_text(encoding="utf-8").split("\n")
    blocks, i = [], 0
    while i < len(lines):
        if lines[i].strip() == "```python":
            start = i + 1
            marker = lines[i - 1].strip() if i > 0 else ""
            skip = re.fullmatch(r"<!-- check: skip \((.+)\) -->", marker)
            j = start
            while lines[j].strip() != "```":
                j += 1
            code = "\n".join(lines[start:j])
            # The output: the next fenced text block, where only blank lines come between.
            k = j + 1
            while k < len(lines) and not lines[k].strip():
                k += 1
            shown = None
            if k < len(lines) and lines[k].strip() == "```text":
                m = k + 1
                while lines[m].strip() != "```":
                    m += 1
                body = lines[k + 1 : m]
                if not any(l.startswith("$ ") for l in body):
                    shown = body
            blocks.append((start, code, shown, skip.group(1) if skip else None))
            i = j + 1
        else:
            i += 1
    return blocks


CASES = [
    pytest.param(doc, block, id=f"{doc.relative_to(ROOT)}:{block[0]}")
    for doc in documents()
    for block in python_blocks(doc)
]


def test_the_documents_have_python_examples():
    assert len(CASES) >= 2


@pytest.mark.parametrize("doc,block", CASES)
def test_python_example_prints_what_it_shows(doc, block, tmp_path):
    line, code, shown, skip = block
    if skip is not None:
        # A marked fragment must still be valid Python.
        compile(code, f"{doc.name}:{line}", "exec")
        return
    # The repository's files the example reads, at the same relative paths.
    for rel in re.findall(r"[\"']((?:gallery|tests/data|examples)/[^\"']+)[\"']", code):
        src = ROOT / rel
        if src.is_file():
            (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(src, tmp_path / rel)
    r = subprocess.run(
        [sys.executable, "-c", code],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, f"{doc.name}:{line}: {r.stderr}"
    if shown is None:
        return
    got = [l.rstrip() for l in r.stdout.rstrip("\n").split("\n")]
    want = [l.rstrip() for l in shown]
    while want and not want[-1]:
        want.pop()
    assert got == want, f"{doc.name}:{line}: printed\n" + "\n".join(got)
