"""test_live.py: the live view (display live, doc/live.md) from the outside. molscope runs in
the background, fed commands on its standard input and answering on its standard output;
the HTTP checks use urllib, the page is opened by a real browser (Debian's chromium driven
by chromedriver through python3-selenium; those checks are skipped when either is missing).

  - a request without the token, or with a wrong one, gets 403, whatever the path, at
    once, and its connection is closed
  - connections without the token (200 idle, partial request lines, garbage) held open do
    not lock the page out, and are closed within a few seconds; so are garbage requests;
    a connection that gave the token keeps a long poll and keep-alive past that time
  - a view change carrying Tcl code, an unknown field or an out-of-range number is refused
    with 400 and changes nothing (the rotate matrix stays the identity, molscope lives on)
  - in a GL session the page shows the image (naturalWidth is the display width, most
    corner pixels are the background, some pixels are not), a drag rotates about the
    screen y axis (molinfo's rotate matrix becomes a y rotation), the wheel scales,
    shift-drag translates; ray-traced passes follow the raster image
  - in a -dispdev text session the images are ray traced only (no pass-0 raster image) and
    the pass count grows while nothing moves
  - `quit` (and `display live off`) close the server: the port refuses connections
  - under mpirun, rank 0 serves and the other ranks say they do not
"""
import collections
from http.client import HTTPConnection
import json
import os
import queue
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mstest import Reporter  # noqa: E402

R = Reporter("live")
EXE = os.environ.get("MOLSCOPE", "molscope")
DATA = os.environ.get("MS_TEST_DATA", os.path.join(os.path.dirname(__file__), "..", "data"))
OUT = os.environ.get("MS_TEST_OUT", tempfile.gettempdir())
os.makedirs(OUT, exist_ok=True)
os.environ["HOME"] = tempfile.mkdtemp(prefix="home.", dir=OUT)   # no user's .molscoperc


class Session:
    """A molscope process with a command channel: cmd() sends one Tcl command and returns
    what it printed between two markers."""

    def __init__(self, dispdev):
        self.p = subprocess.Popen([EXE, "-dispdev", dispdev], stdin=subprocess.PIPE,
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  text=True, bufsize=1)
        self.lines = queue.Queue()
        self.recent = collections.deque(maxlen=40)     # the last lines, for a failed exit
        threading.Thread(target=self._read, daemon=True).start()
        self.n = 0

    def _read(self):
        for line in self.p.stdout:
            self.recent.append(line.rstrip("\n"))
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)

    def send(self, text):
        self.p.stdin.write(text + "\n")
        self.p.stdin.flush()

    def cmd(self, tcl, timeout=20):
        self.n += 1
        tag = "@@%d@@" % self.n
        self.send('puts "%s[%s]%s"' % (tag, tcl, tag))
        end = time.time() + timeout
        while time.time() < end:
            try:
                line = self.lines.get(timeout=max(0.01, end - time.time()))
            except queue.Empty:
                break
            if line is None:
                raise RuntimeError("molscope ended while running: " + tcl)
            if line.startswith(tag) and line.endswith(tag):
                return line[len(tag):-len(tag)]
        raise RuntimeError("no answer to: " + tcl)

    def url(self):
        out = self.cmd("display live on 0")
        if not out.startswith("http://"):
            raise RuntimeError("display live on: " + out)
        return out

    def ended(self, code):
        """An exit status for a report: on a failure, with what molscope printed last (its
        standard error too), since a crash says why only there."""
        if code == 0:
            return "0"
        return "%s; its last output: %s" % (code, " | ".join(self.recent))

    def quit(self):
        try:
            self.send("quit")
            self.p.stdin.close()
        except (BrokenPipeError, ValueError):
            pass
        try:
            return self.p.wait(timeout=15)
        except subprocess.TimeoutExpired:
            self.p.kill()
            return None


def split(url):
    base, token = url.split("/?token=")
    return base, token


def http(url, data=None, ctype=None):
    """(status, body) of a request; urllib's errors become their status."""
    req = urllib.request.Request(url, data=data.encode() if data is not None else None)
    if ctype:
        req.add_header("Content-Type", ctype)
    try:
        with urllib.request.urlopen(req, timeout=10) as r:
            return r.status, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.read()


def state(base, token):
    return json.loads(http("%s/state?token=%s" % (base, token))[1])


def matrix(s, which):
    return [[float(x) for x in row.split()] for row in
            s.cmd("molinfo top get %s" % which).strip("{}").split("} {")]


def is_identity(m, tol=1e-6):
    return all(abs(m[i][j] - (1.0 if i == j else 0.0)) < tol for i in range(4) for j in range(4))


def refused(port):
    s = socket.socket()
    s.settimeout(2)
    try:
        s.connect(("127.0.0.1", port))
        return False
    except OSError:
        return True
    finally:
        s.close()


def wait_for(pred, timeout=10.0, step=0.05):
    end = time.time() + timeout
    while time.time() < end:
        v = pred()
        if v:
            return v
        time.sleep(step)
    return pred()


# ---------------------------------------------------------------- HTTP, no browser

def check_refusals(s, base, token):
    for path in ["/", "/state", "/image.png", "/view", "/nothing"]:
        st, _ = http(base + path)
        R.report(st == 403, "no token: %s gets 403" % path, "status %d" % st)
    st, _ = http(base + "/state?token=" + "0" * len(token))
    R.report(st == 403, "a wrong token gets 403", "status %d" % st)
    st, _ = http(base + "/state?token=" + token[:-1])
    R.report(st == 403, "a truncated token gets 403", "status %d" % st)
    st, _ = http(base + "/view", "ry=30")
    R.report(st == 403, "a view change without the token gets 403", "status %d" % st)

    before = matrix(s, "rotate_matrix")
    view = "%s/view?token=%s" % (base, token)
    for body, what in [("rx=[quit]", "Tcl code in a value"),
                       ("ry=0;puts+hi", "a command after a number"),
                       ("cmd=quit", "an unknown field"),
                       ("ry=1e9", "an out-of-range number"),
                       ("ry=nan", "nan"),
                       ("ry=30&rx=%5Bexit%5D", "a good field with a bad one")]:
        st, _ = http(view, body)
        R.report(st == 400, "refused: %s (400)" % what, "status %d" % st)
    st, _ = http(view, '{"ry": 30}', "application/json")
    R.report(st == 400, "refused: a JSON body (400)", "status %d" % st)
    after = matrix(s, "rotate_matrix")
    R.report(after == before and is_identity(after), "refused changes change nothing",
             "%s -> %s" % (before, after))
    R.report(s.p.poll() is None and s.cmd("expr 1+1") == "2", "molscope still answers")


# ---------------------------------------------------------------- connections without the token

def connect(port):
    return socket.create_connection(("127.0.0.1", port), timeout=10)


def abort(c):
    """Close c with a reset (SO_LINGER 0), so that a flood of connections leaves no local
    port in TIME_WAIT for the other tests running beside this one."""
    c.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
    c.close()


def until_closed(c, limit):
    """What the server sends on c until it closes it, and after how long (None: still open
    after limit seconds)."""
    t0, data = time.time(), b""
    c.settimeout(0.2)
    while time.time() - t0 < limit:
        try:
            chunk = c.recv(4096)
        except socket.timeout:
            continue
        except OSError:
            return data, time.time() - t0
        if not chunk:
            return data, time.time() - t0
        data += chunk
    return data, None


def timed(fn):
    t0 = time.time()
    try:
        v = fn()
    except OSError as e:          # refused, reset, timed out: no status
        v = (None, str(e))
    return v, time.time() - t0


def check_flood(base, token):
    """Any local user can connect without the token: 200 idle connections, 20 that stop in
    the middle of a request line and 20 that send garbage, all held open, must not lock the
    page out; requests without the token are refused at once and closed; what sends no
    complete request is closed within a few seconds."""
    port = int(base.rsplit(":", 1)[1])
    held = []
    try:
        t0 = time.time()
        for _ in range(200):
            held.append(connect(port))
        opened = time.time() - t0
        for i in range(20):
            c = connect(port)
            c.sendall(b"GET /image.png?tok")
            held.append(c)
        for i in range(20):
            c = connect(port)
            c.sendall(b"\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03" + bytes(range(64)))
            held.append(c)
        print("INFO: live: 240 connections without the token opened in %.3f s "
              "(200 idle in %.3f s)" % (time.time() - t0, opened))
        times, codes = [], []
        for _ in range(10):
            for path in ["/", "/image.png"]:
                (st, _), dt = timed(lambda: http("%s%s?token=%s" % (base, path, token)))
                codes.append(st)
                times.append(dt)
        times.sort()
        print("INFO: live: with them held, 20 requests with the token: median %.1f ms, "
              "max %.1f ms" % (1000 * times[len(times) // 2], 1000 * times[-1]))
        R.report(codes == [200] * 20 and times[-1] < 2.0,
                 "with 240 connections without the token held, the page and the image are "
                 "served", "statuses %s, slowest %.2f s" % (sorted(set(map(str, codes))), times[-1]))

        # A client that keeps opening connections as fast as it can meanwhile.
        stop, opened_n = [], [0]

        def flood():
            mine = []
            while not stop and opened_n[0] < 20000:
                try:
                    mine.append(connect(port))
                    opened_n[0] += 1
                except OSError:
                    pass
                if len(mine) > 300:
                    abort(mine.pop(0))
            for c in mine:
                abort(c)
        f = threading.Thread(target=flood, daemon=True)
        f.start()
        time.sleep(0.3)
        times, codes, why = [], [], []
        for _ in range(10):
            (st, body), dt = timed(lambda: http("%s/image.png?token=%s" % (base, token)))
            codes.append(st)
            times.append(dt)
            if st is None:
                why.append(body)
        stop.append(1)
        f.join(20)
        times.sort()
        print("INFO: live: while another client opened %d connections, 10 image requests with "
              "the token: median %.1f ms, max %.1f ms" %
              (opened_n[0], 1000 * times[len(times) // 2], 1000 * times[-1]))
        R.report(codes == [200] * 10 and times[-1] < 2.0,
                 "while a client without the token keeps opening connections, the image is "
                 "served", "statuses %s, slowest %.2f s %s" % (sorted(set(map(str, codes))), times[-1],
                                                               why[:1]))

        def refused_at_once():
            c = connect(port)
            try:
                c.sendall(b"GET /image.png HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
                return until_closed(c, 10)
            finally:
                c.close()
        (data, closed), dt = timed(refused_at_once)
        R.report(isinstance(data, bytes) and data.startswith(b"HTTP/1.1 403") and
                 closed is not None and dt < 1.0,
                 "a full request without the token: 403 at once, then closed",
                 "%r closed after %s (%.2f s)" % (data[:40], closed, dt))

        # Incomplete or garbage requests: answered or closed within a few seconds.
        results = {}

        def probe(name, payload):
            c = connect(port)
            try:
                c.sendall(payload)
                results[name] = until_closed(c, 15)
            finally:
                c.close()
        probes = {"garbage without an end of line": b"\x00\xffgarbage" * 8,
                  "garbage lines": b"NOT HTTP AT ALL\r\n\r\n",
                  "a request line and no headers' end": b"GET / HTTP/1.1\r\nHost: x\r\n",
                  "nothing at all": b""}
        threads = [threading.Thread(target=probe, args=kv, daemon=True) for kv in probes.items()]
        for t in threads:
            t.start()
        for t in threads:
            t.join(20)
        print("INFO: live: closed after (s): " + ", ".join(
            "%s %s" % (n, None if results.get(n, (0, None))[1] is None else
                       "%.2f" % results[n][1]) for n in probes))
        for name in probes:
            data, closed = results.get(name, (b"", None))
            R.report(closed is not None and closed < 7.0,
                     "%s: answered or closed within a few seconds" % name,
                     "%r, closed after %s" % (data[:40], closed))
        gone = 0
        for c in held:
            c.settimeout(0.01)
            try:
                gone += c.recv(4096) == b""
            except (socket.timeout, BlockingIOError):
                pass
            except OSError:
                gone += 1
        R.report(gone == len(held), "the server has closed every connection without the token",
                 "%d of %d closed" % (gone, len(held)))
        st, _ = http("%s/state?token=%s" % (base, token))
        R.report(st == 200, "and still serves the page's requests", str(st))
    finally:
        for c in held:
            c.close()


def check_keepalive(s, base, token):
    """A connection that gave the token keeps the longer time-out: a long poll waits past the
    few seconds allowed to requests without it, and an idle keep-alive connection with the
    token is still usable after them."""
    st0 = wait_for(lambda: settled(base, token), timeout=30, step=0.1)
    if st0 is None:
        R.report(False, "the passes finish before the keep-alive checks", str(state(base, token)))
        return
    host, port = base[len("http://"):].rsplit(":", 1)
    conn = HTTPConnection(host, int(port), timeout=10)
    try:
        conn.request("GET", "/state?token=" + token)
        r = conn.getresponse()
        r.read()
        first = r.status
        t, res = long_poll(base, token, st0["serial"])
        time.sleep(7)
        R.report(t.is_alive(), "a long poll with the token still waits after 7 s", str(res))
        conn.request("GET", "/state?token=" + token)
        r = conn.getresponse()
        r.read()
        R.report(first == 200 and r.status == 200,
                 "a keep-alive connection with the token is still served after 7 s idle",
                 "%s %s" % (first, r.status))
        s.cmd("rotate x by 5")
        t.join(10)
        R.report(res.get("status") == 200 and res["state"]["serial"] > st0["serial"],
                 "and the long poll is answered by the next change", str(res))
    except OSError as e:
        R.report(False, "a keep-alive connection with the token is still served after 7 s idle",
                 str(e))
    finally:
        conn.close()


# ---------------------------------------------------------------- the browser

def browser():
    """A headless chromium driven through chromedriver, or (None, why)."""
    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    driver = shutil.which("chromedriver") or "/usr/bin/chromedriver"
    if not os.path.exists(chromium) or not os.path.exists(driver):
        return None, "chromium or chromedriver is not installed (Debian: chromium chromium-driver)"
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
        from selenium.webdriver.common import utils
    except ImportError:
        return None, "python3-selenium is not installed"

    class LoopbackService(Service):
        """chromedriver reached at 127.0.0.1, not "localhost": a machine with no /etc/hosts
        (a fresh minbase Debian) cannot resolve that name, and selenium would give up."""
        @property
        def service_url(self):
            return "http://127.0.0.1:%d" % self.port

        def is_connectable(self):
            return utils.is_connectable(self.port, "127.0.0.1")

    o = webdriver.ChromeOptions()
    o.binary_location = chromium
    profile = tempfile.mkdtemp(prefix="chrome.", dir=OUT)
    for a in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic",
              "--disable-background-networking", "--disable-component-update",
              "--disable-sync", "--no-first-run", "--disable-dev-shm-usage",
              # chromedriver talks to chromium through a pipe, not a "localhost" port
              "--remote-debugging-pipe",
              "--user-data-dir=" + profile, "--window-size=700,700"]:
        o.add_argument(a)
    try:
        return webdriver.Chrome(service=LoopbackService(driver), options=o), None
    except Exception as e:  # noqa: BLE001 - any start failure is a reason to skip
        return None, "chromium did not start: %s" % str(e).splitlines()[0]


PIXELS_JS = """
const img = document.getElementById('view');
if (!img.complete || img.naturalWidth === 0) return null;
const c = document.createElement('canvas');
c.width = img.naturalWidth; c.height = img.naturalHeight;
const g = c.getContext('2d'); g.drawImage(img, 0, 0);
const d = g.getImageData(0, 0, c.width, c.height).data;
let lit = 0;
for (let i = 0; i < d.length; i += 4) if (d[i] + d[i+1] + d[i+2] > 60) lit++;
const corner = Array.from(g.getImageData(2, 2, 1, 1).data.slice(0, 3));
return {w: img.naturalWidth, h: img.naturalHeight, lit: lit, corner: corner,
        serial: Number(img.dataset.serial || 0), passes: Number(img.dataset.passes || 0)};
"""


def check_browser(s, url):
    drv, why = browser()
    if drv is None:
        R.skip("browser", why)
        return
    try:
        from selenium.webdriver.common.action_chains import ActionChains
        from selenium.webdriver.common.by import By
        from selenium.webdriver.common.keys import Keys
        drv.set_page_load_timeout(20)
        drv.get(url + "&fit=0")     # the display keeps its size (320 x 240)
        px = wait_for(lambda: drv.execute_script(PIXELS_JS), timeout=20)
        R.report(px is not None and px["w"] == 320 and px["h"] == 240,
                 "the image appears at the display size", str(px))
        if px is None:
            return
        R.report(px["corner"] == [0, 0, 0], "its corner is the black background", str(px["corner"]))
        R.report(px["lit"] > 500, "the molecule is drawn (lit pixels)", str(px["lit"]))
        # passes follow the raster image while nothing moves
        traced = wait_for(lambda: drv.execute_script(PIXELS_JS)["passes"] >= 2, timeout=20)
        R.report(bool(traced), "ray-traced passes replace the image in the page",
                 str(drv.execute_script(PIXELS_JS)))

        img = drv.find_element(By.ID, "view")
        ActionChains(drv).move_to_element(img).click_and_hold() \
            .move_by_offset(40, 0).move_by_offset(40, 0).release().perform()
        m = wait_for(lambda: (lambda r: None if is_identity(r) else r)(matrix(s, "rotate_matrix")))
        ok = m is not None and abs(m[1][1] - 1) < 1e-6 and abs(m[0][2]) > 0.1 and \
            abs(m[0][2] - (-m[2][0])) < 1e-6 and abs(m[0][0] - m[2][2]) < 1e-6
        R.report(ok, "a drag rotates about the screen y axis (molinfo rotate_matrix)", str(m))
        sc0 = matrix(s, "scale_matrix")[0][0]
        drv.execute_script("document.getElementById('view').dispatchEvent(new WheelEvent("
                           "'wheel', {deltaY: -100, bubbles: true, cancelable: true}));")
        sc1 = wait_for(lambda: (lambda v: v if abs(v - sc0) > 1e-9 else None)(
            matrix(s, "scale_matrix")[0][0]))
        R.report(sc1 is not None and abs(sc1 / sc0 - 1.1) < 1e-3,
                 "the wheel scales by 1.1 (molinfo scale_matrix)", "%s -> %s" % (sc0, sc1))
        g0 = matrix(s, "global_matrix")
        serial = drv.execute_script(PIXELS_JS)["serial"]
        ActionChains(drv).key_down(Keys.SHIFT).move_to_element(img).click_and_hold() \
            .move_by_offset(30, 0).release().key_up(Keys.SHIFT).perform()
        g1 = wait_for(lambda: (lambda g: g if g != g0 else None)(matrix(s, "global_matrix")))
        R.report(g1 is not None and g1[0][3] > g0[0][3] and abs(g1[1][3] - g0[1][3]) < 1e-6,
                 "shift-drag translates along screen x (molinfo global_matrix)",
                 "%s -> %s" % (g0, g1))
        later = wait_for(lambda: drv.execute_script(PIXELS_JS)["serial"] > serial, timeout=10)
        R.report(bool(later), "the page shows new images after the view changed",
                 "serial %d before the change" % serial)
    finally:
        drv.quit()


# ---------------------------------------------------------------- long polls

def long_poll(base, token, since):
    """Start GET /state?since= in a thread; returns (thread, result dict)."""
    res = {}

    def run():
        t0 = time.time()
        try:
            st, body = http("%s/state?token=%s&since=%d" % (base, token, since))
            res["status"], res["state"] = st, json.loads(body) if st == 200 else None
        except OSError as e:
            res["status"], res["error"] = None, str(e)
        res["seconds"] = time.time() - t0
    t = threading.Thread(target=run, daemon=True)
    t.start()
    return t, res


def settled(base, token):
    """The state once the passes are done and the serial holds still."""
    a = state(base, token)
    time.sleep(0.3)
    b = state(base, token)
    return b if a["serial"] == b["serial"] and b["passes"] == b["maxpasses"] else None


def check_long_poll(s, base, token):
    st0 = wait_for(lambda: settled(base, token), timeout=30, step=0.1)
    if st0 is None:
        R.report(False, "the passes finish", str(state(base, token)))
        return
    t, res = long_poll(base, token, st0["serial"])
    time.sleep(0.6)
    R.report(t.is_alive(), "a long poll waits while nothing changes", str(res))
    s.cmd("rotate x by 5")
    t.join(10)
    ok = res.get("status") == 200 and res["state"]["serial"] > st0["serial"]
    R.report(ok, "a change answers it with the new serial", str(res))
    t, res = long_poll(base, token, st0["serial"] - 1)
    t.join(5)
    R.report(res.get("status") == 200 and res["seconds"] < 2,
             "a long poll for an old serial is answered at once", str(res))


# ---------------------------------------------------------------- sessions

def gl_session():
    s = Session("opengl")
    try:
        s.cmd("mol new %s/1a8o.pdb" % DATA)
        s.cmd("display resize 320 240")
        s.cmd("axes location off")
        url = s.url()
        base, token = split(url)
        port = int(base.rsplit(":", 1)[1])
        R.report(base.startswith("http://127.0.0.1:") and len(token) == 32,
                 "the URL is on 127.0.0.1 with a 128-bit token", url)
        st = s.cmd("display live status")
        R.report(url in st, "display live status gives the URL", st)
        err = s.cmd("catch {display live on 0} m; set m")
        R.report("already on" in err, "a second display live on is refused", err)
        first = wait_for(lambda: state(base, token)["serial"] > 0, timeout=20)
        R.report(bool(first), "the first image is made")
        check_refusals(s, base, token)
        check_browser(s, url)
        check_long_poll(s, base, token)
        check_keepalive(s, base, token)
        st1 = wait_for(lambda: settled(base, token), timeout=30, step=0.1)
        t, res = long_poll(base, token, st1["serial"] if st1 else 0)
        time.sleep(0.3)
        code = s.quit()
        R.report(code == 0, "quit ends molscope", s.ended(code))
        t.join(5)
        R.report(not t.is_alive(), "quit ends a waiting long poll", str(res))
        R.report(refused(port), "after quit the port refuses connections")
    finally:
        if s.p.poll() is None:
            s.p.kill()


def text_session():
    s = Session("text")
    try:
        s.cmd("mol new %s/1a8o.pdb" % DATA)
        s.cmd("display resize 160 120")
        s.cmd("render aasamples TachyonInternal 65535")      # passes go on through the test
        base, token = split(s.url())
        port = int(base.rsplit(":", 1)[1])
        first = wait_for(lambda: (lambda st: st if st["serial"] > 0 else None)(state(base, token)),
                         timeout=20)
        R.report(first is not None and first["passes"] >= 1,
                 "text session: the first image is ray traced (no raster)", str(first))
        a = state(base, token)
        time.sleep(0.5)
        b = state(base, token)
        R.report(b["passes"] > a["passes"] and b["serial"] > a["serial"],
                 "text session: the pass count grows while nothing moves", "%s -> %s" % (a, b))
        st, png = http("%s/image.png?token=%s" % (base, token))
        R.report(st == 200 and png[:8] == b"\x89PNG\r\n\x1a\n", "the image is a PNG", str(st))
        check_flood(base, token)
        s.cmd("set sel [atomselect top all]")
        for cmd in ["rotate y by 10", "$sel moveby {0.5 0 0}", "mol modstyle 0 top VDW",
                    "color Display Background white", "animate goto 0",
                    "display projection Orthographic"]:
            time.sleep(0.3)
            b = state(base, token)
            s.cmd(cmd)
            c = wait_for(lambda: (lambda st: st if st["passes"] < b["passes"] else None)(
                state(base, token)), timeout=10)
            R.report(c is not None, "'%s' restarts the passes" % cmd, "%s -> %s" % (b, c))
        for cmd in ["molinfo top get rotate_matrix", "display get projection", "$sel get x",
                    "measure center $sel", "display live status"]:
            a = state(base, token)
            s.cmd(cmd)
            time.sleep(0.2)
            b = state(base, token)
            R.report(b["passes"] > a["passes"], "'%s' does not restart them" % cmd,
                     "%s -> %s" % (a, b))
        s.cmd("display live off")
        R.report(refused(port), "display live off closes the port")
        R.report(s.cmd("display live status") == "off", "display live status is off")
        code = s.quit()
        R.report(code == 0, "quit ends molscope", s.ended(code))
    finally:
        if s.p.poll() is None:
            s.p.kill()


MPI_SCRIPT = """
mol new %s/1a8o.pdb
display resize 64 48
set r [display live on 0]
puts "rank [parallel noderank]: $r"
after 4000 {set go 1}
vwait go
set st [display live status]
puts "rank [parallel noderank]: [expr {$st eq "off" ? "off" : "images [dict get $st images]"}]"
quit
"""


def mpi_session():
    """Under mpirun -np 2: rank 0 serves while the ranks wait in the event loop, rank 1
    says it does not."""
    if not shutil.which("mpirun"):
        R.skip("mpi", "no mpirun")
        return
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    probe = subprocess.run(["timeout", "60", "mpirun", "-np", "2", EXE, "-dispdev", "text"],
                           input="puts [parallel nodecount]\n", capture_output=True, text=True,
                           env=env)
    if probe.stdout.replace("\r", "").split("\n").count("2") != 2:
        R.skip("mpi", "molscope is built without MPI or mpirun does not start it")
        return
    p = subprocess.Popen(["timeout", "60", "mpirun", "-np", "2", EXE, "-dispdev", "text"],
                         stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True, env=env)
    p.stdin.write(MPI_SCRIPT % DATA)
    p.stdin.close()
    lines, url = [], None
    for line in p.stdout:
        line = line.replace("\r", "").rstrip("\n")
        lines.append(line)
        if line.startswith("rank 0: http://"):
            url = line.split(": ", 1)[1]
            base, token = split(url)
            got = wait_for(lambda: state(base, token)["serial"] > 0, timeout=3.5)
            R.report(bool(got), "mpi: rank 0 serves images while the ranks wait")
            R.report(http(base + "/state")[0] == 403, "mpi: and refuses a request without the token")
    p.wait(timeout=60)
    R.report(url is not None, "mpi: rank 0 prints the URL", " | ".join(lines[-6:]))
    R.report("rank 1: display live: served by rank 0 only" in lines, "mpi: rank 1 does not serve",
             " | ".join(lines[-6:]))
    R.report("rank 1: off" in lines and any(l.startswith("rank 0: images ") for l in lines),
             "mpi: status on rank 0 only", " | ".join(lines[-6:]))


def main():
    probe = subprocess.run([EXE, "-dispdev", "text"], input="catch {display live on 0} m; puts $m\n",
                           capture_output=True, text=True, timeout=60)
    if "without libmicrohttpd" in probe.stdout + probe.stderr:
        R.skip("all", "molscope was built without libmicrohttpd")
        return 0
    if "without Embree" in subprocess.run(
            [EXE, "-dispdev", "text"], input="render TachyonInternal /nonexistent/x.png\n",
            capture_output=True, text=True, timeout=60).stderr:
        R.skip("all", "molscope was built without Embree")
        return 0
    gl_session()
    text_session()
    mpi_session()
    return 1 if R.failures else 0


if __name__ == "__main__":
    sys.exit(main())
