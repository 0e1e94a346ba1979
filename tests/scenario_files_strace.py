#!/usr/bin/env python3
"""Every bundled example, run under strace, opens nothing but its own folder tree, the output
folder, owsim's modules, the system's libraries and GDAL/PROJ's installed data, and makes no
network call (issue 33: a scenario is data).

    scenario_files_strace.py OWSIM SOURCE_DIR WORK_DIR
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys

owsim, source, work = map(pathlib.Path, sys.argv[1:4])
examples = source / "examples"
modules = owsim.resolve().parent / "lib"
# owsim's own libraries beside the command, where the modules are shared (the sanitizer build).
OWN_LIBRARY = re.compile(r"^libowsim_\w+\.so(\.[0-9.]+)?$")
# What any program on this machine reads to run (libraries, the loader's cache, the kernel's
# facts TBB and the allocator ask) and GDAL/PROJ's installed data and configuration.
SYSTEM = ("/lib/", "/lib64/", "/usr/lib/", "/usr/lib64/", "/etc/ld.so.cache", "/proc/", "/sys/",
          "/usr/share/proj/", "/usr/share/gdal/", "/etc/gdal/", "/etc/gcrypt/", "/dev/null",
          "/usr/share/locale/", "/usr/share/zoneinfo/", "/etc/localtime")
USER_CONFIG = re.compile(r"^/[^\s]*/(\.gdal/gdalrc|\.local/share/proj/[^/]+)$")
CALL = re.compile(r'^\d+\s+(\w+)\((.*)')
PATH = re.compile(r'"([^"]*)"')

# A container that forbids ptrace cannot run this check: skipped (ctest's SKIP_RETURN_CODE), said.
if subprocess.run(["strace", "-qq", "-e", "trace=none", "true"], capture_output=True).returncode:
    print("strace cannot trace here (ptrace not permitted): skipped")
    sys.exit(77)

shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
# In a sanitizer build, LeakSanitizer stops the world with ptrace, which strace already holds.
env = dict(os.environ)
env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS", ""), "detect_leaks=0"]))
problems = []
runs = 0
for scenario in sorted(examples.glob("*.yaml")) + sorted(examples.glob("campaigns/*.yaml")):
    if any(line.startswith("base:") for line in scenario.read_text().splitlines()):
        continue  # a sweep file: its base is run here
    out = work / scenario.stem
    log = work / (scenario.stem + ".strace")
    subprocess.run(["strace", "-f", "-qq", "-o", str(log), "-e",
                    "trace=network,open,openat,openat2,creat", str(owsim), "run", str(scenario),
                    "--frames", "2", "--out", str(out), "--quiet"], check=True, env=env)
    runs += 1
    tree = scenario.parent.resolve()
    for line in log.read_text().splitlines():
        call = CALL.match(line)
        if not call:
            continue
        name, rest = call.groups()
        if name in ("socket", "connect", "bind", "sendto", "sendmsg", "getaddrinfo"):
            problems.append(f"{scenario.name}: network call: {line}")
            continue
        found = PATH.search(rest)
        if not found or re.search(r"= -1 E[A-Z]+", rest):
            continue  # nothing was opened (a library or config file looked for and not there)
        path = found.group(1)
        resolved = str(pathlib.Path(path).resolve())  # relative: against this script's folder
        allowed = (resolved.startswith(SYSTEM) or path.startswith(SYSTEM)
                   or USER_CONFIG.match(path)
                   or pathlib.Path(resolved).is_relative_to(tree)
                   or pathlib.Path(resolved).is_relative_to(out.resolve())
                   or pathlib.Path(resolved).is_relative_to(modules.resolve())
                   or resolved == str(owsim.resolve())
                   or (pathlib.Path(resolved).parent == owsim.resolve().parent
                       and OWN_LIBRARY.match(pathlib.Path(resolved).name)))
        if not allowed:
            problems.append(f"{scenario.name}: opened {path}: {line}")

print(f"{runs} examples run under strace")
if runs < 6:
    problems.append(f"only {runs} examples found")
for problem in problems:
    print(problem)
sys.exit(1 if problems else 0)
