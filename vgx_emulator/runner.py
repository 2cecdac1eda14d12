"""vgx-run: run an unmodified ported IRIS GL program headless and save what
it drew (docs/porting.md, "Running a program").

The program runs as ``__main__``.  Every frame point (swapbuffers, gflush,
finish) is counted; after ``--frames`` of them the program is stopped.  A
``qread`` on an empty queue first gets a REDRAW for the current window if
the program asked for REDRAW events and drew at least one frame but fewer
than asked (one per frame, so a program that never draws cannot loop);
otherwise it ends the program cleanly.  A loop that only polls ``qtest``
(POLLS empty polls with no frame point between them) is treated the same
way, and one that reads a device's state POLLS times (getbutton,
getvaluator, getdev) with no frame point ends cleanly.  What the screen
shows of the current window (or of the last window closed; with
``--screen``, of every window) is then saved as a PNG.  ``--menu 3,2.1`` answers
the program's dopup calls (docs/text-and-menus.md).  ``--out x.gif``
(or ``.mp4``) saves every (``--every K``: every K-th) frame as an animation;
``--trace DIR`` pictures every bank after every pass of one frame
(docs/trace.md).

Usage: ``vgx-run [OPTIONS] PROGRAM.py [OPTIONS] [-- PROGRAM ARGS]``.  An
option vgx-run does not know is an error (``--fames 3``); the program's own
options go after ``--``, bare words are passed to the program as well.  A
program that raises shows its own traceback, from its first frame on.
"""
import argparse
import runpy
import sys
import time
import traceback
from pathlib import Path

from .display import screen_image
from .display.png import write_png
from .events import REDRAW, QueueExhausted


#: empty qtest polls without a frame point after which a polling loop is
#: taken to be waiting for input (it gets what a waiting qread gets)
POLLS = 2000


class FramesDone(BaseException):
    """Raised by the runner's frame hook once enough frames were drawn."""


def run_program(path, frames=1, argv=None, menu=None, trace=None, collect=None, every=1,
                screen=False, inputs=None):
    """Run ``path`` headless for at most ``frames`` frames; return the
    (h, w, 3) uint8 image it left on the screen (None if it drew nothing).

    ``menu``: scripted dopup answers (``"3,2.1"``, see vgx_emulator.menus),
    also taken from a leading ``--menu ANSWERS`` in ``argv`` (so that a
    FIGURES entry's args can carry them).  While answers are left and the
    program queues RIGHTMOUSE, a right-button press and release is queued
    whenever it finishes a frame or waits for input, as a user would click;
    the run then lasts until every answer was taken (at most 10 extra
    frames per answer).

    ``trace``: a vgx_emulator.trace.Trace to install for the run;
    ``collect``: a list that receives the image of every ``every``-th frame
    (frames 1, 1 + every, ...: an animation, display/anim.py).

    ``screen``: the image (and each collected frame) is the part of the
    screen that holds every open window, composed as readdisplay(3G) shows
    it (display.screen_image), not the current window alone: a program of
    several windows, pictured whole.

    ``inputs``: scripted input, ``"N:DEV=VAL[,DEV=VAL...]"`` strings (or
    their parse, parse_inputs): after the program's N-th frame point (0:
    when it first waits for input or polls an empty queue, when a loop that
    reads a device's state would end, or at its first frame point), each
    device changes as the window system reports it
    (EventQueue.device_input: an entry when the program queues the device,
    tied valuators with a button, the setvaluator range), in order."""
    from irisgl._current import machine
    from . import menus
    machine.reset()
    script = inputs if isinstance(inputs, dict) else parse_inputs(inputs or [])
    argv = list(argv or [])
    if len(argv) >= 2 and argv[0] == "--menu":
        menu, argv = argv[1], argv[2:]
    if menu is not None:
        menus.script(menu, machine)
    answers = menus.pending(machine)
    drawn = {"n": 0, "posted_at": -1}
    rightmouse = 101                     # device.h RIGHTMOUSE, dopup's button

    def click():
        """Queue a RIGHTMOUSE press/release for the next scripted answer."""
        ev = machine.events
        if (menus.pending(machine) and rightmouse in ev.queued
                and not any(d == rightmouse for d, _ in ev.entries)):
            ev.device_input(rightmouse, 1)       # as the window system: tied valuators too
            ev.device_input(rightmouse, 0)
            return True
        return False

    def give(n):
        """The scripted input due after frame point n (and frame 0's, once)."""
        for k in sorted(k for k in script if k <= n):
            for dev, val in script.pop(k):
                machine.events.device_input(dev, val)

    def on_frame(m, win):
        drawn["n"] += 1
        drawn["polls"] = drawn["reads"] = 0
        give(drawn["n"])
        if collect is not None and (drawn["n"] - 1) % every == 0:
            collect.append(screen_image(m) if screen else m.image(win))
        if drawn["n"] >= frames and (not menus.pending(machine)
                                     or drawn["n"] >= frames + 10 * answers):
            raise FramesDone()
        click()

    def on_wait():
        give(drawn["n"])
        if machine.events.entries or click():
            return
        w = machine.current
        # only to a program that marks frames (swapbuffers/gflush/finish): a
        # single-buffered one drawing on input would have its picture redrawn
        # by an expose no real window got (mapw(3G), 4Dgifts mapw.c)
        if (w is not None and REDRAW in machine.events.queued
                and 0 < drawn["n"] < frames and drawn["posted_at"] != drawn["n"]):
            drawn["posted_at"] = drawn["n"]
            machine.events.enter(REDRAW, w.gid)

    def on_poll():
        """qtest on an empty queue: a loop that polls with no frame point in
        between (curve1.c: ``while (TRUE) if (qtest()) ...``) is waiting for
        input; after POLLS such polls it is treated as a qread that waits."""
        give(drawn["n"])
        drawn["polls"] = drawn.get("polls", 0) + 1
        if drawn["polls"] >= POLLS:
            drawn["polls"] = 0
            machine.events._wait()

    def on_state():
        """getbutton/getvaluator/getdev: a loop that reads a device POLLS
        times with no frame point in between (alias_back.c: ``while
        (!getbutton(ESCKEY)) ...``) waits for input no one gives headless:
        it ends the program cleanly, as an exhausted queue does, unless
        scripted input is due: that is given then (not at the first read,
        which may come before the program queues its devices: input.c reads
        getdev before its qdevice calls)."""
        drawn["reads"] = drawn.get("reads", 0) + 1
        if drawn["reads"] >= POLLS:
            drawn["reads"] = 0
            if not any(k <= drawn["n"] for k in script):
                raise QueueExhausted()
            give(drawn["n"])           # what it waits for is scripted: give it now

    if trace is not None:
        trace.install(machine)
    img = execute(machine, path, argv, {"frame": on_frame, "wait": on_wait, "poll": on_poll,
                                        "state": on_state},
                  cleanup=trace.uninstall if trace is not None else None)
    if screen and machine.windows:
        return screen_image(machine)
    return img


def parse_inputs(specs):
    """``["N:DEV=VAL,DEV=VAL", ...]`` -> {N: [(device, value), ...]}: N a
    frame count (0 = before the first frame), DEV a device.h name
    (LEFTMOUSE, MOUSEX, ESCKEY, KEYBD ...) or number, VAL an integer or, for
    KEYBD, one character.  A ValueError names what is wrong."""
    from irisgl import constants as K
    out = {}
    for spec in specs:
        head, sep, body = spec.partition(":")
        if not sep or not head.strip().isdigit():
            raise ValueError(f"input {spec!r}: FRAME:DEV=VAL[,DEV=VAL...], FRAME >= 0")
        for item in body.split(","):
            name, eq, val = item.strip().partition("=")
            dev = int(name) if name.isdigit() else getattr(K, name, None)
            if not eq or not isinstance(dev, int) or isinstance(dev, bool):
                raise ValueError(f"input {spec!r}: {item!r} is not DEV=VAL with a device.h name")
            if len(val) == 1 and not val.isdigit():
                v = ord(val)
            else:
                try:
                    v = int(val, 0)
                except ValueError:
                    raise ValueError(f"input {spec!r}: value {val!r} is not an integer "
                                     "or one character") from None
            out.setdefault(int(head), []).append((dev, v))
    return out


def execute(machine, path, argv, hooks, cleanup=None):
    """Run ``path`` as ``__main__`` with ``argv`` and the machine's hooks
    set (``frame``, ``wait``, ``poll``, ``display``, ``chooser``: see
    machine.py, events.py, menus.py), then clear them and run ``cleanup``;
    a clean end (FramesDone, an exhausted queue, exit status 0) returns
    what the screen shows of the current window (or of the last one closed)."""
    places = {"frame": (machine, "frame_hook"), "wait": (machine.events, "wait_hook"),
              "poll": (machine.events, "poll_hook"), "state": (machine.events, "state_hook"),
              "display": (machine, "display_hook"),
              "chooser": (machine.menus, "chooser")}
    for k, v in hooks.items():
        setattr(*places[k], v)
    old_argv = sys.argv
    sys.argv = [str(path)] + list(argv or [])
    try:
        runpy.run_path(str(path), run_name="__main__")
    except (FramesDone, QueueExhausted):
        pass
    except SystemExit as e:
        if e.code not in (0, None):
            raise
    finally:
        sys.argv = old_argv
        for k in hooks:
            setattr(*places[k], None)
        if cleanup is not None:
            cleanup()
    if machine.current is not None:
        return machine.image(machine.current)
    return machine.last_image


def run_window(path, argv=None, fps=30.0, frames=None):
    """Run ``path`` in real windows (vgx_emulator/display/tkwindow.py) until
    it ends, its last window is closed or (``frames``) enough frames were
    drawn; return the (h, w, 3) image it left.  Raises ``NoDisplay`` when
    there is no display to open a window on."""
    from irisgl._current import machine
    from .display.tkwindow import TkDisplay
    machine.reset()
    display = TkDisplay(machine, fps)
    drawn = {"n": 0}

    def on_frame(m, win):
        display.frame(m, win)
        drawn["n"] += 1
        if frames is not None and drawn["n"] >= frames:
            raise FramesDone()

    return execute(machine, path, argv,
                   {"frame": on_frame, "wait": display.wait, "poll": display.poll,
                    "state": display.poll,
                    "display": display.drawn, "chooser": display.popup},
                   cleanup=display.close_all)


def program_traceback(path, exc):
    """The lines of ``exc``'s traceback from the first frame of the program
    ``path`` on: the runner's and runpy's frames above it are left out.  For
    a GLError (a call used wrongly) the frames inside irisgl and
    vgx_emulator below the program's last frame are left out too: the
    message names the call."""
    from .errors import GLError
    target = Path(path).resolve()

    def in_program(tb):
        try:
            return Path(tb.tb_frame.f_code.co_filename).resolve() == target
        except (OSError, ValueError):
            return False

    tb = exc.__traceback__
    while tb is not None and not in_program(tb):
        tb = tb.tb_next
    if tb is None:                        # raised before the program ran
        tb = exc.__traceback__
    frames = traceback.extract_tb(tb)
    if isinstance(exc, GLError):
        import irisgl
        inside = [Path(__file__).resolve().parent, Path(irisgl.__file__).resolve().parent]
        while len(frames) > 1 and any(Path(frames[-1].filename).resolve().is_relative_to(d)
                                      for d in inside):
            frames.pop()
    lines = ["Traceback (most recent call last):\n"] + traceback.format_list(frames)
    return lines + traceback.format_exception_only(type(exc), exc)


def _program_failed(prog, exc):
    """Print the program's own traceback on standard error; exit status 1."""
    sys.stderr.write("".join(program_traceback(prog, exc)))
    print(f"vgx-run: {prog.name} stopped by {type(exc).__name__}", file=sys.stderr)
    return 1


def main(argv=None):
    ap = argparse.ArgumentParser(prog="vgx-run", description=__doc__.splitlines()[0])
    ap.add_argument("program", help="a ported IRIS GL program (.py)")
    ap.add_argument("--out", default=None,
                    help="PNG to write (default: PROGRAM.png); .gif or .mp4: an animation "
                         "of the frames drawn")
    ap.add_argument("--every", type=int, default=1, metavar="K",
                    help="with --out .gif/.mp4: keep every K-th frame (default 1)")
    ap.add_argument("--trace", default=None, metavar="DIR",
                    help="write a picture of every bank after every pass of one frame "
                         "and DIR/index.html (docs/trace.md)")
    ap.add_argument("--trace-frame", type=int, default=None, metavar="N",
                    help="with --trace: the frame traced (default: the last, --frames)")
    ap.add_argument("--frames", type=int, default=1, help="frames to let it draw (default 1)")
    ap.add_argument("--input", action="append", default=[], metavar="N:DEV=VAL[,...]",
                    help="scripted input after the N-th frame point (0: when the program "
                         "first waits or polls, or at its first frame point): e.g. "
                         "0:LEFTMOUSE=1,LEFTMOUSE=0 or 5:KEYBD=q; repeatable")
    ap.add_argument("--screen", action="store_true",
                    help="picture every open window where it is on the screen (the smallest "
                         "screen rectangle holding them), not only the current one")
    ap.add_argument("--menu", default=None,
                    help="answers of the program's dopup calls, one per call, comma-separated:"
                         " item numbers (title not counted), 2.1 = item 1 of item 2's submenu")
    ap.add_argument("--window", action="store_true",
                    help="show the program's windows on the display and feed them real input")
    ap.add_argument("--fps", type=float, default=30.0,
                    help="with --window: at most this many frames a second (default 30; "
                         "0 = unpaced); with --out .gif/.mp4: the animation's pace")
    argv = list(sys.argv[1:] if argv is None else argv)
    head, tail = (argv[:argv.index("--")], argv[argv.index("--") + 1:]) if "--" in argv \
        else (argv, [])
    a, rest = ap.parse_known_args(head)
    unknown = [x for x in rest if x.startswith("-") and len(x) > 1]
    if unknown:
        ap.error(f"unrecognized option {unknown[0]} (vgx-run's options are listed by "
                 f"--help; the program's own options go after --: "
                 f"vgx-run {a.program} -- {unknown[0]} ...)")
    a.args = rest + tail
    if a.frames < 1:
        ap.error("--frames must be >= 1")
    try:
        inputs = parse_inputs(a.input)
    except ValueError as e:
        ap.error(str(e))
    if a.menu is not None:
        from .menus import parse_answers
        try:
            parse_answers(a.menu)
        except ValueError as e:
            ap.error(str(e))
    prog = Path(a.program)
    if not prog.is_file():
        ap.error(f"no such program: {prog}")
    t0 = time.perf_counter()
    if a.window and a.input:
        ap.error("--input scripts a headless run; in a --window run the input is yours")
    if a.window and (a.trace is not None or
                     (a.out is not None and Path(a.out).suffix.lower() in (".gif", ".mp4"))):
        ap.error("--trace and .gif/.mp4 output run headless: drop --window")
    if a.window:
        from .display.tkwindow import NoDisplay
        try:
            img = run_window(prog, a.args, a.fps,
                             frames=a.frames if "--frames" in head else None)
        except NoDisplay as e:
            print(f"vgx-run: no display for --window ({e}); run without --window to "
                  "run headless", file=sys.stderr)
            return 2
        except Exception as e:
            return _program_failed(prog, e)
        if img is None or a.out is None:
            return 0
        write_png(Path(a.out), img)
        return 0
    if a.every < 1:
        ap.error("--every must be >= 1")
    if a.trace_frame is not None and a.trace_frame < 1:
        ap.error("--trace-frame must be >= 1")
    animate = a.out is not None and Path(a.out).suffix.lower() in (".gif", ".mp4")
    tr = None
    if a.trace is not None:
        from .trace import Trace
        tr = Trace(a.trace_frame or a.frames, keep=False, outdir=a.trace)
    frames = [] if animate else None
    try:
        img = run_program(prog, max(a.frames, a.trace_frame or 0), a.args, menu=a.menu,
                          trace=tr, collect=frames, every=a.every, screen=a.screen,
                          inputs=inputs)
    except Exception as e:
        return _program_failed(prog, e)
    if tr is not None:
        index = tr.write(title=f"vgx-run --trace: {prog.name} {' '.join(a.args)}")
        print(f"vgx-run: {prog.name}: {len(tr.steps)} passes of frame {tr.frame} -> {index}")
    if img is None:
        print(f"vgx-run: {prog} opened no window; nothing saved", file=sys.stderr)
        return 1
    out = Path(a.out) if a.out else prog.with_suffix(".png")
    if animate:
        from .display.anim import AnimationError, save_animation
        try:
            save_animation(out, frames or [img], a.fps, a.every)
        except AnimationError as e:
            print(f"vgx-run: {e}", file=sys.stderr)
            return 2
        print(f"vgx-run: {prog.name}: {len(frames or [img])} frames -> {out} "
              f"({time.perf_counter() - t0:.2f} s)")
        return 0
    write_png(out, img)
    print(f"vgx-run: {prog.name}: {img.shape[1]}x{img.shape[0]} -> {out} "
          f"({time.perf_counter() - t0:.2f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
