#!/usr/bin/env python3
"""The Python distributions, installed as a user would, outside the checkout.

1. `python -m build` in bindings/python: an sdist and a platform wheel.
2. The sdist carries the C sources (csrc/) and the build backend.
3. For the wheel and for the sdist: a fresh virtual environment in a
   temporary directory, `pip install <file>`, then from that directory: import,
   the version, both backends (ctypes and cffi) reading the Simulator through
   a Sensor and recording from a session's virtual sensor (tare, record, save
   CSV), the bundled library loaded from the installed package, and the
   console scripts `leptrino --version`, `leptrino-sim --help`,
   `leptrino stream --sim -c 5`, `python -m leptrino --version`.
4. The wheel is tagged manylinux (the build backend runs auditwheel repair);
   `auditwheel show` on it prints the manylinux tag it is consistent with and
   fails when the bundled code needs a library outside the policy.
5. bindings/python copied alone: the install fails with a message that says
   what it needs.

    python test/python/dist_check.py [--tools-python PY] [--keep]

--tools-python: a Python with `build` and `auditwheel` installed (default:
this one). Needs network access to PyPI for numpy, cffi and setuptools
(pip's cache makes later runs fast). Exits non-zero on the first failure.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import zipfile
from pathlib import Path
from typing import List, Optional

ROOT = Path(__file__).resolve().parent.parent.parent
PKG = ROOT / "bindings" / "python"

SMOKE = r"""
import os, subprocess, sys
import leptrino
expected = sys.argv[1]
assert leptrino.__version__ == expected, (leptrino.__version__, expected)
for be in ("ctypes", "cffi"):
    assert leptrino.library_version(be) == expected
    path = leptrino.get_backend(be).path
    assert "site-packages" in path and path.endswith("libleptrino.so"), path
    with leptrino.Simulator(backend=be, seed=7) as port, leptrino.Sensor(port, backend=be) as s:
        x = s.read()
        assert len(x.raw) == 6 and s.product_info.model == "PFS055YA501U6"
        rec = s.record(count=100)
        assert len(rec) == 100 and rec.si.shape == (100, 6) and rec.missing() == 0
    print(f"{be}: {s.product_info.model} read {x.force}, recorded {len(rec)} samples")
    with leptrino.Sensor(sim={"constant": True}, backend=be) as s:  # the session
        s.tare(20)
        rec = s.record(count=50)
        assert abs(rec.si).max() < 1e-9 and rec.metadata["library_version"] == expected
        rec.save(f"smoke-{be}.csv")
    rows = open(f"smoke-{be}.csv").read().splitlines()
    assert rows[0].startswith("# leptrino-metadata: {") and len(rows) == 52, rows[:3]
"""


def run(cmd: List[str], cwd: Optional[Path] = None, check: bool = True,
        env: Optional[dict] = None) -> subprocess.CompletedProcess:
    print("+", " ".join(cmd), flush=True)
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=env, timeout=900)
    if check and r.returncode != 0:
        sys.stdout.write(r.stdout[-4000:])
        sys.stderr.write(r.stderr[-4000:])
        raise SystemExit(f"dist_check: failed ({r.returncode}): {' '.join(cmd)}")
    return r


def clean_env() -> dict:
    """No variable of the developer's setup may point the install at the checkout."""
    env = dict(os.environ)
    for k in ("LEPTRINO_LIBRARY", "LEPTRINO_SOURCE_DIR", "LEPTRINO_CLI", "LEPTRINO_SIM",
              "PYTHONPATH", "LEPTRINO_BACKEND", "VIRTUAL_ENV"):
        env.pop(k, None)
    return env


def project_version() -> str:
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    m = re.search(r"project\s*\(\s*leptrino\s+VERSION\s+([0-9.]+)", text)
    assert m, "no project(leptrino VERSION ...)"
    return m.group(1)


def check_sdist(sdist: Path, version: str) -> None:
    with tarfile.open(sdist) as tf:
        names = set(tf.getnames())
    top = f"leptrino-{version}"
    need = ["build_backend/leptrino_build.py", "setup.py", "pyproject.toml",
            "csrc/CMakeLists.txt", "csrc/include/leptrino/leptrino.h",
            "csrc/src/CMakeLists.txt", "csrc/include/leptrino/session.h",
            "csrc/tools/leptrino/CMakeLists.txt", "csrc/tools/leptrino-sim/main.c"]
    if (ROOT / "LICENSE").is_file():
        need.append("csrc/LICENSE")
    missing = [n for n in need if f"{top}/{n}" not in names]
    if missing:
        raise SystemExit(f"dist_check: the sdist lacks {missing}")
    stray = [n for n in names if "/_lib/" in n or "/_bin/" in n or n.endswith("_version.py")]
    if stray:
        raise SystemExit(f"dist_check: the sdist carries build output {stray}")
    print(f"sdist: {len(names)} entries, C sources and build backend present")


def check_wheel(wheel: Path) -> None:
    with zipfile.ZipFile(wheel) as zf:
        infos = {i.filename: i for i in zf.infolist()}
        wheel_meta = zf.read(f"leptrino-{wheel.name.split('-')[1]}.dist-info/WHEEL").decode()
    for name in ("leptrino/_lib/libleptrino.so", "leptrino/_bin/leptrino",
                 "leptrino/_bin/leptrino-sim", "leptrino/_version.py", "leptrino/py.typed"):
        if name not in infos:
            raise SystemExit(f"dist_check: the wheel lacks {name}")
    for name in ("leptrino/_bin/leptrino", "leptrino/_bin/leptrino-sim"):
        if not (infos[name].external_attr >> 16) & 0o111:
            raise SystemExit(f"dist_check: {name} is not executable in the wheel")
    if "Root-Is-Purelib: false" not in wheel_meta:
        raise SystemExit("dist_check: the wheel says it is pure")
    if not re.search(r"-py3-none-(manylinux|macosx)_\w+\.whl$", wheel.name):
        raise SystemExit(f"dist_check: the wheel's tag names no portable platform (the build "
                         f"runs auditwheel repair on Linux): {wheel.name}")
    print(f"wheel: {wheel.name}, library and programs present")


def install_and_smoke(artifact: Path, work: Path, version: str) -> None:
    venv = work / "venv"
    env = clean_env()
    run([sys.executable, "-m", "venv", str(venv)], cwd=work, env=env)
    py = venv / "bin" / "python"
    run([str(py), "-m", "pip", "install", "-q", str(artifact)], cwd=work, env=env)
    r = run([str(py), "-c", SMOKE, version], cwd=work, env=env)
    print(r.stdout, end="")
    r = run([str(venv / "bin" / "leptrino"), "--version"], cwd=work, env=env)
    if version not in r.stdout + r.stderr:
        raise SystemExit(f"dist_check: leptrino --version says {r.stdout!r}")
    r = run([str(venv / "bin" / "leptrino-sim"), "--help"], cwd=work, env=env)
    if "leptrino-sim" not in r.stdout + r.stderr:
        raise SystemExit(f"dist_check: leptrino-sim --help says {r.stdout!r}")
    r = run([str(venv / "bin" / "leptrino"), "stream", "--sim", "-c", "5"], cwd=work, env=env)
    rows = [ln for ln in r.stdout.splitlines() if ln and not ln.startswith("#")]
    if len(rows) != 6:
        raise SystemExit(f"dist_check: leptrino stream --sim -c 5 wrote {rows}")
    r = run([str(py), "-m", "leptrino", "--version"], cwd=work, env=env)
    if version not in r.stdout:
        raise SystemExit(f"dist_check: python -m leptrino --version says {r.stdout!r}")
    print(f"{artifact.name}: installed in a fresh venv and working "
          f"(leptrino --version: {r.stdout.strip()})")


def copied_alone(work: Path) -> None:
    """bindings/python without the rest of the tree: a clear failure."""
    alone = work / "python-alone"
    shutil.copytree(PKG, alone, ignore=shutil.ignore_patterns(
        "build", "dist", "_lib", "_bin", "_version.py", "*.egg-info", "__pycache__"))
    env = clean_env()
    r = run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-w", str(work / "w"),
             str(alone)], cwd=work, check=False, env=env)
    text = r.stdout + r.stderr
    if r.returncode == 0 or "cannot find the C sources" not in text \
            or "LEPTRINO_SOURCE_DIR" not in text or "sdist" not in text:
        raise SystemExit(f"dist_check: bindings/python alone: rc {r.returncode}, "
                         f"output lacks the explanation:\n{text[-3000:]}")
    print("bindings/python alone: refused with a message naming the sdist, a checkout "
          "and LEPTRINO_SOURCE_DIR")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tools-python", default=sys.executable,
                    help="Python with build and auditwheel (default: this one)")
    ap.add_argument("--keep", action="store_true", help="keep the temporary directory")
    args = ap.parse_args()
    version = project_version()
    work = Path(tempfile.mkdtemp(prefix="leptrino-dist-"))
    try:
        dist = work / "dist"
        run([args.tools_python, "-m", "build", "-o", str(dist), str(PKG)], env=clean_env())
        sdists = list(dist.glob(f"leptrino-{version}.tar.gz"))
        wheels = list(dist.glob(f"leptrino-{version}-*.whl"))
        if len(sdists) != 1 or len(wheels) != 1:
            raise SystemExit(f"dist_check: expected one sdist and one wheel of {version}, "
                             f"got {sorted(p.name for p in dist.iterdir())}")
        check_sdist(sdists[0], version)
        check_wheel(wheels[0])
        r = run([args.tools_python, "-m", "auditwheel", "show", str(wheels[0])])
        m = re.search(r'consistent\s+with\s+the\s+following\s+platform\s+tag:\s+"([^"]+)"',
                      r.stdout)  # auditwheel wraps its text at any of these spaces
        if not m or not m.group(1).startswith("manylinux"):
            raise SystemExit(f"dist_check: auditwheel show:\n{r.stdout}{r.stderr}")
        print(f"auditwheel show: consistent with {m.group(1)}")
        for art in (wheels[0], sdists[0]):
            sub = work / art.name.replace(".", "_")
            sub.mkdir()
            install_and_smoke(art, sub, version)
        copied_alone(work)
        print("dist_check: ok")
    finally:
        if args.keep:
            print(f"kept {work}")
        else:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
