"""The bundled programs: `leptrino` (the command-line tool) and
`leptrino-sim` (the virtual sensor), built from the same C sources as the
library and installed in leptrino/_bin by the wheel.

The console scripts `leptrino` and `leptrino-sim` of this package, and
`python -m leptrino`, replace the Python process with the program (exec), so
its options, output, signals and exit codes are exactly the C tool's.
LEPTRINO_CLI / LEPTRINO_SIM name another copy (a source-tree run uses the
CMake build's programs this way).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import List, NoReturn, Optional, Sequence

BIN_DIR = Path(__file__).resolve().parent / "_bin"

#: program name -> environment variable that overrides its path
PROGRAMS = {"leptrino": "LEPTRINO_CLI", "leptrino-sim": "LEPTRINO_SIM"}


def program_path(name: str) -> Path:
    """Path of the bundled program name ("leptrino" or "leptrino-sim").
    FileNotFoundError, saying how to get it, when this install has none."""
    if name not in PROGRAMS:
        raise ValueError(f"no bundled program {name!r}; there are {', '.join(PROGRAMS)}")
    env = os.environ.get(PROGRAMS[name])
    path = Path(env) if env else BIN_DIR / name
    if not path.is_file():
        where = f"{PROGRAMS[name]}={env}" if env else str(path)
        raise FileNotFoundError(
            f"leptrino: the {name} program is not here ({where} does not exist). pip install "
            f"of the wheel or sdist bundles it; from a checkout, build it with `make` and run "
            f"build/dev/tools/{name}/{name}, or set {PROGRAMS[name]} to its path."
        )
    return path


def run(name: str, args: Optional[Sequence[str]] = None) -> NoReturn:
    """Replace this process with the program name and args (default: sys.argv[1:])."""
    argv: List[str] = [name] + list(sys.argv[1:] if args is None else args)
    try:
        path = program_path(name)
        sys.stdout.flush()
        sys.stderr.flush()
        os.execv(str(path), argv)
    except OSError as exc:
        print(f"{exc}" if isinstance(exc, FileNotFoundError) else
              f"leptrino: cannot run {name}: {exc}", file=sys.stderr)
        raise SystemExit(1) from None
    raise AssertionError("unreachable")  # pragma: no cover


def leptrino() -> NoReturn:
    """Console script `leptrino`."""
    run("leptrino")


def leptrino_sim() -> NoReturn:
    """Console script `leptrino-sim`."""
    run("leptrino-sim")
