#!/usr/bin/env python3
"""`rgraph serve` driven as a tool and as a person would: its JSON API (toggle a pass, set a
parameter, fetch intermediates, bad requests refused with 400 and nothing changed, a broken script
reported with file:line while the last good plan keeps rendering, then fixed), the page in headless
Chromium (a pass switched off through its checkbox changes the graph and the image), and a clean
exit on SIGTERM. Every request goes to 127.0.0.1 on the port the server printed; loops are bounded.

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
import urllib.request

rgraph, root, tmp_root = sys.argv[1], sys.argv[2], sys.argv[3]
checks = {"passed": 0, "failed": 0}


def check(name, ok, detail=""):
    checks["passed" if ok else "failed"] += 1
    print(("ok   " if ok else "FAIL ") + name + ("" if ok else ": " + str(detail)), flush=True)


def request(url, body=None):
    data = None if body is None else (body if isinstance(body, bytes) else json.dumps(body).encode())
    req = urllib.request.Request(url, data=data, method="POST" if data is not None else "GET")
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
    if line.startswith("rgraph serve: http://"):
        base = line.split()[2].rstrip("/")
check("serve prints its address", base is not None and base.startswith("http://127.0.0.1:"), base)
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
    ("enabled not a boolean", "/api/pass", {"name": "fxaa", "enabled": "no"}, "expected"),
]:
    code, _, reply = request(base + url, body)
    check("400 for " + name, code == 400 and expect in json.loads(reply).get("error", ""), (code, reply))
s = state(base)
check("bad requests changed nothing", any(p["name"] == "ec" and p["value"] == 1.5 for p in s["params"]) and
      all(p["enabled"] for p in s["passes"] if p["name"] in ("gbuffer", "fxaa")))

# Intermediates: an HDR target, a G-buffer channel decoded by its layout, an EXR download.
for resource, fmt, magic in [("hdr", "png", b"\x89PNG"), ("GB1", "png", b"\x89PNG"), ("gbuffer.smoothness", "png", b"\x89PNG"),
                             ("hdr", "exr", b"\x76\x2f\x31\x01")]:
    code, _, body = request(base + "/api/image?resource=%s&ev=1&format=%s" % (resource, fmt))
    check("image %s as %s" % (resource, fmt), code == 200 and body[:4] == magic, (code, body[:80]))
for query, expect in [("resource=nothing", "no texture"), ("resource=hdr&ev=x", "ev"), ("resource=hdr&format=jpg", "format")]:
    code, _, body = request(base + "/api/image?" + query)
    check("400 for image " + query, code == 400 and expect in json.loads(body).get("error", ""), (code, body))

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
        target = cdp("Target.createTarget", {"url": base + "/"})["result"]["targetId"]
        session = cdp("Target.attachToTarget", {"targetId": target, "flatten": True})["result"]["sessionId"]
        cdp("Runtime.enable", {}, session)
        check("the page shows the passes", until(session, "!!document.querySelector('input[data-pass=\"sky\"]')"))
        check("the page shows the graph", until(session, "[...document.querySelectorAll('#graph td')].some(td => td.textContent === 'sky')"))
        check("the page shows an image", until(session, "document.getElementById('view').naturalWidth === 160"))
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

server.send_signal(signal.SIGTERM)
try:
    code = server.wait(timeout=60)
except subprocess.TimeoutExpired:
    server.kill()
    code = None
log.close()
check("SIGTERM stops it cleanly (exit 0)", code == 0, code)
with open(log_path) as f:
    text = f.read()
check("no validation message", "validation" not in text, [l for l in text.splitlines() if "validation" in l][:3])
shutil.rmtree(tmp, ignore_errors=True)
print("%d passed, %d failed" % (checks["passed"], checks["failed"]))
sys.exit(1 if checks["failed"] else 0)
