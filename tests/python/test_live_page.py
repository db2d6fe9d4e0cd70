"""test_live_page.py: the live page as a working session (doc/live.md, issue 24), driven in
headless chromium (selenium) the way a person uses it, every check reading back what the
session holds through molscope's own prompt (molinfo, mol, animate, display, color):

  - the HTTP endpoints behind the page (/tcl /cmd /session /render /download) need the
    token, refuse bodies that are not forms, too large or missing their fields (400), and
    answer commands with their result or their error as JSON
  - the console runs Tcl as the prompt does (result, output, error shown in red, the
    session answering afterwards), keeps a history on the arrow keys, and runs Python
    when molscope was built with it
  - the molecules panel lists `molinfo list`, loads a file by its path (a bad path shows
    the error), sets top, active, shown, and deletes
  - the representations panel lists what `molinfo get "{rep i}"` says, creates and
    deletes reps, shows and hides them, and changes method, parameters, colouring,
    selection (a bad one shows its error inline and changes nothing) and material
  - the trajectory controls move `molinfo top get frame` (slider, step, ends, play and
    pause) and set `animate speed` and `animate style`
  - the display controls set projection, background (the image's corner follows), depth
    cue, axes, AO, shadows, raster or progressive images, and reset the view; a drag shows
    coarse images (half the width), then the whole image and its passes
  - render runs `render <method> <file>` and offers the file for download
  - two browser sessions see each other's changes and the terminal's
  - the display follows the window's size and its device pixel ratio (a 2x screen gets a
    2x image laid out at the viewport's size); screenshots at three sizes show a molecule
  - a drag on a scene of over 150 000 triangles draws decimated meshes, still showing the
    molecule, and the whole image after it is the same as before any drag
"""
import io
import json
import os
import sys
import time
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mstest import Reporter  # noqa: E402
from test_live import (DATA, EXE, OUT, PIXELS_JS, Session, browser, http, is_identity,  # noqa: E402
                       matrix, split, wait_for)

R = Reporter("live_page")


def post(base, token, path, fields):
    status, body = http("%s/%s?token=%s" % (base, path, token),
                        urllib.parse.urlencode(fields, doseq=True))
    return status, body


def answer(base, token, path, fields):
    status, body = post(base, token, path, fields)
    return json.loads(body) if status == 200 else {"status": status, "body": body}


# ---------------------------------------------------------------- HTTP, no browser

def check_endpoints(s, base, token):
    for path in ["/tcl", "/cmd", "/render"]:
        st, _ = http(base + path, "cmd=quit")
        R.report(st == 403, "no token: POST %s gets 403" % path, "status %d" % st)
    for path in ["/session", "/download"]:
        st, _ = http(base + path)
        R.report(st == 403, "no token: GET %s gets 403" % path, "status %d" % st)
    a = answer(base, token, "tcl", {"cmd": "puts hi; expr {6*7}"})
    R.report(a.get("ok") and a.get("result") == "42" and a.get("output") == "hi\n",
             "/tcl answers the result and the output", str(a))
    a = answer(base, token, "cmd", {"w": ["mol", "modstyle", "0", "0", "Nope 1"]})
    R.report(a.get("ok") is False and "Nope" in a.get("error", ""),
             "/cmd answers a command's error", str(a))
    a = answer(base, token, "cmd", {"w": ["set", "x y", "{"]})
    R.report(a.get("ok") and a.get("result") == "{", "/cmd passes each word whole", str(a))
    st, body = http("%s/tcl?token=%s" % (base, token), '{"cmd": "quit"}', "application/json")
    R.report(st == 400, "/tcl refuses a body that is not a form", "%d %r" % (st, body))
    st, body = post(base, token, "tcl", {"cmd": "x" * ((1 << 20) + 10)})
    R.report(st == 400 and b"too large" in body, "/tcl refuses a body over 1 MiB",
             "%d %r" % (st, body[:80]))
    st, _ = post(base, token, "tcl", {"lang": "perl", "cmd": "1"})
    R.report(st == 400, "/tcl refuses an unknown language", str(st))
    st, _ = post(base, token, "render", {"method": "TachyonInternal"})
    R.report(st == 400, "/render without a file is refused", str(st))
    st, _ = http("%s/download?token=%s" % (base, token))
    R.report(st == 404, "/download before any render gets 404", str(st))
    st, body = http("%s/session?token=%s" % (base, token))
    sess = json.loads(body) if st == 200 else {}
    mols = sess.get("session", {}).get("molecules", [])
    R.report(st == 200 and [m["id"] for m in mols] == [int(x) for x in s.cmd("molinfo list").split()]
             and any(m["name"] == "NewCartoon" for m in sess.get("methods", [])),
             "/session lists the molecules and the drawing methods", body[:200])
    v0 = sess.get("version")
    st, body = http("%s/session?token=%s" % (base, token))
    R.report(json.loads(body).get("version") == v0, "reading /session changes nothing (same version)",
             "%s -> %s" % (v0, json.loads(body).get("version")))
    R.report(s.p.poll() is None and s.cmd("expr 2+2") == "4", "the terminal still answers")


# ---------------------------------------------------------------- the page

class Page:
    """One browser on the page, with helpers that act as a person would."""

    def __init__(self, drv, url):
        from selenium.webdriver.common.by import By
        from selenium.webdriver.support.ui import Select
        self.drv, self.By, self.Select = drv, By, Select
        drv.set_page_load_timeout(20)
        drv.get(url)

    def el(self, id_):
        return self.drv.find_element(self.By.ID, id_)

    def css(self, sel):
        return self.drv.find_elements(self.By.CSS_SELECTOR, sel)

    def again(self, action, tries=20):
        """action(), which finds its element each time, run again when the page replaced that
        element meanwhile (it redraws parts of itself as news from molscope arrives)."""
        from selenium.common.exceptions import StaleElementReferenceException
        for _ in range(tries - 1):
            try:
                return action()
            except StaleElementReferenceException:
                time.sleep(0.05)
        return action()

    def click(self, sel):
        """Click the element sel finds, found again if the page redrew it meanwhile."""
        def action():
            wait_for(lambda: self.css(sel), timeout=5)
            return self.css(sel)[0].click()
        return self.again(action)

    def choose(self, id_, text):
        self.Select(self.el(id_)).select_by_visible_text(text)

    def js(self, code, *args):
        return self.drv.execute_script(code, *args)

    def pixels(self):
        return self.js(PIXELS_JS)

    def serial(self):
        px = self.pixels()
        return px["serial"] if px else 0

    def console(self, text):
        from selenium.webdriver.common.keys import Keys
        box = self.el("console-input")
        box.click()
        box.send_keys(text)
        box.send_keys(Keys.ENTER)

    def log(self):
        return self.el("console-log").text

    def spans(self, cls):
        """The console's lines of a kind (res: results, err: errors, out, cmd, note)."""
        return self.js("return [...document.querySelectorAll('#console-log .' + arguments[0])]"
                       ".map(e => e.textContent.trim());", cls)

    def reps(self):
        """The rep table's rows (style, colouring, selection), read at once in the page."""
        return self.js("return [...document.querySelectorAll('#reps tbody tr')].map("
                       "tr => [...tr.cells].slice(1).map(td => td.textContent));")

    def molids(self):
        return self.js("return [...document.querySelectorAll('#mols tbody tr')].map("
                       "tr => tr.dataset.molid);")

    def fill(self, find, text, end=None):
        """Select what a field holds and type text over it, then Enter or Tab (the change).
        find() gives the field: found again when the page has just rebuilt it (a rep's
        parameters are redrawn when the page learns of the new method), the typing, which
        selects all first, starting over."""
        from selenium.webdriver.common.keys import Keys

        def action():
            box = find()
            box.click()
            box.send_keys(Keys.CONTROL, "a")    # the modifier is held for this call only
            box.send_keys(text)
            box.send_keys(end or Keys.TAB)
        self.again(action)

    def type_into(self, id_, text, enter=True):
        from selenium.webdriver.common.keys import Keys
        self.fill(lambda: self.el(id_), text, Keys.ENTER if enter else Keys.TAB)


def changed(fn, old, timeout=10):
    return wait_for(lambda: (lambda v: v if v != old else None)(fn()), timeout=timeout)


def check_console(s, p):
    p.console("expr {6*7}")
    R.report(wait_for(lambda: "42" in p.spans("res")), "console: a command's result is shown", p.log())
    p.console('puts "hello from the page"')
    R.report(wait_for(lambda: "hello from the page" in p.spans("out")), "console: its output is shown",
             p.log()[-200:])
    p.console("mol modstyle 0 0 NoSuchMethod")
    err = wait_for(lambda: [e for e in p.spans("err") if "NoSuchMethod" in e])
    R.report(bool(err), "console: an error is shown with its message (in red)", p.log()[-200:])
    p.console("set survived yes")
    R.report(wait_for(lambda: "yes" in p.spans("res")) and s.cmd("set survived") == "yes",
             "console: the session survives an error and shares the terminal's variables",
             p.log()[-100:])
    from selenium.webdriver.common.keys import Keys
    box = p.el("console-input")
    box.send_keys(Keys.ARROW_UP)
    first = box.get_attribute("value")
    box.send_keys(Keys.ARROW_UP)
    second = box.get_attribute("value")
    box.send_keys(Keys.ARROW_DOWN)
    third = box.get_attribute("value")
    R.report(first == "set survived yes" and second == "mol modstyle 0 0 NoSuchMethod" and
             third == first, "console: the arrow keys walk the history", "%r %r %r" % (first, second, third))
    box.send_keys(Keys.CONTROL, "a")
    box.send_keys(Keys.DELETE)
    if p.el("console-lang").is_displayed():
        p.choose("console-lang", "Python")
        p.console("print(6 * 7 + 1)")
        R.report(wait_for(lambda: "43" in p.spans("out"), timeout=30), "console: Python runs (gopython)",
                 p.log()[-200:])
        p.console("1/0")
        R.report(wait_for(lambda: any("ZeroDivisionError" in e for e in p.spans("err"))),
                 "console: a Python exception is shown as an error", p.log()[-200:])
        p.choose("console-lang", "Tcl")
    else:
        R.skip("console python", "molscope was built without Python")


def check_molecules(s, p):
    rows = p.molids
    R.report(wait_for(lambda: rows() == s.cmd("molinfo list").split()),
             "molecules: the list is molinfo list", "%s vs %s" % (rows(), s.cmd("molinfo list")))
    p.type_into("load-path", os.path.join(DATA, "nonexistent.pdb"))
    R.report(bool(wait_for(lambda: p.el("load-error").text)) and s.cmd("molinfo num") == "1",
             "molecules: a bad path shows its error and loads nothing", p.el("load-error").text)
    p.type_into("load-path", os.path.join(DATA, "1a8o.pdb"), enter=False)
    p.el("load-button").click()
    R.report(wait_for(lambda: len(rows()) == 2) and s.cmd("molinfo num") == "2" and
             p.el("load-error").text == "", "molecules: Load reads a file by its path on the server",
             str(rows()))
    new = rows()[1]
    R.report(s.cmd("molinfo top") == new, "molecules: the new molecule is top", s.cmd("molinfo top"))
    wait_for(lambda: p.css("#mols tbody tr[data-molid='%s'] .mol-top:checked" % new))
    p.click("#mols tbody tr[data-molid='0'] .mol-top")
    R.report(wait_for(lambda: s.cmd("molinfo top") == "0"), "molecules: T makes a molecule top",
             s.cmd("molinfo top"))
    p.click("#mols tbody tr[data-molid='%s'] .mol-shown" % new)
    R.report(wait_for(lambda: s.cmd("molinfo %s get drawn" % new) == "0"),
             "molecules: D hides a molecule", s.cmd("molinfo %s get drawn" % new))
    p.click("#mols tbody tr[data-molid='%s'] .mol-active" % new)
    R.report(wait_for(lambda: s.cmd("molinfo %s get active" % new) == "0"),
             "molecules: A makes it inactive", s.cmd("molinfo %s get active" % new))
    p.click("#mols tbody tr[data-molid='%s'] .mol-delete" % new)
    R.report(wait_for(lambda: s.cmd("molinfo list") == "0" and rows() == ["0"]),
             "molecules: the delete button deletes", "%s / %s" % (s.cmd("molinfo list"), rows()))


def repget(s, what, i):
    """molinfo 0 get "{<what> <i>}": rep i's style, colouring, selection or material."""
    return s.cmd('lindex [molinfo 0 get "{%s %d}"] 0' % (what, i))


def molinfo_reps(s):
    """[method, colouring, selection] of each rep of molecule 0, as molinfo gives them."""
    n = int(s.cmd("molinfo 0 get numreps"))
    return [[repget(s, "rep", i).split()[0], repget(s, "color", i), repget(s, "selection", i)]
            for i in range(n)]


def check_reps(s, p):
    R.report(wait_for(lambda: p.reps() == molinfo_reps(s)), "reps: the list matches molinfo",
             "%s vs %s" % (p.reps(), molinfo_reps(s)))
    n0 = int(s.cmd("molinfo 0 get numreps"))
    serial = p.serial()
    p.el("rep-add").click()
    R.report(wait_for(lambda: s.cmd("molinfo 0 get numreps") == str(n0 + 1) and len(p.reps()) == n0 + 1),
             "reps: Create Rep adds one", str(p.reps()))
    k = n0                      # the new rep is the selected one
    R.report(wait_for(lambda: p.css("#reps tbody tr.sel") and
                      p.css("#reps tbody tr.sel")[0].get_attribute("data-rep") == str(k)),
             "reps: the new rep is selected")
    p.choose("rep-method", "VDW")
    R.report(wait_for(lambda: repget(s, "rep", k).startswith("VDW")),
             "reps: the drawing method changes (mol modstyle)", repget(s, "rep", k))
    R.report(bool(changed(p.serial, serial)), "reps: the image changes with the rep")
    wait_for(lambda: p.css("#rep-params input"))
    p.fill(lambda: p.css("#rep-params input")[0], "0.5")
    R.report(wait_for(lambda: repget(s, "rep", k).startswith("VDW 0.5")),
             "reps: a parameter changes (sphere scale 0.5)", repget(s, "rep", k))
    p.choose("rep-color", "ColorID")
    wait_for(lambda: p.el("rep-colorid").is_displayed())
    p.fill(lambda: p.el("rep-colorid"), "7")
    R.report(wait_for(lambda: repget(s, "color", k) == "ColorID 7"),
             "reps: the colouring changes (ColorID 7)", repget(s, "color", k))
    p.type_into("rep-sel", "resid <")
    err = wait_for(lambda: p.el("rep-sel-error").text)
    R.report(bool(err) and repget(s, "selection", k) == "all",
             "reps: a bad selection shows its error inline and changes nothing", str(err))
    p.type_into("rep-sel", "resid 1 to 20")
    R.report(wait_for(lambda: repget(s, "selection", k) == "resid 1 to 20") and
             wait_for(lambda: p.el("rep-sel-error").text == ""),
             "reps: a good selection applies and clears the error",
             repget(s, "selection", k))
    p.choose("rep-material", "Glossy")
    R.report(wait_for(lambda: repget(s, "material", k) == "Glossy"),
             "reps: the material changes", repget(s, "material", k))
    p.click("#reps tbody tr[data-rep='%d'] .rep-shown" % k)
    R.report(wait_for(lambda: s.cmd("mol showrep 0 %d" % k) == "0"), "reps: the box hides a rep")
    p.click("#reps tbody tr[data-rep='%d'] .rep-shown" % k)
    R.report(wait_for(lambda: s.cmd("mol showrep 0 %d" % k) == "1"), "reps: and shows it again")
    R.report(wait_for(lambda: p.reps() == molinfo_reps(s)), "reps: the list still matches molinfo",
             "%s vs %s" % (p.reps(), molinfo_reps(s)))
    mol_list = s.cmd("string map {\\n { }} [mol list 0]")
    R.report("Representation: VDW 0.5" in mol_list and "ColorID 7" in mol_list and
             "resid 1 to 20" in mol_list, "reps: mol list shows what the panel set", mol_list)
    p.el("rep-delete").click()
    R.report(wait_for(lambda: s.cmd("molinfo 0 get numreps") == str(n0) and len(p.reps()) == n0),
             "reps: Delete Rep deletes the selected rep", str(p.reps()))


def frame(s):
    return int(s.cmd("molinfo top get frame"))


def check_trajectory(s, p):
    from selenium.webdriver.common.action_chains import ActionChains
    n = int(s.cmd("molinfo top get numframes"))
    p.el("anim-start").click()
    R.report(wait_for(lambda: frame(s) == 0), "trajectory: |< goes to the first frame", str(frame(s)))
    slider = p.el("frame")
    w = slider.size["width"]
    ActionChains(p.drv).move_to_element_with_offset(slider, int(w * 0.25), 0).click().perform()
    R.report(wait_for(lambda: frame(s) >= n // 2), "trajectory: the slider moves the frame",
             "frame %d of %d" % (frame(s), n))
    R.report(wait_for(lambda: p.el("frame-label").text.startswith(str(frame(s)) + " ")),
             "trajectory: the label shows the frame", p.el("frame-label").text)
    f0 = frame(s)
    p.el("anim-prev").click()
    R.report(wait_for(lambda: frame(s) == f0 - 1), "trajectory: < steps back", str(frame(s)))
    p.el("anim-next").click()
    R.report(wait_for(lambda: frame(s) == f0), "trajectory: > steps forward", str(frame(s)))
    p.el("anim-end").click()
    R.report(wait_for(lambda: frame(s) == n - 1), "trajectory: >| goes to the last frame", str(frame(s)))
    R.report(wait_for(lambda: p.el("frame").get_attribute("value") == str(n - 1)),
             "trajectory: the slider follows the frame", p.el("frame").get_attribute("value"))
    p.choose("anim-style", "Rock")
    R.report(wait_for(lambda: s.cmd("animate style") == "Rock"), "trajectory: style Rock",
             s.cmd("animate style"))
    p.js("const e = document.getElementById('anim-speed'); e.value = 0.5;"
         "e.dispatchEvent(new Event('change'));")
    R.report(wait_for(lambda: abs(float(s.cmd("animate speed")) - 0.5) < 1e-9),
             "trajectory: the speed slider sets animate speed", s.cmd("animate speed"))
    p.el("anim-play").click()
    seen = set()
    wait_for(lambda: seen.add(frame(s)) or len(seen) >= 3, timeout=10, step=0.05)
    R.report(len(seen) >= 3, "trajectory: play runs the frames", str(sorted(seen)))
    p.el("anim-pause").click()
    time.sleep(0.5)
    f1 = frame(s)
    time.sleep(1.0)
    R.report(frame(s) == f1, "trajectory: pause stops", "%d -> %d" % (f1, frame(s)))
    p.choose("anim-style", "Loop")


def corner(p):
    px = p.pixels()
    return px["corner"] if px else None


def check_display(s, p):
    p.choose("disp-projection", "Orthographic")
    R.report(wait_for(lambda: s.cmd("display get projection") == "Orthographic"),
             "display: projection", s.cmd("display get projection"))
    p.choose("disp-background", "white")
    R.report(wait_for(lambda: s.cmd("color Display Background") == "white"),
             "display: background colour", s.cmd("color Display Background"))
    R.report(wait_for(lambda: corner(p) == [255, 255, 255], timeout=15),
             "display: the image's background turns white", str(corner(p)))
    p.choose("disp-background", "black")
    for box, what in [("disp-depthcue", "depthcue"), ("disp-ao", "ambientocclusion"),
                      ("disp-shadows", "shadows")]:
        before = s.cmd("display get %s" % what)
        p.el(box).click()
        R.report(wait_for(lambda: s.cmd("display get %s" % what) != before),
                 "display: %s toggles" % what, "%s -> %s" % (before, s.cmd("display get %s" % what)))
    p.el("disp-ao").click()
    p.el("disp-shadows").click()
    p.choose("disp-axes", "Off")
    R.report(wait_for(lambda: s.cmd("axes location") == "Off"), "display: axes location",
             s.cmd("axes location"))
    p.choose("disp-mode", "raster only")
    R.report(wait_for(lambda: s.cmd("display live mode") == "raster"), "display: raster mode",
             s.cmd("display live mode"))
    s.cmd("rotate y by 10")
    time.sleep(2.0)
    px = p.pixels()
    R.report(px and px["passes"] == 0 and s.cmd("dict get [display live status] passes") == "0",
             "display: in raster mode no ray-traced pass follows", str(px))
    p.choose("disp-mode", "progressive ray tracing")
    R.report(wait_for(lambda: (p.pixels() or {}).get("passes", 0) >= 2, timeout=20),
             "display: progressive mode refines the image again", str(p.pixels()))
    check_drag(s, p)
    p.el("disp-reset").click()
    R.report(wait_for(lambda: is_identity(matrix(s, "rotate_matrix"))), "display: Reset view",
             str(matrix(s, "rotate_matrix")))


DRAG_JS = """
const done = arguments[arguments.length - 1];
const img = document.getElementById('view');
const r = img.getBoundingClientRect();
let x = r.x + r.width / 2, n = 0;
const widths = [];
const obs = new MutationObserver(() => widths.push(img.naturalWidth));
obs.observe(img, {attributes: true, attributeFilter: ['data-serial']});
img.dispatchEvent(new MouseEvent('mousedown', {clientX: x, clientY: r.y + 50, bubbles: true}));
const timer = setInterval(() => {
  x += 3;
  window.dispatchEvent(new MouseEvent('mousemove', {clientX: x, clientY: r.y + 50, bubbles: true}));
  if (++n === 60) {
    clearInterval(timer);
    window.dispatchEvent(new MouseEvent('mouseup', {bubbles: true}));
    setTimeout(() => { obs.disconnect(); done(widths); }, 300);
  }
}, 25);
"""


def check_drag(s, p):
    """While the page drags, coarse images (half the width, no passes); then the whole one."""
    width = int(s.cmd("display get size").split()[0])
    p.drv.set_script_timeout(30)
    widths = p.drv.execute_async_script(DRAG_JS)
    R.report(width // 2 in widths, "a drag shows coarse images (half the display width)",
             "display %d, images %s" % (width, widths))
    R.report(bool(wait_for(lambda: (lambda px: px and px["w"] == width and px["passes"] >= 1)(p.pixels()),
                           timeout=20)),
             "after the drag the whole image and its passes follow", str(p.pixels()))


def check_render(s, p, base, token):
    out = os.path.join(OUT, "live_page_render.png")
    if os.path.exists(out):
        os.remove(out)
    p.choose("render-method", "TachyonInternal")
    p.type_into("render-file", out, enter=False)
    p.el("render-button").click()
    R.report(wait_for(lambda: p.el("render-status").text.startswith("done"), timeout=60),
             "render: the page says when the file is written", p.el("render-status").text)
    R.report(os.path.exists(out), "render: render TachyonInternal wrote the file on the server")
    href = p.el("render-link").get_attribute("href")
    st, body = http(href) if href else (0, b"")
    size = [int(x) for x in s.cmd("display get size").split()]
    ok = st == 200 and body[:8] == b"\x89PNG\r\n\x1a\n"
    if ok:
        from PIL import Image
        ok = list(Image.open(io.BytesIO(body)).size) == size
    R.report(ok, "render: the download link gives the image (display size)", "%s %d bytes" % (st, len(body)))
    p.type_into("render-file", "/nonexistent-dir/x.png", enter=False)
    p.el("render-button").click()
    R.report(wait_for(lambda: "nonexistent" in p.el("render-status").text or
                      "cannot" in p.el("render-status").text, timeout=30),
             "render: a file that cannot be written shows the error", p.el("render-status").text)


def check_two_viewers(s, p1, p2):
    n0 = int(s.cmd("molinfo 0 get numreps"))
    wait_for(lambda: len(p2.reps()) == n0)
    p1.el("rep-add").click()
    R.report(wait_for(lambda: len(p2.reps()) == n0 + 1), "two viewers: a rep added in one appears in the other",
             str(p2.reps()))
    p2.choose("disp-projection", "Perspective")
    R.report(wait_for(lambda: p1.el("disp-projection").get_attribute("value") == "Perspective"),
             "two viewers: a display change in the other shows in the first")
    s.cmd("mol modselect %d 0 {resid 3 to 9}" % n0)
    R.report(wait_for(lambda: any(r[2] == "resid 3 to 9" for r in p1.reps()) and
                      any(r[2] == "resid 3 to 9" for r in p2.reps())),
             "two viewers: both follow a change typed at the terminal", "%s / %s" % (p1.reps(), p2.reps()))
    s.cmd("mol delrep %d 0" % n0)
    serial1 = p1.serial()
    p2.js("document.getElementById('view').dispatchEvent(new WheelEvent('wheel', "
          "{deltaY: -100, bubbles: true, cancelable: true}));")
    R.report(bool(changed(p1.serial, serial1)), "two viewers: a view change in one redraws the other")


def molecule_fraction(png, rect):
    """Fraction of the viewport's pixels that are not the black background."""
    from PIL import Image
    im = Image.open(io.BytesIO(png)).convert("RGB")
    x, y, w, h = [int(round(v)) for v in rect]
    im = im.crop((x, y, x + w, y + h))
    data = im.getdata()
    lit = sum(1 for r, g, b in data if r + g + b > 60)
    return lit / max(1, len(data))


def check_sizes(s, p):
    fracs = []
    sizes = []
    for w, h, dpr in [(1100, 800, 0), (640, 560, 0), (900, 600, 2)]:
        if dpr:         # a 2x screen: chromium's device metrics emulation
            p.drv.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                                  {"width": w, "height": h, "deviceScaleFactor": dpr, "mobile": False})
        else:
            p.drv.set_window_size(w, h)
        vp = p.js("const r = document.getElementById('viewport').getBoundingClientRect();"
                  "return [r.width, r.height, window.devicePixelRatio];")
        want = [round(vp[0] * vp[2]), round(vp[1] * vp[2])]
        ok = wait_for(lambda: [int(x) for x in s.cmd("display get size").split()] == want, timeout=10)
        R.report(bool(ok) and (not dpr or vp[2] == dpr),
                 "size %dx%d (pixel ratio %s): the display follows the viewport in device pixels"
                 % (w, h, vp[2]), "%s vs %s" % (s.cmd("display get size"), want))
        ok = wait_for(lambda: (lambda px: px and [px["w"], px["h"]] == want and px["passes"] >= 1)(p.pixels()),
                      timeout=20)
        rect = p.js("const r = document.getElementById('view').getBoundingClientRect();"
                    "return [r.x * devicePixelRatio, r.y * devicePixelRatio,"
                    " r.width * devicePixelRatio, r.height * devicePixelRatio];")
        png = p.drv.get_screenshot_as_png()
        path = os.path.join(OUT, "live_page_%dx%d.png" % (w, h))
        with open(path, "wb") as f:
            f.write(png)
        frac = molecule_fraction(png, rect)
        fracs.append(frac)
        sizes.append(want)
        css = p.js("const i = document.getElementById('view'); return [i.clientWidth, i.clientHeight];")
        R.report(abs(css[0] - want[0] / vp[2]) <= 1 and abs(css[1] - want[1] / vp[2]) <= 1,
                 "size %dx%d: the image is laid out at the viewport's CSS size" % (w, h),
                 "%s for an image of %s at ratio %s" % (css, want, vp[2]))
        R.report(bool(ok) and 0.01 < frac < 0.8,
                 "size %dx%d: the screenshot shows a molecule" % (w, h),
                 "lit fraction %.4f, image %s (%s)" % (frac, p.pixels(), path))
    R.report(len(set(map(tuple, sizes))) == 3, "the three sizes give three display sizes", str(sizes))
    p.drv.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})


def page_session():
    s = Session("opengl")
    drv1 = drv2 = None
    try:
        s.cmd("mol new %s/helix.psf" % DATA)
        s.cmd("mol addfile %s/helix.dcd waitfor all" % DATA)
        s.cmd("mol modstyle 0 0 NewCartoon")
        url = s.url()
        base, token = split(url)
        check_endpoints(s, base, token)
        drv1, why = browser()
        if drv1 is None:
            R.skip("browser", why)
            return
        drv1.set_window_size(1100, 800)
        p1 = Page(drv1, url)
        R.report(bool(wait_for(lambda: p1.pixels(), timeout=20)), "the page shows the image")
        R.report(bool(wait_for(lambda: p1.css("#mols tbody tr"), timeout=20)), "the page lists the molecules")
        check_console(s, p1)
        check_molecules(s, p1)
        check_reps(s, p1)
        check_trajectory(s, p1)
        check_display(s, p1)
        check_render(s, p1, base, token)
        drv2, why = browser()
        if drv2 is None:
            R.skip("two viewers", why)
        else:
            drv2.set_window_size(1100, 800)
            p2 = Page(drv2, url + "&fit=0")
            wait_for(lambda: p2.css("#mols tbody tr"), timeout=20)
            check_two_viewers(s, p1, p2)
            drv2.quit()
            drv2 = None
        check_sizes(s, p1)
        p1.console("display live off")
        R.report(wait_for(lambda: s.cmd("display live status") == "off"),
                 "display live off from the page's console stops the server",
                 s.cmd("display live status"))
        R.report(s.p.poll() is None and s.cmd("expr 3+3") == "6", "molscope lives on after that")
    finally:
        for d in (drv1, drv2):
            if d is not None:
                d.quit()
        code = s.quit()
        R.report(code == 0, "quit ends molscope", s.ended(code))


# ---------------------------------------------------------------- drag frames: level of detail

def live(s, key):
    return s.cmd("dict get [display live status] %s" % key)


def png_of(base, token):
    """The session's current image (PIL, RGB) from the page's own endpoint."""
    from PIL import Image
    st, body = http("%s/image.png?token=%s" % (base, token))
    return Image.open(io.BytesIO(body)).convert("RGB") if st == 200 else None


def lit_fraction(img):
    px = list(img.getdata())
    return sum(1 for p in px if sum(p) > 60) / float(len(px))


def differs_from_snapshot(s, img, name):
    """Pixels of img unlike `render snapshot` of the session now (-1: not the same size)."""
    from PIL import Image
    snap = os.path.join(OUT, "live_lod_%s.png" % name)
    s.cmd("render snapshot %s" % snap)
    ref = Image.open(snap).convert("RGB")
    if img is None or img.size != ref.size:
        return -1
    return sum(1 for a, b in zip(ref.getdata(), img.getdata()) if a != b)


def drag_samples(s, base, token, moves):
    """Turn the view as the page does while it drags (POST /view), and after each move the
    status and image of the drag's frame: [(coarse, triangles, image)]."""
    out = []
    for _ in range(moves):
        before = int(live(s, "images"))
        http("%s/view?token=%s" % (base, token), "ry=4")
        if wait_for(lambda: int(live(s, "images")) > before and live(s, "coarse") == "1", timeout=5):
            out.append((live(s, "coarse"), int(live(s, "triangles")), png_of(base, token)))
    return out


def lod_session():
    """A drag on a scene of more than 150 000 mesh triangles (1tii, NewCartoon at resolution 20)
    draws its coarse images from decimated meshes (display live status: coarse 1, at most
    150 000 triangles) that still show the molecule; the whole image after the drag draws
    every triangle and is, pixel for pixel, what `render snapshot` (never decimated) draws of
    the same view, as the image before the drag is."""
    s = Session("opengl")
    try:
        s.cmd("mol new %s/1tii.pdb" % DATA)
        s.cmd("mol modstyle 0 0 NewCartoon 0.3 20 4.1 0")
        s.cmd("display resize 480 360")
        base, token = split(s.url())
        s.cmd("display live mode raster")
        full = wait_for(lambda: live(s, "coarse") == "0" and int(live(s, "images")) > 0 and
                        live(s, "triangles"), timeout=60)
        R.report(full and int(full) > 150000, "lod: the whole scene has over 150 000 triangles",
                 str(full))
        time.sleep(0.5)
        first = png_of(base, token)
        differ = differs_from_snapshot(s, first, "before")
        R.report(differ == 0, "lod: before a drag the page's image is render snapshot's",
                 "%d pixels differ" % differ)
        samples = drag_samples(s, base, token, 8)
        coarse = [(t, im) for c, t, im in samples if c == "1" and im is not None and im.size == (240, 180)]
        R.report(coarse and all(t <= 150000 for t, _ in coarse) and min(t for t, _ in coarse) > 5000,
                 "lod: a drag's frames draw the decimated scene (150 000 triangles at most)",
                 str([t for t, _ in coarse]) + " of " + str(full))
        lit0 = lit_fraction(first)
        R.report(coarse and all(lit_fraction(im) > 0.6 * lit0 for _, im in coarse),
                 "lod: the drag's frames show the molecule (lit pixels as in the whole image)",
                 "%s vs %.3f" % ([round(lit_fraction(im), 3) for _, im in coarse], lit0))
        after = wait_for(lambda: live(s, "coarse") == "0" and live(s, "triangles") == full, timeout=20)
        R.report(bool(after), "lod: after the drag the whole image draws every triangle",
                 live(s, "triangles"))
        differ = differs_from_snapshot(s, png_of(base, token), "after")
        R.report(differ == 0, "lod: the whole image after a drag is the full-quality image "
                 "(render snapshot of that view, pixel for pixel)", "%d pixels differ" % differ)
    finally:
        code = s.quit()
        R.report(code == 0, "lod: quit ends molscope", s.ended(code))


def main():
    probe = __import__("subprocess").run([EXE, "-dispdev", "text"],
                                         input="catch {display live on 0} m; puts $m\n",
                                         capture_output=True, text=True, timeout=60)
    if "without libmicrohttpd" in probe.stdout + probe.stderr:
        R.skip("all", "molscope was built without libmicrohttpd")
        return 0
    page_session()
    lod_session()
    return 1 if R.failures else 0


if __name__ == "__main__":
    sys.exit(main())
