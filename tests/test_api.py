"""Every IRIS GL call exists (never a NameError), is classified, and
docs/api.md is what the code says (irisgl.apidoc)."""
from pathlib import Path

import pytest

import irisgl
from irisgl import apidoc, names
from irisgl._current import API, HEADLESS, IMPLEMENTED, NOT_EMULATED

DOC = Path(__file__).resolve().parent.parent / "docs" / "api.md"


def test_every_gl_h_call_is_exported():
    star = {}
    exec("from irisgl import *", star)
    missing = [n for n in names.GL_CALLS if not callable(star.get(n))]
    assert missing == []


def test_every_call_is_classified():
    unclassified = [n for n in names.GL_CALLS if n not in API]
    assert unclassified == []
    assert {s for s, _ in API.values()} <= {IMPLEMENTED, HEADLESS, NOT_EMULATED}


def test_headless_and_not_emulated_calls_say_why():
    silent = [n for n, (s, why) in API.items() if s != IMPLEMENTED and len(why) < 10]
    assert silent == []


@pytest.mark.parametrize("name", sorted(n for n, (s, _) in API.items() if s == NOT_EMULATED))
def test_not_emulated_call_raises_glerror_naming_it(name, open_window):
    open_window(8, 8)
    with pytest.raises(irisgl.GLError, match=rf"^{name}: not emulated: .{{10,}}"):
        getattr(irisgl, name)()


def test_not_emulated_call_in_lenient_mode_reports_and_goes_on(capsys):
    import vgx_emulator
    vgx_emulator.set_error_mode("lenient")
    assert irisgl.dglopen("host", 0) is None
    assert capsys.readouterr().err.startswith("GL: dglopen: not emulated")


def test_docs_api_md_is_generated_from_the_code():
    assert DOC.read_text() == apidoc.render(), "run: python -m irisgl.apidoc"
