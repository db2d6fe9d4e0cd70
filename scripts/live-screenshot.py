"""live-screenshot.py: makes doc/live-page.png, the screenshot of the live page that
doc/live.md shows: 1tii as NewCartoon with its heme as Licorice, a command typed in the
console, in headless chromium at 1100 x 640, reduced to a 64-colour palette to stay small.
    MOLSCOPE=src/molscope MOLSCOPE_TCLLIB=tcl /usr/bin/python3 scripts/live-screenshot.py
"""
import io
import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "tests", "python"))
from test_live import Session, browser, wait_for  # noqa: E402
from PIL import Image  # noqa: E402


def main():
    data = os.path.join(here, "..", "tests", "data")
    s = Session("opengl")
    drv = None
    try:
        s.cmd("mol new %s/1tii.pdb" % data)
        s.cmd("mol modstyle 0 0 NewCartoon")
        s.cmd("mol modcolor 0 0 Structure")
        s.cmd("mol addrep 0")
        s.cmd("mol modselect 1 0 {resname HEM or (hetero and not water)}")
        s.cmd("mol modstyle 1 0 Licorice 0.3 12 12")
        url = s.url()
        drv, why = browser()
        if drv is None:
            print("live-screenshot: " + why)
            return 1
        drv.set_window_size(1100, 760)
        drv.get(url)
        wait_for(lambda: drv.execute_script("return document.querySelector('#reps tbody tr')"), timeout=30)
        box = drv.find_element("id", "console-input")
        box.send_keys("measure center [atomselect top protein]\n")
        time.sleep(1)
        wait_for(lambda: int(drv.execute_script("return Number(document.getElementById('view')"
                                                ".dataset.passes || 0)")) >= 8, timeout=60)
        png = drv.get_screenshot_as_png()
        im = Image.open(io.BytesIO(png)).convert("RGB").quantize(64)
        out = os.path.join(here, "..", "doc", "live-page.png")
        im.save(out, optimize=True)
        print("%s: %dx%d, %d bytes" % (out, im.size[0], im.size[1], os.path.getsize(out)))
    finally:
        if drv is not None:
            drv.quit()
        s.quit()
    return 0


if __name__ == "__main__":
    sys.exit(main())
