#!/usr/bin/env python3
"""Size report of leptrino for a bare-metal target, as JSON on stdout.

- core: .text/.data/.bss of each object of libleptrino.a and their total
  (flash = text + data), from the target's `size`;
- contexts: sizeof each context (lep_client, lep_device, lep_frame_decoder),
  read from the symbol sizes of cmake/size_contexts.c compiled for the target;
- firmware: the MCU example (examples/mcu) linked with --gc-sections: its
  total, and the sections it keeps from libleptrino.a, per object, read from
  the linker map (what a host-client firmware really pays for leptrino),
  apart from the C library and compiler runtime it pulls in.

With --check, each budget is printed to stderr as "budget <name>: <value> <=
<limit> ok|FAIL", with "(target T NOT MET; ceiling C)" where the figure is
above issue 12's target but within the regression ceiling; the exit status is
1 if any figure exceeds its ceiling.
"""
import argparse
import json
import os
import re
import subprocess
import sys

# name, target (issue 12), ceiling enforced now, path in the report.
# Where the measured figure is above its target, the ceiling is the figure as
# measured when the target was last missed (a regression guard): the check
# then fails on growth and prints the target as not met. Lower a ceiling to
# its target as soon as the code fits; never raise one without saying why.
BUDGETS = [
    # 5811 + 12: LEP_E_LOST's text "stream lost" (issue 21: the session's lost
    # stream is its own code, and every code has its text in the core)
    ("core_flash_bytes", 5 * 1024, 5823, ("core", "total", "flash")),
    ("core_data_bss_bytes", 0, 0, ("core", "total", "data_bss")),
    ("firmware_leptrino_code_bytes", 2 * 1024, 2205, ("firmware", "leptrino", "flash")),
    ("firmware_leptrino_data_bss_bytes", 0, 0, ("firmware", "leptrino", "data_bss")),
    ("client_context_bytes", 256, 256, ("contexts", "lep_client")),
]


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def core_sizes(size_tool, library):
    objects = {}
    for line in run([size_tool, "-B", library]).splitlines()[1:]:
        f = line.split()
        if len(f) < 6:
            continue
        name = re.sub(r" \(ex .*\)$", "", " ".join(f[5:]))
        name = re.sub(r"\.obj$|\.o$", "", name)
        text, data, bss = int(f[0]), int(f[1]), int(f[2])
        objects[name] = {"text": text, "data": data, "bss": bss}
    return objects, total(objects.values())


def total(rows):
    t = {"text": 0, "data": 0, "bss": 0}
    for r in rows:
        for k in t:
            t[k] += r[k]
    t["flash"] = t["text"] + t["data"]
    t["data_bss"] = t["data"] + t["bss"]
    return t


def contexts(nm_tool, obj):
    out = {}
    for line in run([nm_tool, "-S", obj]).splitlines():
        f = line.split()
        if len(f) == 4 and f[3].startswith("lep_sizeof_"):
            out[f[3][len("lep_sizeof_"):]] = int(f[1], 16)
    return out


NOT_LOADED = (".debug", ".comment", ".ARM.attributes", ".stab", ".gnu.attributes", ".note", ".line")


def kind_of(output_section):
    if output_section.startswith(".bss") or output_section.startswith(".noinit"):
        return "bss"
    if output_section.startswith(".data"):
        return "data"
    return "text"


def map_sizes(map_path, library_name):
    """Kept input sections of the linker map, grouped into leptrino (objects of
    library_name), runtime (libc, libgcc) and application."""
    lines = open(map_path, encoding="utf-8", errors="replace").read().splitlines()
    try:
        start = lines.index("Linker script and memory map")
    except ValueError:
        sys.exit(f"{map_path}: not a GNU ld map")
    groups = {"leptrino": {}, "runtime": {}, "application": {}}
    out_sec = None
    pending = None
    entry = re.compile(r"^\s+0x([0-9a-fA-F]+)\s+0x([0-9a-fA-F]+)\s+(\S.*)$")
    for line in lines[start + 1:]:
        if line.startswith("."):
            out_sec = line.split()[0]
            if out_sec.startswith(NOT_LOADED):
                out_sec = None  # debug info, comments, attributes: not in the image
            pending = None
            continue
        if out_sec is None or line.startswith("/DISCARD/") or line.startswith("OUTPUT("):
            if line.startswith("/DISCARD/"):
                out_sec = None
            continue
        m = re.match(r"^ (\.\S+|COMMON)\s*(.*)$", line)
        rest = None
        if m:
            rest = m.group(2)
            pending = m.group(1)
            if not rest:
                continue
            line = " " * 16 + rest
        me = entry.match(line)
        if not me or pending is None:
            continue
        size, origin = int(me.group(2), 16), me.group(3).strip()
        pending = None
        if size == 0:
            continue
        mo = re.match(r"^(.*?)\((.*)\)$", origin)
        if mo and os.path.basename(mo.group(1)) == library_name:
            group, obj = "leptrino", re.sub(r"\.obj$|\.o$", "", mo.group(2))
        elif mo:
            group, obj = "runtime", os.path.basename(mo.group(1))
        else:
            group, obj = "application", re.sub(r"\.obj$|\.o$", "", os.path.basename(origin))
        row = groups[group].setdefault(obj, {"text": 0, "data": 0, "bss": 0})
        row[kind_of(out_sec)] += size
    result = {}
    for g, objs in groups.items():
        result[g] = dict(total(objs.values()), by_object=objs)
    return result


def lookup(report, path):
    v = report
    for p in path:
        v = v[p]
    return v


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--target", required=True)
    ap.add_argument("--flags", default="")
    ap.add_argument("--size-tool", required=True)
    ap.add_argument("--nm-tool", required=True)
    ap.add_argument("--library", required=True)
    ap.add_argument("--contexts", required=True)
    ap.add_argument("--firmware")
    ap.add_argument("--map")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--output")
    a = ap.parse_args()

    objects, core_total = core_sizes(a.size_tool, a.library)
    report = {
        "target": a.target,
        "flags": a.flags,
        "core": {"objects": objects, "total": core_total},
        "contexts": contexts(a.nm_tool, a.contexts),
    }
    if a.firmware and a.map:
        fw_objs, fw_total = core_sizes(a.size_tool, a.firmware)
        report["firmware"] = {"name": os.path.basename(a.firmware), "total": fw_total}
        report["firmware"].update(map_sizes(a.map, os.path.basename(a.library)))

    failed = False
    if a.check:
        report["budgets"] = {}
        for name, target, ceiling, path in BUDGETS:
            try:
                value = lookup(report, path)
            except KeyError:
                print(f"budget {name}: not measured FAIL", file=sys.stderr)
                failed = True
                continue
            ok = value <= ceiling
            failed |= not ok
            report["budgets"][name] = {"value": value, "target": target, "ceiling": ceiling,
                                       "target_met": value <= target, "ok": ok}
            verdict = "ok" if ok else "FAIL"
            note = "" if value <= target else f" (target {target} NOT MET; ceiling {ceiling})"
            print(f"budget {name}: {value} <= {min(target, ceiling) if value <= target else ceiling} "
                  f"{verdict}{note}", file=sys.stderr)
    text = json.dumps(report, indent=2)
    print(text)
    if a.output:
        with open(a.output, "w", encoding="utf-8") as f:
            f.write(text + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
