"""The device's wire format, protocol version 2 (docs/protocol.md), written
independently of the C++ codec: the frames the experiment needs.

Frame: 'FF', version, type, sequence, u16 payload length, payload,
CRC-16/CCITT-FALSE over version..payload; all numbers little-endian."""
import math
import struct
from dataclasses import dataclass, field

VERSION = 2
MAGIC = b"FF"
HEADER = 7
MAX_PAYLOAD = 1400

SET_CONDITION, QUERY_STATUS, START_STREAM = 0x01, 0x02, 0x03
QUERY_CONDITION = 0x08
SET_SENSOR_PROFILE, QUERY_SENSOR_PROFILE = 0x09, 0x0A
ACK, STATUS, FORCE, SAMPLES, TICKS, CONDITION, SENSOR_PROFILE, ERROR = 0x81, 0x82, 0x83, 0x84, 0x85, 0x86, 0x87, 0xE0
KNOWN_TYPES = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, SET_SENSOR_PROFILE, QUERY_SENSOR_PROFILE,
               ACK, STATUS, FORCE, SAMPLES, TICKS, CONDITION, SENSOR_PROFILE, ERROR}

KINDS = {"heightmap": 0, "frictionmap": 1, "neutral": 2, "general": 3}
TARGET_CODES = {"top": 0, "middle": 1, "bottom": 2}
ERROR_NAMES = {1: "too short", 2: "bad magic", 3: "version", 4: "length", 5: "CRC", 6: "unknown type",
               7: "malformed", 8: "busy"}
# The status message's fault counters, in ff::Fault's order with its to_string
# names (src/core/fault_counters.cpp; test_exp_protocol checks them against it).
FAULT_NAMES = ["non_finite_coordinate", "off_screen", "non_increasing_time", "jump_rejected",
               "jump_confirmed", "stale_sample", "sensor_timeout", "lift_off", "touch_down",
               "mailbox_overflow", "bad_strength", "bad_calibration", "bad_tick_time",
               "sample_time_implausible", "time_base_reset", "bad_sensor_profile"]
# What the firmware counts beside the faults (ff::protocol::DeviceCount), the
# touch sensor's states, and the zForce driver's counts (ff::ZforceCount, its
# to_string names with "_" for " "): each in its enum's order, as Status
# carries them (firmware 1.1 on; test_exp_protocol checks them against the C++).
DEVICE_COUNT_NAMES = ["conditions_set", "conditions_refused", "sensor_profiles_set", "sensor_profiles_refused",
                      "tick_stalls", "hid_frames_dropped", "sensor_restarts", "mouse_moves_skipped",
                      "udp_send_failures", "force_read_errors", "force_rezeros", "force_rezeros_refused",
                      "force_periods_missed", "udp_unavailable"]
SENSOR_STATES = ["booting", "configuring", "running", "failed", "unknown"]
ZFORCE_COUNT_NAMES = ["frames_read", "samples", "wrong_header", "length_over_max", "truncated", "malformed_tag",
                      "unknown_tag", "impossible_value", "bus_error", "resync_bytes", "other_finger_ignored",
                      "ghost_or_invalid", "resumed_without_down", "unexpected_response", "config_retry",
                      "sensor_rebooted", "track_lost", "timestamp_beside_the_touches",
                      "timestamp_inside_the_touches"]
# Counts of normal operation (a trial's condition, the load cells' re-zeroing
# between touches, every zForce report): not worth a log line.
ROUTINE_COUNTS = {"conditions_set", "sensor_profiles_set", "force_rezeros"}
ZFORCE_COUNTS_THAT_MOVE = {"frames_read", "samples", "timestamp_beside_the_touches", "timestamp_inside_the_touches"}


class ProtocolError(Exception):
    pass


def crc16(data, crc=0xFFFF):
    """CRC-16/CCITT-FALSE: poly 0x1021, init 0xFFFF, no reflection, no xor-out."""
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) & 0xFFFF if crc & 0x8000 else (crc << 1) & 0xFFFF
    return crc


def frame(msg_type, sequence, payload=b""):
    if len(payload) > MAX_PAYLOAD:
        raise ProtocolError("payload too long")
    body = struct.pack("<BBBH", VERSION, msg_type, sequence & 0xFF, len(payload)) + payload
    return MAGIC + body + struct.pack("<H", crc16(body))


def unframe(data):
    """(type, sequence, payload) of a datagram, or ProtocolError saying which check failed."""
    if len(data) < HEADER + 2:
        raise ProtocolError("too short")
    if data[:2] != MAGIC:
        raise ProtocolError("bad magic")
    if data[2] != VERSION:
        raise ProtocolError(f"protocol version {data[2]}, this program speaks {VERSION}")
    n = struct.unpack_from("<H", data, 5)[0]
    if n > MAX_PAYLOAD or len(data) != HEADER + n + 2:
        raise ProtocolError("bad length")
    if crc16(data[2:HEADER + n]) != struct.unpack_from("<H", data, HEADER + n)[0]:
        raise ProtocolError("bad CRC")
    if data[3] not in KNOWN_TYPES:
        raise ProtocolError(f"unknown type 0x{data[3]:02X}")
    return data[3], data[4], bytes(data[HEADER:HEADER + n])


def _f32(v):
    if not math.isfinite(v):
        raise ProtocolError("non-finite number")
    return struct.pack("<f", v)


@dataclass
class Condition:
    kind: str = "neutral"
    target: str = "middle"
    strength: float = 1.0
    idle_amplitude: float = 0.0
    s_curve: float = 0.0
    calibration: list = field(default_factory=lambda: [(0.0, 0.0), (1.0, 4095.0)])
    scene: bytes = b""  # the encoded scene of a general condition

    def payload(self):
        if not 0.0 < self.strength <= 1.0:
            raise ProtocolError("strength outside (0, 1]")
        out = struct.pack("<BB", KINDS[self.kind], TARGET_CODES[self.target])
        out += _f32(self.strength) + _f32(self.idle_amplitude) + _f32(self.s_curve)
        out += struct.pack("<B", len(self.calibration))
        for a, c in self.calibration:
            out += _f32(a) + _f32(c)
        return out + (self.scene if self.kind == "general" else b"")


def decode_condition(p):
    if len(p) < 15:
        raise ProtocolError("malformed condition")
    kind, target = p[0], p[1]
    strength, idle, s_curve = struct.unpack_from("<fff", p, 2)
    n = p[14]
    scene = p[15 + 8 * n:] if kind == KINDS["general"] else b""
    if len(p) != 15 + 8 * n + len(scene) or kind not in KINDS.values() or target > 2:
        raise ProtocolError("malformed condition")
    cal = [struct.unpack_from("<ff", p, 15 + 8 * i) for i in range(n)]
    names = {v: k for k, v in KINDS.items()}
    tnames = {v: k for k, v in TARGET_CODES.items()}
    return Condition(names[kind], tnames[target], strength, idle, s_curve, [tuple(c) for c in cal], bytes(scene))


# Scenes of general conditions (the core's ff::scenes, docs/protocol.md "Scene").
RENDERING_CODES = {"constant": 0, "position": 1, "directional": 2}


def scene(rendering, elements):
    """rendering name, [element bytes]: closed-form evaluation, default table settings."""
    head = struct.pack("<B", RENDERING_CODES[rendering]) + _f32(0.5) + _f32(0.0)
    head += struct.pack("<B", 0) + _f32(4.0) + struct.pack("<BBB", 1, 0, len(elements))
    return head + b"".join(elements)


def sine_band(y0, amplitude, wavelength, a=0.2, half_width=10.0, feather=20.0, weight=1.0):
    """A slippery band along y0 + amplitude sin(2 pi x / wavelength) (path sink, sine curve)."""
    return (struct.pack("<B", 1) + _f32(weight) + struct.pack("<B", 1)
            + b"".join(_f32(v) for v in (0.0, y0, 600.0, 0.0, amplitude, wavelength, a, half_width, feather)))


def texture(wavelength_x, wavelength_y, height, weight=1.0):
    return struct.pack("<B", 5) + b"".join(_f32(v) for v in (weight, wavelength_x, wavelength_y, height))


FAMILIARISATION = {
    # the core's scenes::familiarisation_path() and scenes::bump_map()
    "familiarisation-path": Condition("general", "middle", 1.0, scene=scene("position", [sine_band(240.0, 120.0, 400.0)])),
    "bump-map": Condition("general", "middle", 1.0, scene=scene("directional", [texture(160.0, 160.0, 20.0)])),
}


def set_condition(seq, condition):
    return frame(SET_CONDITION, seq, condition.payload())


def query_status(seq):
    return frame(QUERY_STATUS, seq)


def start_stream(seq, decimation):
    return frame(START_STREAM, seq, struct.pack("<B", decimation))


@dataclass
class Ack:
    command: int
    ok: bool
    detail: int


@dataclass
class Status:
    firmware_version: int
    kind: int
    target: int
    strength: float
    ticks: int
    tick_cycles_mean: int
    tick_cycles_max: int
    protocol_errors: int
    watchdog_trips: int
    stream_overruns: int
    force_mn: float
    over_force: bool
    finger: bool
    carrier_hz: float
    faults: list
    # isr cycles mean/max/p99, last preparation us, slowest loop pass us, zForce stamp layouts beside/inside
    silicon: tuple = ()
    device: list = field(default_factory=list)         # DEVICE_COUNT_NAMES order ([] before firmware 1.1)
    sensor_state: str = "unknown"
    sensor_counts: list = field(default_factory=list)  # ZFORCE_COUNT_NAMES order

    @property
    def firmware(self):
        return f"{self.firmware_version >> 8}.{self.firmware_version & 0xFF}"

    def counters(self):
        """The counters worth logging when they change: faults, refusals and errors."""
        c = dict(protocol_errors=self.protocol_errors, watchdog_trips=self.watchdog_trips,
                 stream_overruns=self.stream_overruns)
        for i, v in enumerate(self.faults):
            c[FAULT_NAMES[i] if i < len(FAULT_NAMES) else f"fault{i}"] = v
        for i, v in enumerate(self.device):
            name = DEVICE_COUNT_NAMES[i] if i < len(DEVICE_COUNT_NAMES) else f"device{i}"
            if name not in ROUTINE_COUNTS:
                c[name] = v
        for i, v in enumerate(self.sensor_counts):
            name = ZFORCE_COUNT_NAMES[i] if i < len(ZFORCE_COUNT_NAMES) else f"zforce{i}"
            if name not in ZFORCE_COUNTS_THAT_MOVE:
                c["zforce_" + name] = v
        return c


@dataclass
class Force:
    t_us: int
    force_mn: float
    over_force: bool


@dataclass
class Error:
    code: int
    offending_type: int

    def text(self):
        return f"device error: {ERROR_NAMES.get(self.code, self.code)} (message type 0x{self.offending_type:02X})"


@dataclass
class ConditionEcho:
    """The device's reply to QueryCondition: the condition it renders, as sent."""
    payload: bytes


def query_condition(seq):
    return frame(QUERY_CONDITION, seq)


STATUS_FIXED = struct.Struct("<HBBfIIIIIIfBf7IB")  # docs/protocol.md Status
SENSOR_PROFILE_FORMAT = struct.Struct("<6fIf")       # docs/protocol.md Sensor profile
SENSOR_PROFILE_BEFORE_TREMOR_HZ = struct.Struct("<6fI")  # a firmware from before the tremor's frequency


@dataclass
class SensorProfile:
    """What the tracker knows of its sensor (ff::SensorProfile; ff-track-bench --calibrate)."""
    white_noise_px: float = 1.0
    correlated_noise_px: float = 0.0
    correlation_time_ms: float = 0.0
    tremor_px: float = 0.0
    report_rate_hz: float = 200.0
    jitter_us: float = 150.0
    latency_us: int = 0
    tremor_hz: float = 0.0  # 0: not measured


def _sensor_profile_payload(profile):
    floats = b"".join(_f32(getattr(profile, n)) for n in ("white_noise_px", "correlated_noise_px",
                                                          "correlation_time_ms", "tremor_px", "report_rate_hz",
                                                          "jitter_us"))
    return floats + struct.pack("<I", int(profile.latency_us)) + _f32(profile.tremor_hz)


def set_sensor_profile(seq, profile):
    return frame(SET_SENSOR_PROFILE, seq, _sensor_profile_payload(profile))


def query_sensor_profile(seq):
    return frame(QUERY_SENSOR_PROFILE, seq)


def decode(data):
    """A device->host datagram as (sequence, message object); Ticks as
    (sequence, [(t_us, amplitude, dac, finger), ...])."""
    t, seq, p = unframe(data)
    try:
        if t == ACK and len(p) == 3:
            return seq, Ack(p[0], p[1] == 0, p[2])
        if t == FORCE and len(p) == 9:
            tu, f, o = struct.unpack("<IfB", p)
            return seq, Force(tu, f, bool(o))
        if t == ERROR and len(p) == 2:
            return seq, Error(p[0], p[1])
        if t == STATUS and len(p) >= STATUS_FIXED.size:
            v = STATUS_FIXED.unpack_from(p)
            n = v[-1]
            at = STATUS_FIXED.size + 4 * n
            faults = list(struct.unpack_from(f"<{n}I", p, STATUS_FIXED.size))
            device, state, sensor = [], "unknown", []
            if len(p) > at:  # firmware 1.1 on: device counts, sensor state, zForce counts
                m = p[at]
                device = list(struct.unpack_from(f"<{m}I", p, at + 1))
                at += 1 + 4 * m
                if len(p) < at + 2 or p[at] >= len(SENSOR_STATES):
                    raise ProtocolError("malformed Status")
                state = SENSOR_STATES[p[at]]
                k = p[at + 1]
                sensor = list(struct.unpack_from(f"<{k}I", p, at + 2))
                at += 2 + 4 * k
            if len(p) != at:
                raise ProtocolError("malformed Status")
            return seq, Status(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10],
                               bool(v[11] & 1), bool(v[11] & 2), v[12], faults, tuple(v[13:20]), device, state,
                               sensor)
        if t == TICKS and p and len(p) == 1 + 10 * p[0]:
            ticks = []
            for i in range(p[0]):
                tu, a, code = struct.unpack_from("<IfH", p, 1 + 10 * i)
                ticks.append((tu, a, code & 0x0FFF, bool(code & 0x8000)))
            return seq, ticks
        if t == CONDITION:
            decode_condition(p)  # checks it
            return seq, ConditionEcho(p)
        if t == SENSOR_PROFILE and len(p) in (SENSOR_PROFILE_FORMAT.size, SENSOR_PROFILE_BEFORE_TREMOR_HZ.size):
            fmt = SENSOR_PROFILE_FORMAT if len(p) == SENSOR_PROFILE_FORMAT.size else SENSOR_PROFILE_BEFORE_TREMOR_HZ
            v = fmt.unpack(p)
            if all(math.isfinite(x) for x in v[:6] + v[7:]):
                return seq, SensorProfile(*v)
        if t == SAMPLES:
            return seq, None  # not used by the experiment
    except struct.error:
        pass
    raise ProtocolError(f"malformed message type 0x{t:02X}")


# ------------------------------------------------ device side (for stand-ins and tests)

def ack(seq, command, ok=True, detail=0):
    return frame(ACK, seq, struct.pack("<BBB", command, 0 if ok else 1, detail))


def sensor_profile(seq, profile):
    """The device's answer to QuerySensorProfile."""
    return frame(SENSOR_PROFILE, seq, _sensor_profile_payload(profile))


def force(seq, t_us, force_mn, over_force=False):
    return frame(FORCE, seq, struct.pack("<I", t_us) + _f32(force_mn) + struct.pack("<B", int(over_force)))


def status(seq, firmware_version=0x0200, force_mn=0.0, faults=(), device=None, sensor_state=2, sensor_counts=(),
           **kw):
    """device=None: a firmware 1.0 Status, ending after the faults."""
    fixed = STATUS_FIXED.pack(firmware_version, kw.get("kind", 2), kw.get("target", 1), kw.get("strength", 1.0),
                              kw.get("ticks", 0), 0, 0, kw.get("protocol_errors", 0), 0, 0, force_mn, 0,
                              34900.0, 0, 0, 0, 0, 0, 0, 0, len(faults))
    p = fixed + struct.pack(f"<{len(faults)}I", *faults)
    if device is not None:
        p += struct.pack(f"<B{len(device)}I", len(device), *device)
        p += struct.pack(f"<BB{len(sensor_counts)}I", sensor_state, len(sensor_counts), *sensor_counts)
    return frame(STATUS, seq, p)


def ticks(seq, records):
    p = struct.pack("<B", len(records))
    for tu, a, code, finger in records:
        p += struct.pack("<I", tu) + _f32(a) + struct.pack("<H", (code & 0x0FFF) | (0x8000 if finger else 0))
    return frame(TICKS, seq, p)
