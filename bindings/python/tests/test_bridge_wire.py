"""leptrino.bridge's wire formats, checked against published values and
independent decoders (rosbags' CDR deserializer, zenoh's own serializer):
RIHS01 type hashes, CDR bytes, the rmw_zenoh attachment, keys and tokens."""

from __future__ import annotations

import struct

import pytest

from leptrino.bridge import cdr, typehash
from leptrino.bridge import rmw_zenoh as rz
from leptrino.bridge.mcap_out import ros2msg_schema

# Published RIHS01 hashes (ROS 2 Jazzy). std_msgs/String: rmw_zenoh's
# docs/design.md examples. The others appear verbatim in public ROS 2
# tooling (see docs/bridge.md, "Type hashes").
PUBLISHED = {
    "std_msgs/msg/String":
        "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18",
    "geometry_msgs/msg/WrenchStamped":
        "RIHS01_8dc3deaf06b2ab281f9f9a742a8961c328ca7cec16e3fd6586d3a5c83fa78f77",
    "diagnostic_msgs/msg/DiagnosticArray":
        "RIHS01_5a8a36efb05fb25070fa0fb3810290c0e6cd4862b54a8fb975a1ee8dc55a333e",
    "std_srvs/srv/Trigger":
        "RIHS01_eeff2cd6fa5ad9d27cdf4dec64818317839b62f212a91e6b5304b634b2062c5f",
    "builtin_interfaces/msg/Time":
        "RIHS01_b106235e25a4c5ed35098aa0a61a3ee9c9b18d197f398b0e4206cea9acf9c197",
}


@pytest.fixture(scope="module")
def store():
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    # rosbags files a .msg it parses under msg/; the CDR layout is the same
    ts.register(get_types_from_msg("uint8 structure_needs_at_least_one_member",
                                   "std_srvs/msg/Trigger_Request"))
    ts.register(get_types_from_msg("bool success\nstring message",
                                   "std_srvs/msg/Trigger_Response"))
    return ts


def test_type_hashes_match_published_values(monkeypatch):
    monkeypatch.setitem(typehash.MESSAGES, "std_msgs/msg/String", "string data\n")
    for name, want in PUBLISHED.items():
        assert typehash.rihs01(name) == want, name


def test_type_hashes_match_rosbags(store):
    for name in ("geometry_msgs/msg/WrenchStamped", "diagnostic_msgs/msg/DiagnosticArray",
                 "diagnostic_msgs/msg/KeyValue", "std_msgs/msg/Header",
                 "std_msgs/msg/Empty"):  # the DDS command topics' type
        assert typehash.rihs01(name) == store.hash_rihs01(name), name


def test_canonical_json_of_time():
    text = typehash.canonical_json(typehash.type_description("builtin_interfaces/msg/Time"))
    assert text == (
        '{"type_description": {"type_name": "builtin_interfaces/msg/Time", "fields": ['
        '{"name": "sec", "type": {"type_id": 6, "capacity": 0, "string_capacity": 0, '
        '"nested_type_name": ""}}, '
        '{"name": "nanosec", "type": {"type_id": 7, "capacity": 0, "string_capacity": 0, '
        '"nested_type_name": ""}}]}, "referenced_type_descriptions": []}')


def test_msg_parser_types_and_errors():
    f = typehash.parse_fields(
        "int32 A=1\nstring<=8 s\nfloat64[3] v\nKeyValue[<=4] kv\nuint8[] b  # c\n", "pkg")
    assert f == [("s", 21, 0, 8, ""), ("v", 11 + 48, 3, 0, ""),
                 ("kv", 1 + 96, 4, 0, "pkg/msg/KeyValue"), ("b", 3 + 144, 0, 0, "")]
    assert typehash.parse_fields("", "p") == [
        ("structure_needs_at_least_one_member", 3, 0, 0, "")]
    with pytest.raises(ValueError, match="not a field"):
        typehash.parse_fields("float64", "p")


def _wrench_batch(frame, t_utc, si, raw=None, rated=(200, 200, 400, 4, 4, 4)):
    """The C encoder (lep_ros_wrench_cdr) on a batch filled here."""
    import leptrino
    from leptrino.bridge.wrench_batch import WrenchBatch

    wb = WrenchBatch(leptrino.get_backend(), rated, frame, cap=8)
    n = len(t_utc)
    wb.arrays.t_utc[:n] = t_utc
    wb.arrays.si[:n] = si
    wb.arrays.raw[:n] = raw if raw is not None else [[0] * 6] * n
    wb.arrays.n = n
    return wb.encode()


def test_wrench_golden_bytes(store):
    (got,), (raw,), stamps = _wrench_batch("ft", [1700000000.25],
                                           [(1.0, -2.0, 0.5, 0.25, -0.125, 3.0)],
                                           [(10000, -10000, 5000, 2500, 0, -1)])
    want = bytes.fromhex(
        "00010000"          # encapsulation: CDR little-endian
        "00f15365"          # header.stamp.sec 1700000000
        "80b2e60e"          # header.stamp.nanosec 250000000
        "03000000" "667400"  # frame_id: length 3 with the NUL, "ft\0"
        "00"                # padding to 8 (offset 15 -> 16)
        "000000000000f03f"  # force.x 1.0
        "00000000000000c0"  # force.y -2.0
        "000000000000e03f"  # force.z 0.5
        "000000000000d03f"  # torque.x 0.25
        "000000000000c0bf"  # torque.y -0.125
        "0000000000000840")  # torque.z 3.0
    assert got == want
    assert stamps == [1700000000_250000000]
    msg = store.deserialize_cdr(got, "geometry_msgs/msg/WrenchStamped")
    assert (msg.header.stamp.sec, msg.header.stamp.nanosec) == (1700000000, 250000000)
    assert msg.header.frame_id == "ft"
    assert (msg.wrench.force.x, msg.wrench.force.y, msg.wrench.torque.z) == (1.0, -2.0, 3.0)
    # wrench_raw: counts x rated / 10000, the same header
    m = store.deserialize_cdr(raw, "geometry_msgs/msg/WrenchStamped")
    assert raw[:20] == got[:20]
    assert (m.wrench.force.x, m.wrench.force.y, m.wrench.force.z) == (200.0, -200.0, 200.0)
    assert (m.wrench.torque.x, m.wrench.torque.y) == (1.0, 0.0)
    assert m.wrench.torque.z == pytest.approx(-4e-4)


@pytest.mark.parametrize("frame", ["", "a", "abcd", "sensor_frame_7", "é"])
def test_wrench_matches_rosbags_serializer(store, frame):
    """Every frame_id length (so every padding) gives rosbags' own bytes."""
    Time = store.types["builtin_interfaces/msg/Time"]
    Header = store.types["std_msgs/msg/Header"]
    V = store.types["geometry_msgs/msg/Vector3"]
    W = store.types["geometry_msgs/msg/Wrench"]
    WS = store.types["geometry_msgs/msg/WrenchStamped"]
    ref = WS(header=Header(stamp=Time(sec=5, nanosec=6), frame_id=frame),
             wrench=W(force=V(x=1.5, y=2.5, z=-3.5), torque=V(x=0.1, y=0.2, z=0.3)))
    want = bytes(store.serialize_cdr(ref, "geometry_msgs/msg/WrenchStamped"))
    (got,), _, _ = _wrench_batch(frame, [5.000000006], [(1.5, 2.5, -3.5, 0.1, 0.2, 0.3)])
    assert got == want


def test_wrench_batch_stamps_and_refusals():
    """A batch: stamps rounded to the ns and never going back; bad input refused."""
    from leptrino.errors import LeptrinoError

    w, r, stamps = _wrench_batch("f", [10.5, 10.4999999, 11.0],
                                 [(i, 0, 0, 0, 0, 0) for i in range(3)])
    assert stamps == [10_500_000_000, 10_500_000_000, 11_000_000_000]
    assert [struct.unpack_from("<d", p, 20)[0] for p in w] == [0.0, 1.0, 2.0]
    assert len(set(map(len, w + r))) == 1
    with pytest.raises(LeptrinoError):
        _wrench_batch("f", [float("nan")], [(0,) * 6])
    with pytest.raises(ValueError):
        _wrench_batch("a\x00b", [1.0], [(0,) * 6])
    with pytest.raises(ValueError):
        _wrench_batch("x" * 256, [1.0], [(0,) * 6])


def test_diagnostic_array_decodes(store):
    payload = cdr.encode_diagnostic_array(
        7, 8, "f", [(cdr.WARN, "leptrino: a", "rate", "0001", [("k", "v"), ("gaps", "3")]),
                    (cdr.OK, "b", "", "", [])])
    msg = store.deserialize_cdr(payload, "diagnostic_msgs/msg/DiagnosticArray")
    assert msg.header.frame_id == "f" and msg.header.stamp.nanosec == 8
    assert [s.level for s in msg.status] == [1, 0]
    assert [(kv.key, kv.value) for kv in msg.status[0].values] == [("k", "v"), ("gaps", "3")]
    assert msg.status[1].values == []


def test_trigger_request_and_response(store):
    assert cdr.encode_trigger_request() == b"\x00\x01\x00\x00\x00"
    r = store.deserialize_cdr(cdr.encode_trigger_response(True, "tared"),
                              "std_srvs/msg/Trigger_Response")
    assert r.success is True and r.message == "tared"
    with pytest.raises(ValueError):
        cdr.check_encapsulation(b"\x01")
    with pytest.raises(ValueError):
        cdr.encode_trigger_response(True, "a\x00b")


def test_attachment_layout_and_zenoh_serializer():
    import zenoh
    import zenoh.ext as ze

    gid = bytes(range(16))
    att = rz.attachment(5, 1_700_000_000_000_000_001, gid)
    assert len(att) == 33
    assert att == struct.pack("<qq", 5, 1_700_000_000_000_000_001) + b"\x10" + gid
    # zenoh's own serializer (which rmw_zenoh uses) reads it back
    z = ze.z_deserialize(tuple[ze.Int64, ze.Int64, bytes], zenoh.ZBytes(att))
    assert z == (5, 1_700_000_000_000_000_001, gid)
    assert rz.parse_attachment(att) == (5, 1_700_000_000_000_000_001, gid)
    with pytest.raises(ValueError):
        rz.parse_attachment(att[:-1])
    with pytest.raises(ValueError):
        rz.attachment(1, 2, b"short")


def test_keys_and_tokens_match_design_examples():
    """The examples of rmw_zenoh's docs/design.md, rebuilt."""
    h = PUBLISHED["std_msgs/msg/String"]
    assert rz.data_key(0, "/chatter", "std_msgs/msg/String", h) == \
        f"0/chatter/std_msgs::msg::dds_::String_/{h}"
    assert rz.data_key(0, rz.fully_qualified("/robot1", "chatter"), "std_msgs/msg/String",
                       h) == f"0/robot1/chatter/std_msgs::msg::dds_::String_/{h}"
    talker = rz.Entity(2, "8b20917502ee955ac4476e0266340d5c", 0, 10, rz.PUBLISHER, "/",
                       "talker", "/chatter", "std_msgs/msg/String", h, rz.qos_keyexpr(True, 7))
    assert talker.token() == (
        "@ros2_lv/2/8b20917502ee955ac4476e0266340d5c/0/10/MP/%/%/talker/%chatter/"
        f"std_msgs::msg::dds_::String_/{h}/::,7:,:,:,,")
    node = rz.Entity(2, "aac3178e146ba6f1fc6e6a4085e77f21", 0, 0, rz.NODE, "/", "listener")
    assert node.token() == "@ros2_lv/2/aac3178e146ba6f1fc6e6a4085e77f21/0/0/NN/%/%/listener"
    assert rz.qos_keyexpr(False, 5) == "2::,5:,:,:,,"
    ns = rz.Entity(0, "z", 1, 1, rz.NODE, "/cell/ft", "a")
    assert ns.token() == "@ros2_lv/0/z/1/1/NN/%/%cell%ft/a"
    assert len(talker.gid()) == 16 and talker.gid() != node.gid()


def test_names_are_checked():
    assert rz.normalize_namespace("") == "/"
    assert rz.normalize_namespace("cell/ft/") == "/cell/ft"
    for bad in ("1a", "a-b", "a b", "*"):
        with pytest.raises(ValueError):
            rz.check_name(bad)
    with pytest.raises(ValueError):
        rz.normalize_namespace("/a/**")


def test_ros2msg_schema_parses_with_mcap_ros2():
    from mcap_ros2._dynamic import generate_dynamic

    for t in ("geometry_msgs/msg/WrenchStamped", "diagnostic_msgs/msg/DiagnosticArray"):
        text = ros2msg_schema(t).decode()
        assert text.startswith(typehash.MESSAGES[t].rstrip("\n"))
        assert t in generate_dynamic(t, text)


def test_dds_names_and_configuration():
    """ROS 2's DDS names and --dds-interface's configuration fragment."""
    from leptrino.bridge import dds

    assert dds.topic_name("/cell/a/wrench") == "rt/cell/a/wrench"
    assert rz.dds_type_name("std_msgs/msg/Empty") == "std_msgs::msg::dds_::Empty_"
    assert dds.config_xml(None) is None
    xml = dds.config_xml("127.0.0.1")
    assert '<NetworkInterface address="127.0.0.1"/>' in xml
    assert "<AllowMulticast>false</AllowMulticast>" in xml
    assert '<Peer address="127.0.0.1"/>' in xml
    with pytest.raises(ValueError):
        dds.config_xml("eth0; <x/>")
    assert dds.pad4(b"\x00\x01\x00\x00\x01") == b"\x00\x01\x00\x00\x01\x00\x00\x00"
    assert dds.pad4(b"1234") == b"1234"


def test_dds_configuration_honours_cyclonedds_uri(monkeypatch):
    """Kilted's compatibility line first, then CYCLONEDDS_URI (which may
    override it), then --dds-interface's fragment."""
    from leptrino.bridge import dds

    compat = "<Compatibility><IgnoreTypeInformation>1.15</IgnoreTypeInformation></Compatibility>"
    assert compat in dds.COMPAT_XML
    monkeypatch.setenv("CYCLONEDDS_URI", "file:///etc/cyclone.xml")
    cfg = dds.domain_config("127.0.0.1")
    assert cfg == f"{dds.COMPAT_XML},file:///etc/cyclone.xml,{dds.config_xml('127.0.0.1')}"
    assert dds.domain_config(None) == f"{dds.COMPAT_XML},file:///etc/cyclone.xml"
    monkeypatch.delenv("CYCLONEDDS_URI")
    assert dds.domain_config("127.0.0.1") == f"{dds.COMPAT_XML},{dds.config_xml('127.0.0.1')}"
    assert dds.domain_config(None) == dds.COMPAT_XML


def test_dds_impl_choice(monkeypatch):
    """--dds-impl: cyclone when asked; auto falls back to cyclone where rclpy
    does not import or the interface is not loopback; rclpy asked for and
    missing is an error that says how to install it."""
    from leptrino.bridge import dds, rclpy_transport

    assert dds.choose_impl(dds.DdsOptions(impl="cyclone"))[0] == "cyclone"
    with pytest.raises(ValueError):
        dds.choose_impl(dds.DdsOptions(impl="fast"))
    monkeypatch.setattr(rclpy_transport, "unavailable", lambda: "rclpy: No module named 'rclpy'")
    impl, why = dds.choose_impl(dds.DdsOptions())
    assert impl == "cyclone" and "rclpy not available" in why
    with pytest.raises(ValueError, match="ros-jazzy"):
        dds.choose_impl(dds.DdsOptions(impl="rclpy"))
    monkeypatch.setattr(rclpy_transport, "unavailable", lambda: "")
    assert dds.choose_impl(dds.DdsOptions(interface="127.0.0.1"))[0] == "rclpy"
    impl, why = dds.choose_impl(dds.DdsOptions(interface="192.0.2.1"))
    assert impl == "cyclone" and "loopback" in why
    with pytest.raises(ValueError, match="loopback"):
        dds.choose_impl(dds.DdsOptions(impl="rclpy", interface="192.0.2.1"))
    assert rclpy_transport.interface_env(None) == {}


def test_foxglove_address():
    from leptrino.bridge.foxglove_out import parse_address

    assert parse_address("8765") == ("127.0.0.1", 8765)
    assert parse_address("0.0.0.0:9000") == ("0.0.0.0", 9000)
    assert parse_address("[::1]:8765") == ("::1", 8765)
    for bad in ("", "host:", "x:99999", "a:b"):
        with pytest.raises(ValueError):
            parse_address(bad)


@pytest.mark.parametrize("frame", ["", "a", "abcd", "sensor_frame_7", "é"])
def test_c_wrench_encoder_matches_the_schema(frame):
    """The C fast path (lep_ros_wrench_cdr) writes the bytes the schema-driven
    encoder (bridge/schema.py, from the one description) writes."""
    from leptrino.bridge import schema

    t = [1700000000.25, 1700000000.2508333, 5.5]
    si = [(1.0, -2.0, 0.5, 0.25, -0.125, 3.0), (1e-9, 2e9, -0.0, 7.0, 8.0, 9.0),
          (0.0,) * 6]
    got, _raw, stamps = _wrench_batch(frame, t, si, None)
    for payload, stamp, w in zip(got, stamps, si):
        sec, nsec = divmod(stamp, 10**9)
        want = schema.encode("geometry_msgs/msg/WrenchStamped",
                             (((sec, nsec), frame), (w[:3], w[3:])))
        assert payload == want


def test_schema_decoder_refuses_what_is_not_the_message():
    from leptrino.bridge import schema

    ok = schema.encode("geometry_msgs/msg/Vector3Stamped", (((1, 2), "ab"), (1.0, 2.0, 3.0)))
    assert schema.decode("geometry_msgs/msg/Vector3Stamped", ok + b"\0\0\0") == \
        (((1, 2), "ab"), (1.0, 2.0, 3.0))
    for bad in (ok[:-1], ok + b"\0" * 4, b"\x01" + ok[1:], ok[:12] + b"\xff" + ok[13:]):
        with pytest.raises(ValueError):
            schema.decode("geometry_msgs/msg/Vector3Stamped", bad)
