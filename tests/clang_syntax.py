#!/usr/bin/env python3
"""Checks that every translation unit of the project compiles with clang, warning-free.

The CI build uses GCC, which accepts some C++20 that clang 14 refuses (a structured binding captured by a lambda
broke the remesh library under clang from afd47f9 to a9ac065, seen only by `make fuzz`). This configures the
project with clang into a temporary directory, takes each compile command of its compile_commands.json and runs it
with -fsyntax-only (parsing, templates instantiated, diagnostics; no code generated), on every core.

Usage: clang_syntax.py SOURCE_DIR [PART] (PART: check only the files whose path contains it). Exit 0 when all
compile without a warning, 1 otherwise, 77 (skipped) without clang.
"""
import concurrent.futures
import json
import os
import shlex
import shutil
import subprocess
import sys
import tempfile


def syntax_command(entry):
    """The compile command with its output dropped and -fsyntax-only added."""
    args = shlex.split(entry["command"])
    out, skip = [], False
    for a in args:
        if skip:
            skip = False
        elif a == "-o":
            skip = True
        elif a != "-c":
            out.append(a)
    return out + ["-fsyntax-only", "-Werror"]


def check(entry):
    r = subprocess.run(syntax_command(entry), cwd=entry["directory"], capture_output=True, text=True)
    return entry["file"], r.returncode, r.stderr


def main():
    source = os.path.abspath(sys.argv[1])
    if shutil.which("clang++") is None or shutil.which("clang") is None:
        print("SKIP: clang or clang++ is not installed (scripts/bootstrap installs them)")
        return 77
    with tempfile.TemporaryDirectory(prefix="carbonmesh-clang-") as work:
        env = dict(os.environ, CC="clang", CXX="clang++")
        configure = subprocess.run(
            ["cmake", "-S", source, "-B", work, "-DCMAKE_BUILD_TYPE=Release",
             "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON"],
            env=env, capture_output=True, text=True)
        if configure.returncode != 0:
            print(configure.stdout[-3000:], configure.stderr[-3000:])
            print("FAIL: cmake could not configure the project with clang")
            return 1
        with open(os.path.join(work, "compile_commands.json")) as f:
            entries = json.load(f)
        if len(sys.argv) > 2:
            entries = [e for e in entries if sys.argv[2] in e["file"]]
        if not entries:
            print("FAIL: the clang configure listed no compile commands")
            return 1
        with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 2) as pool:
            results = list(pool.map(check, entries))
    failed = [(f, err) for f, rc, err in results if rc != 0]
    for f, err in failed:
        print(f"--- {os.path.relpath(f, source)}\n{err}")
    print(f"clang: {len(results) - len(failed)} of {len(results)} translation units compile without a warning")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
