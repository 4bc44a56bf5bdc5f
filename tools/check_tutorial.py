#!/usr/bin/python3
"""Runs every command of docs/tutorial.md as written, in order, in an empty folder, and checks its exit code.

Every line of a ```sh block is one command, run with bash from the work folder (a `cd` stays inside its own
line). A line ending in `# exit N` must exit with N, every other line with 0. A block right after an
`<!-- not run: reason -->` comment is skipped (e.g. commands on the reader's own model). The commands find
`carbonmesh` on PATH (BUILD/tools/carbonmesh) and the repository in $CARBONMESH_SRC. Everything the commands
print goes to the log (default WORK/tutorial.log) so the excerpts in the tutorial can be compared with it.

Usage: tools/check_tutorial.py [--build build] [--work DIR] [--update-images]
  --update-images  copy the PNGs the commands wrote to WORK/img into docs/img
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def commands(markdown):
    """(line number, command) of every runnable line of the ```sh blocks."""
    out, in_block, skip, previous = [], False, False, ""
    for number, line in enumerate(markdown.splitlines(), 1):
        stripped = line.strip()
        if not in_block and stripped.startswith("```sh"):
            in_block, skip = True, previous.startswith("<!-- not run")
        elif in_block and stripped.startswith("```"):
            in_block = False
        elif in_block and not skip and stripped and not stripped.startswith("#"):
            out.append((number, stripped))
        if stripped:
            previous = stripped
    return out


def expected_exit(command):
    match = re.search(r"#\s*exit\s+(\d+)\s*$", command)
    return int(match.group(1)) if match else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work", help="work folder (default: a new temporary folder, kept)")
    parser.add_argument("--tutorial", default=os.path.join(ROOT, "docs", "tutorial.md"))
    parser.add_argument("--update-images", action="store_true")
    args = parser.parse_args()

    cli_dir = os.path.join(os.path.abspath(args.build), "tools", "carbonmesh")
    if not os.access(os.path.join(cli_dir, "carbonmesh"), os.X_OK):
        sys.exit(f"check_tutorial: {cli_dir}/carbonmesh not found: build first (make build)")
    work = os.path.abspath(args.work) if args.work else tempfile.mkdtemp(prefix="carbonmesh-tutorial-")
    os.makedirs(work, exist_ok=True)
    if os.listdir(work):
        sys.exit(f"check_tutorial: {work} is not empty: the tutorial starts in an empty folder")
    env = dict(os.environ, PATH=cli_dir + os.pathsep + os.environ["PATH"], CARBONMESH_SRC=ROOT)
    log_path = os.path.join(work, "tutorial.log")
    with open(args.tutorial) as f:
        todo = commands(f.read())
    failures = 0
    with open(log_path + ".partial", "w") as log:
        for number, command in todo:
            start = time.monotonic()
            run = subprocess.run(["bash", "-c", command], cwd=work, env=env, stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, text=True)
            seconds = time.monotonic() - start
            want = expected_exit(command)
            ok = run.returncode == want
            failures += not ok
            log.write(f"$ {command}\n{run.stdout}[exit {run.returncode}, {seconds:.1f} s]\n\n")
            log.flush()
            print(f"{'ok  ' if ok else 'FAIL'} line {number:4d}  exit {run.returncode} (want {want})  "
                  f"{seconds:7.1f} s  {command}", flush=True)
    os.replace(log_path + ".partial", log_path)
    if args.update_images and os.path.isdir(os.path.join(work, "img")):
        for name in sorted(os.listdir(os.path.join(work, "img"))):
            if name.endswith(".png"):
                shutil.copy(os.path.join(work, "img", name), os.path.join(ROOT, "docs", "img", name))
                print(f"docs/img/{name} updated")
    print(f"{len(todo) - failures} of {len(todo)} commands as expected; log {log_path}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
