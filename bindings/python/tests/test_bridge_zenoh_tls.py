"""leptrino-bridge with Zenoh's own security (--zenoh-config): the test makes
a CA and certificates with openssl in tmp_path, runs the bridge (a virtual
sensor) listening on tls/127.0.0.1:PORT, and checks with independent Zenoh
sessions that a client trusting the CA receives the wrench, that one with
another CA cannot connect, and that with mTLS a client without a certificate
is refused. Everything on 127.0.0.1, every wait bounded.

The TLS keys are eclipse-zenoh 1.x's (the version the "bridge" extra
installs): transport/link/tls/{root_ca_certificate, listen_certificate,
listen_private_key, enable_mtls, connect_certificate, connect_private_key}, as
in zenoh's DEFAULT_CONFIG.json5 ("tls" section) and its manual page "TLS
authentication" (zenoh.io/docs/manual/tls)."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional

import pytest
from bridge_net import free_port
from conftest import subprocess_env
import zenoh  # the "bridge" extra (make test and .ci/checks/60-bridge.sh install it)

from leptrino.bridge import Bridge, NodeOptions, SensorSpec, ZenohOptions
from leptrino.bridge import cdr
from leptrino.bridge import rmw_zenoh as rz

WRENCH = "0/a/wrench/geometry_msgs::msg::dds_::WrenchStamped_/**"
TARE = ("0/a/tare/std_srvs::srv::dds_::Trigger_/"
        "RIHS01_eeff2cd6fa5ad9d27cdf4dec64818317839b62f212a91e6b5304b634b2062c5f")
ACL_EXAMPLE = Path(__file__).resolve().parents[3] / "docs" / "zenoh-acl-example.json5"

needs_openssl = pytest.mark.skipif(shutil.which("openssl") is None,
                                   reason="the openssl command is not installed (it makes "
                                          "the test's CA and certificates)")


def _openssl(cwd: Path, *args: str) -> None:
    subprocess.run(["openssl", *args], cwd=cwd, check=True, capture_output=True, timeout=30)


def _ca(d: Path, name: str) -> None:
    _openssl(d, "req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1",
             "-nodes", "-keyout", f"{name}.key", "-out", f"{name}.pem", "-days", "1",
             "-subj", f"/CN=leptrino test {name}",
             "-addext", "basicConstraints=critical,CA:TRUE",
             "-addext", "keyUsage=critical,keyCertSign,cRLSign")


def _leaf(d: Path, name: str, ca: str) -> None:
    ext = d / f"{name}.ext"
    ext.write_text("basicConstraints=CA:FALSE\nsubjectAltName=IP:127.0.0.1,DNS:localhost\n"
                   "keyUsage=critical,digitalSignature\n"
                   "extendedKeyUsage=serverAuth,clientAuth\n")
    _openssl(d, "req", "-new", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1",
             "-nodes", "-keyout", f"{name}.key", "-out", f"{name}.csr", "-subj", f"/CN={name}")
    _openssl(d, "x509", "-req", "-in", f"{name}.csr", "-CA", f"{ca}.pem", "-CAkey",
             f"{ca}.key", "-CAcreateserial", "-days", "1", "-out", f"{name}.pem",
             "-extfile", ext.name)


@pytest.fixture(scope="module")
def pki(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """ca (server and client certificates signed by it) and other-ca (nothing)."""
    if shutil.which("openssl") is None:
        pytest.skip("the openssl command is not installed (it makes the test's certificates)")
    d = tmp_path_factory.mktemp("pki")
    _ca(d, "ca")
    _ca(d, "other-ca")
    _leaf(d, "server", "ca")
    _leaf(d, "client", "ca")
    return d


def bridge_config(d: Path, port: int, mtls: bool) -> Path:
    tls: Dict[str, Any] = {"listen_certificate": str(d / "server.pem"),
                           "listen_private_key": str(d / "server.key")}
    if mtls:
        tls.update(enable_mtls=True, root_ca_certificate=str(d / "ca.pem"))
    conf = {"mode": "peer", "listen": {"endpoints": [f"tls/127.0.0.1:{port}"]},
            "scouting": {"multicast": {"enabled": False}},
            "transport": {"link": {"tls": tls}}}
    p = d / f"bridge-{port}.json5"
    p.write_text("// the bridge's side, written by the test\n" + json.dumps(conf, indent=2))
    return p


def open_client(port: int, ca: Optional[Path], cert: Optional[str] = None,
                user: Optional[str] = None) -> Any:
    """A Zenoh client connecting to the bridge over TLS (raises zenoh.ZError
    when the connection is refused: a client tries once and gives up)."""
    conf = zenoh.Config()
    conf.insert_json5("mode", '"client"')
    conf.insert_json5("connect/endpoints", json.dumps([f"tls/127.0.0.1:{port}"]))
    conf.insert_json5("scouting/multicast/enabled", "false")
    tls: Dict[str, Any] = {}
    if ca is not None:
        tls["root_ca_certificate"] = str(ca)
    if cert is not None:
        d = ca.parent if ca is not None else Path(".")
        tls.update(enable_mtls=True, connect_certificate=str(d / f"{cert}.pem"),
                   connect_private_key=str(d / f"{cert}.key"))
    conf.insert_json5("transport/link/tls", json.dumps(tls))
    if user is not None:
        conf.insert_json5("transport/auth/usrpwd",
                          json.dumps({"user": user, "password": f"{user}-pw"}))
    return zenoh.open(conf)


class Count:
    def __init__(self, session: Any) -> None:
        self.n = 0
        self.lock = threading.Lock()
        self.sub = session.declare_subscriber(WRENCH, self._on)

    def _on(self, sample: Any) -> None:
        with self.lock:
            self.n += 1

    def wait(self, n: int, timeout: float) -> int:
        end = time.monotonic() + timeout
        while time.monotonic() < end and self.n < n:
            time.sleep(0.02)
        return self.n


@pytest.fixture
def tls_bridge(pki: Path, request: pytest.FixtureRequest) -> Iterator[int]:
    port = free_port()
    conf = bridge_config(pki, port, mtls=bool(getattr(request, "param", False)))
    with Bridge([SensorSpec("a", sim={})], NodeOptions(), ZenohOptions(config_file=str(conf))) as b:
        b.start()
        yield port


def test_a_client_trusting_the_ca_receives_the_wrench(pki: Path, tls_bridge: int) -> None:
    s = open_client(tls_bridge, pki / "ca.pem")
    try:
        n = Count(s).wait(600, 10.0)  # 1.2 kHz: half a second's worth
    finally:
        s.close()
    assert n >= 600


def test_a_client_with_another_ca_cannot_connect(pki: Path, tls_bridge: int) -> None:
    t0 = time.monotonic()
    with pytest.raises(zenoh.ZError):
        open_client(tls_bridge, pki / "other-ca.pem").close()
    assert time.monotonic() - t0 < 15.0
    with pytest.raises(zenoh.ZError):  # Zenoh's default roots (webpki) do not know it either
        open_client(tls_bridge, None).close()
    s = open_client(tls_bridge, pki / "ca.pem")  # the bridge is still there for the right one
    try:
        assert Count(s).wait(100, 10.0) >= 100
    finally:
        s.close()


@pytest.mark.parametrize("tls_bridge", [True], indirect=True)
def test_mtls_refuses_a_client_without_a_certificate(pki: Path, tls_bridge: int) -> None:
    with pytest.raises(zenoh.ZError):
        open_client(tls_bridge, pki / "ca.pem").close()
    s = open_client(tls_bridge, pki / "ca.pem", cert="client")
    try:
        assert Count(s).wait(600, 10.0) >= 600
    finally:
        s.close()


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "leptrino.bridge", *args], capture_output=True,
                          text=True, env=subprocess_env(), timeout=60)


def test_the_command_line_over_tls(pki: Path) -> None:
    port = free_port()
    conf = bridge_config(pki, port, mtls=False)
    proc = subprocess.Popen([sys.executable, "-m", "leptrino.bridge", "--sim", "a",
                             "--zenoh-config", str(conf), "--duration", "4"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=subprocess_env())
    try:
        s = None
        end = time.monotonic() + 15.0
        while s is None and time.monotonic() < end:  # the bridge starts listening
            try:
                s = open_client(port, pki / "ca.pem")
            except zenoh.ZError:
                time.sleep(0.2)
        assert s is not None, "the bridge never listened on its tls endpoint"
        try:
            assert Count(s).wait(600, 10.0) >= 600
        finally:
            s.close()
    finally:
        try:
            _, err = proc.communicate(timeout=20)  # it stops by itself after --duration
        finally:
            proc.kill()
    assert proc.returncode == 0, err


@pytest.mark.parametrize("content, flags, message", [
    (None, [], "no such file"),
    ("{mode: ", [], "expected"),
    ("{no_such_key: 1}", [], "unknown field"),
    ('{mode: "client"}', ["--mode", "peer"], "--mode peer contradicts mode"),
    ('{connect: {endpoints: ["tls/127.0.0.1:1"]}}', ["--connect", "tcp/127.0.0.1:1"],
     "--connect tcp/127.0.0.1:1 contradicts connect.endpoints"),
    ('{listen: {endpoints: ["tls/127.0.0.1:1"]}}', ["--listen", "tcp/127.0.0.1:1"],
     "--listen tcp/127.0.0.1:1 contradicts listen.endpoints"),
    ("{scouting: {multicast: {enabled: false}}}", ["--scout"], "--scout contradicts"),
    ('{mode: "router"}', [], "peer or a client"),
])
def test_a_bad_or_contradicted_file_is_refused(tmp_path: Path, content: Optional[str],
                                               flags: List[str], message: str) -> None:
    p = tmp_path / "z.json5"
    if content is not None:
        p.write_text(content)
    r = _cli("--sim", "a", "--zenoh-config", str(p), *flags, "--duration", "1")
    assert r.returncode == 2, r.stderr
    assert message in r.stderr and str(p) in r.stderr
    with pytest.raises(ValueError, match="--zenoh-config"):
        ZenohOptions(mode=flags[1] if flags[:1] == ["--mode"] else None,
                     connect=flags[1:] if flags[:1] == ["--connect"] else [],
                     listen=flags[1:] if flags[:1] == ["--listen"] else [],
                     scout=flags == ["--scout"], config_file=str(p)).config()


def test_flags_agreeing_with_the_file_and_the_bridge_defaults(tmp_path: Path) -> None:
    p = tmp_path / "z.json5"
    p.write_text('{mode: "client", connect: {endpoints: ["tcp/127.0.0.1:1"]}}')
    c = ZenohOptions(mode="client", connect=["tcp/127.0.0.1:1"], config_file=str(p)).config()
    assert json.loads(c.get_json("mode")) == "client"
    assert json.loads(c.get_json("connect/endpoints")) == ["tcp/127.0.0.1:1"]
    assert json.loads(c.get_json("scouting/multicast/enabled")) is False
    p.write_text("{}")  # silent: the bridge's defaults, as without a file
    for given in (ZenohOptions(config_file=str(p)), ZenohOptions(scout=True, config_file=str(p))):
        got, plain = given.config(), ZenohOptions(scout=given.scout).config()
        for key in ("mode", "connect/endpoints", "listen/endpoints",
                    "scouting/multicast/enabled"):
            assert json.loads(got.get_json(key)) == json.loads(plain.get_json(key)), key


def _tare(session: Any, timeout: float) -> List[Any]:
    return list(session.get(TARE, payload=cdr.encode_trigger_request(),
                            attachment=rz.attachment(1, time.time_ns(), bytes(16)),
                            target=zenoh.QueryTarget.ALL_COMPLETE, timeout=timeout))


def test_the_docs_acl_example_lets_only_the_operator_tare(pki: Path, tmp_path: Path) -> None:
    """docs/zenoh-acl-example.json5's access control and user/password
    login, over TLS: the viewer receives the wrench but its tare gets no
    reply, the operator's is served, an unknown user cannot connect."""
    example = zenoh.Config.from_file(str(ACL_EXAMPLE))
    assert json.loads(example.get_json("transport/auth/usrpwd/dictionary_file"))
    users = tmp_path / "users.txt"
    users.write_text("operator:operator-pw\nviewer:viewer-pw\n")
    port = free_port()
    conf = json.loads(bridge_config(pki, port, mtls=False).read_text().split("\n", 1)[1])
    conf["transport"]["auth"] = {"usrpwd": {"dictionary_file": str(users)}}
    conf["access_control"] = json.loads(example.get_json("access_control"))
    path = tmp_path / "bridge.json5"
    path.write_text(json.dumps(conf))
    with Bridge([SensorSpec("a", sim={})], NodeOptions(),
                ZenohOptions(config_file=str(path))) as b:
        b.start()
        with pytest.raises(zenoh.ZError):
            open_client(port, pki / "ca.pem", user="intruder").close()
        viewer = open_client(port, pki / "ca.pem", user="viewer")
        operator = open_client(port, pki / "ca.pem", user="operator")
        try:
            assert Count(viewer).wait(600, 10.0) >= 600
            t0 = time.monotonic()
            assert [r for r in _tare(viewer, 2.0) if r.ok is not None] == []
            assert time.monotonic() - t0 < 5.0
            replies = [r.ok for r in _tare(operator, 10.0) if r.ok is not None]
            assert len(replies) == 1
            assert bytes(replies[0].payload.to_bytes())[4] == 1  # Trigger_Response.success
        finally:
            viewer.close()
            operator.close()
