#!/usr/bin/env python3
"""CPU time of a whole process, as a user runs it: start, work and exit.

Runs COMMAND REPEATS times and prints the median user, system and total
CPU seconds of the child process (getrusage(RUSAGE_CHILDREN) before and
after each run), and the least total. The figures of docs/performance.md's
whole-process table, e.g.

    bench/process_cpu.py 15 ./build/apps/impactkit simulate --omega 0.6 \\
        --transient 0 --periods 100000

    process_cpu.py REPEATS COMMAND...
"""
import resource
import statistics
import subprocess
import sys


def main():
    if len(sys.argv) < 3 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        sys.exit(__doc__)
    repeats, command = int(sys.argv[1]), sys.argv[2:]
    user, system = [], []
    for _ in range(repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(command, stdout=subprocess.DEVNULL, check=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        user.append(after.ru_utime - before.ru_utime)
        system.append(after.ru_stime - before.ru_stime)
    total = [u + s for u, s in zip(user, system)]
    print(f"user {statistics.median(user):.4f} s, system {statistics.median(system):.4f} s, "
          f"total {statistics.median(total):.4f} s (median of {repeats}; least {min(total):.4f} s)")


if __name__ == "__main__":
    main()
