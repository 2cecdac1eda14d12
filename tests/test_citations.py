"""The project's documentation stands on its own: code and docs cite man
pages (``stencil(3G)``) and the project's own docs/ pages, never files
outside the repository, and every "docs/semantics.md §N" names a section
that exists."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = ["irisgl", "vgx_emulator", "study", "programs", "benchmarks", "tests", "docs"]
FORBIDDEN = re.compile(r"\breference (?:sections? )?\d|\bDecisions? \d|porting conventions|"
                       r"porting-conventions|irisgl-reference|reference sheet|pitfalls|"
                       r"\bdesign\.md|\.\./shared|\[M-PG|\[M-AIX")


def _files():
    for folder in FOLDERS:
        for p in (ROOT / folder).rglob("*"):
            if p.suffix in (".py", ".md", ".pyi") and p.name != "test_citations.py":
                yield p
    yield ROOT / "README.md"


def test_no_citation_of_files_outside_the_repository():
    bad = []
    for p in _files():
        for i, line in enumerate(p.read_text(errors="replace").splitlines(), 1):
            if FORBIDDEN.search(line):
                bad.append(f"{p.relative_to(ROOT)}:{i}: {line.strip()[:80]}")
    assert bad == [], (
        "cite a man page (stencil(3G)) or a section of the project's docs instead: the old "
        "'reference N' is docs/semantics.md §N; Decisions 1-2 are §6, 3-4 §5, 5 and 13 §1, "
        "6 §3, 7-8 §2, 9 §9, 10 §10, 11 §11, 12 §4, 14 §14, 15 §8; 'porting conventions' "
        "1-3 are docs/porting.md §1-3, 4 is §5, 5 is §4")


def test_semantics_sections_cited_exist():
    text = (ROOT / "docs" / "semantics.md").read_text()
    sections = {int(n) for n in re.findall(r"^## (\d+)\. ", text, re.M)}
    assert sections == set(range(1, 21))
    cited = set()
    for p in _files():
        for m in re.finditer(r"semantics\.md((?: ?§\d+,?)+)", p.read_text(errors="replace")):
            cited |= {int(n) for n in re.findall(r"§(\d+)", m.group(1))}
    assert cited and cited <= sections


def test_docs_links_resolve():
    """Every relative link of a docs page or the README names a file."""
    bad = []
    for p in list((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]:
        for target in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", p.read_text()):
            if not (p.parent / target).exists():
                bad.append(f"{p.name}: {target}")
    assert bad == []
