#!/usr/bin/env python3
"""`rgraph serve` under load and faults: a bounded soak on 127.0.0.1.

    tools/soak.py [--rgraph build/rgraph] [--clients 16] [--seconds 60] [--size 160x90]
                  [--warmup 20] [--seed 1] [--max-rss-growth 0.10] [--max-shutdown 2.0]

Serves the default pipeline plus a pass of its own (`soak_tint`, whose shader lives beside the
script) from a temporary folder, then for --seconds runs --clients clients against it, each a
loop of requests on fresh connections: the state, the graph, images (PNG and EXR, textures and
G-buffer channels), and about 10 % invalid requests (unknown names, values out of range, bodies
that are not JSON, a 2 MiB body, wrong methods, no token, a foreign Host or Origin, a pass whose
switch would break the graph). One writer sets parameters and switches a pass, and remembers
what the server acknowledged last. Meanwhile the faults: the script broken and restored, the
pass's shader deleted and restored, a pipeline file saved with the same bytes, the process
stopped and continued — once during the warm-up (so that the steady state holds what a reload
needs), then again, checked. Then SIGTERM while the clients still send.

Prints requests per second, latency percentiles per endpoint, status counts, the server's RSS
(at start, after the warm-up, at the end, the largest) and the shutdown time, then a line of
checks. Fails (exit 1) on: a crash, any 5xx other than 503 "shutting down" after SIGTERM, a valid
request refused or an invalid one accepted, a request sent before SIGTERM left without an
answer (one sent after it may find the server closing, as it may find it gone), a final state
that is not the last acknowledged values, frames that stop while a shader is missing, a reload
with nothing edited, RSS growth over --max-rss-growth after the warm-up, or a shutdown slower
than --max-shutdown seconds (or an exit status other than 0).
"""
import argparse
import http.client
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

PIPELINE = """require "pipelines.deferred"  -- the default pipeline, and a pass of the soak's own
local rg = require "rg"
rg.resource "soak_tint" { format = "rgba16f", export = true }
rg.pass "soak_tint" { kind = "fullscreen", shader = "soak_tint.frag", reads = { "hdr" }, writes = { "soak_tint" } }
"""
SHADER = """#version 460
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D hdr;
void main() { color = texelFetch(hdr, ivec2(gl_FragCoord.xy), 0) * 0.5; }
"""


def percentile(values, q):
    if not values:
        return float("nan")
    v = sorted(values)
    return v[min(len(v) - 1, int(q * (len(v) - 1) + 0.5))]


def rss_mib(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return None


class Server:
    def __init__(self, host, port, token):
        self.host, self.port, self.token = host, port, token

    def request(self, method, path, body=None, headers=None, timeout=60):
        """(status, body bytes); status None when the connection closed without an answer,
        'refused' when nothing listens."""
        h = {"Authorization": "Bearer " + self.token, "Connection": "close"}
        if body is not None:
            h["Content-Type"] = "application/json"
        h.update(headers or {})
        h = {k: v for k, v in h.items() if v is not None}
        conn = http.client.HTTPConnection(self.host, self.port, timeout=timeout)
        try:
            conn.request(method, path, body=body, headers=h)
            r = conn.getresponse()
            return r.status, r.read()
        except ConnectionRefusedError:
            return "refused", b""
        except (http.client.RemoteDisconnected, ConnectionResetError, BrokenPipeError) as e:
            return None, type(e).__name__.encode()
        except OSError as e:  # a timeout: no answer either
            return None, str(e).encode()
        finally:
            conn.close()

    def state(self):
        status, body = self.request("GET", "/api/state")
        s = json.loads(body) if status == 200 and body else {}
        return s if isinstance(s, dict) else {}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rgraph", default=os.path.join(ROOT, "build", "rgraph"))
    ap.add_argument("--clients", type=int, default=16)
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--size", default="160x90")
    ap.add_argument("--warmup", type=float, default=20, help="seconds at least; the faults run once in it")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--max-rss-growth", type=float, default=0.10)
    ap.add_argument("--max-shutdown", type=float, default=2.0)
    ap.add_argument("--tmp", default=None, help="folder for the served scripts (default: a new temporary one)")
    args = ap.parse_args()

    checks = {"passed": 0, "failed": 0}

    def check(name, ok, detail=""):
        checks["passed" if ok else "failed"] += 1
        print(("ok   " if ok else "FAIL ") + name + ("" if ok else ": " + str(detail)[:600]), flush=True)

    tmp = tempfile.mkdtemp(prefix="soak_", dir=args.tmp)
    pipeline = os.path.join(tmp, "pipeline.lua")
    shader = os.path.join(tmp, "soak_tint.frag")
    with open(pipeline, "w") as f:
        f.write(PIPELINE)
    with open(shader, "w") as f:
        f.write(SHADER)
    log_path = os.path.join(tmp, "serve.log")
    log = open(log_path, "w")
    proc = subprocess.Popen([args.rgraph, "serve", "--pipeline", pipeline, "--port", "0", "--size", args.size, "--interval", "10"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    url = None
    deadline = time.time() + 180
    while time.time() < deadline and url is None:
        line = proc.stdout.readline()
        if not line:
            break
        log.write(line)
        m = re.match(r"rgraph serve: (http://([\d.]+):(\d+)/\?token=([0-9a-f]+))", line)
        if m:
            url = m
    if url is None:
        proc.kill()
        log.close()
        sys.exit("soak: rgraph serve did not start:\n" + open(log_path).read())
    threading.Thread(target=lambda: shutil.copyfileobj(proc.stdout, log), daemon=True).start()
    server = Server(url.group(2), int(url.group(3)), url.group(4))
    host_header = "%s:%s" % (url.group(2), url.group(3))
    s = {}
    while time.time() < deadline and s.get("frame", 0) < 2:
        s = server.state()
        time.sleep(0.2)
    check("serves frames", s.get("frame", 0) >= 2, s.get("error"))

    # Memory: sampled every 0.25 s; "after the warm-up" and "end" are medians over 2 s.
    rss = {"start": rss_mib(proc.pid), "warm": None, "end": None, "max_after_warm": 0.0, "samples": []}
    t_start = time.time()
    stop_sampling = threading.Event()

    def sample():
        while not stop_sampling.is_set():
            v = rss_mib(proc.pid)
            if v is not None:
                rss["samples"].append((time.time(), v))
                if rss["warm"] is not None:
                    rss["max_after_warm"] = max(rss["max_after_warm"], v)
            time.sleep(0.25)

    def rss_now():
        time.sleep(2.0)
        recent = [v for t, v in rss["samples"] if t >= time.time() - 2.0]
        return percentile(recent, 0.5) if recent else rss_mib(proc.pid)

    # The warm-up's own work: every image once (each export a reload) and a reload of the script
    # with other bytes, so that what is measured after it is the steady state.
    for res, fmt in [("hdr", "png"), ("GB1", "png"), ("gbuffer.smoothness", "png"), ("soak_tint", "png"), ("hdr", "exr"), ("display", "png")]:
        server.request("GET", "/api/image?resource=%s&format=%s" % (res, fmt))
    with open(pipeline, "a") as f:
        f.write("-- warm-up\n")
    threading.Thread(target=sample, daemon=True).start()

    lock = threading.Lock()
    latencies = {}   # endpoint -> [seconds]
    statuses = {}    # status -> count
    problems = []    # (what, detail)
    acknowledged = {"ec": None, "sky": None}
    stopping = threading.Event()   # SIGTERM sent: 503 "shutting down" and refusals are expected
    end_clients = threading.Event()

    term_sent = [None]  # when SIGTERM was sent
    closing = [0]       # requests sent after it that found the server closing (printed)

    def record(endpoint, status, started, valid, body, what):
        seconds = time.time() - started
        with lock:
            statuses[status] = statuses.get(status, 0) + 1
            latencies.setdefault(endpoint, []).append(seconds)
            if status is None:
                # A request sent after SIGTERM may find the server closing (the listening socket
                # goes with its queue of connections not yet accepted), as it may find it gone;
                # one sent before must be answered.
                if term_sent[0] is None or started < term_sent[0]:
                    when = " (answer due after SIGTERM)" if stopping.is_set() else ""
                    problems.append(("no answer", what + ": " + body[:200].decode(errors="replace") + when))
                else:
                    closing[0] += 1
            elif status == "refused":
                if not stopping.is_set():
                    problems.append(("connection refused", what))
            elif stopping.is_set() and status == 503 and b"shutting down" in body:
                pass
            elif isinstance(status, int) and status >= 500:
                problems.append(("%d" % status, what + " -> " + body[:200].decode(errors="replace")))
            elif valid and status != 200:
                problems.append(("valid request refused %s" % status, what + " -> " + body[:200].decode(errors="replace")))
            elif not valid and not (400 <= status < 500):
                problems.append(("invalid request accepted %s" % status, what))

    images = [("hdr", "png"), ("GB1", "png"), ("gbuffer.smoothness", "png"), ("soak_tint", "png"), ("hdr", "exr"), ("display", "png")]
    invalid = [
        ("POST", "/api/pass", json.dumps({"name": "gbufer", "enabled": False}), {}),
        ("POST", "/api/pass", json.dumps({"name": "tonemap", "enabled": False}), {}),  # fxaa reads what only it writes
        ("POST", "/api/param", json.dumps({"name": "ecc", "value": 1}), {}),
        ("POST", "/api/param", json.dumps({"name": "ec", "value": 100}), {}),
        ("POST", "/api/param", '{"name": "ec", "value": 1e400}', {}),
        ("POST", "/api/param", "{name", {}),
        ("POST", "/api/param", "x" * (2 << 20), {}),
        ("POST", "/api/param", json.dumps({"name": "ec", "value": 1}), {"Content-Type": "text/plain"}),
        ("POST", "/api/pass", json.dumps({"name": "sky", "enabled": False}), {"Origin": "http://evil.example"}),
        ("GET", "/api/state", None, {"Host": "evil.example"}),
        ("GET", "/api/state", None, {"Authorization": None}),
        ("DELETE", "/api/param", None, {}),
        ("GET", "/api/image?resource=nosuch.thing", None, {}),
        ("GET", "/api/image?resource=../../etc/passwd", None, {}),
        ("GET", "/api/image?resource=hdr&ev=x", None, {}),
    ]

    def reader(k):
        rng = random.Random(args.seed * 1000 + k)
        while not end_clients.is_set():
            r = rng.random()
            if r < 0.10:
                method, path, body, headers = rng.choice(invalid)
                endpoint, valid = path.split("?")[0] + " (invalid)", False
            elif r < 0.55:
                method, path, body, headers, endpoint, valid = "GET", "/api/state", None, {}, "/api/state", True
            elif r < 0.70:
                method, path, body, headers, endpoint, valid = "GET", "/api/graph", None, {}, "/api/graph", True
            else:
                res, fmt = rng.choice(images)
                method, path, body, headers = "GET", "/api/image?resource=%s&format=%s&ev=%d" % (res, fmt, rng.randint(-2, 2)), None, {}
                endpoint, valid = "/api/image", True
            t0 = time.time()
            status, reply = server.request(method, path, body, headers)
            record(endpoint, status, t0, valid, reply, method + " " + path[:80])
            time.sleep(rng.uniform(0.0, 0.05))

    def writer():
        rng = random.Random(args.seed)
        while not end_clients.is_set():
            if rng.random() < 0.6:
                path, key, field, value = "/api/param", "ec", "value", round(rng.uniform(-2, 2), 3)
            else:
                path, key, field, value = "/api/pass", "sky", "enabled", rng.random() < 0.5
            t0 = time.time()
            status, reply = server.request("POST", path, json.dumps({"name": key, field: value}))
            record(path, status, t0, True, reply, "%s %s = %s" % (key, field, value))
            if status == 200:
                with lock:
                    acknowledged[key] = value
            time.sleep(rng.uniform(0.05, 0.2))

    threads = [threading.Thread(target=writer, daemon=True)]
    threads += [threading.Thread(target=reader, args=(k,), daemon=True) for k in range(max(1, args.clients - 1))]
    for t in threads:
        t.start()

    def log_text():
        with open(log_path) as f:
            return f.read()

    def wait_state(predicate, seconds):
        end = time.time() + seconds
        st = server.state()
        while time.time() < end and not (st and predicate(st)):
            time.sleep(0.2)
            st = server.state()
        return st

    def faults(checked):
        """The script saved with the same bytes, broken and restored; the pass's shader deleted
        and restored; the process stopped and continued. `checked`: each step's outcome is a check."""
        expect = check if checked else (lambda name, ok, detail="": None)
        reloads_before = log_text().count("rgraph serve: reloaded")
        # A save with the same bytes: no reload.
        os.utime(pipeline)
        time.sleep(2.0)
        expect("a save with the same bytes reloads nothing", log_text().count("rgraph serve: reloaded") == reloads_before,
               log_text().count("rgraph serve: reloaded") - reloads_before)
        # A broken script: reported with file:line, frames go on; then restored.
        with open(pipeline, "a") as f:
            f.write('rg.pass "broken" {\n')
        st = wait_state(lambda st: st.get("error") and "pipeline.lua:" in st["error"], 30)
        frame = st.get("frame", 0)
        expect("a broken script is reported with file:line", bool(st.get("error") and "pipeline.lua:" in st["error"]), st.get("error"))
        st = wait_state(lambda st: st.get("frame", 0) > frame + 3, 30)
        expect("frames go on while the script is broken", st.get("frame", 0) > frame + 3, (frame, st.get("frame")))
        with open(pipeline, "w") as f:
            f.write(PIPELINE)
        st = wait_state(lambda st: not st.get("error"), 60)
        expect("the restored script clears the error", not st.get("error"), st.get("error"))
        # The pass's shader deleted: reported, frames go on, the error stays put; then restored.
        os.remove(shader)
        st = wait_state(lambda st: st.get("error") and "soak_tint" in st["error"], 30)
        expect("a deleted shader is reported", bool(st.get("error") and "soak_tint" in st["error"]), st.get("error"))
        frame, flicker = st.get("frame", 0), 0
        for _ in range(15):
            time.sleep(0.2)
            st = server.state()
            flicker += not st.get("error")
        expect("frames go on while the shader is missing", st.get("frame", 0) > frame + 3, (frame, st.get("frame")))
        expect("the error holds while the shader is missing", flicker == 0, "%d of 15 states without it" % flicker)
        with open(shader, "w") as f:
            f.write(SHADER)
        st = wait_state(lambda st: not st.get("error"), 60)
        expect("the restored shader clears the error", not st.get("error"), st.get("error"))
        # Stopped and continued: requests wait, nothing is lost.
        proc.send_signal(signal.SIGSTOP)
        time.sleep(1.5)
        proc.send_signal(signal.SIGCONT)

    # The warm-up: the faults once, unchecked, so that the steady state holds what a reload needs;
    # then the faults again, checked, and the load to the end.
    faults(checked=False)
    time.sleep(max(0.0, t_start + args.warmup - time.time()))
    rss["warm"] = rss_now()
    warm_seconds = time.time() - t_start
    faults(checked=True)
    time.sleep(max(0.0, t_start + args.seconds - 2.0 - time.time()))
    rss["end"] = rss_now()

    # The final state against the last acknowledged values (no lost or half-applied update).
    with lock:
        writer_thread = threads[0]
    end_clients.set()  # the writer stops first, so that its last answer is the last change
    writer_thread.join(timeout=60)
    # The state is gathered after each frame: two more frames, and it shows every change made.
    frame = server.state().get("frame", 0)
    st = wait_state(lambda st: st.get("frame", 0) >= frame + 2, 60)
    with lock:
        ec, sky = acknowledged["ec"], acknowledged["sky"]
    params = {p["name"]: p["value"] for p in st.get("params", [])}
    passes = {p["name"]: p for p in st.get("passes", [])}
    check("the final state holds the last acknowledged parameter", ec is None or abs(params.get("ec", 1e9) - ec) < 1e-9, (ec, params.get("ec")))
    check("the final state holds the last acknowledged switch",
          sky is None or (passes.get("sky", {}).get("enabled") == sky and passes.get("sky", {}).get("kept") == sky),
          (sky, passes.get("sky")))
    check("no frame error at the end", not st.get("error"), st.get("error"))

    # SIGTERM under load: the readers go on until the server is gone.
    end_clients.clear()
    for t in threads[1:]:
        t.join(timeout=0)  # still running
    load = [threading.Thread(target=reader, args=(100 + k,), daemon=True) for k in range(4)]
    for t in load:
        t.start()
    time.sleep(1.0)
    stopping.set()
    t_term = term_sent[0] = time.time()
    proc.send_signal(signal.SIGTERM)
    try:
        code = proc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        code = None
    shutdown = time.time() - t_term
    end_clients.set()
    stop_sampling.set()
    for t in threads + load:
        t.join(timeout=90)
    log.close()

    elapsed = t_term - t_start
    total = sum(statuses.values())
    print("soak: %d clients, %.0f s at %s: %d requests, %.1f per second" % (args.clients, elapsed, args.size, total, total / elapsed))
    print("  %-24s %7s %8s %8s %8s %8s" % ("endpoint", "count", "p50 ms", "p95 ms", "p99 ms", "max ms"))
    for ep in sorted(latencies):
        v = latencies[ep]
        print("  %-24s %7d %8.1f %8.1f %8.1f %8.1f" % (ep, len(v), 1e3 * percentile(v, 0.5), 1e3 * percentile(v, 0.95),
                                                     1e3 * percentile(v, 0.99), 1e3 * max(v)))
    print("  status counts: " + ", ".join("%s: %d" % (k, statuses[k]) for k in sorted(statuses, key=str)))
    # Growth: at the end against after the warm-up (a reload holds two plans for a moment; the
    # largest sample is printed, the end is what stays).
    warm = rss["warm"] or rss["start"] or 0.0
    growth = ((rss.get("end") or 0.0) - warm) / warm if warm else float("nan")
    print("  RSS MiB: start %.0f, after the warm-up (%.0f s) %.0f, end %.0f (growth %+.1f %%), max after the warm-up %.0f" %
          (rss["start"] or 0, warm_seconds, warm, rss.get("end") or 0, 100 * growth, rss["max_after_warm"]))
    print("  shutdown: %.2f s after SIGTERM, exit %s; %d requests sent after it found the server closing" %
          (shutdown, code, closing[0]))
    for what, detail in problems[:20]:
        print("  problem: %s: %s" % (what, detail))
    if len(problems) > 20:
        print("  ... %d problems in all" % len(problems))

    check("every request answered, no 5xx, valid accepted, invalid refused", not problems, "%d problems" % len(problems))
    check("RSS grows at most %.0f %% from the warm-up to the end" % (100 * args.max_rss_growth), growth <= args.max_rss_growth,
          "%.1f %%" % (100 * growth))
    check("SIGTERM under load exits 0 within %.1f s" % args.max_shutdown, code == 0 and shutdown <= args.max_shutdown, (code, shutdown))
    text = open(log_path).read()
    check("no validation message", "validation" not in text.lower(), [l for l in text.splitlines() if "alidation" in l][:3])
    if checks["failed"] == 0:
        shutil.rmtree(tmp, ignore_errors=True)
    else:
        print("soak: the server's log and scripts are in " + tmp)
    print("%d passed, %d failed" % (checks["passed"], checks["failed"]))
    return 1 if checks["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
