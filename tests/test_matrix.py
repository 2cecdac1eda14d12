"""Transformations, projections, matrix modes and stacks, viewport
(docs/semantics.md §1, §2).

Every expected matrix is written out from the man-page formulas of the
reference (row vectors, ``C <- T . C``), never taken from the library.
"""
import math

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403
from irisgl import GLError

I4 = np.eye(4)
R2 = math.sqrt(0.5)


def cur():
    return np.asarray(getmatrix(), np.float64)


def assert_matrix(expected, atol=1e-6):
    np.testing.assert_allclose(cur(), np.asarray(expected, np.float64), atol=atol, rtol=1e-6)


def xform(p, m=None):
    """Row vector p (3 or 4 numbers) times the current matrix; returns x, y, z, w."""
    p = list(p) + [1.0] * (4 - len(p))
    return np.asarray(p, np.float64) @ (cur() if m is None else m)


@pytest.fixture
def win(open_window):
    """A window whose single matrix starts as identity (winopen loads the
    pixel ortho2; the modelling tests below start from identity)."""
    gid = open_window(64, 48)
    loadmatrix(I4)
    return gid


# -- modelling transformations ---------------------------------------------------
def test_initial_mode_is_msingle(win):
    assert getmmode() == MSINGLE


def test_default_projection_after_winopen_is_pixel_ortho2(open_window):
    open_window(64, 48)
    # ortho2(-0.5, 63.5, -0.5, 47.5): 2/64, 2/48, -1, row 3 = (-63/64, -47/48, 0, 1)
    assert_matrix([[1 / 32, 0, 0, 0], [0, 1 / 24, 0, 0], [0, 0, -1, 0],
                   [-63 / 64, -47 / 48, 0, 1]])


def test_translate(win):
    translate(1.5, -2.0, 3.25)
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1.5, -2.0, 3.25, 1]])


def test_scale(win):
    scale(2.0, -3.0, 0.5)
    assert_matrix([[2, 0, 0, 0], [0, -3, 0, 0], [0, 0, 0.5, 0], [0, 0, 0, 1]])


@pytest.mark.parametrize("ax, expected", [
    ("x", [[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]]),
    ("y", [[0, 0, -1, 0], [0, 1, 0, 0], [1, 0, 0, 0], [0, 0, 0, 1]]),
    ("z", [[0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
])
def test_rot_90_degrees(win, ax, expected):
    rot(90.0, ax)
    assert_matrix(expected)


def test_rot_right_hand_rule(win):
    """x -> y about z, y -> z about x, z -> x about y."""
    rot(90, "z")
    np.testing.assert_allclose(xform((1, 0, 0)), (0, 1, 0, 1), atol=1e-6)
    loadmatrix(I4)
    rot(90, "x")
    np.testing.assert_allclose(xform((0, 1, 0)), (0, 0, 1, 1), atol=1e-6)
    loadmatrix(I4)
    rot(90, "y")
    np.testing.assert_allclose(xform((0, 0, 1)), (1, 0, 0, 1), atol=1e-6)


def test_rot_45_about_x(win):
    rot(45.0, "x")
    assert_matrix([[1, 0, 0, 0], [0, R2, R2, 0], [0, -R2, R2, 0], [0, 0, 0, 1]])


@pytest.mark.parametrize("ax", ["x", "X", "y", "Y", "z", "Z"])
def test_rotate_takes_tenths_and_any_case_axis(win, ax):
    rotate(300, ax)            # 30 degrees
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    exp = {"x": [[1, 0, 0, 0], [0, c, s, 0], [0, -s, c, 0], [0, 0, 0, 1]],
           "y": [[c, 0, -s, 0], [0, 1, 0, 0], [s, 0, c, 0], [0, 0, 0, 1]],
           "z": [[c, s, 0, 0], [-s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}[ax.lower()]
    assert_matrix(exp)


def test_rot_uppercase_axis(win):
    rot(-90.0, "Z")
    assert_matrix([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def _z_rotation(tenths):
    a = math.radians(tenths / 10.0)
    return [[math.cos(a), math.sin(a), 0, 0], [-math.sin(a), math.cos(a), 0, 0],
            [0, 0, 1, 0], [0, 0, 0, 1]]


@pytest.mark.parametrize("given, tenths", [(1.5, 1), (900.7, 900), (-900.7, -900),
                                           (np.float32(450.9), 450), (40000, 40000 - 65536),
                                           (-32769, 32767)])
def test_rotate_takes_a_c_short_angle(win, given, tenths):
    """rotate(3G)'s Angle is a C short: a float is truncated toward zero
    (a port of ``float a; rotate(a, 'z')``) and a value past the short's
    range wraps as C converts it."""
    rotate(given, "z")
    assert_matrix(_z_rotation(tenths), atol=1e-7)


def test_other_angle_arguments_are_c_shorts_too(win):
    """perspective's fovy, lookat's twist and polarview's azim, inc and twist
    are Angles as well: the same matrices as with the truncated values."""
    mmode(MPROJECTION)
    perspective(450.9, 1.0, 1.0, 10.0)
    a = getmatrix()
    perspective(450, 1.0, 1.0, 10.0)
    assert np.array_equal(a, getmatrix())
    mmode(MVIEWING)
    for call, real, whole in ((lookat, (0, 0, 5, 0, 0, 0, 900.9), (0, 0, 5, 0, 0, 0, 900)),
                              (polarview, (5, 450.5, 300.2, -10.7), (5, 450, 300, -10))):
        loadmatrix(np.eye(4))
        call(*real)
        a = getmatrix()
        loadmatrix(np.eye(4))
        call(*whole)
        assert np.array_equal(a, getmatrix())


def test_translate_then_rotate_rotates_vertex_first(win):
    translate(1, 0, 0)
    rotate(900, "z")
    # C = Rz(90) . T(1,0,0)
    assert_matrix([[0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 1, 0], [1, 0, 0, 1]])
    # (1,0,0): rotated to (0,1,0), then translated to (1,1,0)
    np.testing.assert_allclose(xform((1, 0, 0)), (1, 1, 0, 1), atol=1e-6)


def test_rotate_then_translate_translates_vertex_first(win):
    rotate(900, "z")
    translate(1, 0, 0)
    # (1,0,0): translated to (2,0,0), then rotated to (0,2,0)
    np.testing.assert_allclose(xform((1, 0, 0)), (0, 2, 0, 1), atol=1e-6)


def test_scale_then_translate_order(win):
    scale(2, 2, 2)
    translate(1, 1, 1)
    # C = T . S: (1,1,1) -> (2,2,2) -> (4,4,4)
    assert_matrix([[2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 0], [2, 2, 2, 1]])


def test_multmatrix_premultiplies(win):
    translate(1, 2, 3)
    m = [[1, 2, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    multmatrix(m)
    # m . T : rows of m combine rows of T
    assert_matrix([[1, 2, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 2, 3, 1]])
    loadmatrix(m)
    translate(1, 2, 3)
    # T . m : row 3 = (1,2,3,1) . m = (1, 2+2, 3, 1)
    assert_matrix([[1, 2, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 4, 3, 1]])


@pytest.mark.parametrize("form", ["list", "ndarray", "Matrix", "tuple"])
def test_multmatrix_accepts_any_4x4(win, form):
    rows = [[2, 0, 0, 0], [0, 3, 0, 0], [0, 0, 4, 0], [5, 6, 7, 1]]
    m = {"list": rows, "ndarray": np.array(rows, np.float64), "Matrix": Matrix(rows),
         "tuple": tuple(tuple(r) for r in rows)}[form]
    multmatrix(m)
    assert_matrix(rows)


def test_loadmatrix_replaces(win):
    translate(9, 9, 9)
    rows = [[1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0], [3, 4, 5, 1]]
    loadmatrix(rows)
    assert_matrix(rows)


def test_getmatrix_returns_new_matrix(win):
    translate(1, 2, 3)
    m = getmatrix()
    assert isinstance(m, Matrix)
    assert m.shape == (4, 4) and m.dtype == np.float32
    assert m[3][0] == 1 and m[3][1] == 2 and m[3][2] == 3   # m[row][col]
    m[3][0] = 100.0            # a copy: the state does not change
    assert getmatrix()[3][0] == 1


@pytest.mark.parametrize("buf", [lambda: Matrix(), lambda: np.zeros((4, 4), np.float32),
                                 lambda: np.zeros((4, 4), np.float64),
                                 lambda: np.zeros(16, np.float32)])
def test_getmatrix_fills_given_array(win, buf):
    scale(2, 3, 4)
    translate(1, 2, 3)
    b = buf()
    r = getmatrix(b)
    assert r is None           # C returns void
    # C = T . S: row 3 = (1,2,3,1) . S = (2, 6, 12, 1)
    np.testing.assert_allclose(np.asarray(b).reshape(4, 4),
                               [[2, 0, 0, 0], [0, 3, 0, 0], [0, 0, 4, 0], [2, 6, 12, 1]])


# -- projections -----------------------------------------------------------------
def test_ortho(win):
    ortho(-1, 3, -2, 6, 1, 5)
    assert_matrix([[0.5, 0, 0, 0], [0, 0.25, 0, 0], [0, 0, -0.5, 0], [-0.5, -0.5, -1.5, 1]])


def test_ortho2_is_ortho_with_near_minus1_far_1(win):
    ortho2(-0.5, 63.5, -0.5, 47.5)
    assert_matrix([[1 / 32, 0, 0, 0], [0, 1 / 24, 0, 0], [0, 0, -1, 0],
                   [-63 / 64, -47 / 48, 0, 1]])


def test_window_frustum(win):
    window(-1, 3, -2, 2, 1, 3)
    assert_matrix([[0.5, 0, 0, 0], [0, 0.5, 0, 0], [0.5, 0, -2, -1], [0, 0, -3, 0]])


def test_perspective_90(win):
    perspective(900, 2.0, 1.0, 3.0)        # cot(45 deg) = 1
    assert_matrix([[0.5, 0, 0, 0], [0, 1, 0, 0], [0, 0, -2, -1], [0, 0, -3, 0]])


def test_perspective_60(win):
    perspective(600, 1.5, 2.0, 10.0)       # f = cot(30 deg) = sqrt(3)
    f = math.sqrt(3.0)
    assert_matrix([[f / 1.5, 0, 0, 0], [0, f, 0, 0], [0, 0, -12 / 8, -1], [0, 0, -40 / 8, 0]],
                  atol=1e-5)


def test_perspective_equals_window(win):
    t = 0.5 * math.tan(math.radians(20.0))
    perspective(400, 4 / 3, 0.5, 20.0)
    p = cur()
    window(-t * 4 / 3, t * 4 / 3, -t, t, 0.5, 20.0)
    np.testing.assert_allclose(p, cur(), rtol=1e-6, atol=1e-6)


def test_projection_loads_top_in_msingle(win):
    translate(5, 5, 5)
    pushmatrix()
    rotate(450, "x")
    ortho(-1, 3, -2, 6, 1, 5)              # replaces, not premultiplies
    assert_matrix([[0.5, 0, 0, 0], [0, 0.25, 0, 0], [0, 0, -0.5, 0], [-0.5, -0.5, -1.5, 1]])
    popmatrix()                            # the level below is untouched
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [5, 5, 5, 1]])


@pytest.mark.parametrize("mode", ["MVIEWING", "MPROJECTION", "MTEXTURE"])
def test_projection_replaces_projection_in_multi_modes(win, mode):
    mmode(MVIEWING)
    translate(1, 2, 3)
    mmode(MPROJECTION)
    translate(7, 7, 7)                     # replaced below, not premultiplied
    mmode({"MVIEWING": MVIEWING, "MPROJECTION": MPROJECTION, "MTEXTURE": MTEXTURE}[mode])
    perspective(900, 2.0, 1.0, 3.0)
    if mode == "MVIEWING":
        # ModelView untouched
        assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 2, 3, 1]])
    mmode(MPROJECTION)
    assert_matrix([[0.5, 0, 0, 0], [0, 1, 0, 0], [0, 0, -2, -1], [0, 0, -3, 0]])
    mmode(MVIEWING)
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 2, 3, 1]])


def test_mprojection_matrix_calls_modify_projection(win):
    mmode(MPROJECTION)
    ortho(-1, 3, -2, 6, 1, 5)
    translate(1, 0, 0)                     # premultiplies Projection
    assert_matrix([[0.5, 0, 0, 0], [0, 0.25, 0, 0], [0, 0, -0.5, 0], [0, -0.5, -1.5, 1]])
    mmode(MVIEWING)
    assert_matrix(I4)


# -- mmode rules -----------------------------------------------------------------
def test_mmode_msingle_to_mviewing_resets(win):
    translate(1, 2, 3)
    pushmatrix()
    mmode(MVIEWING)
    assert getmmode() == MVIEWING
    assert_matrix(I4)
    mmode(MPROJECTION)
    assert_matrix(I4)


def test_mmode_among_multi_modes_keeps_everything(win):
    mmode(MVIEWING)
    translate(1, 2, 3)
    pushmatrix()
    scale(2, 2, 2)
    mmode(MPROJECTION)
    ortho2(0, 2, 0, 2)
    mmode(MTEXTURE)
    scale(3, 3, 3)
    mmode(MVIEWING)
    # S . T: vertex scaled first, then translated (row 3 of S is (0,0,0,1))
    assert_matrix([[2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 0], [1, 2, 3, 1]])
    popmatrix()                            # the pushed level survived
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 2, 3, 1]])
    mmode(MPROJECTION)
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, 0], [-1, -1, 0, 1]])
    mmode(MTEXTURE)
    assert_matrix(np.diag([3, 3, 3, 1]))


def test_mmode_back_to_msingle_resets(win):
    mmode(MVIEWING)
    translate(1, 2, 3)
    pushmatrix()
    mmode(MPROJECTION)
    ortho2(0, 2, 0, 2)
    mmode(MSINGLE)
    assert_matrix(I4)
    with pytest.raises(GLError):
        popmatrix()
    mmode(MVIEWING)
    assert_matrix(I4)
    mmode(MPROJECTION)
    assert_matrix(I4)


def test_mmode_msingle_to_msingle_keeps(win):
    translate(1, 2, 3)
    mmode(MSINGLE)
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 2, 3, 1]])


# -- stacks ----------------------------------------------------------------------
def test_push_pop_restore(win):
    translate(1, 0, 0)
    pushmatrix()
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 0, 0, 1]])  # duplicated
    scale(2, 2, 2)
    popmatrix()
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 0, 0, 1]])


@pytest.mark.parametrize("mode", [MSINGLE, MVIEWING])
def test_stack_depth_32(win, mode):
    mmode(mode)
    for i in range(31):                    # depth 32 including the bottom
        translate(1, 0, 0)
        pushmatrix()
    with pytest.raises(GLError) as e:
        pushmatrix()
    assert str(e.value).startswith("pushmatrix")
    for i in range(31):
        popmatrix()
        assert cur()[3, 0] == pytest.approx(31 - i)
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 0, 0, 1]])
    with pytest.raises(GLError) as e:
        popmatrix()
    assert str(e.value).startswith("popmatrix")


@pytest.mark.parametrize("mode", [MPROJECTION, MTEXTURE])
def test_no_stack_in_projection_and_texture(win, mode):
    mmode(mode)
    with pytest.raises(GLError):
        pushmatrix()
    with pytest.raises(GLError):
        popmatrix()


# -- lookat / polarview -------------------------------------------------------------
def test_lookat_down_minus_z_is_translation(win):
    lookat(0, 0, 5, 0, 0, 0, 0)
    assert_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, -5, 1]])


def test_lookat_from_plus_x(win):
    lookat(5, 0, 0, 0, 0, 0, 0)
    # f = (-1,0,0), s = f x Y = (0,0,-1), u = s x f = (0,1,0)
    # R rows: (s.x u.x -f.x)=(0,0,1); (s.y,u.y,-f.y)=(0,1,0); (s.z,u.z,-f.z)=(-1,0,0)
    R = np.array([[0, 0, 1, 0], [0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 0, 1]], float)
    T = np.eye(4)
    T[3, :3] = (-5, 0, 0)
    assert_matrix(T @ R)
    np.testing.assert_allclose(xform((5, 0, 0)), (0, 0, 0, 1), atol=1e-6)     # eye -> origin
    np.testing.assert_allclose(xform((0, 0, 0)), (0, 0, -5, 1), atol=1e-6)    # ref on -z
    np.testing.assert_allclose(xform((0, 1, 0)), (0, 1, -5, 1), atol=1e-6)    # +Y stays up
    np.testing.assert_allclose(xform((0, 0, -1)), (1, 0, -5, 1), atol=1e-6)   # right


def test_lookat_twist(win):
    lookat(0, 0, 5, 0, 0, 0, 900)
    # L = T(0,0,-5) . I . Rz(-90 deg); Rz(-90) rows: (0,-1,0), (1,0,0), (0,0,1)
    assert_matrix([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, -5, 1]])
    # world up now points along eye +x
    np.testing.assert_allclose(xform((0, 1, 0)), (1, 0, -5, 1), atol=1e-6)


def test_lookat_along_y_uses_minus_z_up(win):
    lookat(0, 5, 0, 0, 0, 0, 0)
    # f = (0,-1,0); s = f x (0,0,-1) = (1,0,0); u = s x f = (0,0,-1)
    R = np.array([[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]], float)
    T = np.eye(4)
    T[3, :3] = (0, -5, 0)
    assert_matrix(T @ R)
    assert np.all(np.isfinite(cur()))
    np.testing.assert_allclose(xform((0, 0, -1)), (0, 1, -5, 1), atol=1e-6)   # -Z is up
    np.testing.assert_allclose(xform((1, 0, 0)), (1, 0, -5, 1), atol=1e-6)


def _lookat_numpy(vx, vy, vz, px, py, pz, twist):
    """lookat(3G)'s matrix with numpy's norm and cross (the reference the
    float form in geometry/stack.py must equal bit for bit)."""
    from vgx_emulator.geometry import stack as S
    fwd = np.array((px - vx, py - vy, pz - vz), np.float64)
    fwd /= np.linalg.norm(fwd)
    side = np.cross(fwd, (0.0, 1.0, 0.0))
    if np.linalg.norm(side) < 1e-12 * max(1.0, np.abs(fwd).max()):
        side = np.cross(fwd, (0.0, 0.0, -1.0))
    side /= np.linalg.norm(side)
    r = np.eye(4)
    r[:3, 0], r[:3, 1], r[:3, 2] = side, np.cross(side, fwd), -fwd
    return S.translation(-vx, -vy, -vz) @ r @ S.rotation(-twist / 10.0, "z")


def test_lookat_matches_numpys_vector_formulas_bit_for_bit():
    """geometry.stack.lookat works on Python floats (a third of the time);
    its matrix is the one numpy's norm and cross give, to the last bit,
    over random eyes, references and twists, near-vertical lines of sight
    and a direction whose squares underflow (a non-finite matrix, no
    exception)."""
    from vgx_emulator.geometry import stack as S
    rng = np.random.default_rng(7)
    cases = [(0, 0, 5, 0, 0, 0, 0), (0, 5, 0, 0, 0, 0, 0), (0, -5, 0, 0, 0, 0, 300),
             (1, 2, 3, 1, 2.0000001, 3, 0), (0, 0, 0, 1e-13, 1, 0, 0)]
    for _ in range(3000):
        v = rng.normal(size=7) * rng.choice([1e-3, 1.0, 100.0, 1e4])
        v[6] = rng.uniform(-3600, 3600)
        if rng.random() < 0.2:               # nearly along Y
            v[3], v[5] = v[0], v[2] + rng.normal() * 1e-12
        cases.append(tuple(float(x) for x in v))
    for c in cases:
        c = tuple(float(x) for x in c)
        assert np.array_equal(S.lookat(*c), _lookat_numpy(*c)), c
    with np.errstate(all="ignore"):
        tiny = S.lookat(0.0, 0.0, 0.0, 1e-170, 0.0, 0.0, 0.0)
    assert not np.isfinite(tiny).all()


def test_lookat_premultiplies(win):
    translate(1, 0, 0)
    lookat(0, 0, 5, 0, 0, 0, 0)
    # C = L . T: (0,0,0) -> eye (0,0,-5) -> +(1,0,0)
    np.testing.assert_allclose(xform((0, 0, 0)), (1, 0, -5, 1), atol=1e-6)


def test_polarview_hand_value(win):
    polarview(10, 900, 0, 0)
    # rotate(-900,'z') then translate(0,0,-10): (0,1,0) -> (1,0,0) -> (1,0,-10)
    np.testing.assert_allclose(xform((0, 1, 0)), (1, 0, -10, 1), atol=1e-6)


@pytest.mark.parametrize("args", [(10, 900, 0, 0), (7.5, 300, 450, 0), (3, -200, 600, 150),
                                  (12, 1234, 789, -456)])
def test_polarview_equals_translate_and_three_rotates(win, args):
    dist, azim, inc, twist = args
    translate(0.25, 0, 0)
    polarview(dist, azim, inc, twist)
    got = cur()
    loadmatrix(I4)
    translate(0.25, 0, 0)
    translate(0, 0, -dist)
    rotate(-twist, "z")
    rotate(-inc, "x")
    rotate(-azim, "z")
    np.testing.assert_allclose(got, cur(), atol=1e-5)


# -- viewport ----------------------------------------------------------------------
def test_default_viewport_is_window(win):
    assert tuple(getviewport()) == (0, 63, 0, 47)


def test_viewport_and_scrmask(win):
    scrmask(1, 2, 3, 4)
    viewport(10, 40, 5, 30)
    assert tuple(getviewport()) == (10, 40, 5, 30)
    assert tuple(getscrmask()) == (10, 40, 5, 30)       # viewport resets scrmask
    scrmask(12, 20, 6, 8)
    assert tuple(getscrmask()) == (12, 20, 6, 8)
    assert tuple(getviewport()) == (10, 40, 5, 30)
    reshapeviewport()
    assert tuple(getviewport()) == (0, 63, 0, 47)
    assert tuple(getscrmask()) == (0, 63, 0, 47)


def test_push_pop_viewport(win):
    viewport(10, 40, 5, 30)
    scrmask(12, 20, 6, 8)
    pushviewport()
    viewport(0, 5, 0, 5)
    assert tuple(getviewport()) == (0, 5, 0, 5)
    popviewport()
    assert tuple(getviewport()) == (10, 40, 5, 30)
    assert tuple(getscrmask()) == (12, 20, 6, 8)
    with pytest.raises(GLError):
        popviewport()


def test_viewport_stack_8_entries(win):
    # VPSTACKDEPTH 8 entries including the current one (docs/decisions.md)
    for i in range(7):
        viewport(i, 40, 0, 40)
        pushviewport()
    with pytest.raises(GLError):
        pushviewport()
    for i in reversed(range(7)):
        popviewport()
        assert tuple(getviewport()) == (i, 40, 0, 40)


# -- end to end -------------------------------------------------------------------
PIXELS = [(0, 0), (63, 47), (10, 20), (63, 0), (0, 47), (31, 23)]


def test_ortho2_pixel_mapping_pnt2i(win):
    ortho2(-0.5, 63.5, -0.5, 47.5)
    cpack(0xFF0000FF)
    for x, y in PIXELS:
        pnt2i(x, y)
    img = lrectread(0, 0, 63, 47)
    assert img.shape == (48, 64) and img.dtype == np.uint32
    expected = np.zeros((48, 64), np.uint32)
    for x, y in PIXELS:
        expected[y, x] = 0xFF0000FF
    np.testing.assert_array_equal(img, expected)


def test_lrectread_subrect_and_fill(win):
    ortho2(-0.5, 63.5, -0.5, 47.5)
    cpack(0xFF00FF00)
    pnt2i(11, 21)
    block = lrectread(10, 20, 12, 22)
    assert block.shape == (3, 3)
    assert block[1, 1] == 0xFF00FF00 and block.sum() == 0xFF00FF00
    buf = np.zeros(9, np.uint32)
    assert lrectread(10, 20, 12, 22, buf) == 9
    assert buf[4] == 0xFF00FF00        # left to right, bottom to top


def test_viewport_maps_ortho_to_subrect(win):
    viewport(16, 31, 8, 23)
    ortho2(-0.5, 15.5, -0.5, 15.5)
    cpack(0xFFFFFFFF)
    pnt2i(0, 0)
    pnt2i(15, 15)
    pnt2i(3, 5)
    img = lrectread(0, 0, 63, 47)
    ys, xs = np.nonzero(img)
    assert sorted(zip(xs.tolist(), ys.tolist())) == sorted([(16, 8), (31, 23), (19, 13)])


def test_scrmask_bounds_drawing_and_clear(win):
    ortho2(-0.5, 63.5, -0.5, 47.5)
    scrmask(5, 9, 10, 12)
    cpack(0xFF0000FF)
    clear()
    cpack(0xFF00FF00)
    rectfi(0, 0, 63, 47)
    img = lrectread(0, 0, 63, 47)
    inside = np.zeros((48, 64), bool)
    inside[10:13, 5:10] = True
    assert np.all(img[inside] == 0xFF00FF00)
    assert np.all(img[~inside] == 0)


def test_pushviewport_saves_depth_range(win):
    lsetdepth(-100, 100)
    pushviewport()
    lsetdepth(0, 5)
    viewport(1, 2, 3, 4)
    popviewport()
    assert tuple(lgetdepth()) == (-100, 100)
    assert tuple(getviewport()) == (0, 63, 0, 47)


def test_viewport_partly_outside_window(win):
    # viewport (-8..7, -6..5), ortho2 16 x 12 units: x -> x - 8, y -> y - 6
    viewport(-8, 7, -6, 5)
    ortho2(-0.5, 15.5, -0.5, 11.5)
    cpack(0xFF0000FF)
    pnt2i(15, 11)
    pnt2i(8, 6)
    pnt2i(0, 0)                            # lands at (-8, -6): off the window
    img = lrectread(0, 0, 63, 47)
    ys, xs = np.nonzero(img)
    assert sorted(zip(xs.tolist(), ys.tolist())) == [(0, 0), (7, 5)]
