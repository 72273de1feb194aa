#!/usr/bin/env python3
"""The HTML report opened in a real browser (headless Chromium, Debian's `chromium`).

Builds a throwaway project from copies of canonical scenes and goldens, replaces one
golden by the run of a changed scene (its restitution e moved by one ULP or by one
percent, the scene's own sha256 kept, so the gate compares old physics with new),
runs `impulse check --report`, opens index.html in Chromium and checks what a
reviewer relies on:

- the page runs without a script error (the page counts them into
  <html data-script-errors>, which --dump-dom shows) and its script finished;
- the failed scene's section comes first, before a passed scene checked earlier;
- its replay advances when played (?autoplay, then a virtual-time budget);
- the divergence marker is on the page;
- a screenshot has the window's size, is not blank (many distinct colours) and
  shows the divergence marker's red.

With --screenshot PATH the screenshot is kept there (the README's pictures are
made so). Standard library only. Exit 0 when every check holds, 1 otherwise.
"""

import argparse
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

DIVERGENCE_RED = (0xD3, 0x2F, 0x2F)  # .divergence-marker in page_style.cpp
WINDOW = (1100, 1400)


def fail(message):
    print("report_in_browser: FAILED: " + message, file=sys.stderr)
    sys.exit(1)


def changed_restitution(scene_text, change):
    match = re.search(r'"restitution"\s*:\s*([-+0-9.eE]+)', scene_text)
    if match is None:
        fail("the scene has no restitution to change")
    e = float(match.group(1))
    new_e = math.nextafter(e, math.inf) if change == "one-ulp" else e * 1.01
    if new_e > 1.0:  # e = 1 can only go down
        new_e = math.nextafter(e, 0.0) if change == "one-ulp" else e * 0.99
    return scene_text[: match.start(1)] + repr(new_e) + scene_text[match.end(1) :]


def run(command, expect=None):
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    if expect is not None and done.returncode != expect:
        fail("%s exited %d, expected %d:\n%s%s" % (command[:3], done.returncode, expect,
                                                   done.stdout, done.stderr))
    return done


def changed_golden(tmp, source, impulse, root, name, change):
    """Replaces ROOT's golden of `name` by the run of the scene with e changed."""
    with open(os.path.join(source, "harness", "scenes", name + ".json")) as f:
        scene_text = f.read()
    changed_scene = os.path.join(tmp, "changed", name + ".json")
    os.makedirs(os.path.dirname(changed_scene), exist_ok=True)
    with open(changed_scene, "w") as f:
        f.write(changed_restitution(scene_text, change))
    trajectory = os.path.join(tmp, "changed", name + ".trajectory.json")
    done = run([impulse, "run", changed_scene, "--out", trajectory, "--quiet"])
    if done.returncode != 0:
        return done.stderr.strip()
    golden_path = os.path.join(root, "goldens", name + ".json")
    with open(golden_path) as f:
        sha = re.search(r'"scene_sha256": "([0-9a-f]+)"', f.read()).group(1)
    with open(trajectory) as f:
        text = f.read()
    # The digest covers frames and events only, so the golden stays readable.
    with open(golden_path, "w") as f:
        f.write(re.sub(r'"scene_sha256": "[0-9a-f]+"', '"scene_sha256": "%s"' % sha, text, 1))
    return None


def make_project(tmp, source, impulse, scenes, changed, change, strict):
    """TMP/root with copies of `scenes`; the goldens of `changed` made from changed scenes.

    A changed scene the tool refuses (e = 0.99 with an energy-conserved expectation)
    fails when `strict`, else keeps its golden and is left out of `changed`."""
    root = os.path.join(tmp, "root")
    os.makedirs(os.path.join(root, "harness", "scenes"))
    os.makedirs(os.path.join(root, "goldens"))
    for name in scenes:
        for folder in (os.path.join("harness", "scenes"), "goldens"):
            shutil.copy(os.path.join(source, folder, name + ".json"), os.path.join(root, folder))
    for name in list(changed):
        refusal = changed_golden(tmp, source, impulse, root, name, change)
        if refusal is not None and strict:
            fail("the changed scene %s was refused: %s" % (name, refusal))
        if refusal is not None:
            print("report_in_browser: %s keeps its golden: %s" % (name, refusal))
            changed.remove(name)
    return root


def chromium_command(profile):
    browser = shutil.which("chromium")
    if browser is None:
        fail("chromium is not installed: scripts/setup installs it (Debian's chromium)")
    return [browser, "--headless", "--no-sandbox", "--disable-gpu",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            "--no-first-run", "--hide-scrollbars", "--force-device-scale-factor=1",
            "--force-color-profile=srgb", "--user-data-dir=" + profile]


def png_facts(path):
    """(width, height, distinct colours, has the divergence red) of an 8-bit RGB(A) PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(path + " is not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos : pos + 8])
        chunk = data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", chunk)
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    width, height, depth, colour_type, _, _, interlace = header
    if depth != 8 or colour_type not in (2, 6) or interlace != 0:
        fail("%s: unexpected PNG format (depth %d, colour type %d)" % (path, depth, colour_type))
    channels = 3 if colour_type == 2 else 4
    raw, stride = zlib.decompress(idat), width * channels
    previous, colours, pos = bytearray(stride), set(), 0
    for _ in range(height):
        kind, line = raw[pos], bytearray(raw[pos + 1 : pos + 1 + stride])
        pos += 1 + stride
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up, corner = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        for i in range(0, stride, channels):
            colours.add(bytes(line[i : i + 3]))
        previous = line
    return width, height, len(colours), bytes(DIVERGENCE_RED) in colours


def check_dom(dom, changed, passed_first):
    errors = re.search(r'data-script-errors="(\d+)"', dom)
    if errors is None or errors.group(1) != "0":
        text = re.search(r'data-script-error-text="([^"]*)"', dom)
        fail("the page had script errors: %s" % (text.group(1) if text else "its script did not run"))
    if 'data-ready="1"' not in dom:
        fail("the page's script did not finish (no data-ready)")
    sections = re.findall(r'<section id="scene-([^"]+)" class="([a-z]+)"', dom)
    if not sections or sections[0][1] != "failed" or sections[0][0] not in changed:
        fail("the first section is %s, expected a failed scene of %s" % (sections[:1], changed))
    if passed_first is not None and (passed_first, "passed") not in sections:
        fail("the passed scene %s has no section" % passed_first)
    frame = re.search(r'<div class="replay"[^>]*data-frame="(\d+)"', dom)
    if frame is None or int(frame.group(1)) <= 0:
        fail("the replay did not advance when played (frame %s)" % (frame.group(1) if frame else "absent"))
    if 'class="divergence-marker"' not in dom:
        fail("the divergence marker is missing")
    return int(frame.group(1))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--impulse", required=True, help="the built impulse binary")
    parser.add_argument("--source", required=True, help="the project's source folder")
    parser.add_argument("--change", choices=["one-ulp", "one-percent"], default="one-percent")
    parser.add_argument("--scenes", default="bullet,drop-box",
                        help="scenes copied, comma separated, or 'all' (the canonical ones)")
    parser.add_argument("--changed", default="drop-box",
                        help="scenes whose golden is changed, comma separated, or 'all' "
                             "(those that state a restitution); the first one is checked first")
    parser.add_argument("--window", default="%dx%d" % WINDOW, help="screenshot size, WxH")
    parser.add_argument("--screenshot", help="keep the screenshot at this path")
    args = parser.parse_args()
    canonical = sorted(f[:-5] for f in os.listdir(os.path.join(args.source, "harness", "scenes"))
                       if f.endswith(".json"))
    scenes = canonical if args.scenes == "all" else args.scenes.split(",")
    changed = args.changed.split(",")
    if args.changed == "all":
        changed = [n for n in scenes if '"restitution"' in
                   open(os.path.join(args.source, "harness", "scenes", n + ".json")).read()]
    window = tuple(int(v) for v in args.window.split("x"))
    with tempfile.TemporaryDirectory(prefix="impulse-browser-") as tmp:
        profile = os.path.join(tmp, "profile")
        browser = chromium_command(profile)
        root = make_project(tmp, args.source, args.impulse, scenes, changed, args.change,
                            args.changed != "all")
        report = os.path.join(tmp, "report")
        run([args.impulse, "check", *scenes, "--root", root, "--report", report], expect=1)
        page = "file://" + os.path.join(report, "index.html")
        dom = run(browser + ["--virtual-time-budget=3000", "--dump-dom", page + "?autoplay"], expect=0)
        passed = [n for n in scenes if n not in changed]
        frame = check_dom(dom.stdout, changed, passed[0] if passed else None)
        shot = os.path.join(tmp, "shot.png")
        run(browser + ["--virtual-time-budget=1000", "--window-size=%d,%d" % window,
                       "--screenshot=" + shot,
                       page + "?at=divergence"], expect=0)
        if not os.path.isfile(shot):
            fail("chromium wrote no screenshot")
        width, height, colours, red = png_facts(shot)
        if (width, height) != window:
            fail("the screenshot is %dx%d, expected %dx%d" % (width, height, *window))
        if colours < 16:
            fail("the screenshot looks blank: %d distinct colours" % colours)
        if not red:
            fail("the screenshot does not show the divergence marker's red")
        if args.screenshot:
            shutil.copy(shot, args.screenshot)
        print("report_in_browser: ok: %s first, replay at frame %d after playing, %dx%d screenshot "
              "with %d colours and the divergence marker; index.html %d bytes"
              % (changed[0], frame, width, height, colours,
                 os.path.getsize(os.path.join(report, "index.html"))))


if __name__ == "__main__":
    main()
