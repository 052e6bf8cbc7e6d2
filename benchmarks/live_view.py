"""How the live view keeps up: the simulator feeds it N steps per second (pick-and-light,
random steps) while headless Chromium shows it; prints the events the page drew per
second, the events still waiting to be drawn, and the time of a script round trip
into the page (how usable it stays).

    python benchmarks/live_view.py [--rates 100 300 1000] [--seconds 8]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))


def main() -> None:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    from ros_support import free_port, wait_until

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rates", type=float, nargs="+", default=[100.0, 300.0, 1000.0])
    parser.add_argument("--seconds", type=float, default=8.0)
    args = parser.parse_args()
    print("| steps/s asked | events drawn/s | waiting at the end | script round trip, median ms (max) |")
    print("|---|---|---|---|")
    for rate in args.rates:
        with tempfile.TemporaryDirectory() as tmp:
            port = free_port()
            steps = int(rate * (args.seconds + 10))
            sim = subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "robosc",
                    "simulate",
                    str(ROOT / "examples/pick_and_light.rscd"),
                    "--random",
                    str(steps),
                    "--rate",
                    str(rate),
                    "--seed",
                    "1",
                    "--quiet",
                    "--view",
                    "--port",
                    str(port),
                ],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
            options = webdriver.ChromeOptions()
            options.binary_location = "/usr/bin/chromium"
            for flag in (
                "--headless=new",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-dev-shm-usage",
                "--disable-background-networking",
                "--no-first-run",
                f"--user-data-dir={tmp}/c",
            ):
                options.add_argument(flag)
            driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
            try:
                time.sleep(2)
                driver.get(f"http://127.0.0.1:{port}/")
                page = driver

                def live(page: webdriver.Chrome = page) -> bool:
                    return bool(page.execute_script("return document.getElementById('status').textContent") == "live")

                def count(page: webdriver.Chrome = page) -> int:
                    return int(page.execute_script("return count;"))

                assert wait_until(live, 10)
                time.sleep(2)
                first, start = count(), time.monotonic()
                trips = []
                while time.monotonic() - start < args.seconds:
                    t = time.perf_counter()
                    driver.execute_script("return document.getElementById('count').textContent;")
                    trips.append((time.perf_counter() - t) * 1000)
                    time.sleep(0.2)
                drawn = (count() - first) / (time.monotonic() - start)
                waiting = driver.execute_script("return pending.length;")
                print(f"| {rate:g} | {drawn:.0f} | {waiting} | {statistics.median(trips):.1f} ({max(trips):.1f}) |")
            finally:
                driver.quit()
                sim.terminate()
                sim.wait()


if __name__ == "__main__":
    main()
