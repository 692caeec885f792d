"""What the Python tests share: the built module and the softbody executable beside it.

ctest sets PYTHONPATH to the module's folder and SOFTBODY_EXE to the executable
(tests/python/CMakeLists.txt).
"""
import json
import os
import subprocess

import softbody  # noqa: F401  (imported here so that a missing module fails every test at once)

SOFTBODY_EXE = os.environ.get("SOFTBODY_EXE", "")


def simulate(scene, ticks, threads=None, sets=()):
    """`softbody simulate`'s summary (a dict) and its stderr, for the same scene and keys."""
    command = [SOFTBODY_EXE, "simulate", "--scene", scene, "--ticks", str(ticks)]
    if threads is not None:
        command += ["--threads", str(threads)]
    for key, value in sets:
        command += ["--set", f"{key}={value}"]
    run = subprocess.run(command, capture_output=True, text=True, timeout=120, check=False)
    summary = json.loads(run.stdout) if run.stdout.strip() else None
    return summary, run.stderr, run.returncode


def error_line(stderr):
    """The command line's one-line error without its 'softbody: ' prefix (and the help hint)."""
    line = stderr.strip().splitlines()[-1]
    assert line.startswith("softbody: "), line
    return line[len("softbody: "):]
