#!/usr/bin/env python3
"""Estimates a command's wall time on an idle machine from a run on a busy one.

    scripts/quiet-wall.py [--cores N] -- build/apps/msp fit MESH -o X.glb --json X.json

Runs the command under `perf sched record` (root, or perf_event_paranoid <= 1) and replays the
scheduler trace of its threads: at each instant r of them want a core (running or runnable) and a
of them run; on an idle machine with N cores the same work would go min(N, r) / a times faster,
so the instant counts dt * a / min(N, r) (dt while r = 0: the command waits for something else).
On a machine shared by other work this removes the waiting for the other processes and keeps the
command's own structure: its serial parts, its threads, its waits on them. With `msp fit` (no
--quiet) the stages it prints on stderr split the estimate ("fill", "tessellate2" for the second
time a stage runs). Prints one line per stage: estimated idle-machine seconds and CPU seconds.
"""
import collections
import os
import re
import subprocess
import sys
import tempfile
import threading
import time


def record(command, trace):
    """Runs command under perf sched; returns [(monotonic time, stage)] from its stderr."""
    stamps = []
    perf = ["perf", "sched", "record", "-k", "mono", "-o", trace, "--"] + command
    proc = subprocess.Popen(perf, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)

    def read():
        buf = b""
        while True:
            c = proc.stderr.read(1)
            if not c:
                break
            buf += c
            if buf.endswith(b"..."):
                name = buf.rsplit(b": ", 1)[-1][:-3].decode(errors="replace").strip()
                stamps.append((time.clock_gettime(time.CLOCK_MONOTONIC), name))
                buf = b""
            elif c == b"\n":
                buf = b""

    reader = threading.Thread(target=read)
    reader.start()
    proc.wait()
    reader.join()
    end = time.clock_gettime(time.CLOCK_MONOTONIC)
    if proc.returncode != 0:
        sys.exit("quiet-wall: the command (or perf) failed with status %d" % proc.returncode)
    count = collections.Counter()
    named = []
    for t, name in stamps:
        count[name] += 1
        named.append((t, name if count[name] == 1 else "%s%d" % (name, count[name])))
    return named, end


EVENT = re.compile(r"\s*\S+\s+(-?\d+)/(-?\d+)\s+([\d.]+):\s+(\S+):\s*(.*)")


def replay(trace, stamps, end, cores):
    out = subprocess.run(["perf", "script", "-i", trace, "-F", "comm,pid,tid,time,event,trace"],
                         capture_output=True, text=True, check=True).stdout
    root, mine, state = None, set(), {}
    quiet, cpu = collections.Counter(), collections.Counter()
    last = None

    def stage(t):
        name = "start"
        for s, n in stamps:
            if t >= s:
                name = n
        return name

    for line in out.splitlines():
        m = EVENT.match(line)
        if not m:
            continue
        t, event, body = float(m.group(3)), m.group(4), m.group(5)
        if root is not None and last is not None and t > last and last < end:
            running = sum(1 for v in state.values() if v == "run")
            wanting = running + sum(1 for v in state.values() if v == "wait")
            name = stage(last)
            dt = t - last
            quiet[name] += dt if wanting == 0 else dt * running / min(cores, wanting)
            cpu[name] += dt * running
        last = t
        if root is None:
            m = re.search(r"comm=perf-exec pid=(\d+)", body)
            if m:
                root = int(m.group(1))
                mine.add(root)
                state[root] = "wait"
            continue
        if event == "sched:sched_process_fork":
            m = re.search(r" pid=(\d+) child_comm=\S+ child_pid=(\d+)", body)
            if m and int(m.group(1)) in mine:
                mine.add(int(m.group(2)))
                state[int(m.group(2))] = "sleep"
        elif event == "sched:sched_switch":
            m = re.search(r"prev_pid=(\d+).*prev_state=(\S+) ==> .*next_pid=(\d+)", body)
            prev, prev_state, nxt = int(m.group(1)), m.group(2), int(m.group(3))
            if prev in mine:
                state[prev] = "wait" if prev_state.startswith("R") else "sleep"
            if nxt in mine:
                state[nxt] = "run"
        elif event in ("sched:sched_waking", "sched:sched_wakeup", "sched:sched_wakeup_new"):
            m = re.search(r"pid=(\d+)", body)
            who = int(m.group(1))
            if who in mine and state.get(who) != "run":
                state[who] = "wait"
    return quiet, cpu


def main():
    args = sys.argv[1:]
    cores = os.cpu_count() or 1
    if args[:1] == ["--cores"]:
        cores, args = int(args[1]), args[2:]
    if args[:1] == ["--"]:
        args = args[1:]
    if not args:
        sys.exit(__doc__)
    with tempfile.TemporaryDirectory() as tmp:
        trace = os.path.join(tmp, "sched.data")
        stamps, end = record(args, trace)
        quiet, cpu = replay(trace, stamps, end, cores)
    order = ["start"] + [n for _, n in stamps]
    print("%-16s %8s %8s" % ("stage", "idle s", "cpu s"))
    for name in order:
        if name in quiet:
            print("%-16s %8.3f %8.3f" % (name, quiet[name], cpu[name]))
    print("%-16s %8.3f %8.3f" % ("total", sum(quiet.values()), sum(cpu.values())))


if __name__ == "__main__":
    main()
