#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Helpers for bench/compare_peers.sh (python3 standard library only).

  peerlib.py exec TIMING STDOUT STDERR -- CMD...
                                        run CMD, write {"wall", "cpu"} of the whole
                                        process tree to TIMING; exit status of CMD
  peerlib.py liggghts LOG CODE CONFIG [TIMING [ROUND]]   one JSON result line from a LIGGGHTS
                                        (or LAMMPS) log
  peerlib.py tumble STDOUT CODE CONFIG [TIMING [ROUND]]  one JSON result line from `tumble bench --json`
  peerlib.py table RESULTS.jsonl        the comparison table (medians per config), and the
                                        ratios round by round with intervals

cpu/wall of a whole process (setup and warm-up included) is the contention
indicator: about 1 per process when it had a core to itself, lower when it
waited for one (other jobs on the machine).

A result line has: code, config, size, particles, steps, seconds,
updates_per_second, contacts_per_particle, neighbor_builds, procs.
updates/s = particles * steps / wall time of the timed run.
"""
import json
import math
import os
import re
import resource
import statistics
import subprocess
import sys
import time

LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
BUILDS = re.compile(r"Neighbor list builds = (\d+)")
DANGEROUS = re.compile(r"Dangerous builds = (\d+)")
# the code's own count of its memory per process, MB: LIGGGHTS, then LAMMPS
MEMORY = re.compile(r"(?:Memory usage per processor = |Per MPI rank memory allocation \(min/avg/max\) = [0-9.]+ \| )"
                    r"([0-9.]+)")
THERMO_HEAD = re.compile(r"^\s*Step\s+Atoms\s+KinEng\s+(c_)?rke\s+(c_)?zavg\s*$")  # LIGGGHTS, LAMMPS


# Two-sided 95 % quantiles of Student's t for 1 to 30 degrees of freedom.
T_975 = (12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
         2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042)


def ratio_interval(ratios):
    """The geometric mean of ratios paired round by round (each from two runs
    of the same round, so that the host's speed of the hour cancels), with its
    95 % t interval on their logarithms: (mean, low, high); low and high are
    None for fewer than 2 ratios."""
    logs = [math.log(x) for x in ratios]
    mean = statistics.fmean(logs)
    if len(logs) < 2:
        return math.exp(mean), None, None
    dof = len(logs) - 1
    half = (T_975[dof - 1] if dof <= len(T_975) else 1.96) * statistics.stdev(logs) / math.sqrt(len(logs))
    return math.exp(mean), math.exp(mean - half), math.exp(mean + half)


def fmt_interval(ratios):
    mean, low, high = ratio_interval(ratios)
    return f"{mean:.3f}" if low is None else f"{mean:.3f} [{low:.3f}, {high:.3f}]"


def print_round_ratios(rounds, pairs, rate):
    """The ratios of pairs of configurations within each round: rounds maps
    a round to {configuration: result}, pairs lists (name, numerator
    configuration, denominator configuration), rate names the result's
    speed. Each ratio with the rounds that ran both, their geometric mean
    and 95 % t interval (ratio_interval), median and values."""
    out = []
    for name, top, bottom in pairs:
        ratios = [runs[top][rate] / runs[bottom][rate] for _, runs in sorted(rounds.items())
                  if top in runs and bottom in runs]
        if ratios:
            out.append((name, str(len(ratios)), fmt_interval(ratios), f"{statistics.median(ratios):.3f}",
                        " ".join(f"{x:.3f}" for x in ratios)))
    if out:
        print()
        print_table(("round by round", "rounds", "geometric mean [95 % t]", "median", "by round"), out)
        print()


def fail(msg):
    print(f"peerlib: {msg}", file=sys.stderr)
    sys.exit(1)


def parse_liggghts(path, code, config):
    text = open(path, encoding="utf-8", errors="replace").read()
    if "ERROR" in text:
        line = next(l for l in text.splitlines() if "ERROR" in l)
        fail(f"{path}: LIGGGHTS stopped: {line.strip()}")
    loops = LOOP.findall(text)
    if not loops:
        fail(f"{path}: no 'Loop time of ...' line (did LIGGGHTS finish?)")
    seconds, procs, steps, atoms = loops[-1]  # the last run is the timed one
    seconds, procs, steps, atoms = float(seconds), int(procs), int(steps), int(atoms)
    builds = BUILDS.findall(text)
    dangerous = DANGEROUS.findall(text)
    # last thermo line of the timed run: step atoms ke rke zavg
    lines = text.splitlines()
    z = None
    atoms_end = None
    for i, l in enumerate(lines):
        if THERMO_HEAD.match(l):
            j = i + 1
            while j < len(lines) and re.match(r"^\s*\d+\s", lines[j]):
                f = lines[j].split()
                atoms_end, z = int(f[1]), float(f[4])
                j += 1
    size = round(atoms ** (1.0 / 3.0))
    memory = MEMORY.findall(text)
    return {
        "code": code, "config": config, "size": size, "particles": atoms,
        "particles_end": atoms_end, "steps": steps, "seconds": seconds,
        "updates_per_second": atoms * steps / seconds,
        "contacts_per_particle": z,
        "neighbor_builds": int(builds[-1]) if builds else None,
        "dangerous_builds": int(dangerous[-1]) if dangerous else None,
        "procs": procs,
        "bytes_per_particle": float(memory[-1]) * 2**20 * procs / atoms if memory else None,
    }


def parse_tumble(path, code, config):
    lines = [l for l in open(path, encoding="utf-8", errors="replace").read().splitlines() if l.strip()]
    if not lines:
        fail(f"{path}: tumble bench printed nothing")
    try:
        d = json.loads(lines[-1])
    except json.JSONDecodeError as e:
        fail(f"{path}: last line of `tumble bench --json` is not JSON ({e}): {lines[-1][:200]}")
    for k in ("particles", "steps", "seconds", "updates_per_second", "contacts_per_particle"):
        if k not in d:
            fail(f"{path}: tumble bench JSON lacks '{k}'")
    n = int(d["particles"])
    return {
        "code": code, "config": config, "size": round(n ** (1.0 / 3.0)), "particles": n,
        "particles_end": n, "steps": int(d["steps"]), "seconds": float(d["seconds"]),
        "updates_per_second": float(d["updates_per_second"]),
        "contacts_per_particle": float(d["contacts_per_particle"]),
        "neighbor_builds": d.get("neighbor_builds"), "dangerous_builds": None,
        "procs": int(d.get("threads", 1)), "version": d.get("version"),
        "bytes_per_particle": d.get("bytes_per_particle"),
    }


def run_timed(timing, stdout, stderr, cmd):
    t0 = time.monotonic()
    with open(stdout, "wb") as o:
        if os.path.abspath(stderr) == os.path.abspath(stdout):
            rc = subprocess.call(cmd, stdout=o, stderr=subprocess.STDOUT)
        else:
            with open(stderr, "wb") as e:
                rc = subprocess.call(cmd, stdout=o, stderr=e)
    wall = time.monotonic() - t0
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)  # all waited-for descendants
    with open(timing, "w") as f:
        json.dump({"wall": wall, "cpu": ru.ru_utime + ru.ru_stime, "rc": rc}, f)
    return rc


def add_timing(result, timing):
    if timing and os.path.exists(timing):
        t = json.load(open(timing))
        result["process_wall"] = t["wall"]
        result["process_cpu"] = t["cpu"]
        result["cpu_per_wall"] = t["cpu"] / t["wall"] if t["wall"] > 0 else None
    return result


def fmt_rate(x):
    return f"{x / 1e6:.3f} M" if x >= 1e6 else f"{x / 1e3:.1f} k"


def print_table(header, rows):
    """Prints rows of strings under a header, columns padded to their widest cell."""
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(header)]
    line = lambda cells: "  ".join(c.ljust(w) for c, w in zip(cells, widths)).rstrip()
    print(line(header))
    print(line(["-" * w for w in widths]))
    for r in rows:
        print(line(r))


def table(path):
    rows = [json.loads(l) for l in open(path, encoding="utf-8") if l.strip()]
    if not rows:
        fail(f"{path}: no results")
    groups = {}
    for r in rows:
        groups.setdefault((r["size"], r["code"], r["config"]), []).append(r)
    summary = []
    for (size, code, config), rs in groups.items():
        ups = [r["updates_per_second"] for r in rs]
        summary.append({
            "size": size, "code": code, "config": config, "particles": rs[0]["particles"],
            "steps": rs[0]["steps"], "runs": len(rs), "median": statistics.median(ups),
            "min": min(ups), "max": max(ups),
            "seconds": statistics.median(r["seconds"] for r in rs),
            "z": rs[-1]["contacts_per_particle"], "builds": rs[-1]["neighbor_builds"],
            "lost": any(r["particles_end"] not in (None, r["particles"]) for r in rs),
            "cpu_wall": [r["cpu_per_wall"] for r in rs if r.get("cpu_per_wall") is not None],
            "procs": rs[0].get("procs", 1),
            "memory": rs[-1].get("bytes_per_particle"),
        })
    summary.sort(key=lambda s: (s["size"], s["code"] != "tumble", s["code"], s["procs"], s["config"]))
    hdr = ("N", "code", "config", "runs", "median updates/s", "min..max", "wall s",
           "cpu/wall", "contacts/sphere", "nbr builds", "bytes/sphere", "tumble/peer")
    out = []
    for s in summary:
        # tumble on as many threads as the peer has processes
        t = [x for x in summary if x["size"] == s["size"] and x["code"] == "tumble" and x["procs"] == s["procs"]]
        t1 = [x for x in summary if x["size"] == s["size"] and x["code"] == "tumble" and x["procs"] == 1]
        if s["code"] == "tumble":
            ratio = "-" if s["procs"] == 1 or not t1 else f"x{s['median'] / t1[0]['median']:.2f} vs 1 thread"
        elif t:
            ratio = f"{t[0]['median'] / s['median']:.2f}"
        else:
            ratio = "n/a"
        out.append((f"{s['particles']}", s["code"], s["config"], str(s["runs"]), fmt_rate(s["median"]),
                    f"{fmt_rate(s['min'])}..{fmt_rate(s['max'])}", f"{s['seconds']:.2f}",
                    "?" if not s["cpu_wall"] else f"{min(s['cpu_wall']):.2f}..{max(s['cpu_wall']):.2f}",
                    "?" if s["z"] is None else f"{s['z']:.3f}",
                    "?" if s["builds"] is None else str(s["builds"]),
                    "?" if s["memory"] is None else f"{s['memory']:.0f}", ratio))
    print_table(hdr, out)
    rounds = {}  # (size, round): {(size, code, config, procs): result}
    for r in rows:
        if "round" in r:
            rounds.setdefault((r["size"], r["round"]), {})[(r["size"], r["code"], r["config"], r.get("procs", 1))] = r
    configs = sorted({k for runs in rounds.values() for k in runs}, key=lambda k: (k[0], k[1] != "tumble", k[1:]))
    pairs = []
    for size, code, config, procs in configs:
        tumble = [k for k in configs if k[0] == size and k[1] == "tumble" and k[3] == procs]
        one = [k for k in configs if k[0] == size and k[1] == "tumble" and k[3] == 1]
        if code != "tumble" and tumble:
            pairs.append((f"N={size}^3: tumble {tumble[0][2]} / {code} {config}", tumble[0], (size, code, config, procs)))
        if code == "tumble" and procs > 1 and one:
            pairs.append((f"N={size}^3: tumble {config} / {one[0][2]}", (size, code, config, procs), one[0]))
    print_round_ratios(rounds, pairs, "updates_per_second")
    bad = [s for s in summary if s["lost"]]
    for s in bad:
        print(f"WARNING: {s['code']} {s['config']} N={s['particles']}: atom count changed during the run")
    for s in summary:
        if s["z"] is not None and not (5.0 <= s["z"] <= 7.0):
            print(f"WARNING: {s['code']} {s['config']} N={s['particles']}: "
                  f"{s['z']:.3f} contacts per sphere, expected about 6")
    print("steps per run: " + ", ".join(sorted({f"{s['steps']}" for s in summary})) +
          "; updates/s = particles x steps / wall time of the timed steps; ratio = tumble median / peer median,"
          " tumble on as many threads as the peer has MPI ranks")
    print("bytes/sphere: tumble: growth of its resident memory over the set-up and run; peers: their own"
          " count of memory per process (LIGGGHTS 'Memory usage per processor', LAMMPS 'Per MPI rank memory"
          " allocation', avg) x processes / spheres, fixed overhead included")
    print("cpu/wall: CPU time over wall time of each whole process, about 1 per process when it had"
          " its cores to itself; lower values mean it waited for a CPU and its numbers are low")


def main(argv):
    if len(argv) >= 7 and argv[1] == "exec" and argv[5] == "--":
        sys.exit(run_timed(argv[2], argv[3], argv[4], argv[6:]))
    elif len(argv) in (5, 6, 7) and argv[1] in ("liggghts", "tumble"):
        f = parse_liggghts if argv[1] == "liggghts" else parse_tumble
        result = add_timing(f(argv[2], argv[3], argv[4]), argv[5] if len(argv) >= 6 else None)
        if len(argv) == 7:
            result["round"] = int(argv[6])
        print(json.dumps(result))
    elif len(argv) == 3 and argv[1] == "table":
        table(argv[2])
    else:
        fail(__doc__)


if __name__ == "__main__":
    main(sys.argv)

