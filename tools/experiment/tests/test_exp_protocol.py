"""The Python codec against frames built by hand from docs/protocol.md (and,
once the C++ encoder is on the branch, against its frames)."""
import struct

import pytest

from ffexp import protocol


def test_crc_check_value():
    assert protocol.crc16(b"123456789") == 0x29B1


def test_force_example_from_the_doc():
    doc = bytes.fromhex("46 46 02 83 09 09 00 04 03 02 01 00 00 80 3F 01 BE 08")
    assert protocol.force(9, 0x01020304, 1.0, True) == doc
    seq, m = protocol.decode(doc)
    assert seq == 9 and m == protocol.Force(0x01020304, 1.0, True)


def test_set_condition_is_40_bytes_by_hand():
    c = protocol.Condition("frictionmap", "bottom", 0.66)
    f = protocol.set_condition(5, c)
    assert len(f) == 40
    payload = (bytes([1, 2]) + struct.pack("<f", 0.66) + struct.pack("<f", 0.0) + struct.pack("<f", 0.0)
               + bytes([2]) + struct.pack("<ffff", 0.0, 0.0, 1.0, 4095.0))
    body = bytes([2, 0x01, 5]) + struct.pack("<H", len(payload)) + payload
    assert f == b"FF" + body + struct.pack("<H", protocol.crc16(body))
    t, seq, p = protocol.unframe(f)
    d = protocol.decode_condition(p)
    assert (d.kind, d.target, d.calibration) == ("frictionmap", "bottom", [(0.0, 0.0), (1.0, 4095.0)])
    assert d.strength == pytest.approx(0.66, abs=1e-7)


@pytest.mark.parametrize("mutate, why", [
    (lambda f: f[:8], "too short"),
    (lambda f: b"FG" + f[2:], "bad magic"),
    (lambda f: f[:2] + b"\x01" + f[3:], "version 1"),
    (lambda f: f[:-3] + bytes([f[-3] ^ 1]) + f[-2:], "bad CRC"),
    (lambda f: f + b"\x00", "bad length"),
])
def test_bad_frames_say_why(mutate, why):
    f = protocol.ack(1, protocol.SET_CONDITION)
    with pytest.raises(protocol.ProtocolError, match=why):
        protocol.decode(mutate(f))


def test_status_and_ticks_round_trip():
    s = protocol.status(3, firmware_version=0x0203, force_mn=250.0, faults=[1, 0, 7], protocol_errors=2)
    seq, m = protocol.decode(s)
    assert m.firmware == "2.3" and m.force_mn == 250.0 and m.faults == [1, 0, 7] and m.protocol_errors == 2
    seq, t = protocol.decode(protocol.ticks(4, [(10, 0.5, 2047, True), (510, 0.25, 1023, False)]))
    assert t == [(10, 0.5, 2047, True), (510, 0.25, 1023, False)]


def test_status_tail_round_trips_and_a_firmware_1_0_status_has_none():
    old = protocol.decode(protocol.status(1, faults=[0, 2]))[1]
    assert old.device == [] and old.sensor_state == "unknown" and old.sensor_counts == []
    assert old.counters() == {"protocol_errors": 0, "watchdog_trips": 0, "stream_overruns": 0,
                              "non_finite_coordinate": 0, "off_screen": 2}
    device = list(range(1, len(protocol.DEVICE_COUNT_NAMES) + 1))
    sensor = [50, 40, 0, 0, 0, 0, 0, 0, 3]  # frames read, samples, ..., bus error
    m = protocol.decode(protocol.status(2, faults=[], device=device, sensor_state=3, sensor_counts=sensor))[1]
    assert m.device == device and m.sensor_state == "failed" and m.sensor_counts == sensor
    c = m.counters()
    assert c["conditions_refused"] == 2 and c["force_periods_missed"] == 13 and c["udp_unavailable"] == len(device)
    assert "conditions_set" not in c and "force_rezeros" not in c  # routine, not news
    assert c["zforce_bus_error"] == 3 and "zforce_frames_read" not in c and "zforce_samples" not in c


@pytest.mark.parametrize("cut", [1, 2, 5])
def test_a_status_tail_cut_short_is_malformed(cut):
    f = protocol.status(2, device=[1, 2], sensor_state=2, sensor_counts=[7])
    _, _, p = protocol.unframe(f)
    with pytest.raises(protocol.ProtocolError):
        protocol.decode(protocol.frame(protocol.STATUS, 2, p[:-cut]))


def test_a_sensor_state_past_unknown_is_malformed():
    with pytest.raises(protocol.ProtocolError):
        protocol.decode(protocol.status(2, device=[], sensor_state=5))


def test_nan_refused():
    with pytest.raises(protocol.ProtocolError):
        protocol.Condition("heightmap", "top", float("nan")).payload()


def test_fault_names_are_the_cores_in_its_order():
    # The C++ source is the authority: the enum's order in fault_counters.hpp
    # and each member's to_string name in fault_counters.cpp.
    import re
    from pathlib import Path
    root = Path(__file__).resolve().parents[3]
    header = (root / "include/frictionfield/core/fault_counters.hpp").read_text()
    enum = re.search(r"enum class Fault[^{]*\{(.*?)kCount", header, re.S).group(1)
    members = re.findall(r"^\s*(\w+),", enum, re.M)
    source = (root / "src/core/fault_counters.cpp").read_text()
    names = dict(re.findall(r'case Fault::(\w+): return "(\w+)";', source))
    assert protocol.FAULT_NAMES == [names[m] for m in members]


def test_set_sensor_profile_is_the_docs_example():
    doc = bytes.fromhex("46 46 02 09 03 20 00 00 00 C0 3F 00 00 00 3F 00 00 7A 43 00 00 80 3E 00 00 48 43"
                        " 00 00 16 43 B8 0B 00 00 00 00 18 41 64 4A")
    p = protocol.SensorProfile(1.5, 0.5, 250.0, 0.25, 200.0, 150.0, 3000, 9.5)
    assert protocol.set_sensor_profile(3, p) == doc
    assert protocol.query_sensor_profile(4) == protocol.frame(protocol.QUERY_SENSOR_PROFILE, 4)


def test_a_sensor_profile_reply_decodes_and_a_non_finite_one_is_malformed():
    p = protocol.SensorProfile(1.02, 1.5, 30.0, 1.0, 1000.0, 205.0, 2000)
    _, _, payload = protocol.unframe(protocol.set_sensor_profile(7, p))
    seq, m = protocol.decode(protocol.frame(protocol.SENSOR_PROFILE, 7, payload))
    assert seq == 7 and m == protocol.SensorProfile(*struct.unpack("<6fIf", payload))
    assert abs(m.white_noise_px - 1.02) < 1e-6 and m.latency_us == 2000 and m.tremor_hz == 0.0
    # a firmware from before the tremor's frequency answers 28 bytes: not measured
    seq, m = protocol.decode(protocol.frame(protocol.SENSOR_PROFILE, 7, payload[:28]))
    assert m.latency_us == 2000 and m.tremor_hz == 0.0
    tremor_hz = struct.pack("<6fIf", 1, 0, 0, 1, 200, 150, 0, 9.25)
    assert protocol.decode(protocol.frame(protocol.SENSOR_PROFILE, 7, tremor_hz))[1].tremor_hz == 9.25
    with pytest.raises(protocol.ProtocolError):
        protocol.decode(protocol.frame(protocol.SENSOR_PROFILE, 8, tremor_hz[:-1]))
    for bad in (struct.pack("<6fI", float("nan"), 0, 0, 0, 200, 150, 0),
                struct.pack("<6fIf", 1, 0, 0, 0, 200, 150, 0, float("inf"))):
        with pytest.raises(protocol.ProtocolError):
            protocol.decode(protocol.frame(protocol.SENSOR_PROFILE, 8, bad))
    with pytest.raises(protocol.ProtocolError):
        protocol.set_sensor_profile(9, protocol.SensorProfile(white_noise_px=float("inf")))


def _enum_members(header, enum):
    """The members of `enum class <enum>` in order, without kCount."""
    import re
    body = re.search(r"enum class " + enum + r"\b[^{]*\{(.*?)\}", header, re.S).group(1)
    body = re.sub(r"//[^\n]*", "", body)
    return [m.strip() for m in body.split(",") if m.strip() and m.strip() != "kCount"]


def test_device_sensor_and_zforce_names_are_the_firmwares_in_its_order():
    import re
    from pathlib import Path
    root = Path(__file__).resolve().parents[3]
    header = (root / "include/frictionfield/protocol/device_counts.hpp").read_text()
    source = (root / "src/protocol/device_counts.cpp").read_text()
    names = dict(re.findall(r'case DeviceCount::(\w+): return "(\w+)";', source))
    assert protocol.DEVICE_COUNT_NAMES == [names[m] for m in _enum_members(header, "DeviceCount")]
    states = dict(re.findall(r'case SensorState::(\w+): return "(\w+)";', source))
    states["Unknown"] = "unknown"
    assert protocol.SENSOR_STATES == [states[m] for m in _enum_members(header, "SensorState")]
    header = (root / "include/frictionfield/drivers/zforce_sensor.hpp").read_text()
    source = (root / "src/drivers/zforce_sensor.cpp").read_text()
    names = dict(re.findall(r'case ZforceCount::(\w+): return "([\w ]+)";', source))
    assert protocol.ZFORCE_COUNT_NAMES == [names[m].replace(" ", "_") for m in _enum_members(header, "ZforceCount")]


def test_a_payload_is_at_most_1400_bytes():
    assert len(protocol.frame(protocol.SET_CONDITION, 1, bytes(1400))) == 7 + 1400 + 2
    with pytest.raises(protocol.ProtocolError, match="payload too long"):
        protocol.frame(protocol.SET_CONDITION, 1, bytes(1401))


def test_an_unknown_type_with_a_good_crc_is_refused_by_name():
    body = bytes([2, 0x7F, 1, 0, 0])
    with pytest.raises(protocol.ProtocolError, match="unknown type 0x7F"):
        protocol.unframe(b"FF" + body + struct.pack("<H", protocol.crc16(body)))


@pytest.mark.parametrize("strength", [0.0, -0.25, 1.0000001, float("inf")])
def test_a_strength_outside_0_to_1_is_not_sent(strength):
    with pytest.raises(protocol.ProtocolError, match=r"strength outside \(0, 1\]"):
        protocol.Condition("heightmap", "top", strength).payload()


def _condition_payload(kind=0, target=0, n=2, tail=b""):
    """A condition by hand (docs/protocol.md Condition): kind, target, three
    floats, n calibration pairs, then what follows."""
    pairs = b"".join(struct.pack("<ff", i / max(n - 1, 1), 4095.0 * i) for i in range(n))
    return bytes([kind, target]) + struct.pack("<fff", 0.5, 0.0, 0.0) + bytes([n]) + pairs + tail


def test_a_hand_made_condition_decodes():
    c = protocol.decode_condition(_condition_payload(kind=1, target=2))
    assert (c.kind, c.target, c.strength, c.calibration, c.scene) == ("frictionmap", "bottom", 0.5,
                                                                       [(0.0, 0.0), (1.0, 4095.0)], b"")
    c = protocol.decode_condition(_condition_payload(kind=3, target=1, tail=b"scene"))
    assert (c.kind, c.target, c.scene) == ("general", "middle", b"scene")


@pytest.mark.parametrize("payload", [
    _condition_payload()[:14],          # ends before the calibration's count
    _condition_payload()[:-1],          # a calibration pair cut short
    _condition_payload(tail=b"\x00"),   # a byte after the calibration of a kind without a scene
    _condition_payload(kind=4),         # no such kind
    _condition_payload(target=3),       # no such target
], ids=["no-count", "short-pair", "trailing-byte", "kind-4", "target-3"])
def test_a_malformed_condition_is_refused(payload):
    with pytest.raises(protocol.ProtocolError, match="malformed condition"):
        protocol.decode_condition(payload)
    # the device's echo of it is malformed too, not a condition to trust
    with pytest.raises(protocol.ProtocolError, match="malformed"):
        protocol.decode(protocol.frame(protocol.CONDITION, 3, payload))


def test_the_condition_echo_is_the_payload_sent():
    payload = protocol.Condition("heightmap", "top", 0.33).payload()
    seq, m = protocol.decode(protocol.frame(protocol.CONDITION, 6, payload))
    assert seq == 6 and m == protocol.ConditionEcho(payload)


def test_error_names_are_the_docs_codes():
    import re
    from pathlib import Path
    table = (Path(__file__).resolve().parents[3] / "docs/protocol.md").read_text()
    row = re.search(r"\| 0xE0 \| Error \|.*?code u8 \(([^)]*)\)", table).group(1)
    assert protocol.ERROR_NAMES == {int(n): name for n, name in re.findall(r"(\d+) ([^,]+)", row)}


def test_a_device_error_decodes_and_says_what_it_refused():
    seq, m = protocol.decode(protocol.frame(protocol.ERROR, 4, bytes([5, 0x01])))
    assert seq == 4 and m == protocol.Error(5, 0x01)
    assert m.text() == "device error: CRC (message type 0x01)"
    assert protocol.Error(42, 0x0A).text() == "device error: 42 (message type 0x0A)"
    with pytest.raises(protocol.ProtocolError, match="malformed message type 0xE0"):
        protocol.decode(protocol.frame(protocol.ERROR, 4, bytes([5])))


def test_a_status_with_bytes_after_its_zforce_counts_is_malformed():
    _, _, p = protocol.unframe(protocol.status(2, device=[1], sensor_state=2, sensor_counts=[7]))
    with pytest.raises(protocol.ProtocolError, match="malformed Status"):
        protocol.decode(protocol.frame(protocol.STATUS, 2, p + b"\x00"))


def test_samples_decode_to_nothing_the_experiment_uses():
    # docs/protocol.md Samples: one report without taken times
    p = bytes([1, 0]) + struct.pack("<IffB", 1000, 10.0, 20.0, 1)
    assert protocol.decode(protocol.frame(protocol.SAMPLES, 8, p)) == (8, None)


def test_the_device_side_sensor_profile_reply_is_the_set_payload():
    p = protocol.SensorProfile(1.5, 0.5, 250.0, 0.25, 200.0, 150.0, 3000, 9.5)
    _, _, payload = protocol.unframe(protocol.set_sensor_profile(3, p))
    assert protocol.sensor_profile(3, p) == protocol.frame(protocol.SENSOR_PROFILE, 3, payload)
    assert protocol.decode(protocol.sensor_profile(3, p))[1] == protocol.SensorProfile(*struct.unpack("<6fIf", payload))
