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
    assert c["conditions_refused"] == 2 and c["force_periods_missed"] == len(device)
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
