#!/usr/bin/env python3
"""Input tests of sss-viewer: a real window, real X input from xdotool, checked results.

Each case starts the viewer with --dump-state, sends mouse and key events with xdotool, quits
it with Ctrl+Q and checks what the viewer wrote: the camera, the UI layout, the transfer
function and its undo history (sss-viewer writes them as JSON after every frame and at exit).

Needs an X server; ctest runs it under xvfb-run (tests/CMakeLists.txt):
    xvfb-run -a -s "-screen 0 1280x720x24" viewer_input.py --viewer PATH --work DIR CASE

Synchronisation never relies on a fixed sleep. The state file's "frame" counts the frames
drawn; after an event is sent, a frame that starts after the next one has been written has
polled it (Viewer.sync). Dear ImGui 1.86 reads key states once per frame, so a key goes down
and up in separate frames (Viewer.key), and the pointer is moved before a button goes down.
Exit status: 0 pass, 1 fail (the reason on stderr, with the viewer's log).
"""

import argparse
import json
import math
import os
import pathlib
import subprocess
import sys
import time

WINDOW = (640, 480)
CASE_SECONDS = 45  # one case, start to exit; ctest's TIMEOUT is 60
POLL_SECONDS = 0.01

# Small, fast scenes on llvmpipe (frames of ~10 ms and ~40 ms at 640x480).
MESH_SCENE = ["--mesh", "procedural:torus", "--mesh-mode", "blinn-phong"]
VOLUME_SCENE = ["--volume", "procedural:blobs", "--volume-mode", "emission-absorption"]

# The viewer's input constants (apps/viewer/sss_viewer.cpp, handleInput).
ORBIT_DEGREES_PER_PIXEL = 0.3
ZOOM_PER_WHEEL_STEP = 0.88


class Failure(Exception):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)


def close(a, b, tolerance=1e-4):
    return abs(a - b) <= tolerance * max(1.0, abs(a), abs(b))


def close_vec(a, b, tolerance=1e-4):
    return all(close(x, y, tolerance) for x, y in zip(a, b))


class Viewer:
    """One sss-viewer process in a window, driven by xdotool."""

    def __init__(self, exe, xdotool, work, name, args):
        self.xdotool = xdotool
        self.work = work
        self.state_path = work / f"{name}.state.json"
        self.log_path = work / f"{name}.log"
        self.deadline = time.monotonic() + CASE_SECONDS
        self.pointer = None  # where move() last put the pointer (window pixels)
        self.state_path.unlink(missing_ok=True)
        command = [exe, "--size", f"{WINDOW[0]}x{WINDOW[1]}", "--no-vsync", "--dump-state", str(self.state_path),
                   "--timeout", str(CASE_SECONDS + 5), *args]
        with open(self.log_path, "w") as log:
            log.write(" ".join(command) + "\n")
        self.log = open(self.log_path, "a")
        self.proc = subprocess.Popen(command, cwd=work, stdout=self.log, stderr=subprocess.STDOUT)
        try:
            # Mapped (--onlyvisible) and drawn a few frames: ImGui has laid out its windows.
            self.window = self.xdo("search", "--sync", "--onlyvisible", "--name", "^sss-viewer$").split()[0]
            self.initial = self.wait(lambda s: s["frame"] >= 3, "the first frames")
            self.xdo("windowfocus", "--sync", self.window)
        except Failure as failure:
            self.kill()
            raise Failure(f"{failure}\n--- {self.log_path} (tail)\n{self.log_tail()}")
        except BaseException:
            self.kill()
            raise

    # ---- xdotool -------------------------------------------------------------------------
    def xdo(self, *args):
        remaining = max(1.0, self.deadline - time.monotonic())
        try:
            done = subprocess.run([self.xdotool, *args], capture_output=True, text=True, timeout=remaining)
        except subprocess.TimeoutExpired:
            raise Failure(f"xdotool {' '.join(args)}: no answer in {remaining:.0f} s")
        if done.returncode != 0:
            raise Failure(f"xdotool {' '.join(args)} failed ({done.returncode}): {done.stderr.strip()}")
        return done.stdout

    def move(self, x, y):
        position = (round(x), round(y))
        # mousemove --sync waits for a motion event, so it would wait (15 s) for none if the
        # pointer is there already.
        if position != self.pointer:
            self.xdo("mousemove", "--window", self.window, "--sync", *map(str, position))
            self.pointer = position
        return self.sync()

    def press(self, button):
        self.xdo("mousedown", str(button))
        return self.sync()

    def release(self, button):
        self.xdo("mouseup", str(button))
        return self.sync()

    def drag(self, button, start, end, steps=3):
        """Moves to start, holds `button`, moves to end in `steps` frames, releases."""
        self.move(*start)
        self.press(button)
        for i in range(1, steps + 1):
            t = i / steps
            self.move(start[0] + t * (end[0] - start[0]), start[1] + t * (end[1] - start[1]))
        return self.release(button)

    def click(self, button, at):
        self.move(*at)
        self.press(button)
        return self.release(button)

    def wheel(self, at, steps):
        """Scrolls `steps` notches at `at`: > 0 towards the scene (button 4), < 0 away (button 5)."""
        self.move(*at)
        self.xdo("click", "--repeat", str(abs(steps)), "--delay", "1", "4" if steps > 0 else "5")
        return self.sync()

    def key(self, combo):
        """Presses and releases `combo` (xdotool names: f, F1, ctrl+z), each in its own frame."""
        self.xdo("keydown", combo)
        self.sync()
        self.xdo("keyup", combo)
        return self.sync()

    # ---- state ---------------------------------------------------------------------------
    def read(self):
        try:
            with open(self.state_path) as f:
                return json.load(f)
        except FileNotFoundError:
            return None  # not written yet (it is replaced by a rename, never seen half-written)

    def wait(self, predicate, what):
        state = None
        while time.monotonic() < self.deadline:
            state = self.read()
            if state is not None and predicate(state):
                return state
            if self.proc.poll() is not None:
                raise Failure(f"sss-viewer exited ({self.proc.returncode}) while waiting for {what}")
            time.sleep(POLL_SECONDS)
        raise Failure(f"timed out waiting for {what}; last state frame: {state and state['frame']}")

    def sync(self):
        """Waits until the viewer has handled everything sent so far; returns its state."""
        frame = self.wait(lambda s: True, "the state file")["frame"]
        return self.wait(lambda s: s["frame"] >= frame + 2, f"frame {frame + 2}")

    def quit(self):
        """Ctrl+Q; waits for the exit (status 0) and returns the state written at exit."""
        self.xdo("keydown", "ctrl+q")
        try:
            code = self.proc.wait(timeout=max(1.0, self.deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            raise Failure("sss-viewer did not exit after Ctrl+Q")
        finally:
            subprocess.run([self.xdotool, "keyup", "ctrl+q"], capture_output=True, timeout=10)
        check(code == 0, f"sss-viewer exited with status {code}")
        state = self.read()
        check(state is not None and not state["running"], "no state written at exit")
        check(state["glErrors"] == 0, f"{state['glErrors']} GL error(s), the last: {state['lastGlError']}")
        return state

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()

    def log_tail(self, lines=30):
        self.log.flush()
        return "".join(open(self.log_path).readlines()[-lines:])


# ---- geometry helpers ------------------------------------------------------------------------
def free_point(state, dx=0, dy=0):
    """A point of the scene no UI window covers (the middle of the free area) plus (dx, dy)."""
    ui = state["ui"]
    x0, y0, x1, y1 = 0.0, 0.0, float(state["window"][0]), float(state["window"][1])
    if ui["panel"]:
        x0 = ui["panel"][2]
    if ui["overlay"]:
        y0 = ui["overlay"][3]
    if ui["transferFunction"]:
        y1 = ui["transferFunction"][1]
    check(x1 - x0 > 150 and y1 - y0 > 100, f"no free scene area in the window: {(x0, y0, x1, y1)}")
    return ((x0 + x1) / 2 + dx, (y0 + y1) / 2 + dy)


def canvas_pixel(state, value, opacity):
    """The pixel nearest to (value, opacity) on the transfer-function canvas."""
    x0, y0, x1, y1 = state["ui"]["tfCanvas"]
    return (round(x0 + value * (x1 - x0)), round(y1 - opacity * (y1 - y0)))


def canvas_coords(state, pixel):
    x0, y0, x1, y1 = state["ui"]["tfCanvas"]
    return ((pixel[0] - x0) / (x1 - x0), (y1 - pixel[1]) / (y1 - y0))


def pixel_size(state):
    x0, y0, x1, y1 = state["ui"]["tfCanvas"]
    return (1.0 / (x1 - x0), 1.0 / (y1 - y0))


def points(state):
    return [(p["value"], p["opacity"]) for p in state["transferFunction"]["points"]]


def find_point(state, value, opacity, tolerance):
    """Index of the point within `tolerance` (canvas units, per axis) of (value, opacity)."""
    for i, (v, o) in enumerate(points(state)):
        if abs(v - value) <= tolerance[0] and abs(o - opacity) <= tolerance[1]:
            return i
    return None


def camera_basis(camera):
    """Camera.right() and Camera.up() (src/core/camera.cpp) from yaw and pitch."""
    yaw, pitch = math.radians(camera["yaw"]), math.radians(camera["pitch"])
    towards_eye = (math.sin(yaw) * math.cos(pitch), math.sin(pitch), math.cos(yaw) * math.cos(pitch))
    forward = tuple(-c for c in towards_eye)
    right = (-forward[2], 0.0, forward[0])  # forward x (0, 1, 0)
    n = math.hypot(*right)
    right = tuple(c / n for c in right)
    up = (right[1] * forward[2] - right[2] * forward[1], right[2] * forward[0] - right[0] * forward[2],
          right[0] * forward[1] - right[1] * forward[0])
    return right, up


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def wrap_degrees(d):
    return (d + 180.0) % 360.0 - 180.0


# ---- cases -------------------------------------------------------------------------------------
def case_orbit(v):
    """Left drag over the scene orbits by 0.3 degrees per pixel; a drag on the overlay does not."""
    before = v.initial["camera"]
    overlay = v.initial["ui"]["overlay"]
    on_overlay = ((overlay[0] + overlay[2]) / 2, (overlay[1] + overlay[3]) / 2)
    state = v.drag(1, on_overlay, (on_overlay[0] + 40, on_overlay[1] + 40))
    check(state["camera"] == before, f"a drag on the overlay window moved the camera: {state['camera']}")

    start = free_point(v.initial, -30, -15)
    dx, dy = 60, 30
    after = v.drag(1, start, (start[0] + dx, start[1] + dy))["camera"]
    want_yaw = wrap_degrees(before["yaw"] - ORBIT_DEGREES_PER_PIXEL * dx)
    want_pitch = before["pitch"] + ORBIT_DEGREES_PER_PIXEL * dy
    check(close(after["yaw"], want_yaw, 1e-3) and close(after["pitch"], want_pitch, 1e-3),
          f"orbit: yaw, pitch {after['yaw']}, {after['pitch']}; expected {want_yaw}, {want_pitch}")
    check(close_vec(after["target"], before["target"]) and close(after["distance"], before["distance"]),
          f"orbit moved the target or the distance: {before} -> {after}")
    v.quit()


def case_pan(v):
    """Right and middle drags pan: the scene point under the cursor follows it."""
    before = v.initial["camera"]
    right, up = camera_basis(before)
    per_pixel = 2.0 * math.tan(math.radians(before["fovY"]) / 2) / v.initial["window"][1]
    moved = (0.0, 0.0)
    camera = before
    for button, (dx, dy) in ((3, (50, -20)), (2, (-20, 40))):
        start = free_point(v.initial, -dx / 2, -dy / 2)
        camera = v.drag(button, start, (start[0] + dx, start[1] + dy))["camera"]
        moved = (moved[0] + dx, moved[1] + dy)
        shift = [a - b for a, b in zip(camera["target"], before["target"])]
        # Camera::pan(-dx, dy) * per_pixel * distance along right and up.
        want_right = -moved[0] * per_pixel * before["distance"]
        want_up = moved[1] * per_pixel * before["distance"]
        check(close(dot(shift, right), want_right, 1e-3) and close(dot(shift, up), want_up, 1e-3),
              f"button {button}: target moved {dot(shift, right):.5f} right, {dot(shift, up):.5f} up; "
              f"expected {want_right:.5f}, {want_up:.5f}")
    check(camera["yaw"] == before["yaw"] and camera["pitch"] == before["pitch"]
          and close(camera["distance"], before["distance"]), f"pan changed more than the target: {camera}")
    v.quit()


def case_zoom(v):
    """The wheel zooms by 0.88 per notch, in towards the scene (button 4) and out (button 5)."""
    before = v.initial["camera"]
    at = free_point(v.initial)
    camera = v.wheel(at, 3)["camera"]
    want = before["distance"] * ZOOM_PER_WHEEL_STEP ** 3
    check(close(camera["distance"], want), f"3 notches in: distance {camera['distance']}, expected {want}")
    camera = v.wheel(at, -2)["camera"]
    want = before["distance"] * ZOOM_PER_WHEEL_STEP
    check(close(camera["distance"], want), f"2 notches out: distance {camera['distance']}, expected {want}")
    check(close_vec(camera["target"], before["target"]) and camera["yaw"] == before["yaw"],
          f"zoom changed more than the distance: {camera}")
    # Over a UI window the wheel scrolls the window, not the camera.
    panel = v.initial["ui"]["panel"]
    camera2 = v.wheel(((panel[0] + panel[2]) / 2, (panel[1] + panel[3]) / 2), 2)["camera"]
    check(camera2 == camera, f"the wheel over the panel zoomed: {camera} -> {camera2}")
    v.quit()


def case_reframe(v):
    """F restores the framed camera after pans and zooms."""
    framed = v.initial["camera"]
    start = free_point(v.initial, -20, 0)
    v.drag(3, start, (start[0] + 40, start[1] + 25))
    moved = v.wheel(free_point(v.initial), 2)["camera"]
    check(not close_vec(moved["target"], framed["target"]) and not close(moved["distance"], framed["distance"]),
          f"the pan and zoom did not move the camera: {moved}")
    camera = v.key("f")["camera"]
    check(close_vec(camera["target"], framed["target"], 1e-5) and close(camera["distance"], framed["distance"], 1e-5),
          f"after F: {camera}; framed: {framed}")
    v.quit()


def case_toggle_ui(v):
    """F1 hides the UI (nothing of ImGui is drawn; the scene takes drags everywhere) and shows it again."""
    ui = v.initial["ui"]
    check(ui["shown"] and ui["vertices"] > 0 and ui["panel"], f"UI not drawn at the start: {ui}")
    state = v.key("F1")
    ui = state["ui"]
    check(not ui["shown"] and ui["vertices"] == 0 and ui["panel"] is None and ui["overlay"] is None,
          f"after F1 the UI is still drawn: {ui}")
    # Where the panel was, a drag now orbits.
    camera = v.drag(1, (100, 240), (140, 240))["camera"]
    check(close(camera["yaw"], wrap_degrees(v.initial["camera"]["yaw"] - 40 * ORBIT_DEGREES_PER_PIXEL), 1e-3),
          f"with the UI hidden a drag over the panel's place did not orbit: {camera}")
    ui = v.key("F1")["ui"]
    check(ui["shown"] and ui["vertices"] > 0 and ui["panel"], f"a second F1 did not show the UI: {ui}")
    v.quit()


def read_png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    check(head[:8] == b"\x89PNG\r\n\x1a\n" and head[12:16] == b"IHDR", f"{path} is not a PNG")
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def case_screenshot(v):
    """F12 writes the scene to the screenshot field's file (sss-viewer.png in the working directory)."""
    path = v.work / "sss-viewer.png"
    check(not path.exists(), f"{path} exists before F12")
    check(v.initial["screenshots"] == [], "a screenshot was written before F12")
    state = v.key("F12")
    check(state["screenshots"] == ["sss-viewer.png"], f"F12: screenshots {state['screenshots']}")
    check(path.is_file(), f"F12 wrote no {path}")
    size = read_png_size(path)
    check(size == tuple(state["window"]), f"screenshot is {size}, the window {state['window']}")
    v.quit()


def case_tf_add(v):
    """A click on empty canvas adds a point there, selected, as one undo step."""
    before = v.initial
    check(before["ui"]["tfCanvas"], "no transfer-function canvas")
    pixel = canvas_pixel(before, 0.45, 0.85)
    want = canvas_coords(before, pixel)
    tolerance = pixel_size(before)
    check(find_point(before, *want, (4 * tolerance[0], 4 * tolerance[1])) is None, "a point is already there")
    state = v.click(1, pixel)
    tf = state["transferFunction"]
    check(len(tf["points"]) == len(before["transferFunction"]["points"]) + 1,
          f"{len(tf['points'])} points after the click, {len(before['transferFunction']['points'])} before")
    added = find_point(state, *want, (1e-3, 1e-3))
    check(added is not None, f"no point at {want}: {points(state)}")
    check(tf["selected"] == added, f"selected {tf['selected']}, the new point is {added}")
    check(tf["undo"] == 1 and tf["redo"] == 0, f"undo/redo depth {tf['undo']}/{tf['redo']}, expected 1/0")
    final = v.quit()
    check(points(final) == points(state), "the function changed after the click")


def movable_point(state):
    """An inner point with room around it: the one nearest to value 0.55."""
    pts = points(state)
    return min(range(1, len(pts) - 1), key=lambda i: abs(pts[i][0] - 0.55))


def case_tf_move(v):
    """Dragging a point moves it by the pointer's movement; the whole drag is one undo step."""
    before = v.initial
    i = movable_point(before)
    value, opacity = points(before)[i]
    start = canvas_pixel(before, value, opacity)
    dx, dy = 25, -30  # right and up
    state = v.drag(1, start, (start[0] + dx, start[1] + dy), steps=4)
    px = pixel_size(before)
    want = (value + dx * px[0], opacity - dy * px[1])
    moved = find_point(state, *want, (1e-3, 1e-3))
    check(moved is not None, f"point {i} ({value}, {opacity}) not at {want} after the drag: {points(state)}")
    check(len(points(state)) == len(points(before)), "the drag changed the number of points")
    check(find_point(state, value, opacity, (1e-3, 1e-3)) is None, "the point is also still at its old place")
    tf = state["transferFunction"]
    check(tf["undo"] == 1, f"a drag is one undo step, got {tf['undo']}")
    v.quit()


def case_tf_delete(v):
    """A right-click on a point removes it; so does Delete on the selected point."""
    before = v.initial
    count = len(points(before))
    i = movable_point(before)
    value, opacity = points(before)[i]
    state = v.click(3, canvas_pixel(before, value, opacity))
    check(len(points(state)) == count - 1, f"right-click: {len(points(state))} points, expected {count - 1}")
    check(find_point(state, value, opacity, (1e-3, 1e-3)) is None, f"right-click left ({value}, {opacity})")
    # Select another inner point with a click (no drag), then Delete.
    j = movable_point(state)
    value, opacity = points(state)[j]
    state = v.click(1, canvas_pixel(state, value, opacity))
    check(state["transferFunction"]["selected"] == j, f"click on point {j} selected {state['transferFunction']['selected']}")
    state = v.key("Delete")
    check(len(points(state)) == count - 2, f"Delete: {len(points(state))} points, expected {count - 2}")
    check(find_point(state, value, opacity, (1e-3, 1e-3)) is None, f"Delete left ({value}, {opacity})")
    check(state["transferFunction"]["undo"] == 2, f"two removals are two undo steps, got {state['transferFunction']['undo']}")
    v.quit()


def case_tf_undo_redo(v):
    """Ctrl+Z undoes a move and an add in turn, Ctrl+Y redoes them."""
    initial = points(v.initial)
    added_state = v.click(1, canvas_pixel(v.initial, 0.45, 0.85))
    added = points(added_state)
    check(len(added) == len(initial) + 1, "the click added no point")
    start = canvas_pixel(added_state, *added[movable_point(added_state)])
    moved = points(v.drag(1, start, (start[0] + 10, start[1] - 20)))
    check(moved != added, "the drag moved no point")

    state = v.key("ctrl+z")
    check(points(state) == added, f"first Ctrl+Z: {points(state)}; expected the function after the add {added}")
    state = v.key("ctrl+z")
    check(points(state) == initial, f"second Ctrl+Z: {points(state)}; expected the initial function {initial}")
    tf = state["transferFunction"]
    check(tf["undo"] == 0 and tf["redo"] == 2, f"undo/redo depth {tf['undo']}/{tf['redo']}, expected 0/2")
    state = v.key("ctrl+y")
    check(points(state) == added, f"Ctrl+Y: {points(state)}; expected {added}")
    state = v.key("ctrl+y")
    check(points(state) == moved, f"second Ctrl+Y: {points(state)}; expected {moved}")
    check(points(v.quit()) == moved, "the function at exit differs from the last redo")


CASES = {
    "orbit": (case_orbit, MESH_SCENE),
    "pan": (case_pan, MESH_SCENE),
    "zoom": (case_zoom, MESH_SCENE),
    "reframe": (case_reframe, MESH_SCENE),
    "toggle-ui": (case_toggle_ui, MESH_SCENE),
    "screenshot": (case_screenshot, MESH_SCENE),
    "tf-add": (case_tf_add, VOLUME_SCENE),
    "tf-move": (case_tf_move, VOLUME_SCENE),
    "tf-delete": (case_tf_delete, VOLUME_SCENE),
    "tf-undo-redo": (case_tf_undo_redo, VOLUME_SCENE),
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--viewer", required=True, help="the sss-viewer executable")
    parser.add_argument("--xdotool", default="xdotool")
    parser.add_argument("--work", required=True, help="folder for the state file, log and screenshots")
    parser.add_argument("case", choices=sorted(CASES))
    args = parser.parse_args()
    if not os.environ.get("DISPLAY"):
        print("viewer_input: no DISPLAY (run under xvfb-run)", file=sys.stderr)
        return 1
    run, scene = CASES[args.case]
    work = pathlib.Path(args.work).resolve() / args.case
    work.mkdir(parents=True, exist_ok=True)
    for old in work.iterdir():
        old.unlink()
    started = time.monotonic()
    viewer = None
    try:
        viewer = Viewer(str(pathlib.Path(args.viewer).resolve()), args.xdotool, work, args.case, scene)
        run(viewer)
    except Failure as failure:
        print(f"FAIL {args.case}: {failure}", file=sys.stderr)
        if viewer:
            print(f"--- {viewer.log_path} (tail)\n{viewer.log_tail()}", file=sys.stderr)
        return 1
    finally:
        if viewer:
            viewer.kill()
    print(f"PASS {args.case} ({time.monotonic() - started:.1f} s): {run.__doc__}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
