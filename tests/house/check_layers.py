#!/usr/bin/env python3
"""The house's map, checked: which room of graph/ (and passes/) may include which, and that no
source file of the project outgrows one job (800 lines). The map is graph/README.md's; a new arrow
goes there and here together. Usage: check_layers.py SOURCE_ROOT. Exit 0 when the house keeps its
map, 1 with one line per break (file:line: what it includes and why that is not allowed)."""
import os
import re
import sys

# Each room and the rooms it may include from (its own always). Lower rooms never name higher ones.
ALLOWED = {
    "core": set(),
    "image": {"core"},
    "shader": {"core"},
    "lighting": {"core", "scene"},
    "layout": {"core", "shader"},
    "lua": {"core", "layout"},
    "scene": {"core", "image", "lua"},  # never lighting: the light table reads the scene
    "gpu": {"core", "image", "shader"},
    "passes": {"core", "image", "shader", "lighting", "layout", "scene", "gpu"},
    "bake": {"core", "image", "lighting", "scene"},
    "runtime": {"core", "image", "shader", "lighting", "layout", "lua", "scene", "gpu", "passes", "bake"},
    "golden": {"core", "image", "lua", "runtime", "bake"},
    "api": {"core", "image", "scene", "runtime", "rgraph"},
    "cli": {"core", "image", "shader", "lighting", "layout", "lua", "scene", "gpu", "passes", "bake", "runtime", "golden"},
}
# Files of a room that may use less than the whole room above them: the library the renderer
# links takes baked lightmaps (bake/lightmap.h) but not the baker.
NARROW = {
    ("runtime", "bake"): {"bake/lightmap.h"},
    ("golden", "bake"): {"bake/lightmap.h"},
}
# A room below `passes` does not name its namespace either (a forward declaration is an arrow too).
BELOW_PASSES = {"core", "image", "shader", "lighting", "layout", "lua", "scene", "gpu"}
NAMES_PASSES = re.compile(r"\bpasses::|namespace\s+rg::passes\b|namespace\s+passes\b")
MAX_LINES = 800
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def room_of(rel):
    parts = rel.split("/")
    if parts[0] == "graph" and len(parts) > 2:
        return parts[1]
    if parts[0] == "passes":
        return "passes"
    return None


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    rooms = set(ALLOWED)
    breaks = []
    checked = 0
    for top in ("graph", "passes", "include", "tests", "tools"):
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if not name.endswith((".cpp", ".h")):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root)
                with open(path, encoding="utf-8") as f:
                    lines = f.read().split("\n")
                checked += 1
                if len(lines) - 1 > MAX_LINES:
                    breaks.append(f"{rel}: {len(lines) - 1} lines; a file holds one job (at most {MAX_LINES} lines): split it by responsibility")
                room = room_of(rel)
                if rel.startswith("include/"):
                    for i, line in enumerate(lines, 1):
                        m = INCLUDE.match(line)
                        if m:
                            breaks.append(f"{rel}:{i}: includes \"{m.group(1)}\": the public header names nothing of rgraph's internals")
                    continue
                if room is None:
                    continue  # tests and tools may use any room
                if room not in ALLOWED:
                    breaks.append(f"{rel}: room '{room}' is not on the map (tests/house/check_layers.py, graph/README.md)")
                    continue
                for i, line in enumerate(lines, 1):
                    code = line.split("//")[0]
                    if room in BELOW_PASSES and NAMES_PASSES.search(code):
                        breaks.append(f"{rel}:{i}: names rg::passes: '{room}' is below 'passes' and may not know it")
                    m = INCLUDE.match(line)
                    if not m or "/" not in m.group(1):
                        continue  # a file of the same room
                    target = m.group(1).split("/")[0]
                    if target not in rooms and target != "rgraph":
                        continue  # a third-party header in quotes
                    if target == room:
                        continue
                    if target not in ALLOWED[room]:
                        breaks.append(f"{rel}:{i}: includes \"{m.group(1)}\": '{room}' may not use '{target}' "
                                      f"(it may use: {', '.join(sorted(ALLOWED[room])) or 'nothing'})")
                    elif (room, target) in NARROW and m.group(1) not in NARROW[(room, target)]:
                        breaks.append(f"{rel}:{i}: includes \"{m.group(1)}\": '{room}' may use only "
                                      f"{', '.join(sorted(NARROW[(room, target)]))} of '{target}'")
    for b in breaks:
        print(b)
    print(f"check_layers: {checked} files, {len(breaks)} breaks of the map")
    return 1 if breaks else 0


if __name__ == "__main__":
    sys.exit(main())
