#!/usr/bin/env python3
"""Whether a change leaves the GPU code as it was, checked without a GPU: `save` compiles every
CUDA translation unit of a build's gvdp (its own nvcc command, from ninja) into a cubin for its
architecture without line info, `diff` compares two such folders section by section - the code
(.text.*), constants and kernel parameters - and names each translation unit whose code differs.
A cubin's internal-linkage names carry a hash of the preprocessed unit (anything, a comment, that
moves its lines changes it) and its symbol and string tables follow them: names are compared
without the hash, those tables not at all. A refactor that moves code (session 61's split of
pt_body.h) should leave every section the same; a change that means to change the GPU code shows
where it did.

Usage: scripts/same_cubins.py save DIR [--build BUILD]   (about 3 minutes on 2 cores)
       scripts/same_cubins.py diff BEFORE AFTER
Exit status: 0 the same, 1 some code differs (each unit named), 2 bad arguments or input (a
one-line error).
"""
import argparse
import os
import re
import shlex
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sass_lines import sections  # noqa: E402  (the ELF section reader, written once)

SKIPPED = (".strtab", ".shstrtab", ".symtab", ".nv.rel", ".rela", ".rel")  # names, relocations


def fail(message):
    print(f"same_cubins: {message}", file=sys.stderr)
    sys.exit(2)


def nvcc_commands(build):
    """The nvcc compile commands of the build's gvdp target."""
    try:
        out = subprocess.run(["ninja", "-C", build, "-t", "commands", "src/gvdp"], check=True,
                             capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        fail(f"cannot list the commands of '{build}' (ninja -t commands src/gvdp): {e}")
    return sorted({c for c in out.splitlines() if "/nvcc " in c and " -c " in c})


def cubin_command(command, out):
    """The compile command turned into one that writes a cubin without line info to `out`."""
    args = shlex.split(command)
    result, skip = [], 0
    for a in args:
        if skip:
            skip -= 1
            continue
        if a in ("-MT", "-MF", "-o"):
            skip = 1
        elif a in ("-lineinfo", "-MD"):
            pass
        elif a == "-c":
            result.append("-cubin")
        elif a.startswith("--generate-code=arch=compute_"):
            result.append("-arch=sm_" + re.search(r"compute_(\d+)", a).group(1))
        else:
            result.append(a)
    return result + ["-o", out]


def save(folder, build):
    commands = nvcc_commands(build)
    if not commands:
        fail(f"'{build}' has no nvcc command for src/gvdp (a build without CUDA?)")
    os.makedirs(folder, exist_ok=True)
    for command in commands:
        source = shlex.split(command)[shlex.split(command).index("-c") + 1]
        name = re.sub(r"[^A-Za-z0-9_.]", "_", source.split("/src/", 1)[-1]) + ".cubin"
        print(f"  {name}", flush=True)
        r = subprocess.run(cubin_command(command, os.path.join(folder, name)), cwd=build,
                           capture_output=True, text=True)
        if r.returncode:
            fail(f"nvcc failed on {source}: {r.stderr.strip().splitlines()[-1:]}")
    print(f"saved {len(commands)} cubins in {folder}")


def section_bytes(path):
    """{name: bytes} of each section of a cubin (sass_lines.sections; empty for NOBITS)."""
    try:
        data = open(path, "rb").read()
    except OSError as e:
        fail(f"cannot read '{path}': {e.strerror}")
    if data[:4] != b"\x7fELF" or data[4] != 2:
        fail(f"'{path}' is not a 64-bit ELF file")
    return {name: data[offset:offset + size] for name, (offset, size) in sections(data).items()}


def unhashed(name):
    """A section name without the hashes an internal-linkage name carries (of the unit's path and
    preprocessed text): _INTERNAL_<hash>_<n>_<file>_<cu|cpp>_<hash>[_]<n> and the anonymous
    namespace's _GLOBAL__N__<hash>_<file>_<cu|cpp>_<hash>."""
    name = re.sub(r"_INTERNAL_[0-9a-f]{8}_\d+_\w+?_(?:cpp|cu)_[0-9a-f]{8}_?\d*", "_INTERNAL_", name)
    return re.sub(r"_GLOBAL__N__[0-9a-f]{8}_\w+?_(?:cpp|cu)_[0-9a-f]{8}", "_GLOBAL__N__", name)


def differing(before, after):
    """Names of the sections whose code or data differ (or that only one side has)."""
    a = {unhashed(n): b for n, b in section_bytes(before).items() if not n.startswith(SKIPPED)}
    b = {unhashed(n): d for n, d in section_bytes(after).items() if not n.startswith(SKIPPED)}
    return sorted(n for n in a.keys() | b.keys() if a.get(n) != b.get(n))


def diff(before, after):
    for folder in (before, after):
        if not os.path.isdir(folder):
            fail(f"no folder '{folder}' (make one with: same_cubins.py save DIR)")
    names = sorted(n for n in os.listdir(before) if n.endswith(".cubin"))
    if not names:
        fail(f"'{before}' has no cubins")
    changed = 0
    for name in names:
        if not os.path.exists(os.path.join(after, name)):
            print(f"{name}: only in {before}")
            changed += 1
            continue
        d = differing(os.path.join(before, name), os.path.join(after, name))
        if d:
            changed += 1
            print(f"{name}: {len(d)} sections differ: {', '.join(d[:4])}{' ...' if len(d) > 4 else ''}")
    for name in sorted(set(os.listdir(after)) - set(names)):
        if name.endswith(".cubin"):
            print(f"{name}: only in {after}")
            changed += 1
    print(f"{len(names) - changed} of {len(names)} translation units with the same GPU code")
    return 1 if changed else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    s = sub.add_parser("save")
    s.add_argument("folder")
    s.add_argument("--build", default="build")
    d = sub.add_parser("diff")
    d.add_argument("before")
    d.add_argument("after")
    args = parser.parse_args()
    if args.command == "save":
        save(args.folder, os.path.abspath(args.build))
        return 0
    return diff(args.before, args.after)


if __name__ == "__main__":
    sys.exit(main())
