#!/usr/bin/python3
"""tools/farm.py on a local Dask cluster of 3 worker processes: the Cornell bake in 4 shards merged
bit-identical to the whole bake, a rerun served by the cache, a worker killed in the middle of a
shard with the result still identical, the golden suite in 3 shards as one JUnit file holding every
test once, and a sequence's frames rendered in chunks identical to one run.

usage: test_farm.py RGRAPH SOURCE_ROOT
"""

import glob
import logging
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

RGRAPH, ROOT = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
FARM = [sys.executable, os.path.join(ROOT, "tools", "farm.py"), "--rgraph", RGRAPH]
# Big enough that a shard takes a few seconds (a worker can be killed inside one), small enough for CI.
SCENE = ["--scene", "scripts/scenes/cornell.lua", "--scene-arg", "samples=384"]
failures = []
FAMILY = subprocess.run([RGRAPH, "devices", "--family"], capture_output=True, text=True).stdout.strip()


def check(name, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + name + (f": {detail}" if detail and not ok else ""), flush=True)
    if not ok:
        failures.append(name)


def run(argv, env=None, **kw):
    t0 = time.monotonic()
    p = subprocess.run(argv, cwd=ROOT, env={**os.environ, **(env or {})}, capture_output=True,
                       text=True, **kw)
    p.seconds = time.monotonic() - t0
    return p


def same_bytes(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def main():
    tmp = tempfile.mkdtemp(prefix="rgraph-farm-")
    try:
        test_bake(tmp)
        test_kill(tmp)
        test_golden(tmp)
        test_render(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


def test_bake(tmp):
    whole = os.path.join(tmp, "whole.exr")
    p = run([RGRAPH, "bake", *SCENE, "--rebake", "--out", whole], {"RG_CACHE_DIR": f"{tmp}/cache-whole"})
    check("whole bake", p.returncode == 0, p.stderr)
    print(f"     whole bake: {p.seconds:.1f} s", flush=True)
    merged = os.path.join(tmp, "merged.exr")
    env = {"RG_CACHE_DIR": f"{tmp}/cache-farm"}
    p = run([*FARM, "--workers", "3", "--work", f"{tmp}/work", "bake", "--shards", "4", *SCENE,
             "--out", merged], env)
    check("farm bake, 4 shards on 3 workers", p.returncode == 0, p.stdout + p.stderr)
    print(f"     farm bake: {p.seconds:.1f} s", flush=True)
    check("farm bake shows progress and an ETA", "4/4 shards done" in p.stderr and "ETA" in p.stderr, p.stderr)
    check("4 merged shards are the whole bake bit for bit", os.path.isfile(merged) and same_bytes(merged, whole))
    p = run([*FARM, "--workers", "3", "--work", f"{tmp}/work", "bake", "--shards", "4", *SCENE,
             "--out", merged], env)
    check("a rerun finds every shard in the cache", p.returncode == 0 and
          "all 4 shards up to date in the cache" in p.stderr, p.stderr)
    # Two workers baking the same shard into one cache at once: both finish, the entry is whole.
    race = {"RG_CACHE_DIR": f"{tmp}/cache-race"}
    argv = [RGRAPH, "bake", *SCENE, "--shard", "3/4", "--rebake"]
    procs = [subprocess.Popen(argv, cwd=ROOT, env={**os.environ, **race}, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True) for _ in range(2)]
    codes = [p.wait(timeout=300) for p in procs]
    p = run([RGRAPH, "bake", *SCENE, "--shard", "3/4"], race)
    leftovers = [f for f in glob.glob(f"{tmp}/cache-race/lightmaps/*") if ".tmp-" in f]
    check("two writers of one cache entry leave it whole", codes == [0, 0] and p.returncode == 0 and
          "up to date in the cache" in p.stdout and not leftovers, f"{codes} {p.stdout} {leftovers}")
    parts = sorted(glob.glob(f"{tmp}/work/bake-part-*-of-4.exr"))
    p = run([RGRAPH, "bake", "--merge", *parts[:3], "--out", f"{tmp}/partial.exr"])
    check("a merge without every shard is refused, naming it",
          p.returncode == 2 and "lack shard 4/4" in p.stderr and not os.path.exists(f"{tmp}/partial.exr"),
          p.stderr)
    p = run([RGRAPH, "bake", "--merge", parts[0], parts[0], *parts[2:]])
    check("a shard given twice is refused", p.returncode == 2 and "is given twice" in p.stderr, p.stderr)
    other = os.path.join(tmp, "other-part.exr")
    p = run([RGRAPH, "bake", *SCENE, "--scene-arg", "light=dynamic", "--shard", "2/4", "--out", other],
            {"RG_CACHE_DIR": f"{tmp}/cache-other"})
    p = run([RGRAPH, "bake", "--merge", parts[0], other, *parts[2:]])
    check("a part of another scene is refused", p.returncode == 2 and "is of another bake" in p.stderr,
          p.stderr)
    p = run([*FARM, "--workers", "2", "--retries", "1", "--work", f"{tmp}/work-fail", "bake",
             "--shards", "2", "--scene", "scripts/scenes/furnace.lua"])
    check("a shard that fails for good is named, after its retries",
          p.returncode == 3 and "failed for good" in p.stderr and "after 2 runs" in p.stderr and
          "declares no scene.lightmap" in p.stderr, p.stderr)
    p = run([RGRAPH, "render", *SCENE, "--size", "8x8", "--out", f"{tmp}/x.exr"],
            {"RG_CACHE_DIR": f"{tmp}/cache-farm"})
    check("the merged bake is in the cache for render", p.returncode == 0 and "baking" not in p.stderr,
          p.stderr)


def test_kill(tmp):
    """A worker killed (SIGKILL) while it bakes a shard: the scheduler runs the shard again
    elsewhere, and the merge is still the whole bake bit for bit."""
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=3, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=logging.ERROR)
    client = Client(cluster)
    try:
        work = f"{tmp}/work-kill"
        merged = os.path.join(tmp, "merged-kill.exr")
        farm = subprocess.Popen([*FARM, "--scheduler", cluster.scheduler_address, "--work", work,
                                 "bake", "--shards", "4", *SCENE, "--out", merged], cwd=ROOT,
                                env={**os.environ, "RG_CACHE_DIR": f"{tmp}/cache-kill"},
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        # The first shard to start: its mark names the worker's pid; killed 0.3 s later, inside
        # the shard's bake (a shard takes seconds here).
        killed = None
        deadline = time.monotonic() + 60
        while killed is None and time.monotonic() < deadline and farm.poll() is None:
            marks = glob.glob(f"{work}/attempts/bake/*")
            words = open(marks[0]).read().split() if marks else []
            if len(words) == 2:
                time.sleep(0.3)
                pid = int(words[1])
                os.kill(pid, signal.SIGKILL)
                killed = pid
            time.sleep(0.02)
        out, err = farm.communicate(timeout=300)
        check("a worker was killed in the middle of a shard", killed is not None)
        check("the farm finished after the worker died", farm.returncode == 0, out + err)
        check("the killed worker's shard ran again", "ran 2 times" in err, err)
        check("the merge is still the whole bake bit for bit",
              os.path.isfile(merged) and same_bytes(merged, os.path.join(tmp, "whole.exr")))
    finally:
        client.close()
        cluster.close()


def test_golden(tmp):
    """The golden suite in 3 shards on a cluster of two device families: two workers on the
    machine's own, one whose family is set apart (RG_DEVICE_FAMILY, as a farm names a second GPU
    kind); one JUnit file with a suite per family, each holding every test once."""
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=logging.ERROR)
    client = Client(cluster)
    second = subprocess.Popen([shutil.which("dask-worker") or "dask-worker", cluster.scheduler_address, "--nthreads", "1",
                               "--no-dashboard", "--no-nanny"],
                              env={**os.environ, "RG_DEVICE_FAMILY": "second"},
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        client.wait_for_workers(3, timeout=60)
        junit = os.path.join(tmp, "junit.xml")
        p = run([*FARM, "--scheduler", cluster.scheduler_address, "--work", f"{tmp}/work-test",
                 "test", "--shards", "3", "--junit", junit])
        check("the golden suite in 3 shards on two device families", p.returncode == 0,
              p.stdout + p.stderr)
        print(f"     golden suite, 3 shards x 2 families: {p.seconds:.1f} s", flush=True)
        check("reported per device family", f"farm: {FAMILY}: " in p.stdout and "farm: second: " in p.stdout,
              p.stdout)
        expected = sorted(os.path.basename(f)[:-4] for f in glob.glob(f"{ROOT}/tests/golden/*.lua"))
        suites = {s.get("name"): s for s in ET.parse(junit).getroot().iter("testsuite")} \
            if os.path.isfile(junit) else {}
        check("one JUnit file with a suite per family",
              sorted(suites) == sorted([f"golden ({FAMILY})", "golden (second)"]), str(sorted(suites)))
        for name, suite in suites.items():
            names = [c.get("name") for c in suite.iter("testcase")]
            check(f"{name} holds every test once", sorted(names) == expected,
                  f"{sorted(names)} vs {expected}")
            shards = {c.get("shard") for c in suite.iter("testcase")}
            check(f"{name} ran in 3 shards", shards == {"1/3", "2/3", "3/3"}, str(shards))
    finally:
        second.terminate()
        second.wait(timeout=30)
        client.close()
        cluster.close()


def test_render(tmp):
    # The default pipeline carries history (SSR's previous frame, exposure): chunks warm up from 0.
    opts = ["--size", "64x36"]
    p = run([RGRAPH, "render", "--frames", "0..5", "--out", f"{tmp}/one/f.####.exr", *opts])
    check("one run of frames 0..5", p.returncode == 0, p.stderr)
    p = run([*FARM, "--workers", "3", "--work", f"{tmp}/work-render", "render", "--frames", "0..5",
             "--chunk", "2", "--out", f"{tmp}/farm/f.####.exr", "--", *opts])
    check("frames 0..5 in chunks of 2", p.returncode == 0, p.stdout + p.stderr)
    same = [f for f in range(6) for ext in ("exr", "png")
            if os.path.isfile(f"{tmp}/farm/f.{f:04d}.{ext}") and
            same_bytes(f"{tmp}/farm/f.{f:04d}.{ext}", f"{tmp}/one/f.{f:04d}.{ext}")]
    check("every chunked frame is the one run's bit for bit", len(same) == 12, f"{len(same)} of 12 files")


if __name__ == "__main__":
    sys.exit(main())
