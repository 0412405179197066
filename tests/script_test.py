"""What the tests of scripts/*.py share: the path of the gvdp binary they are given (--gvdp), a
run of the script under test, and checks counted and reported at the end."""
import argparse
import os
import subprocess
import sys


class ScriptTest:
    def __init__(self, script):
        here = os.path.dirname(os.path.abspath(__file__))
        self.script = os.path.join(here, '..', 'scripts', script)
        self.failures = []
        ap = argparse.ArgumentParser()
        ap.add_argument('--gvdp', required=True)
        self.gvdp = ap.parse_args().gvdp

    def check(self, ok, what):
        if not ok:
            self.failures.append(what)

    def run(self, *args):
        return subprocess.run([sys.executable, self.script, *args], capture_output=True,
                              text=True)

    def finish(self, name):
        """Prints the failures and the verdict; exits 1 on any failure."""
        for f in self.failures:
            print('FAIL:', f)
        print(f'{name}:', 'FAILED' if self.failures else 'passed')
        sys.exit(1 if self.failures else 0)
