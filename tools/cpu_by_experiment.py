"""The CPU time of each experiment of `reproduce`, run alone.

`reproduce --record-times` keeps the wall time of each experiment while the others
run beside it (data/reproduce_times.csv); that cannot say where the CPU goes, since
the experiments share the cores. This script runs `evhi reproduce --quiet NAME` (the
full experiment, without progress bars) for each
experiment of the full set in a fresh process, one after the other, and keeps the
process's own accounting (wait4: user and system seconds of all its threads, peak
resident memory) with the wall time:

    python3 tools/cpu_by_experiment.py [--bin target/release/evhi] [--out data/reproduce_cpu.csv]

Run it from the repository root on a quiet machine after `cargo build --release`;
each run rewrites its experiment's files under data/ and figures/ with what is
committed (the main job's promise), so `git status` stays clean. The experiments, and
their order, are those of the set `all` in data/reproduce_times.csv (rewrite it with
`reproduce --record-times` when the set changes). The last row sums the others.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time


def machine():
    cpu = "unknown CPU"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    mem = int(open("/proc/meminfo").readline().split()[1]) / 1048576.0
    # The logical CPUs this process may use (evhi's own count also heeds cgroup quotas).
    return f"{cpu}, {len(os.sched_getaffinity(0))} cores, {mem:.0f} GiB"


def experiments(times_csv):
    names = []
    for line in open(times_csv):
        parts = line.strip().split(",")
        if len(parts) == 3 and parts[0] == "all" and not parts[1].startswith("("):
            names.append(parts[1])
    if not names:
        sys.exit(f"{times_csv}: no row of the set `all`")
    return names


def run(binary, name):
    # stderr goes to a file, not a pipe: a pipe read only after the wait would block a
    # child that writes more than the pipe holds.
    with tempfile.TemporaryFile() as err:
        start = time.monotonic()
        proc = subprocess.Popen(
            [binary, "reproduce", "--quiet", name], stdout=subprocess.DEVNULL, stderr=err
        )
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.monotonic() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode != 0:
            err.seek(0)
            text = err.read().decode("utf-8", "replace")
            sys.exit(f"`{binary} reproduce --quiet {name}` failed ({proc.returncode}):\n{text}")
    # ru_maxrss is in KiB on Linux.
    return wall, usage.ru_utime, usage.ru_stime, usage.ru_maxrss / 1024.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", default="target/release/evhi")
    ap.add_argument("--times", default="data/reproduce_times.csv")
    ap.add_argument("--out", default="data/reproduce_cpu.csv")
    args = ap.parse_args()
    if not os.access(args.bin, os.X_OK):
        sys.exit(f"--bin {args.bin}: not an executable (run `cargo build --release` first)")
    # The tree the binary is assumed to be built from ("-dirty": with uncommitted changes).
    git = lambda *a: subprocess.run(["git", *a], capture_output=True, text=True)
    commit = git("rev-parse", "--short", "HEAD").stdout.strip() or "unknown"
    if git("status", "--porcelain", "--untracked-files=no").stdout.strip():
        commit += "-dirty"
    day = time.strftime("%Y-%m-%d", time.gmtime())
    rows = []
    for name in experiments(args.times):
        wall, user, sys_s, rss = run(args.bin, name)
        print(f"{name}: {wall:.1f} s wall, {user + sys_s:.1f} s CPU", file=sys.stderr)
        rows.append((name, wall, user, sys_s, user + sys_s, rss))
    total = ["(sum)"] + [sum(r[i] for r in rows) for i in range(1, 5)] + [max(r[5] for r in rows)]
    lines = [
        "# produced by `python3 tools/cpu_by_experiment.py` on "
        + day
        + " at commit "
        + commit
        + " (evhi: --bin "
        + args.bin
        + ", assumed built from that tree)",
        "# each experiment of `evhi reproduce` alone, `evhi reproduce --quiet NAME` in a fresh "
        "process, one after the other, once; wall, user and system seconds and peak "
        "resident memory (MiB) of the whole process as wait4 reports them (every thread "
        "counted); the last row sums the others (its peak is the largest); machine: "
        + machine(),
        "experiment,wall_s,user_s,sys_s,cpu_s,peak_rss_mib",
    ]
    for r in rows + [tuple(total)]:
        lines.append(f"{r[0]},{r[1]:.2f},{r[2]:.2f},{r[3]:.2f},{r[4]:.2f},{r[5]:.0f}")
    tmp = args.out + f".tmp-{os.getpid()}"
    try:
        with open(tmp, "w") as f:
            f.write("\n".join(lines) + "\n")
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, args.out)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
