#!/usr/bin/env python3
"""Docs examples must not rot.

Runs every command line (`$ ...`) of the ```console blocks of each DOC, in
order, with `impactkit` (or `./build/apps/impactkit`) standing for the built
binary, and fails naming the first command that does not do what the doc
shows:

- a command whose shown output starts with `impactkit: error:` must exit with
  status 2 and print exactly that line on stderr;
- every other command must exit with status 0, and the lines shown under it
  must be the lines it prints on stdout, in order and all of them. A shown
  line `...` stands for any number of printed lines (an elision the reader
  sees); what varies from run to run or machine to machine is compared as a
  placeholder: durations ("0.0016 s", "1.2 min"), rates per second, thread
  and core counts, and the scratch directory the commands run in. A command
  shown without output is only run.

With IMPACTKIT_DOCS_UPDATE=1 the shown output of each command that has no
`...` is replaced by what it prints (how the samples are made; review the
diff), and only the rest is checked.

The commands run in a scratch directory holding `out/` and a copy of
examples/systems/, so that the paths the docs use resolve and nothing is
written into the source tree.

    check_docs.py IMPACTKIT SOURCE_DIR DOC...
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# What differs between runs of one command, each with its placeholder.
VARYING = [
    (re.compile(r"\d+(\.\d+)?(e[-+]?\d+)? ?(s|ms|min|µs)\b(?!/)"), "<time>"),
    (re.compile(r"\d+(\.\d+)?(e[-+]?\d+)? (cells|values|impacts|periods)/(CPU-)?s\b"), "<rate>"),
    (re.compile(r"\b\d+ (threads|cores|workers)\b"), "<n> \\1"),
    (re.compile(r"\b\d+ (thread|core|worker)\b"), "<n> \\1s"),
    (re.compile(r"\bimpactkit \d+\.\d+\.\d+\b"), "impactkit <version>"),
]
ELISION = "..."


# IMPACTKIT_DOCS_ALL=1: report every difference, not only the first.
REPORT_ALL = os.environ.get("IMPACTKIT_DOCS_ALL") == "1"
UPDATE = os.environ.get("IMPACTKIT_DOCS_UPDATE") == "1"
failures = []


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    failures.append(message)
    if not REPORT_ALL:
        sys.exit(1)


def console_commands(path):
    """[line number, command, shown output lines, index of the first output
    line in the file] of each `$ ` command."""
    commands, inside, current = [], False, None
    continued = False
    with open(path, encoding="utf-8") as doc:
        for number, raw in enumerate(doc, start=1):
            line = raw.rstrip("\n")
            if re.fullmatch(r"```console\s*", line):
                inside = True
                continue
            if line.startswith("```"):
                inside, continued = False, False
                continue
            if not inside:
                continue
            if continued:
                current[3] = number  # the output begins after the command's last line
                current[1] += " " + line.strip()
                continued = current[1].endswith("\\")
                current[1] = current[1].rstrip("\\").rstrip()
                continue
            if line.startswith("$ "):
                command = re.sub(r"^\./build/apps/impactkit( |$)", r"impactkit\1", line[2:])
                current = [number, command, [], number]
                commands.append(current)
                continued = command.endswith("\\")
                current[1] = command.rstrip("\\").rstrip()
                continue
            if current is not None:
                current[2].append(line)
    return commands


def normalized(line, run_dir):
    line = line.replace(run_dir + "/", "").replace(run_dir, ".")
    for pattern, placeholder in VARYING:
        line = pattern.sub(placeholder, line)
    return line.rstrip()


def matches(shown, printed):
    """Whether the shown lines are the printed ones, `...` eliding any run."""
    if not shown:
        return not printed
    if shown[0] == ELISION:
        return any(matches(shown[1:], printed[k:]) for k in range(len(printed) + 1))
    return bool(printed) and shown[0] == printed[0] and matches(shown[1:], printed[1:])


def first_difference(shown, printed):
    for k, (a, b) in enumerate(zip(shown, printed)):
        if a != b and a != ELISION:
            return f"line {k + 1}: the doc shows\n    {a}\n  the command prints\n    {b}"
    if len(shown) < len(printed):
        return f"the command prints more: {printed[len(shown)]!r}"
    return f"the doc shows more: {shown[len(printed)]!r}"


def main():
    impactkit, source_dir, docs = os.path.realpath(sys.argv[1]), sys.argv[2], sys.argv[3:]
    work = tempfile.mkdtemp(prefix="impactkit-docs.")
    try:
        run_dir = os.path.join(work, "run")
        os.makedirs(os.path.join(run_dir, "out"))
        shutil.copytree(os.path.join(source_dir, "examples", "systems"),
                        os.path.join(run_dir, "examples", "systems"))
        bin_dir = os.path.join(work, "bin")
        os.makedirs(bin_dir)
        os.symlink(impactkit, os.path.join(bin_dir, "impactkit"))
        env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ["PATH"])
        total = 0
        for doc in docs:
            name = os.path.relpath(doc, source_dir)
            commands = console_commands(doc)
            if not any(c.startswith("impactkit ") for _, c, _, _ in commands):
                fail(f"{name}: no `$ impactkit` command in a console block")
            replacements = []  # (first output line index, old count, new lines)
            for number, command, shown, first in commands:
                result = subprocess.run(["bash", "-c", command], cwd=run_dir, env=env,
                                        stdin=subprocess.DEVNULL, capture_output=True, text=True)
                where = f"{name}:{number}: `{command}`"
                while shown and not shown[-1].strip():
                    shown.pop()
                if shown and shown[0].startswith("impactkit: error:"):
                    if result.returncode != 2:
                        fail(f"{where} exited with {result.returncode}, the doc shows an error (2)")
                    if result.stderr.rstrip("\n") != shown[0]:
                        fail(f"{where} printed {result.stderr.strip()!r}, the doc shows {shown[0]!r}")
                else:
                    if result.returncode != 0:
                        fail(f"{where} exited with status {result.returncode}: "
                             f"{result.stderr[:2000]}")
                    if shown and UPDATE and ELISION not in shown:
                        printed = result.stdout.replace(run_dir + "/", "").splitlines()
                        replacements.append((first, len(shown), printed))
                    elif shown:
                        want = [normalized(line, run_dir) for line in shown]
                        got = [normalized(line, run_dir) for line in result.stdout.splitlines()]
                        if not matches(want, got):
                            fail(f"{where}: {first_difference(want, got)}")
                total += 1
            if replacements:
                with open(doc, encoding="utf-8") as f:
                    lines = f.read().split("\n")
                for first, old, new in reversed(replacements):
                    lines[first:first + old] = new
                with open(doc, "w", encoding="utf-8") as f:
                    f.write("\n".join(lines))
        if failures:
            sys.exit(1)
        print(f"ok: {total} commands of {' '.join(docs)} ran as shown")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
