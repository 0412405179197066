#!/usr/bin/env python3
"""Static SASS instructions per source file and line of a kernel, read from a cubin's DWARF line
table (built with -lineinfo): no GPU, nvdisasm or cuobjdump needed, so it runs on the build
machine. A kernel's code size is what its instruction cache holds (pt's worker: 15-20 k
instructions; BENCHMARKS.md, session 31), and the counts show which source a kernel's code is
made of and how many copies of a function were inlined (--copies FILE: runs of that file's
lines, each a copy).

Make a cubin of one translation unit from its ninja command, e.g.
  nvcc <the unit's flags> -arch=sm_90 -lineinfo -cubin src/gvdp/sched/builtin_producer.cpp -o x.cubin
then:
  scripts/sass_lines.py x.cubin ptWorkerKernel producePerlin [--top 30] [--copies noise.h]
(every word after the cubin must appear in the kernel's mangled name)."""
import argparse
import collections
import struct
import sys


def sections(data):
    """Each section of an ELF64 file (a cubin) by name: (offset, size) of its bytes in the file,
    size 0 for one that has none there (NOBITS). scripts/same_cubins.py reads cubins with it too."""
    shoff, = struct.unpack_from('<Q', data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from('<HHH', data, 0x3a)
    raw = [struct.unpack_from('<IIQQQQ', data, shoff + i * shentsize) for i in range(shnum)]
    names = raw[shstrndx][4]

    def name(o):
        return data[names + o:data.index(b'\0', names + o)].decode()

    return {name(r[0]): (r[4], 0 if r[1] == 8 else r[5]) for r in raw}


def uleb(data, p):
    r = s = 0
    while True:
        b = data[p]
        p += 1
        r |= (b & 0x7f) << s
        s += 7
        if b < 0x80:
            return r, p


def sleb(data, p):
    r, q = uleb(data, p)
    bits = 7 * (q - p)
    return (r - (1 << bits) if r >> (bits - 1) & 1 else r), q


def line_sequences(data, offset, size):
    """Each sequence of the DWARF 2 line programs: rows (address, file name, line)."""
    seqs, p, end = [], offset, offset + size
    while p < end:
        unit_len, = struct.unpack_from('<I', data, p)
        unit_end = p + 4 + unit_len
        header_len, = struct.unpack_from('<I', data, p + 6)
        q = p + 10
        min_len, _, line_base, line_range, op_base = struct.unpack_from('<BBbBB', data, q)
        std_lens = list(data[q + 5:q + 4 + op_base])
        q += 4 + op_base
        dirs = ['']
        while data[q]:
            e = data.index(b'\0', q)
            dirs.append(data[q:e].decode())
            q = e + 1
        q += 1
        files = ['']
        while data[q]:
            e = data.index(b'\0', q)
            name = data[q:e].decode()
            d, q = uleb(data, e + 1)
            _, q = uleb(data, q)
            _, q = uleb(data, q)
            files.append(f'{dirs[d]}/{name}' if dirs[d] else name)
        q = p + 10 + header_len
        addr, f, line, rows = 0, 1, 1, []
        while q < unit_end:
            op = data[q]
            q += 1
            if op >= op_base:
                a = op - op_base
                addr += a // line_range * min_len
                line += line_base + a % line_range
                rows.append((addr, files[f], line))
            elif op == 0:  # extended: end_sequence, set_address, others skipped by length
                n, q = uleb(data, q)
                sub, body = data[q], data[q + 1:q + n]
                q += n
                if sub == 1:
                    rows.append((addr, files[f], line))
                    seqs.append(rows)
                    addr, f, line, rows = 0, 1, 1, []
                elif sub == 2:
                    addr = int.from_bytes(body, 'little')
            elif op == 1:
                rows.append((addr, files[f], line))
            elif op == 2:
                a, q = uleb(data, q)
                addr += a * min_len
            elif op == 3:
                a, q = sleb(data, q)
                line += a
            elif op == 4:
                f, q = uleb(data, q)
            elif op == 8:
                addr += (255 - op_base) // line_range * min_len
            elif op == 9:
                addr += struct.unpack_from('<H', data, q)[0]
                q += 2
            else:
                for _ in range(std_lens[op - 1]):
                    _, q = uleb(data, q)
        if rows:
            seqs.append(rows)
        p = unit_end
    return seqs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('cubin')
    ap.add_argument('words', nargs='+', help='words of the kernel name')
    ap.add_argument('--top', type=int, default=30, help='lines shown')
    ap.add_argument('--copies', help='a source file whose inlined copies to count')
    a = ap.parse_args()
    data = open(a.cubin, 'rb').read()
    secs = sections(data)
    if '.debug_line' not in secs:
        sys.exit(f'sass_lines.py: {a.cubin} has no line table (build it with -lineinfo)')
    seqs = line_sequences(data, *secs['.debug_line'])
    by_end = collections.defaultdict(list)
    for s in seqs:
        by_end[s[-1][0]].append(s)
    kernels = [(n, size) for n, (_, size) in secs.items()
               if n.startswith('.text.') and all(w in n for w in a.words)]
    if not kernels:
        sys.exit(f'sass_lines.py: no kernel in {a.cubin} whose name has {" ".join(a.words)}')
    for name, size in kernels:
        print(f'{name[6:]}\n  {size // 16} instructions')
        match = by_end.get(size, [])
        if len(match) != 1:  # sequences are matched to sections by their length
            print('  (no single line sequence of that length)')
            continue
        rows = match[0]
        per_file, per_line = collections.Counter(), collections.Counter()
        runs, run = [], 0
        for (addr, f, line), (nxt, _, _) in zip(rows, rows[1:]):
            n = (nxt - addr) // 16
            per_file[f] += n
            per_line[f'{f}:{line}'] += n
            if a.copies and f.endswith(a.copies):
                run += n
            elif run and n > 40:  # a copy ends where other code runs for a while
                runs.append(run)
                run = 0
        if run:
            runs.append(run)
        for f, n in per_file.most_common(15):
            print(f'  {n:7d}  {f}')
        print('  lines:')
        for key, n in per_line.most_common(a.top):
            print(f'  {n:7d}  {key}')
        if a.copies:
            big = [r for r in runs if r > 30]
            print(f'  {a.copies}: {len(big)} copies of over 30 instructions: {big}')


if __name__ == '__main__':
    main()
