#!/usr/bin/env python3
"""`rgraph serve` driven as a tool and as a person would: its JSON API (toggle a pass, set a
parameter, fetch intermediates, bad requests refused with 400 and nothing changed, a broken script
reported with file:line while the last good plan keeps rendering, then fixed), what a hostile or
careless client sends (a resource that does not exist, a switch that would break the graph, a body
too large, a number out of range, a wrong method), the token, Host, Origin and Content-Type checks,
the page in headless Chromium opened with its token (a pass switched off through its checkbox
changes the graph and the image), and an exit within two seconds on SIGTERM. Every request goes to
127.0.0.1 on the port the server printed; loops are bounded. (tools/soak.py is the load test.)

usage: serve_test.py RGRAPH SOURCE_ROOT TMP_DIR
"""
import json
import re
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.parse
import urllib.request

rgraph, root, tmp_root = sys.argv[1], sys.argv[2], sys.argv[3]
checks = {"passed": 0, "failed": 0}


def check(name, ok, detail=""):
    checks["passed" if ok else "failed"] += 1
    print(("ok   " if ok else "FAIL ") + name + ("" if ok else ": " + str(detail)), flush=True)


token = None


def request(url, body=None, headers=None, method=None, auth=True):
    data = None if body is None else (body if isinstance(body, bytes) else json.dumps(body).encode())
    h = {}
    if auth and token:
        h["Authorization"] = "Bearer " + token
    if data is not None:
        h["Content-Type"] = "application/json"
    h.update(headers or {})
    req = urllib.request.Request(url, data=data, headers=h, method=method or ("POST" if data is not None else "GET"))
    try:
        with urllib.request.urlopen(req, timeout=60) as r:
            return r.status, r.headers.get("Content-Type", ""), r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.headers.get("Content-Type", ""), e.read()


def state(base):
    return json.loads(request(base + "/api/state")[2] or b"{}")


def wait_for(base, predicate, seconds=120):
    deadline = time.time() + seconds
    while time.time() < deadline:
        s = state(base)
        if s and predicate(s):
            return s
        time.sleep(0.3)
    return state(base)


tmp = tempfile.mkdtemp(prefix="serve_", dir=tmp_root)
pipeline = os.path.join(tmp, "pipeline.lua")
good = 'require "pipelines.deferred"  -- the default pipeline, served from a folder of its own\n'
with open(pipeline, "w") as f:
    f.write(good)
env = dict(os.environ, RG_VALIDATION="1")
server = subprocess.Popen([rgraph, "serve", "--pipeline", pipeline, "--port", "0", "--size", "160x90", "--interval", "20"],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
base = None
deadline = time.time() + 180
while time.time() < deadline and base is None:
    line = server.stdout.readline()
    if not line:
        break
    m = re.match(r"rgraph serve: (http://127\.0\.0\.1:\d+)/\?token=([0-9a-f]{32,})$", line.strip())
    if m:
        base, token = m.group(1), m.group(2)
check("serve prints its address with a token", base is not None and token is not None, base)
if base is None:
    server.kill()
    sys.exit(1)
# Its further output goes to a file, so the pipe never fills.
log_path = os.path.join(tmp, "serve.log")
log = open(log_path, "w")
import threading
threading.Thread(target=lambda: shutil.copyfileobj(server.stdout, log), daemon=True).start()

s = wait_for(base, lambda s: s.get("frame", 0) >= 2)
check("renders continuously", s.get("frame", 0) >= 2, s.get("frame"))
check("state lists passes with GPU and CPU times", any(p["name"] == "gbuffer" and p["gpuMs"] is not None and p["cpuMs"] is not None for p in s["passes"]),
      s.get("passes", [])[:3])
params = {p["name"]: p for p in s["params"]}
check("state lists typed parameters with ranges", params.get("ec", {}).get("type") == "number" and params["ec"].get("min") == -16, params.get("ec"))
code, ctype, body = request(base + "/")
check("the page", code == 200 and b"/api/state" in body and "text/html" in ctype, code)
code, _, body = request(base + "/api/graph")
plan = json.loads(body)
check("graph as rgraph graph --format json", code == 200 and any(p["name"] == "gbuffer" for p in plan["passes"]) and "culled" in plan, code)

# A pass switched off: culled from the plan, rebuilt incrementally.
code, _, body = request(base + "/api/pass", {"name": "sky", "enabled": False})
check("toggle a pass", code == 200, body)
s = wait_for(base, lambda s: any(p["name"] == "sky" and not p["enabled"] for p in s["passes"]))
check("the pass is off in the state", any(p["name"] == "sky" and not p["enabled"] and not p["kept"] for p in s["passes"]),
      [p for p in s["passes"] if p["name"] == "sky"])
check("rebuilt and reused counted", s["reused"] > 0, (s["rebuilt"], s["reused"]))
request(base + "/api/pass", {"name": "sky", "enabled": True})

# A parameter: applied next frame.
code, _, body = request(base + "/api/param", {"name": "ec", "value": 1.5})
check("set a parameter", code == 200, body)
s = wait_for(base, lambda s: any(p["name"] == "ec" and p["value"] == 1.5 for p in s["params"]))
check("the parameter holds", any(p["name"] == "ec" and p["value"] == 1.5 for p in s["params"]))

# Bad requests: 400 with the reason; nothing changes.
for name, url, body, expect in [
    ("unknown pass", "/api/pass", {"name": "gbufer", "enabled": False}, "did you mean 'gbuffer'"),
    ("unknown parameter", "/api/param", {"name": "ecc", "value": 1}, "did you mean 'ec'"),
    ("wrong type", "/api/param", {"name": "ec", "value": "bright"}, "ec"),
    ("out of range", "/api/param", {"name": "ec", "value": 100}, "[-16, 16]"),
    ("not JSON", "/api/param", b"{name", "expected"),
    ("enabled not a boolean", "/api/pass", {"name": "taa", "enabled": "no"}, "expected"),
]:
    code, _, reply = request(base + url, body)
    check("400 for " + name, code == 400 and expect in json.loads(reply).get("error", ""), (code, reply))
s = state(base)
check("bad requests changed nothing", any(p["name"] == "ec" and p["value"] == 1.5 for p in s["params"]) and
      all(p["enabled"] for p in s["passes"] if p["name"] in ("gbuffer", "taa")))

# Intermediates: an HDR target, a G-buffer channel decoded by its layout, an EXR download.
for resource, fmt, magic in [("hdr", "png", b"\x89PNG"), ("GB1", "png", b"\x89PNG"), ("gbuffer.smoothness", "png", b"\x89PNG"),
                             ("hdr", "exr", b"\x76\x2f\x31\x01")]:
    code, _, body = request(base + "/api/image?resource=%s&ev=1&format=%s" % (resource, fmt))
    check("image %s as %s" % (resource, fmt), code == 200 and body[:4] == magic, (code, body[:80]))
for query, expect in [("resource=nothing", "no texture"), ("resource=hdr&ev=x", "ev"), ("resource=hdr&format=jpg", "format")]:
    code, _, body = request(base + "/api/image?" + query)
    check("400 for image " + query, code == 400 and expect in json.loads(body).get("error", ""), (code, body))

# A resource the pipeline does not have: 400, and the server goes on rendering (it used to crash
# on the next frame: the failed reload left the executor on a scene it had freed).
for name in ["nosuch.thing", "../../etc/passwd"]:
    frames = state(base)["frame"]
    code, _, body = request(base + "/api/image?resource=" + urllib.parse.quote(name))
    reply = json.loads(body).get("error", "")
    check("400 for image " + name, code == 400 and name in reply and "--capture" not in reply, (code, body[:200]))
    s = wait_for(base, lambda s: s["frame"] > frames + 3, 60)
    check("renders on after the image of " + name, server.poll() is None and s["frame"] > frames + 3, (server.poll(), s.get("frame")))
code, _, body = request(base + "/api/image?resource=GB1&format=png")
check("the next image is served", code == 200 and body[:4] == b"\x89PNG", (code, body[:80]))

# A switch that would leave a kept pass without its input: 400 with the compiler's reason, and
# nothing changes (the plan keeps rendering, a parameter set next is applied).
code, _, body = request(base + "/api/pass", {"name": "tonemap", "enabled": False})
check("400 for a switch that breaks the graph", code == 400 and "its writers 'tonemap' and 'fxaa' are disabled" in json.loads(body).get("error", ""), (code, body[:300]))
s = state(base)
check("the refused switch changed nothing", any(p["name"] == "tonemap" and p["enabled"] and p["kept"] for p in s["passes"]) and not s.get("error"),
      ([p for p in s["passes"] if p["name"] == "tonemap"], s.get("error")))
code, _, body = request(base + "/api/param", {"name": "ec", "value": 0.5})
s = wait_for(base, lambda s: any(p["name"] == "ec" and p["value"] == 0.5 for p in s["params"]), 30)
check("a parameter set after it applies", code == 200 and any(p["name"] == "ec" and p["value"] == 0.5 for p in s["params"]), (code, body))

# One switch rebuilds one pass: the state says what the last build did.
request(base + "/api/pass", {"name": "sky", "enabled": False})
request(base + "/api/pass", {"name": "sky", "enabled": True})
s = wait_for(base, lambda s: s["buildSummary"].startswith("rebuilt 1 pass(es) (sky)"), 30)
check("the build summary is the switch's own", s["buildSummary"].startswith("rebuilt 1 pass(es) (sky), reused"), s["buildSummary"][:120])

# Limits and methods.
code, _, body = request(base + "/api/param", b"{" + b"x" * (2 << 20) + b"}")
check("413 for a body over 1 MiB, not echoed", code == 413 and len(body) < 1000, (code, len(body)))
code, _, body = request(base + "/api/param", b'{"name": "ec", "value": 1e400}')
check("a number out of range is named so", code == 400 and "out of range" in json.loads(body).get("error", ""), (code, body))
code, _, body = request(base + "/api/param", method="DELETE")
check("405 with Allow for a wrong method", code == 405, (code, body))
try:
    urllib.request.urlopen(urllib.request.Request(base + "/api/state", method="POST", data=b"{}",
                                                  headers={"Authorization": "Bearer " + token, "Content-Type": "application/json"}), timeout=30)
    allow = None
except urllib.error.HTTPError as e:
    allow = (e.code, e.headers.get("Allow"))
check("405 names the allowed method", allow == (405, "GET"), allow)

# Security: a token on every call, the Host header this server's, no cross-site POSTs.
code, _, _ = request(base + "/api/state", auth=False)
check("401 without the token", code == 401, code)
code, _, _ = request(base + "/api/state?token=" + "0" * len(token), auth=False)
check("401 with a wrong token", code == 401, code)
code, _, _ = request(base + "/api/state?token=" + token, auth=False)
check("the token as a query parameter", code == 200, code)
code, _, _ = request(base + "/", auth=False)
check("the page itself needs the token", code == 401, code)
req = urllib.request.Request(base + "/?token=" + token)
with urllib.request.urlopen(req, timeout=30) as r:
    cookie = r.headers.get("Set-Cookie", "")
check("the page sets an HttpOnly, SameSite cookie", cookie.startswith("rgraph_token=" + token) and "HttpOnly" in cookie and "SameSite=Strict" in cookie, cookie)
code, _, _ = request(base + "/api/state", auth=False, headers={"Cookie": "rgraph_token=" + token})
check("the cookie is accepted", code == 200, code)
code, _, body = request(base + "/api/state", headers={"Host": "evil.example"})
check("403 for a foreign Host (DNS rebinding)", code == 403 and b"evil.example" in body, (code, body))
code, _, body = request(base + "/api/pass", {"name": "sky", "enabled": False}, headers={"Origin": "http://evil.example"})
check("403 for a cross-site Origin", code == 403, (code, body))
code, _, body = request(base + "/api/pass", b'{"name": "sky", "enabled": false}', headers={"Content-Type": "text/plain"})
check("415 for a POST that is not application/json (a form's)", code == 415, (code, body))
s = state(base)
check("none of them switched the pass", any(p["name"] == "sky" and p["enabled"] for p in s["passes"]))
refused = subprocess.run([rgraph, "serve", "--pipeline", pipeline, "--host", "0.0.0.0", "--port", "0"], capture_output=True, text=True, timeout=120)
check("a non-loopback address without --token is refused", refused.returncode == 2 and "--token" in refused.stderr, (refused.returncode, refused.stderr))

# A broken script: reported with file:line, the last good plan keeps rendering; then fixed.
frames = state(base)["frame"]
with open(pipeline, "w") as f:
    f.write(good + "rg.pass \"broken\" {\n")
s = wait_for(base, lambda s: s.get("error") and "pipeline.lua:" in s["error"], 60)
check("a script error with file:line", bool(s.get("error") and re.search(r"pipeline\.lua:\d+: ", s["error"])), s.get("error"))
s = wait_for(base, lambda s: s["frame"] > frames + 3, 60)
check("the last good plan keeps rendering", s["frame"] > frames + 3, (frames, s["frame"]))
with open(pipeline, "w") as f:
    f.write(good)
s = wait_for(base, lambda s: not s.get("error"), 60)
check("fixed script clears the error", not s.get("error"), s.get("error"))

# The page in headless Chromium, over the DevTools protocol on a pipe: switch a pass off with its
# checkbox and see the graph and the image change.
chromium = os.environ.get("RG_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")
if not chromium:
    print("skip the browser part: Chromium not found (install the Debian package 'chromium')")
else:
    to_browser_r, to_browser_w = os.pipe()
    from_browser_r, from_browser_w = os.pipe()

    def child_fds():  # the DevTools pipe is the browser's fd 3 (in) and 4 (out)
        a, b = os.dup(to_browser_r), os.dup(from_browser_w)
        os.dup2(a, 3)
        os.dup2(b, 4)
        os.set_inheritable(3, True)
        os.set_inheritable(4, True)

    profile = os.path.join(tmp, "chromium")
    browser = subprocess.Popen([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--remote-debugging-pipe",
                                "--user-data-dir=" + profile, "--window-size=1200,900", "about:blank"],
                               close_fds=False, preexec_fn=child_fds,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(to_browser_r)
    os.close(from_browser_w)
    reader = os.fdopen(from_browser_r, "rb")
    writer = os.fdopen(to_browser_w, "wb")
    ids = iter(range(1, 1000000))

    def cdp(method, params=None, session=None):
        msg = {"id": next(ids), "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        writer.write(json.dumps(msg).encode() + b"\0")
        writer.flush()
        buf = b""
        while True:
            c = reader.read(1)
            if not c:
                raise RuntimeError("the browser closed its pipe")
            if c != b"\0":
                buf += c
                continue
            reply = json.loads(buf)
            buf = b""
            if reply.get("id") == msg["id"]:
                return reply

    def evaluate(session, expression):
        r = cdp("Runtime.evaluate", {"expression": expression, "returnByValue": True, "awaitPromise": True}, session)
        return r.get("result", {}).get("result", {}).get("value")

    def until(session, expression, seconds=90):
        deadline = time.time() + seconds
        while time.time() < deadline:
            if evaluate(session, expression):
                return True
            time.sleep(0.5)
        return False

    try:
        target = cdp("Target.createTarget", {"url": base + "/?token=" + token})["result"]["targetId"]
        session = cdp("Target.attachToTarget", {"targetId": target, "flatten": True})["result"]["sessionId"]
        cdp("Runtime.enable", {}, session)
        check("the page shows the passes", until(session, "!!document.querySelector('input[data-pass=\"sky\"]')"))
        check("the page shows the graph", until(session, "[...document.querySelectorAll('#graph td')].some(td => td.textContent === 'sky')"))
        check("the page shows an image", until(session, "document.getElementById('view').naturalWidth === 160"))
        # The graph drawn: the lifetime grid (a row per memory place, W/R marks, culled columns
        # grey) and the pass DAG (an arrow from gbuffer to the lighting it feeds).
        check("the lifetime grid marks gbuffer writing GB1",
              until(session, "!!document.querySelector('#lifetimes g[data-resource=\"GB1\"] rect.use.w[data-pass=\"gbuffer\"]')"))
        check("the lifetime grid marks the lighting reading GB1",
              until(session, "!!document.querySelector('#lifetimes g[data-resource=\"GB1\"] rect.use.r[data-pass=\"lighting_standard\"]')"))
        check("the lifetime grid greys the culled passes", until(session, "document.querySelectorAll('#lifetimes rect.culled').length > 0"))
        check("the pass DAG has gbuffer -> lighting_standard",
              until(session, "!!document.querySelector('#dag path[data-from=\"gbuffer\"][data-to=\"lighting_standard\"]')"))
        evaluate(session, "document.querySelector('#lifetimes g[data-resource=\"GB1\"]').dispatchEvent(new MouseEvent('click')); true")
        check("clicking a resource shows it", until(session, "document.getElementById('resource').value === 'GB1' && document.getElementById('view').src.includes('resource=GB1')"))
        before = evaluate(session, "document.getElementById('view').src")
        evaluate(session, "document.querySelector('input[data-pass=\"sky\"]').click(); true")
        check("a pass switched off on the page", until(session, "document.querySelector('tr[data-pass=\"sky\"]').className === 'off'"))
        check("the graph shows it culled", until(session, "[...document.querySelectorAll('#graph td')].some(td => td.textContent === 'sky (culled)')"))
        check("the image was fetched again", until(session, "document.getElementById('view').src !== " + json.dumps(before) + " && document.getElementById('view').complete"))
        s = state(base)
        check("the server saw the page's switch", any(p["name"] == "sky" and not p["enabled"] for p in s["passes"]))
    except Exception as e:  # a protocol failure is a failed check, not a hang
        check("browser session", False, e)
    browser.kill()
    browser.wait(timeout=30)

t_term = time.time()
server.send_signal(signal.SIGTERM)
try:
    code = server.wait(timeout=60)
except subprocess.TimeoutExpired:
    server.kill()
    code = None
log.close()
check("SIGTERM stops it cleanly (exit 0) within 2 s", code == 0 and time.time() - t_term < 2.0, (code, time.time() - t_term))
with open(log_path) as f:
    text = f.read()
check("no validation message", "validation" not in text, [l for l in text.splitlines() if "validation" in l][:3])
shutil.rmtree(tmp, ignore_errors=True)
print("%d passed, %d failed" % (checks["passed"], checks["failed"]))
sys.exit(1 if checks["failed"] else 0)
