"""The examples of python/examples, each in its quick mode: exit status 0 (each checks its
results against theory and exits 1 otherwise) and its plot written."""
import os
import subprocess
import sys

import pytest


@pytest.mark.parametrize("script, png", [("capstan_sweep.py", "capstan_sweep.png"),
                                         ("drum_study.py", "drum_study.png"),
                                         ("point_cloud.py", "distances.png")])
def test_example_quick(source, tmp_path, script, png):
    env = dict(os.environ, IGA_SOURCE_DIR=str(source), MPLBACKEND="Agg")
    run = subprocess.run([sys.executable, str(source / "python/examples" / script), "--quick",
                          "--out", str(tmp_path)], env=env, capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert (tmp_path / png).stat().st_size > 1000
