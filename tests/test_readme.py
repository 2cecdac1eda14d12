"""The README names every program, opens with its two commands, and shows
how to run one's own program and read its pixels."""
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()


def test_every_program_is_listed():
    progs = [p for p in (ROOT / "programs").rglob("*.py") if not p.name.startswith("_")]
    missing = [str(p.relative_to(ROOT)) for p in progs
               if f"`{p.relative_to(ROOT).as_posix()}`" not in README]
    assert len(progs) >= 19 and missing == []


def test_opens_with_the_two_commands():
    head = README[:README.index("## What this is")]
    assert "pip install -e . && vgx-gallery --out gallery" in head
    assert "pip install -e '.[test]' && python -m pytest -q" in head


def test_own_program_pixels_and_extras():
    for s in ("## Your own program", "vgx_emulator.window_image()", "run_program(",
              "[mesa]", "[plots]", "[notebook]", "[video]", "[cluster]",
              "docs/semantics.md", "docs/porting.md"):
        assert s in README, s
