#!/usr/bin/env python3
"""scripts/sass_lines.py on a cubin compiled here: a kernel of two source files, one of them
inlined twice. Its per-file counts add up to the kernel's size, the inlined file is found in two
copies, and a name no kernel has is a one-line error with exit status 1. Skips (77) without
nvcc."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
script = os.path.join(here, '..', 'scripts', 'sass_lines.py')
nvcc = shutil.which('nvcc') or ('/usr/local/cuda/bin/nvcc' if os.path.exists('/usr/local/cuda/bin/nvcc') else None)
if not nvcc:
    print('no nvcc: skipped')
    sys.exit(77)

with tempfile.TemporaryDirectory() as d:
    with open(os.path.join(d, 'inlined.h'), 'w') as f:
        f.write('__device__ __forceinline__ float wave(float x) {\n'
                '  float s = 0.0f;\n'
                '#pragma unroll\n'
                '  for (int k = 1; k < 24; ++k) s += __sinf(x * k) / k;\n'
                '  return s;\n}\n')
    with open(os.path.join(d, 'kernel.cu'), 'w') as f:
        f.write('#include "inlined.h"\n'
                '__global__ void probeKernel(float* out, const float* in, int n) {\n'
                '  int i = blockIdx.x * blockDim.x + threadIdx.x;\n'
                '  if (i >= n) return;\n'
                '  float a = wave(in[i]);\n'
                '#pragma unroll\n'
                '  for (int k = 1; k < 40; ++k) a = a * in[i + k] + 0.25f * k;\n'
                '  out[i] = a + wave(in[i] * 0.5f + a);\n}\n')
    cubin = os.path.join(d, 'k.cubin')
    subprocess.run([nvcc, '-arch=sm_90', '-O3', '-lineinfo', '-cubin', '-o', cubin,
                    os.path.join(d, 'kernel.cu')], check=True)
    r = subprocess.run([sys.executable, script, cubin, 'probeKernel', '--copies', 'inlined.h'],
                       capture_output=True, text=True)
    print(r.stdout)
    assert r.returncode == 0, r.stderr
    total = int(re.search(r'^\s+(\d+) instructions', r.stdout, re.M).group(1))
    files = {m.group(2): int(m.group(1))
             for m in re.finditer(r'^\s+(\d+)\s+(\S+\.(?:cu|h|hpp))$', r.stdout, re.M)}
    assert any(f.endswith('inlined.h') for f in files), files
    assert any(f.endswith('kernel.cu') for f in files), files
    # The per-file counts cover the kernel (the listing shows the 15 largest files: here all).
    assert sum(files.values()) <= total and sum(files.values()) >= total - 4, (files, total)
    copies = re.search(r'inlined.h: (\d+) copies', r.stdout)
    assert copies and int(copies.group(1)) == 2, r.stdout
    bad = subprocess.run([sys.executable, script, cubin, 'noSuchKernel'], capture_output=True,
                         text=True)
    assert bad.returncode == 1 and bad.stderr.count('\n') == 1 and 'noSuchKernel' in bad.stderr, bad
print('sass_lines_test: passed')
