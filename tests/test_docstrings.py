"""Every public IRIS GL call of ``from irisgl import *`` has a docstring
that names the man page it follows (``stencil(3G)``), so ``help(call)`` and
an editor's hover lead to the documentation."""
import inspect
import re

import irisgl

MAN_PAGE = re.compile(r"\b[A-Za-z0-9_]+\(3G\)")


def _calls():
    for name in irisgl.__all__:
        obj = getattr(irisgl, name)
        if callable(obj) and not isinstance(obj, type):
            yield name, obj


def test_there_are_hundreds_of_calls():
    assert len(list(_calls())) > 500


def test_every_call_has_a_docstring_naming_its_man_page():
    missing = [name for name, f in _calls() if not MAN_PAGE.search(inspect.getdoc(f) or "")]
    assert missing == []
