#!/usr/bin/python3
"""rgraph's work in shards on a Dask distributed cluster: lightmap bakes, the golden suite and
frame ranges of a sequence.

    tools/farm.py [CLUSTER] bake   --shards N [--scene FILE] [--scene-arg NAME=VALUE]... [--out FILE.exr]
    tools/farm.py [CLUSTER] test   --shards N [--junit FILE] [PATTERN]   (on every device family)
    tools/farm.py [CLUSTER] render --frames A..B [--chunk C] [--warmup W] --out PATH [-- RENDER-OPTIONS]

CLUSTER: --workers N starts a local cluster of N worker processes (default 2); --scheduler ADDRESS
joins a running one (dask-scheduler with dask-worker on each machine, dask-ssh, or Dask's Slurm and
Kubernetes deployments). Every worker runs `rgraph` (--rgraph, default build/rgraph) in the
project's folder and must see --work (default out/farm) and RG_CACHE_DIR at the same paths: on many
machines, a shared folder.

Each shard is one Dask task running one rgraph process. A task whose rgraph fails is retried
(--retries, default 2); a task whose worker dies (the machine, the process, the network) is run
again by the scheduler on another. Results are joined on this machine: `rgraph bake --merge` (the
whole lightmap, bit-identical to one bake), one JUnit file (a suite per device family the workers
have, `rgraph devices --family`, every test once in each), the frames checked present. Exit 0 when all is done, 1 when tests failed, 2 for bad usage, 3 naming the shard that
failed for good.
"""

import argparse
import ctypes
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class ShardFailed(Exception):
    """An rgraph run that failed: its command, exit status and last lines."""


def mark_name(name):
    """A shard's name as its attempt marks are named."""
    return name.replace("/", "-of-").replace(" ", "_")


def run_shard(name, argv, cwd, env, attempts_dir, ok_codes=(0,)):
    """Runs on a worker: one rgraph process. Each start leaves a mark in attempts_dir (the host and
    the worker's pid), so the driver can tell which shards ran more than once."""
    os.makedirs(attempts_dir, exist_ok=True)
    safe = mark_name(name)
    n = 1
    while True:
        try:
            fd = os.open(os.path.join(attempts_dir, f"{safe}.{n}"), os.O_CREAT | os.O_EXCL | os.O_WRONLY)
            os.write(fd, f"{os.uname().nodename} {os.getpid()}\n".encode())
            os.close(fd)
            break
        except FileExistsError:
            n += 1
    # The rgraph process ends with its worker (PR_SET_PDEATHSIG): a killed worker leaves no orphan
    # baking on. libc is loaded here, in the worker: nothing is loaded between fork and exec.
    libc = ctypes.CDLL("libc.so.6", use_errno=True)
    start = time.monotonic()
    proc = subprocess.run(argv, cwd=cwd, env={**os.environ, **env}, capture_output=True, text=True,
                          preexec_fn=lambda: libc.prctl(1, signal.SIGKILL))
    seconds = time.monotonic() - start
    if proc.returncode not in ok_codes:
        tail = "\n".join((proc.stdout + proc.stderr).strip().splitlines()[-6:])
        raise ShardFailed(f"{name}: `{' '.join(argv[1:])}` exited {proc.returncode}:\n{tail}")
    return {"name": name, "rc": proc.returncode, "seconds": seconds, "stdout": proc.stdout,
            "host": os.uname().nodename}


def log(msg):
    print(f"farm: {msg}", file=sys.stderr, flush=True)


def run_tasks(client, tasks, retries, label, workers=None):
    """Submits (name, argv, ok_codes) tasks, shows progress and an ETA, returns their results in
    order; on a task that failed for good, exits 3 naming it."""
    from distributed import as_completed

    # The workers' cache is this machine's (RG_CACHE_DIR, else rgraph's default), as the merge's.
    env = {"RG_CACHE_DIR": os.environ["RG_CACHE_DIR"]} if os.environ.get("RG_CACHE_DIR") else {}
    attempts = os.path.join(ARGS.work, "attempts", label)
    shutil.rmtree(attempts, ignore_errors=True)
    futures = {}
    for name, argv, ok in tasks:
        placement = {"workers": workers, "allow_other_workers": False} if workers else {}
        f = client.submit(run_shard, name, argv, ROOT, env, attempts, ok,
                          key=f"rgraph-{label}-{name}-{time.time_ns()}".replace(" ", "-"),
                          retries=retries, pure=False, **placement)
        futures[f] = name
    start, done, results = time.monotonic(), 0, {}
    log(f"{label}: {len(tasks)} shards on {len(workers or client.scheduler_info()['workers'])} workers")
    for f in as_completed(list(futures)):
        name = futures[f]
        if f.status != "finished":
            err = f.exception()
            for other in futures:
                other.cancel()
            kind = type(err).__name__
            runs = len([m for m in os.listdir(attempts) if m.rsplit(".", 1)[0] == mark_name(name)]) \
                if os.path.isdir(attempts) else 0
            log(f"{label}: {name} failed for good ({kind}, after {runs} runs): {err}")
            sys.exit(3)
        results[name] = f.result()
        done += 1
        elapsed = time.monotonic() - start
        eta = elapsed / done * (len(tasks) - done)
        log(f"{label}: {done}/{len(tasks)} shards done ({name} on {results[name]['host']}, "
            f"{results[name]['seconds']:.1f} s), {elapsed:.1f} s elapsed, ETA {eta:.0f} s")
    ran = {}
    for mark in os.listdir(attempts) if os.path.isdir(attempts) else []:
        base = mark.rsplit(".", 1)[0]
        ran[base] = ran.get(base, 0) + 1
    for name, _, _ in tasks:
        count = ran.get(mark_name(name), 1)
        if count > 1:
            log(f"{label}: {name} ran {count} times (a worker died or the run failed; retried)")
    return [results[name] for name, _, _ in tasks], time.monotonic() - start


def rgraph():
    return os.path.abspath(ARGS.rgraph)


def shard_files(stem, ext):
    """Each shard's K/N spec and the file it writes in --work."""
    n = ARGS.shards
    return [(f"{k}/{n}", os.path.join(ARGS.work, f"{stem}-{k}-of-{n}.{ext}")) for k in range(1, n + 1)]


def bake(client):
    n = ARGS.shards
    files = shard_files("bake-part", "exr")
    parts, tasks = [part for _, part in files], []
    for spec, part in files:
        argv = [rgraph(), "bake", "--shard", spec, "--out", part]
        if ARGS.scene:
            argv += ["--scene", ARGS.scene]
        for a in ARGS.scene_arg:
            argv += ["--scene-arg", a]
        if ARGS.threads:
            argv += ["--threads", str(ARGS.threads)]
        tasks.append((f"shard {spec}", argv, (0,)))
    results, wall = run_tasks(client, tasks, ARGS.retries, "bake")
    # The figures each shard printed: its texels, bake seconds and rays.
    texels = rays = bake_s = 0.0
    cached = 0
    for r in results:
        for line in r["stdout"].splitlines():
            m = re.match(r"rgraph: baked shard \S+ (\d+) of \d+ covered texels in ([\d.]+) s: "
                         r"([\d.]+) M rays", line)
            if m:
                texels += float(m.group(1))
                bake_s += float(m.group(2))
                rays += float(m.group(3)) * 1e6
            elif "up to date in the cache" in line:
                cached += 1
    process_s = sum(r["seconds"] for r in results)
    if cached < n:
        log(f"bake: {n - cached} shards baked, {cached} from the cache; {texels:.0f} texels, "
            f"{rays / 1e6:.1f} M rays; wall {wall:.2f} s; per shard: process {process_s / n:.2f} s, "
            f"bake {bake_s / max(n - cached, 1):.2f} s, overhead {(process_s - bake_s) / n:.2f} s; "
            f"{rays / max(bake_s, 1e-9) / 1e6:.2f} M rays/s per worker")
    else:
        log(f"bake: all {n} shards up to date in the cache; wall {wall:.2f} s")
    merge = [rgraph(), "bake", "--merge", *parts] + (["--out", ARGS.out] if ARGS.out else [])
    proc = subprocess.run(merge, cwd=ROOT, capture_output=True, text=True)
    sys.stdout.write(proc.stdout)
    sys.stderr.write(proc.stderr)
    if proc.returncode:
        log("bake: the merge failed")
        sys.exit(3)
    return 0


def device_family(rgraph_path):
    """Runs on a worker: the family its device's goldens are kept under (rgraph devices --family)."""
    p = subprocess.run([rgraph_path, "devices", "--family"], capture_output=True, text=True)
    return p.stdout.strip() or "unknown"


def test(client):
    """The golden suite in N shards on every device family the cluster has: per family, its
    shards run on its workers only; one JUnit file holds a suite per family, every test once in
    each."""
    n = ARGS.shards
    families = {}
    for worker, family in client.run(device_family, rgraph()).items():
        families.setdefault(family, []).append(worker)
    log(f"test: device families: " + ", ".join(f"{f} ({len(w)} workers)" for f, w in sorted(families.items())))
    merged = ET.Element("testsuites", name="rgraph golden")
    totals, status = [], 0
    for family, workers in sorted(families.items()):
        tasks, files = [], []
        for spec, junit in shard_files(f"junit-{family}", "xml"):
            files.append(junit)
            argv = [rgraph(), "test", "--shard", spec, "--junit", junit, "--out", junit[:-4] + "-images"]
            if ARGS.pattern:
                argv.insert(2, ARGS.pattern)
            tasks.append((f"{family} shard {spec}", argv, (0, 1)))  # 1: tests failed, the shard ran
        results, wall = run_tasks(client, tasks, ARGS.retries, f"test-{family}", workers=workers)
        suite = ET.SubElement(merged, "testsuite", name=f"golden ({family})")
        ET.SubElement(ET.SubElement(suite, "properties"), "property", name="device_family", value=family)
        seen, tests, failures, errors, seconds = {}, 0, 0, 0, 0.0
        for k, f in enumerate(files, 1):
            for case in ET.parse(f).getroot().iter("testcase"):
                name = case.get("name")
                if name in seen:
                    log(f"test: {family}: {name} ran in shard {seen[name]} and {k}/{n}")
                    sys.exit(3)
                seen[name] = f"{k}/{n}"
                case.set("shard", f"{k}/{n}")
                case.set("classname", f"golden.{family}")
                suite.append(case)
                tests += 1
                failures += case.find("failure") is not None
                errors += case.find("error") is not None
                seconds += float(case.get("time", "0"))
        suite.set("tests", str(tests)), suite.set("failures", str(failures)), suite.set("errors", str(errors))
        suite.set("time", f"{seconds:.3f}")
        totals.append((tests, failures, errors, seconds))
        print(f"farm: {family}: {tests} tests in {n} shards: {tests - failures - errors} passed, "
              f"{failures} failed, {errors} errors (wall {wall:.1f} s)")
        for r in results:
            for line in r["stdout"].splitlines():
                if line.startswith(("FAIL", "ERROR")):
                    print(f"farm: {family}: {line}")
        status = status or (1 if failures or errors else 0)
    for i, key in enumerate(("tests", "failures", "errors")):
        merged.set(key, str(sum(t[i] for t in totals)))
    merged.set("time", f"{sum(t[3] for t in totals):.3f}")
    out = ARGS.junit or os.path.join(ARGS.work, "junit.xml")
    ET.ElementTree(merged).write(out, encoding="UTF-8", xml_declaration=True)
    log(f"test: JUnit {out} ({len(families)} device famil{'y' if len(families) == 1 else 'ies'})")
    return status


def frame_path(path, frame):
    """rgraph's framePath: a run of '#' in the file name is the number, else .NNNN."""
    head, name = os.path.split(path)
    if "#" in name:
        i = name.index("#")
        j = i
        while j < len(name) and name[j] == "#":
            j += 1
        return os.path.join(head, name[:i] + str(frame).zfill(j - i) + name[j:])
    stem, ext = os.path.splitext(name)
    return os.path.join(head, f"{stem}.{frame:04d}{ext}")


def render(client):
    try:
        a, b = (int(x) for x in ARGS.frames.split(".."))
        assert 0 <= a <= b
    except (ValueError, AssertionError):
        log(f"render: --frames must be A..B with 0 <= A <= B, got '{ARGS.frames}'")
        sys.exit(2)
    if not ARGS.out:
        log("render: --out PATH is needed (e.g. out/shot/frame.####.exr)")
        sys.exit(2)
    tasks = []
    for first in range(a, b + 1, ARGS.chunk):
        last = min(b, first + ARGS.chunk - 1)
        warmup = min(ARGS.warmup, first) if ARGS.warmup >= 0 else first
        argv = [rgraph(), "render", "--frames", f"{first}..{last}", "--warmup", str(warmup),
                "--out", os.path.abspath(ARGS.out), *ARGS.rest]
        tasks.append((f"frames {first}..{last}", argv, (0,)))
    results, wall = run_tasks(client, tasks, ARGS.retries, "render")
    missing = [f for f in range(a, b + 1) if not os.path.isfile(frame_path(os.path.abspath(ARGS.out), f))]
    if missing:
        log(f"render: frames {missing} were not written")
        sys.exit(3)
    log(f"render: frames {a}..{b} in {len(tasks)} chunks, wall {wall:.1f} s, "
        f"{sum(r['seconds'] for r in results) / (b - a + 1):.2f} s of worker time a frame")
    return 0


def main(argv):
    global ARGS
    p = argparse.ArgumentParser(prog="tools/farm.py", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    cluster = p.add_mutually_exclusive_group()
    cluster.add_argument("--workers", type=int, default=2, help="a local cluster of N worker processes")
    cluster.add_argument("--scheduler", help="a running Dask scheduler's address (tcp://HOST:8786)")
    p.add_argument("--retries", type=int, default=2, help="runs again a shard whose rgraph failed")
    p.add_argument("--rgraph", default=os.path.join(ROOT, "build", "rgraph"))
    p.add_argument("--work", default=os.path.join(ROOT, "out", "farm"), help="parts, JUnit files, marks")
    sub = p.add_subparsers(dest="command", required=True)
    b = sub.add_parser("bake", help="a scene's lightmap in N shards, merged")
    b.add_argument("--shards", type=int, required=True)
    b.add_argument("--scene")
    b.add_argument("--scene-arg", action="append", default=[])
    b.add_argument("--out")
    b.add_argument("--threads", type=int, default=0,
                   help="each shard's baking threads (default: a local cluster's cores / workers, "
                        "else every core of its machine)")
    t = sub.add_parser("test", help="the golden suite in N shards, one JUnit file")
    t.add_argument("--shards", type=int, required=True)
    t.add_argument("--junit")
    t.add_argument("pattern", nargs="?")
    r = sub.add_parser("render", help="a frame range of a sequence in chunks")
    r.add_argument("--frames", required=True)
    r.add_argument("--chunk", type=int, default=8)
    r.add_argument("--warmup", type=int, default=-1,
                   help="frames rendered before each chunk, unwritten (default: every frame from 0)")
    r.add_argument("--out")
    r.add_argument("rest", nargs=argparse.REMAINDER, help="-- then options for rgraph render")
    ARGS = p.parse_args(argv)
    if getattr(ARGS, "rest", None) and ARGS.rest[:1] == ["--"]:
        ARGS.rest = ARGS.rest[1:]
    if getattr(ARGS, "shards", 1) < 1 or getattr(ARGS, "chunk", 1) < 1 or ARGS.workers < 1:
        p.error("--shards, --chunk and --workers must be at least 1")
    if not os.access(ARGS.rgraph, os.X_OK):
        p.error(f"no rgraph at {ARGS.rgraph} (build it, or pass --rgraph)")
    os.makedirs(ARGS.work, exist_ok=True)
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        p.error("needs Dask distributed (Debian: python3-distributed, tools/setup.sh installs it)")
    import logging
    logging.getLogger("distributed").setLevel(logging.ERROR)
    if ARGS.command == "bake" and not ARGS.threads and not ARGS.scheduler:
        ARGS.threads = max(1, (os.cpu_count() or 1) // ARGS.workers)
    if ARGS.scheduler:
        client, cluster = Client(ARGS.scheduler), None
    else:
        cluster = LocalCluster(n_workers=ARGS.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR)
        client = Client(cluster)
    try:
        return {"bake": bake, "test": test, "render": render}[ARGS.command](client)
    finally:
        client.close()
        if cluster:
            cluster.close()


ARGS = None

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
