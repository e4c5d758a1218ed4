"""Build step of the leptrino Python package.

build_py runs CMake on the repository root (two levels up, or
LEPTRINO_SOURCE_DIR) with the tests off, builds only the shared library, and
copies it into the package as leptrino/_lib/libleptrino.so.<ABI major>, so
the wheel carries the same .so that C programs link. The version comes from
project(VERSION) in the top CMakeLists.txt, the project's single source.
"""

from __future__ import annotations

import glob
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py as _build_py

try:
    from setuptools.command.bdist_wheel import bdist_wheel as _bdist_wheel
except ImportError:  # setuptools < 70.1
    from wheel.bdist_wheel import bdist_wheel as _bdist_wheel  # type: ignore[no-redef]

HERE = Path(__file__).resolve().parent


def source_dir() -> Path:
    """The repository root holding the C sources."""
    tried = []
    env = os.environ.get("LEPTRINO_SOURCE_DIR")
    for cand in ([Path(env)] if env else []) + [HERE.parent.parent]:
        cand = cand.resolve()
        if (cand / "CMakeLists.txt").is_file() and (cand / "include/leptrino/leptrino.h").is_file():
            return cand
        tried.append(str(cand))
    raise SystemExit(
        "leptrino: cannot find the C sources of libleptrino (looked in "
        + ", ".join(tried)
        + "). Install from a checkout of the repository (pip install ./bindings/python) "
        "or set LEPTRINO_SOURCE_DIR to its root."
    )


def project_version(src: Path) -> str:
    text = (src / "CMakeLists.txt").read_text(encoding="utf-8")
    m = re.search(r"project\s*\(\s*leptrino\s+VERSION\s+([0-9]+(?:\.[0-9]+)*)", text)
    if not m:
        raise SystemExit(f"leptrino: no project(leptrino VERSION x.y.z) in {src}/CMakeLists.txt")
    return m.group(1)


def cmake_exe() -> str:
    exe = shutil.which("cmake")
    if exe is None:
        try:  # the PyPI cmake package, when the build backend asked for it
            import cmake  # type: ignore[import-not-found]

            exe = os.path.join(cmake.CMAKE_BIN_DIR, "cmake")
        except ImportError:
            raise SystemExit("leptrino: CMake >= 3.20 is needed to build libleptrino")
    return exe


class build_py(_build_py):
    """Also build libleptrino with CMake and put it in the package."""

    def run(self) -> None:
        super().run()
        src = source_dir()
        build_temp = Path(self.get_finalized_command("build").build_temp).resolve() / "cmake"
        major = project_version(src).split(".")[0]
        lib = self.build_native(src, build_temp, major)
        if getattr(self, "editable_mode", False):
            dest_dir = HERE / "leptrino" / "_lib"
        else:
            dest_dir = Path(self.build_lib) / "leptrino" / "_lib"
        dest_dir.mkdir(parents=True, exist_ok=True)
        name = f"libleptrino.{major}.dylib" if sys.platform == "darwin" else f"libleptrino.so.{major}"
        shutil.copyfile(lib, dest_dir / name)
        os.chmod(dest_dir / name, 0o755)
        print(f"leptrino: bundled {lib} as {dest_dir / name}")

    def build_native(self, src: Path, build: Path, major: str) -> Path:
        cmake = cmake_exe()
        cache = build / "CMakeCache.txt"
        if cache.is_file():  # a build directory left by a checkout elsewhere: start afresh
            m = re.search(r"^CMAKE_HOME_DIRECTORY:INTERNAL=(.*)$",
                          cache.read_text(encoding="utf-8", errors="replace"), re.M)
            if not m or Path(m.group(1)).resolve() != src:
                shutil.rmtree(build)
        configure = [
            cmake,
            "-S", str(src),
            "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DLEPTRINO_BUILD_TESTS=OFF",
            "-DLEPTRINO_BUILD_STATIC=OFF",
            "-DLEPTRINO_BUILD_SHARED=ON",
            # a user's compiler may warn where ours does not: never fail the install on that
            "-DLEPTRINO_WERROR=OFF",
        ]
        if not os.environ.get("CMAKE_GENERATOR") and not (build / "CMakeCache.txt").exists():
            if shutil.which("ninja"):
                configure += ["-G", "Ninja"]
            else:
                try:
                    import ninja  # type: ignore[import-not-found]

                    configure += ["-G", "Ninja",
                                  f"-DCMAKE_MAKE_PROGRAM={os.path.join(ninja.BIN_DIR, 'ninja')}"]
                except ImportError:
                    pass
        subprocess.check_call(configure)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.check_call([cmake, "--build", str(build), "--target", "leptrino",
                               "--parallel", jobs])
        pattern = "libleptrino.*.dylib" if sys.platform == "darwin" else "libleptrino.so*"
        libs = [Path(p) for p in glob.glob(str(build / "**" / pattern), recursive=True)]
        libs = [p for p in libs if p.is_file() and not p.is_symlink()]
        if not libs:
            raise SystemExit(f"leptrino: the CMake build produced no {pattern} under {build}")
        return libs[0]


class bdist_wheel(_bdist_wheel):
    """The wheel carries a native library, but no CPython extension: py3-none-<platform>."""

    def finalize_options(self) -> None:
        super().finalize_options()
        self.root_is_pure = False

    def get_tag(self):  # type: ignore[no-untyped-def]
        _, _, plat = super().get_tag()
        return "py3", "none", plat


setup(
    version=project_version(source_dir()),
    cmdclass={"build_py": build_py, "bdist_wheel": bdist_wheel},
)
