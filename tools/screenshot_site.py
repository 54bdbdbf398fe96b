#!/usr/bin/env python3
"""Prove that the built documentation site renders: a headless Chromium screenshot of the
front page and of one command's reference page, each checked for what a rendered page has.

    tools/screenshot_site.py SITE OUTDIR    SITE: the built site (build/site); writes
                                            OUTDIR/front.png and OUTDIR/reference-orbit.png

Each screenshot (1280 x 1000, file:// URL: the site works offline) must show the theme's
navigation bar (the top 60 pixel rows mostly one saturated colour, not white) and text
(between 2% and 70% of the pixels below the bar neither white nor near white). An
unstyled page (a missing stylesheet: no bar), an empty one or an error page fails.
Exit 0: both pass; 1: a check failed or chromium failed (the reason on stderr); 77:
chromium is not installed (`tools/setup docs` installs it). Reads the PNGs with
matplotlib (a Debian package the Python tests use already).
"""
import os
import shutil
import subprocess
import sys

PAGES = [("index.html", "front.png"), ("reference/orbit.html", "reference-orbit.png")]
WIDTH, HEIGHT = 1280, 1000


def check(png):
    import matplotlib.image
    import numpy as np
    img = matplotlib.image.imread(png)[:, :, :3]  # floats in [0, 1]
    if img.shape[:2] != (HEIGHT, WIDTH):
        return f"{img.shape[1]} x {img.shape[0]} pixels, not {WIDTH} x {HEIGHT}"
    bar = img[:60]
    spread = bar.max(axis=2) - bar.min(axis=2)  # saturation: 0 for grey and white
    if not (spread > 0.3).mean() > 0.5:
        return "no navigation bar (the top rows are not the theme's colour: an unstyled page?)"
    body = img[100:]
    ink = (body.min(axis=2) < 0.85).mean()
    if not 0.02 < ink < 0.7:
        return f"{100 * ink:.1f}% of the body is ink (a rendered page has 2-70%)"
    return None


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.split("\n\n")[1])
    site, out = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if not chromium:
        print("screenshot_site: chromium is not installed (tools/setup docs installs it)", file=sys.stderr)
        sys.exit(77)
    os.makedirs(out, exist_ok=True)
    failed = False
    for page, name in PAGES:
        path = os.path.join(site, page)
        if not os.path.isfile(path):
            print(f"screenshot_site: {path} does not exist", file=sys.stderr)
            failed = True
            continue
        png = os.path.join(out, name)
        if os.path.exists(png):
            os.remove(png)
        # --no-sandbox: CI runs as root, where Chromium's sandbox refuses to start.
        r = subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                            f"--window-size={WIDTH},{HEIGHT}", f"--screenshot={png}", "file://" + path],
                           capture_output=True, text=True, timeout=180)
        if r.returncode != 0 or not os.path.isfile(png):
            print(f"screenshot_site: chromium failed on {page} (exit {r.returncode}): {r.stderr[-300:]}", file=sys.stderr)
            failed = True
            continue
        why = check(png)
        if why:
            print(f"screenshot_site: {page}: {why} (see {png})", file=sys.stderr)
            failed = True
        else:
            print(f"screenshot_site: {page} renders: {png}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
