"""Make docs/images/fleet_view.gif: the fleet's live view (`robosc sim --view`) of the warehouse
with eight robots and the person, as headless Chromium shows it, a frame every FRAME seconds.

    python scripts/fleet_view_gif.py [--robots 8] [--seconds 60] [--speed 6] [-o docs/images/fleet_view.gif]

Needs Debian's chromium and chromium-driver, selenium and IR-SIM (the test extra and the sim extra)."""

from __future__ import annotations

import argparse
import io
import re
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

from PIL import Image
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

ROOT = Path(__file__).resolve().parent.parent
FRAME = 0.5  # real seconds between two pictures


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", type=int, default=8)
    parser.add_argument("--seconds", type=float, default=60.0, help="real seconds to record")
    parser.add_argument("--speed", type=float, default=6.0, help="simulated seconds per real second")
    parser.add_argument("--width", type=int, default=760, help="pixels across")
    parser.add_argument("-o", "--output", default=str(ROOT / "docs/images/fleet_view.gif"))
    args = parser.parse_args()
    folder = Path(tempfile.mkdtemp(prefix="fleet-view-"))
    model = folder / "warehouse.rscd"
    model.write_text((ROOT / "examples/warehouse.rscd").read_text().replace("component bot[3]", f"component bot[{args.robots}]"))
    port = 8800 + args.robots
    log = open(folder / "sim.log", "wb")  # noqa: SIM115 (closed at the end)
    sim = subprocess.Popen(
        [sys.executable, "-m", "robosc", "sim", str(ROOT / "examples/worlds/warehouse.yaml"), str(model), "--ros", "none",
         "--view", "--port", str(port), "--speed", str(args.speed), "--tasks", "3"],
        stdout=log, stderr=subprocess.STDOUT,
    )
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1500,1250"):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    try:
        url = f"http://127.0.0.1:{port}/"
        while not re.search("live view: http", (folder / "sim.log").read_text()):
            if sim.poll() is not None:
                sys.exit((folder / "sim.log").read_text())
            time.sleep(0.5)
        urllib.request.urlopen(url, timeout=5).read()
        driver.get(url)
        time.sleep(2)
        main_part = driver.find_element("css selector", "main")
        frames = []
        end = time.monotonic() + args.seconds
        while time.monotonic() < end:
            started = time.monotonic()
            picture = Image.open(io.BytesIO(main_part.screenshot_as_png)).convert("RGB")
            height = round(picture.height * args.width / picture.width)
            frames.append(picture.resize((args.width, height), Image.LANCZOS))
            time.sleep(max(0.0, FRAME - (time.monotonic() - started)))
        sample = Image.new("RGB", (args.width, frames[0].height * 4))  # one palette from four moments
        for k in range(4):
            sample.paste(frames[(k * len(frames)) // 4 + len(frames) // 8], (0, k * frames[0].height))
        palette = sample.quantize(colors=256, method=Image.MEDIANCUT)
        shrunk = [f.quantize(palette=palette, dither=Image.NONE) for f in frames]
        shrunk[0].save(args.output, save_all=True, append_images=shrunk[1:], duration=int(FRAME * 1000), loop=0, optimize=True)
        print(f"wrote {args.output}: {len(frames)} frames, {Path(args.output).stat().st_size // 1024} KB")
    finally:
        driver.quit()
        sim.terminate()
        sim.wait(timeout=10)
        log.close()


if __name__ == "__main__":
    main()
