#!/usr/bin/env python3
"""`rgraph watch` under churn: N random edits of a watched pipeline script, valid and invalid.

    tests/cli/watch_churn.py RGRAPH ROOT TMP [N] [SEED]

Each edit replaces the script atomically (write, then rename), then waits for the watcher's
verdict: a valid edit must be reloaded and rendered; an invalid one (a syntax error, an unknown
resource, a wrong type, a raised error, a parameter out of range, a missing shader, an error in
rg.frame) must be reported naming the script while the last good plan stays in place — the next
valid edit renders again. At the end the watcher exits by itself (--max-reloads N) with status 0
and its image is there. Prints the counts; exits 1 on the first wrong verdict.
"""
import atexit
import os
import random
import subprocess
import sys
import time

rgraph, root, tmp = sys.argv[1], sys.argv[2], os.path.join(sys.argv[3], "watch_churn")
count = int(sys.argv[4]) if len(sys.argv) > 4 else 1000
rng = random.Random(int(sys.argv[5]) if len(sys.argv) > 5 else 1)
os.makedirs(tmp, exist_ok=True)
script = os.path.join(tmp, "watched.lua")
log_path = os.path.join(tmp, "watch.log")

BASE = """local rg = require "rg"
rg.param "scale" {{ type = "number", default = {scale}, min = 0, max = 16 }}
rg.resource "pattern" {{ format = "rgba16f" }}
rg.resource "{out}" {{ format = "rgba16f" }}
rg.pass "generate" {{ kind = "compute", shader = "test/pattern.comp", writes = {{ "pattern" }} }}
rg.pass "transform" {{ kind = "fullscreen", shader = "test/transform.frag", reads = {{ "pattern" }}, writes = {{ "{out}" }} }}
{extra}
rg.output "{out}"
"""


def valid():
    extra = rng.choice([
        "",
        f"-- comment {rng.random()}",
        'rg.resource "spare" { format = "rgba8" }\nrg.pass "unused" { kind = "clear", writes = { "spare" } }',
        "function rg.frame(ctx) ctx.params.scale = %.3f end" % rng.uniform(0, 16),
    ])
    return BASE.format(scale="%.4f" % rng.uniform(0, 16), out=rng.choice(["output", "result", "image"]), extra=extra)


def invalid():
    good = valid()
    return rng.choice([
        good + '\nrg.pass "broken" {',                                            # syntax error
        good + '\nrg.pass "x" { kind = "copy", reads = { "nothing" }, writes = { "pattern" } }',  # unknown resource
        good.replace('format = "rgba16f"', "format = 5", 1),                       # wrong type
        'error("churn")\n' + good,                                                 # a raised error
        good.replace("default = ", "default = 100 + ", 1),                        # out of range
        good.replace("test/transform.frag", "test/no_such_shader.frag"),           # missing shader
        good + '\nfunction rg.frame(ctx) error("frame churn") end',                # fails in rg.frame
        good + "\nwhile true do end",                                              # a runaway loop
    ])


def write(text):
    tmp_path = script + ".tmp"
    with open(tmp_path, "w") as f:
        f.write(text)
    os.replace(tmp_path, script)


def verdicts():
    with open(log_path) as f:
        text = f.read()
    # Only whole lines: a line the watcher is writing may be read in part.
    lines = text[:text.rfind("\n") + 1].splitlines()
    return [l for l in lines if l.startswith("rgraph watch: ") and ("reloaded" in l or "failed" in l)], lines


write(valid())
log = open(log_path, "w")
watcher = subprocess.Popen([rgraph, "watch", "--pipeline", script, "--size", "8x8", "--interval", "5", "--max-reloads", str(count),
                            "--out", os.path.join(tmp, "w.exr")], stdout=log, stderr=subprocess.STDOUT, cwd=root)
# A failed check exits at once: the watcher must not outlive the test (it would go on writing the
# log the next run reads).
atexit.register(lambda: watcher.poll() is None and watcher.kill())
deadline = time.time() + 60
while "watching" not in open(log_path).read():
    if time.time() > deadline or watcher.poll() is not None:
        sys.exit("watch did not start:\n" + open(log_path).read())
    time.sleep(0.05)

ok = bad = 0
for i in range(count):
    expect_valid = rng.random() < 0.5
    before = len(verdicts()[0])
    time.sleep(0.011)  # a new modification time, whatever the file system's granularity
    write(valid() if expect_valid else invalid())
    deadline = time.time() + 30
    while True:
        seen, lines = verdicts()
        if len(seen) > before:
            break
        if time.time() > deadline or watcher.poll() is not None:
            sys.exit(f"edit {i}: no verdict from watch (exit {watcher.poll()}):\n" + "\n".join(lines[-20:]))
        time.sleep(0.002)
    verdict = seen[before]
    if expect_valid and "reloaded and rendered" not in verdict:
        sys.exit(f"edit {i}: a valid script was not rendered: {verdict}\n" + "\n".join(lines[-10:]))
    if not expect_valid:
        if "failed" not in verdict:
            sys.exit(f"edit {i}: an invalid script was accepted: {verdict}")
        # This edit's report: from its verdict to the next one (or the end). Its lines after the
        # verdict may still be on their way to the log (a separate write): wait for them a while.
        named_by = time.time() + 10
        while True:
            start = [k for k, l in enumerate(lines) if l.startswith("rgraph watch: ") and ("reloaded" in l or "failed" in l)][before]
            after = "\n".join(lines[start:])
            if "watched.lua" in after or "no_such_shader" in after:
                break
            if time.time() > named_by:
                sys.exit(f"edit {i}: the report does not name the script:\n{after}")
            time.sleep(0.01)
            seen, lines = verdicts()
    ok += expect_valid
    bad += not expect_valid

rc = watcher.wait(timeout=60)
log.close()
if rc != 0:
    sys.exit(f"watch exited {rc}")
if not os.path.exists(os.path.join(tmp, "w.png")):
    sys.exit("no image written")
print(f"watch churn: {count} edits ({ok} valid, each reloaded and rendered; {bad} invalid, each reported), watch exited 0")
