#!/usr/bin/env python3
"""scripts/same_cubins.py on cubins compiled here: a unit whose lines only moved (a comment added
above an internal-linkage kernel, which changes the hash in its names) has the same GPU code, one
whose code changed is named, with exit status 1; a folder that is not there is a one-line error
with exit status 2. Also the cubin command `save` makes of a build's nvcc command. Skips (77)
without nvcc."""
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
script = os.path.join(here, '..', 'scripts', 'same_cubins.py')
spec = importlib.util.spec_from_file_location('same_cubins', script)
same_cubins = importlib.util.module_from_spec(spec)
spec.loader.exec_module(same_cubins)

command = ('/usr/local/cuda/bin/nvcc -DX=1 -I/src -O3 '
           '--generate-code=arch=compute_90,code=[compute_90,sm_90] -lineinfo -std=c++20 -MD -MT '
           'a.o -MF a.o.d -x cu -rdc=true -c /src/gvdp/a.cu -o a.o')
assert same_cubins.cubin_command(command, 'out/a.cubin') == [
    '/usr/local/cuda/bin/nvcc', '-DX=1', '-I/src', '-O3', '-arch=sm_90', '-std=c++20', '-x', 'cu',
    '-rdc=true', '-cubin', '/src/gvdp/a.cu', '-o', 'out/a.cubin'], same_cubins.cubin_command(
        command, 'out/a.cubin')

nvcc = shutil.which('nvcc') or ('/usr/local/cuda/bin/nvcc'
                                if os.path.exists('/usr/local/cuda/bin/nvcc') else None)
if not nvcc:
    print('no nvcc: skipped')
    sys.exit(77)

KERNEL = ('namespace {{\n'
          '__device__ __noinline__ float twice(float x) {{ return {body}; }}\n'
          '}}\n'
          '__global__ void probe(float* out, const float* in) {{\n'
          '  out[threadIdx.x] = twice(in[threadIdx.x]);\n}}\n')


def cubin(folder, name, text):
    os.makedirs(folder, exist_ok=True)
    source = os.path.join(folder, name + '.cu')
    with open(source, 'w') as f:
        f.write(text)
    subprocess.run([nvcc, '-arch=sm_90', '-O3', '-rdc=true', '-cubin', '-o',
                    os.path.join(folder, name + '.cubin'), source], check=True)
    os.remove(source)


def run(*args):
    return subprocess.run([sys.executable, script, *args], capture_output=True, text=True)


with tempfile.TemporaryDirectory() as d:
    before, moved, changed = (os.path.join(d, n) for n in ('before', 'moved', 'changed'))
    for folder, prefix, body in ((before, '', 'x * 2.0f'),
                                 (moved, '// a comment that moves every line\n\n', 'x * 2.0f'),
                                 (changed, '', 'x * 3.0f')):
        cubin(folder, 'unit', prefix + KERNEL.format(body=body))
        cubin(folder, 'other', KERNEL.format(body='x + 1.0f'))
    r = run('diff', before, moved)
    print(r.stdout)
    assert r.returncode == 0 and '2 of 2 translation units with the same GPU code' in r.stdout, r
    r = run('diff', before, changed)
    print(r.stdout)
    assert r.returncode == 1, r
    assert 'unit.cubin:' in r.stdout and 'other.cubin:' not in r.stdout, r.stdout
    assert '1 of 2 translation units' in r.stdout, r.stdout
    bad = run('diff', os.path.join(d, 'none'), before)
    assert bad.returncode == 2 and bad.stderr.count('\n') == 1 and 'none' in bad.stderr, bad
print('same_cubins_test: passed')
