"""Simulator(**options) is derived from the library's option table: the same
names, and the same values accepted and refused, as leptrino-sim."""

from __future__ import annotations

import subprocess

import pytest

import leptrino
from leptrino import _constants as K, _tools


def test_options_are_the_c_table(backend: str) -> None:
    be = leptrino.get_backend(backend)
    table = leptrino.Simulator.option_table(backend=backend)
    sim_rows = [be.text(be.lib.lep_option_name(i)) for i in range(int(be.lib.lep_option_count()))
                if int(be.lib.lep_option_scope(i)) == K.LEP_SCOPE_SIM]
    assert [o.flag for o in table] == [n[len("sim-"):] for n in sim_rows] and len(table) >= 20
    names = [o.name for o in table]
    assert len(set(names)) == len(names)
    assert {"model", "rate", "amplitude", "output_rate_field", "nak", "stall_after",
            "reopen_after", "link", "usb_packets", "ftdi_latency", "ppm"} <= set(names)
    for o in table:
        assert o.flag.replace("-", "_") == o.name and o.help
        assert o.type in ("flag", "int", "float", "str", "choice", "numbers")
        # every default is accepted as given, by name with underscores or dashes
        if o.default is not None and o.type != "str":
            with leptrino.Simulator(backend=backend, **{o.name: o.default}) as port:
                assert port
    amp = next(o for o in table if o.name == "amplitude")
    assert (amp.min, amp.max, amp.default) == (0.0, 4.0, "0.2")
    assert "[0, 4]" in amp.describe() and "(default 0.2)" in amp.describe()


def test_unknown_option_lists_the_table(backend: str) -> None:
    names = [o.name for o in leptrino.Simulator.option_table(backend=backend)]
    with pytest.raises(TypeError) as info:
        leptrino.Simulator(backend=backend, amplitud=0.3)
    text = str(info.value)
    assert "'amplitud'" in text and ", ".join(names) in text


@pytest.mark.parametrize("name,value,ok", [
    ("amplitude", 3.5, True),
    ("amplitude", 5, False),
    ("amplitude", "nan", False),
    ("rate", 10000, True),
    ("rate", 0, False),
    ("serial", "12345678", True),
    ("serial", "12a", False),
    ("model", "CFS018CA201U", True),
    ("model", "NOPE", False),
    ("constant", True, True),
    ("constant", "maybe", False),
    ("overload_every", 0.5, True),
    ("stall", -5, False),
])
def test_values_as_leptrino_sim_takes_them(backend: str, name: str, value: object,
                                           ok: bool) -> None:
    if ok:
        with leptrino.Simulator(backend=backend, **{name: value}) as port:
            with leptrino.Sensor(port, backend=backend) as s:
                assert s.product_info.model
    else:
        with pytest.raises(ValueError, match=name.replace("_", "-")):
            leptrino.Simulator(backend=backend, **{name: value})
    # leptrino-sim (the same table, the same parser) agrees
    sim = str(_tools.program_path("leptrino-sim"))
    flag = "--" + name.replace("_", "-")
    argv = [sim, flag] if value is True else [sim, flag, str(value)]
    r = subprocess.run(argv + ["--exit-after", "0.2"], capture_output=True, text=True,
                       timeout=30)
    assert (r.returncode == 0) == ok, (argv, r.returncode, r.stderr)


def test_combination_checked_by_the_library(backend: str) -> None:
    with pytest.raises(ValueError, match="link"):
        leptrino.Simulator(backend=backend, reopen_after=100)  # needs a link
