"""Shared helpers of the carbonmesh benchmark scripts: running timed commands and keeping docs/benchmarks.md."""
import json
import os
import re
import subprocess
import sys
import tempfile


def timed(command, cwd=None):
    """Runs a command under /usr/bin/time; returns (stdout, wall seconds, peak RSS in MiB)."""
    with tempfile.NamedTemporaryFile(mode="r", suffix=".time") as t:
        full = ["/usr/bin/time", "-f", "%e %M", "-o", t.name] + [str(c) for c in command]
        result = subprocess.run(full, cwd=cwd, capture_output=True, text=True)
        if result.returncode != 0:
            sys.stderr.write(result.stderr)
            raise RuntimeError("failed: " + " ".join(str(c) for c in command))
        seconds, kib = t.read().split()[-2:]
    return result.stdout, float(seconds), int(kib) / 1024.0


def run_json(command):
    """Runs a command that prints one JSON object."""
    out = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    if out.returncode != 0:
        sys.stderr.write(out.stderr)
        raise RuntimeError("failed: " + " ".join(str(c) for c in command))
    return json.loads(out.stdout)


def replace_section(path, name, text):
    """Replaces (or appends) the section between <!-- name:begin --> and <!-- name:end --> in a markdown file."""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    block = f"{begin}\n{text.rstrip()}\n{end}\n"
    old = open(path).read() if os.path.exists(path) else "# Benchmarks\n\nWritten by the programs in tools/bench.\n\n"
    if begin in old and end in old:
        new = re.sub(re.escape(begin) + r".*?" + re.escape(end) + r"\n?", lambda _: block, old, flags=re.S)
    else:
        new = old.rstrip() + "\n\n" + block
    tmp = path + ".partial"
    with open(tmp, "w") as f:
        f.write(new)
    os.replace(tmp, path)


def machine_line():
    cpu = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{os.cpu_count()} cores, {cpu}"
