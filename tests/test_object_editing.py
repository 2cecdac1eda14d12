"""Editing display lists: editobj(3G), maketag(3G), gentag(3G), istag(3G),
objinsert(3G), objreplace(3G), objdelete(3G) (docs/semantics.md §12).

The expectations come from the man pages: editobj opens an object with the
edit point at its end; objinsert(t) puts it just after tag t; objreplace(t)
makes the routines that follow overwrite, one for one, those after tag t
until closeobj, objinsert, objdelete or objreplace; objdelete(t1, t2)
removes what lies between two tags; STARTTAG and ENDTAG name the two ends.
Each routine here is a callfunc(3G) that logs a letter when the object
runs, so the replayed sequence is read directly; the drawing tests read
pixels."""
import pytest

from irisgl import (ENDTAG, STARTTAG, GLError, callfunc, callobj, clear, closeobj, cpack,
                    delobj, editobj, genobj, gentag, isobj, istag, lrectread, makeobj, maketag,
                    newtag, objdelete, objinsert, objreplace)
from banks import box

RED, GREEN, BLUE = 0xFF0000FF, 0xFF00FF00, 0xFFFF0000


@pytest.fixture
def log(open_window):
    open_window(8, 8, pixels=True, cleared=True)
    return []


def step(log, letter):
    """One routine of the object: a callfunc that logs ``letter``."""
    callfunc(log.append, 1, letter)


def build(log, obj, items):
    """makeobj(obj) with ``items``: letters become routines, ints tags."""
    makeobj(obj)
    for it in items:
        maketag(it) if isinstance(it, int) else step(log, it)
    closeobj()


def run(log, obj):
    log.clear()
    callobj(obj)
    return "".join(log)


def test_recording_and_replay(log):
    build(log, 1, ["A", "B", "C"])
    assert log == []                      # recorded, not run
    assert run(log, 1) == "ABC"
    assert run(log, 1) == "ABC"


def test_editobj_appends_at_the_end(log):
    build(log, 1, ["A", "B"])
    editobj(1)
    step(log, "C")
    closeobj()
    assert run(log, 1) == "ABC"


def test_objinsert_inserts_just_after_the_tag(log):
    build(log, 1, ["A", 10, "B", 11, "C"])
    editobj(1)
    objinsert(10)
    step(log, "X")
    step(log, "Y")                        # the edit point moves on after each
    closeobj()
    assert run(log, 1) == "AXYBC"


def test_objinsert_at_the_two_ends(log):
    build(log, 1, ["A", "B"])
    editobj(1)
    objinsert(STARTTAG)
    step(log, "S")
    objinsert(ENDTAG)
    step(log, "E")
    closeobj()
    assert run(log, 1) == "SABE"


def test_objreplace_overwrites_one_for_one_after_the_tag(log):
    build(log, 1, ["A", 10, "B", "C", "D"])
    editobj(1)
    objreplace(10)
    step(log, "X")
    step(log, "Y")                        # two routines sent: B and C replaced
    closeobj()
    assert run(log, 1) == "AXYD"


def test_objinsert_ends_a_replacement(log):
    build(log, 1, [10, "A", "B", "C"])
    editobj(1)
    objreplace(10)
    step(log, "X")                        # replaces A
    objinsert(10)                         # ends the replacement
    step(log, "Y")                        # inserted, replaces nothing
    closeobj()
    assert run(log, 1) == "YXBC"


def test_objdelete_removes_between_tags_and_keeps_them(log):
    build(log, 1, ["A", 10, "B", "C", 11, "D"])
    editobj(1)
    objdelete(10, 11)
    assert istag(10) and istag(11)
    objinsert(10)                         # the tags still mark places
    step(log, "Z")
    closeobj()
    assert run(log, 1) == "AZD"


def test_objdelete_start_to_end_empties_the_object(log):
    build(log, 1, ["A", 10, "B"])
    editobj(1)
    objdelete(STARTTAG, ENDTAG)
    step(log, "N")
    closeobj()
    assert run(log, 1) == "N"


def test_gentag_gives_unused_tags_and_istag_finds_them(log):
    makeobj(1)
    t1 = gentag()
    maketag(t1)
    t2 = gentag()
    maketag(t2)
    assert t1 != t2
    assert istag(t1) and istag(t2) and not istag(max(t1, t2) + 1)
    closeobj()
    assert not istag(t1)                  # istag asks about the open object
    editobj(1)
    assert istag(t1) and gentag() not in (t1, t2)
    closeobj()


def test_genobj_numbers_taken_in_a_row_are_unique(log):
    """genobj(3G) "generates unique 31-bit integer numbers" and "will not
    generate an object name that is currently in use": numbers taken one
    after another before any makeobj differ (a program that takes all its
    names first, then fills them), none is a defined object, a deleted
    object's number is not handed out again, and each object keeps what was
    recorded into it."""
    build(log, 3, ["Z"])
    names = [genobj() for _ in range(7)]
    assert len(set(names)) == 7 and 3 not in names
    assert all(0 < n < 2 ** 31 for n in names)
    for n, letter in zip(names, "ABCDEFG"):
        build(log, n, [letter])
    assert "".join(run(log, n) for n in names) == "ABCDEFG"
    delobj(names[0])
    assert not isobj(names[0])
    assert genobj() not in names + [3]


def test_gentag_numbers_taken_in_a_row_are_unique(log):
    """gentag(3G): tags taken in a row before any maketag differ, also with
    no object open; none is a tag the open object has."""
    tags = [gentag() for _ in range(3)]
    makeobj(1)
    tags += [gentag() for _ in range(3)]
    maketag(tags[-1] + 1)
    assert gentag() != tags[-1] + 1
    closeobj()
    assert len(set(tags)) == 6


def test_a_tag_defined_again_moves_there(log):
    """gentag(3G): "if you later define a tag with the same value, the first
    tag is lost": maketag and newtag of a number the object has take it to
    the new place, and the editing calls find it there; the routines stay."""
    makeobj(1)
    maketag(10)
    step(log, "A")
    maketag(10)                           # the first tag 10 is lost
    step(log, "B")
    step(log, "C")
    closeobj()
    editobj(1)
    objreplace(10)
    step(log, "X")
    closeobj()
    assert run(log, 1) == "AXC"
    editobj(1)
    newtag(10, STARTTAG, 2)               # after A and X now
    objinsert(10)
    step(log, "Y")
    closeobj()
    assert run(log, 1) == "AXYC"


def test_editing_calls_are_not_recorded(log):
    """They are immediate-mode calls (objinsert(3G) etc.): a replay of the
    object does not re-run them."""
    build(log, 1, [10, "A"])
    editobj(1)
    objinsert(10)
    step(log, "B")
    objinsert(ENDTAG)
    step(log, "C")
    closeobj()
    assert run(log, 1) == "BAC"
    assert run(log, 1) == "BAC"


def test_makeobj_closes_an_open_object_and_closeobj_alone_is_ignored(log):
    """SGI's library closes the open object at makeobj and editobj (flight's
    makemtn ends with ``closeobj;``, which calls nothing, then makes the
    next object); closeobj(3G) and objdelete(3G): "if no object is open ...
    the subroutine is ignored"."""
    makeobj(1)
    step(log, "A")                        # no closeobj
    makeobj(2)
    step(log, "B")
    editobj(1)                            # 2 still open: closed first
    step(log, "C")
    closeobj()
    closeobj()                            # nothing open: ignored
    objdelete(STARTTAG, ENDTAG)           # nothing being edited: ignored
    assert run(log, 1) == "AC" and run(log, 2) == "B"


def test_editing_errors(log):
    with pytest.raises(GLError, match="^editobj: object 5 is not defined"):
        editobj(5)
    with pytest.raises(GLError, match="^maketag: no object is open"):
        maketag(1)
    with pytest.raises(GLError, match="^objinsert: no object is being edited"):
        objinsert(1)
    build(log, 1, ["A"])
    editobj(1)
    with pytest.raises(GLError, match="^objreplace: tag 7 is not in object 1"):
        objreplace(7)
    with pytest.raises(GLError, match="^objdelete: tag 7 is not in object 1"):
        objdelete(STARTTAG, 7)
    step(log, "B")                        # the failed calls changed nothing
    closeobj()
    assert run(log, 1) == "AB"


def test_replaced_colour_draws_in_the_edited_object(log):
    """The pixels follow the edit: objreplace of the cpack after a tag
    recolours the rectangle; objinsert adds a second one."""
    makeobj(2)
    maketag(1)
    cpack(RED)
    box(0, 0, 3, 3)                       # pixels 0..3 exactly
    maketag(2)
    closeobj()
    callobj(2)
    img = lrectread(0, 0, 7, 7)
    assert (img[:4, :4] == RED).all() and (img[4:, :] == 0).all()
    editobj(2)
    objreplace(1)
    cpack(GREEN)                          # overwrites cpack(RED), keeps rectf
    objinsert(2)
    cpack(BLUE)
    box(4, 4, 7, 7)
    closeobj()
    cpack(0)
    clear()
    callobj(2)
    img = lrectread(0, 0, 7, 7)
    assert (img[:4, :4] == GREEN).all() and (img[4:, 4:] == BLUE).all()
    assert (img[:4, 4:] == 0).all() and (img[4:, :4] == 0).all()
