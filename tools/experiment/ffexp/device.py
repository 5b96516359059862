"""The device as the study sees it, behind one interface:
  UdpDevice   the Teensy over UDP (--device udp:HOST[:PORT])
  SimDevice   ff-sim, the firmware on this computer (--device sim)
  FakeDevice  in Python, for unit tests

poll() is called once a frame and never blocks; set_condition() waits for
the Ack. A device that has sent nothing for LOST_AFTER_S (Force arrives
every 30 ms) is lost: the study pauses until it answers again. That
timeout is wall-clock time even when the simulator runs faster, so a busy
computer that delays ff-sim for a few ms is not taken for a lost device."""
import abc
import ctypes
import os
import select
import signal
import socket
import subprocess
import sys
import time

from . import protocol

DEFAULT_PORT = 8888
LOST_AFTER_S = 0.5
REPLY_TIMEOUT_S = 0.25
RETRIES = 4
TICK_DECIMATION = 10  # 200 amplitude samples per simulated second


class DeviceLost(Exception):
    pass


class DeviceRefused(Exception):
    pass


class Device(abc.ABC):
    """Common state: the latest force, amplitude and fault counters."""

    def __init__(self, clock):
        self.clock = clock          # seconds of (simulated) monotonic time
        self.force_n = float("nan")
        self.amplitude = float("nan")
        self.amplitudes = []        # (t, amplitude) since the last take_amplitudes()
        self.wall = time.monotonic
        self.last_heard = self.wall()
        self.counters = {}
        self.status = None
        self.sensor_profile = None  # what the device's tracker knows of its touch sensor
        self.errors = []            # datagrams refused and device Errors no request awaited

    # -- what the study calls
    def open(self):
        self.status = self.query_status()
        self.counters = self.status.counters()
        self.sensor_profile = self.query_sensor_profile()
        return self.status

    def close(self):
        pass

    @abc.abstractmethod
    def poll(self):
        """Reads what arrived; returns counters that changed ({} if none)."""

    def lost(self):
        return self.wall() - self.last_heard > LOST_AFTER_S

    @abc.abstractmethod
    def set_condition(self, condition):
        """Waits for the Ack; DeviceRefused if the device refuses, DeviceLost if it does not answer."""

    @abc.abstractmethod
    def query_status(self):
        """The device's Status (protocol.Status)."""

    @abc.abstractmethod
    def query_sensor_profile(self):
        """What the device's tracker knows of its sensor (protocol.SensorProfile)."""

    def finger(self, x, y, force_n):
        """Where the finger is (simulator only: a real device senses it)."""

    def finger_up(self):
        pass

    def take_amplitudes(self):
        a, self.amplitudes = self.amplitudes, []
        return a

    def take_errors(self):
        """{text: how often} since the last call, in the order first seen."""
        counts = {}
        for text in self.errors:
            counts[text] = counts.get(text, 0) + 1
        self.errors = []
        return counts

    def _changed_counters(self, status):
        new = status.counters()
        changed = {k: v for k, v in new.items() if self.counters.get(k) != v}
        self.counters = new
        return changed


class UdpDevice(Device):
    def __init__(self, host, port=DEFAULT_PORT, clock=time.monotonic, time_scale=1.0):
        super().__init__(clock)
        self.name = f"udp:{host}:{port}"
        self.address = (host, port)
        self.time_scale = time_scale  # simulated seconds per wall second (ff-sim --speed)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setblocking(False)
        self.sequence = 0
        self.replies = {}
        self.pending = {}   # sequence -> the reply type awaited
        self.status_every_s = 1.0
        self._next_status = 0.0

    def close(self):
        self.sock.close()

    def _send(self, build):
        self.sequence = (self.sequence + 1) & 0xFF
        data = build(self.sequence)
        try:
            self.sock.sendto(data, self.address)
        except OSError as e:
            raise DeviceLost(f"cannot send to {self.name}: {e.strerror}") from None
        return self.sequence

    def _receive(self, timeout_wall=0.0):
        """Handles every datagram waiting (and waits up to timeout for the first)."""
        changed = {}
        deadline = time.monotonic() + timeout_wall
        while True:
            wait = max(0.0, deadline - time.monotonic())
            select.select([self.sock], [], [], wait)
            try:
                data, _ = self.sock.recvfrom(2048)
            except (BlockingIOError, ConnectionRefusedError):  # nothing (more) within the wait
                return changed
            try:
                seq, msg = protocol.decode(data)
            except protocol.ProtocolError as e:
                self.errors.append(f"datagram refused: {e}")
                continue
            self.last_heard = self.wall()
            if isinstance(msg, protocol.Force):
                self.force_n = msg.force_mn / 1000.0
            elif isinstance(msg, list):  # ticks
                now = self.clock()
                for _, a, _, _ in msg:
                    self.amplitudes.append((now, a))
                if msg:
                    self.amplitude = msg[-1][1]
            elif isinstance(msg, protocol.Status):
                changed.update(self._changed_counters(msg))
                self.status = msg
                if self.pending.get(seq) == protocol.STATUS:
                    self.replies[seq] = msg
            elif isinstance(msg, protocol.ConditionEcho):
                if self.pending.get(seq) == protocol.CONDITION:
                    self.replies[seq] = msg
            elif isinstance(msg, protocol.SensorProfile):
                if self.pending.get(seq) == protocol.SENSOR_PROFILE:
                    self.replies[seq] = msg
            elif isinstance(msg, protocol.Ack):
                if self.pending.get(seq) == protocol.ACK:
                    self.replies[seq] = msg
            elif isinstance(msg, protocol.Error):
                if seq in self.pending:
                    self.replies[seq] = msg
                else:
                    self.errors.append(msg.text())
            deadline = time.monotonic()  # after the first, only what is already there

    def _request(self, build, what, reply_type):
        """Sends, and waits for the reply of that type echoing the sequence."""
        for _ in range(RETRIES):
            seq = self._send(build)
            self.replies.pop(seq, None)
            self.pending = {seq: reply_type}
            end = time.monotonic() + REPLY_TIMEOUT_S
            while time.monotonic() < end:
                self._receive(end - time.monotonic())
                if seq in self.replies:
                    self.pending = {}
                    return self.replies.pop(seq)
        self.pending = {}
        raise DeviceLost(f"{self.name} does not answer {what} ({RETRIES} tries, {REPLY_TIMEOUT_S * 1000:.0f} ms each)")

    def query_status(self):
        reply = self._request(protocol.query_status, "QueryStatus", protocol.STATUS)
        if isinstance(reply, protocol.Error):
            raise DeviceRefused(reply.text())
        return reply

    def set_condition(self, condition):
        reply = self._request(lambda s: protocol.set_condition(s, condition), "SetCondition", protocol.ACK)
        if isinstance(reply, protocol.Error):
            raise DeviceRefused(reply.text())
        if not reply.ok:
            raise DeviceRefused(f"condition refused (prepare status {reply.detail})")
        return reply

    def query_condition(self):
        """The SetCondition payload the device renders (its own encoding)."""
        reply = self._request(protocol.query_condition, "QueryCondition", protocol.CONDITION)
        if isinstance(reply, protocol.Error):
            raise DeviceRefused(reply.text())
        return reply.payload

    def query_sensor_profile(self):
        reply = self._request(protocol.query_sensor_profile, "QuerySensorProfile", protocol.SENSOR_PROFILE)
        if isinstance(reply, protocol.Error):
            raise DeviceRefused(reply.text())
        return reply

    def start_stream(self):
        """Amplitude samples for the bar and the simulated participant; an Ack is not awaited."""
        self._send(lambda s: protocol.start_stream(s, TICK_DECIMATION))

    def poll(self):
        changed = self._receive(0.0)
        now = self.clock()
        if now >= self._next_status:  # fault counters, once a second
            self._next_status = now + self.status_every_s
            self._send(protocol.query_status)
        return changed


def find_ff_sim(repo_root):
    path = os.path.join(repo_root, "build", "native", "tools", "sim", "ff-sim")
    return path if os.access(path, os.X_OK) else None


def _free_udp_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


PR_SET_PDEATHSIG = 1  # linux/prctl.h


def dies_with_this_process():
    """A preexec_fn for Popen that makes the child get SIGTERM when this
    process dies, however it dies (SIGKILL too): Linux's PR_SET_PDEATHSIG.
    None elsewhere, or where libc has no prctl."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl  # looked up before the fork
    except (OSError, AttributeError):
        return None
    parent = os.getpid()

    def preexec():
        prctl(ctypes.c_int(PR_SET_PDEATHSIG), ctypes.c_ulong(signal.SIGTERM), ctypes.c_ulong(0),
              ctypes.c_ulong(0), ctypes.c_ulong(0))
        if os.getppid() != parent:  # it died before the prctl: no signal will come
            os.kill(os.getpid(), signal.SIGTERM)
    return preexec


class SimDevice(UdpDevice):
    """Starts ff-sim (the firmware on the host), talks to it like to the device,
    sends it the finger, and streams the rendered amplitude back."""

    def __init__(self, binary, speed=1.0, clock=time.monotonic, trace=None):
        if binary is None or not os.access(binary, os.X_OK):
            raise DeviceLost(f"ff-sim not found at {binary}: build it (cmake --build --preset native --target ff-sim)")
        port, finger_port = _free_udp_port(), _free_udp_port()
        cmd = [binary, "--port", str(port), "--finger-port", str(finger_port), "--speed", f"{speed:g}", "--quiet"]
        if trace:
            cmd += ["--trace", trace]
        # ff-sim dies with the study, also when the study is killed (SIGKILL) and cannot close it
        self.proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                     preexec_fn=dies_with_this_process())
        line = self._ready_line()
        super().__init__("127.0.0.1", port, clock=clock, time_scale=speed)
        self.name = f"sim:{os.path.basename(binary)} speed {speed:g}"
        self.finger_address = ("127.0.0.1", finger_port)
        self.ready = line

    def _ready_line(self):
        ready, _, _ = select.select([self.proc.stdout], [], [], 10.0)
        line = self.proc.stdout.readline().strip() if ready else ""
        if not line.startswith("ff-sim ready"):
            self.proc.kill()
            err = self.proc.stderr.read().strip().splitlines()
            raise DeviceLost(f"ff-sim did not start: {line or (err[-1] if err else 'no ready line within 10 s')}")
        return line

    def open(self):
        status = super().open()
        self.start_stream()
        return status

    def finger(self, x, y, force_n):
        self.sock.sendto(f"{x:.1f} {y:.1f} {force_n:.3f}".encode(), self.finger_address)

    def finger_up(self):
        self.sock.sendto(b"up", self.finger_address)

    def close(self):
        try:
            self.proc.send_signal(signal.SIGTERM)
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        super().close()


class FakeDevice(Device):
    """In-Python device for unit tests: acks every condition (or refuses),
    reports a force, and can fall silent."""

    name = "fake"

    def __init__(self, clock=time.monotonic, force_n=0.3):
        super().__init__(clock)
        self.conditions = []
        self.silent = False
        self.refuse = False
        self.force_n = force_n
        self.fault_counts = [0] * 4
        self.finger_at = None
        self.profile = protocol.SensorProfile()

    def query_status(self):
        if self.silent:
            raise DeviceLost("fake device silent")
        self.last_heard = self.wall()
        return protocol.Status(0x0200, 2, 1, 1.0, 0, 0, 0, 0, 0, 0, self.force_n * 1000, False, False,
                               34900.0, list(self.fault_counts))

    def query_sensor_profile(self):
        if self.silent:
            raise DeviceLost("fake device silent")
        return self.profile

    def set_condition(self, condition):
        if self.silent:
            raise DeviceLost("fake device silent")
        if self.refuse:
            raise DeviceRefused("condition refused (prepare status 3)")
        self.conditions.append(condition)
        return protocol.Ack(protocol.SET_CONDITION, True, 0)

    def poll(self):
        if self.silent:
            return {}
        return self._changed_counters(self.query_status())  # heard from: query_status

    def finger_up(self):
        self.finger_at = None

    def finger(self, x, y, force_n):
        self.finger_at = (x, y)
        if self.conditions and self.conditions[-1].kind == "frictionmap":
            from . import geometry
            d = abs(y - geometry.path_y(x, self.conditions[-1].target))
            self.amplitude = 1.0 if d < 10 else 0.0
            self.amplitudes.append((self.clock(), self.amplitude))


def open_device(spec, repo_root, speed, clock, trace=None):
    """--device: sim | udp:HOST[:PORT] | fake."""
    if spec == "sim":
        return SimDevice(os.environ.get("FF_SIM") or find_ff_sim(repo_root) or
                         os.path.join(repo_root, "build/native/tools/sim/ff-sim"), speed, clock, trace)
    if spec == "fake":
        return FakeDevice(clock)
    if spec.startswith("udp:"):
        host, _, port = spec[4:].partition(":")
        if not host or (port and not port.isdigit()):
            raise ValueError(f"--device {spec}: expected udp:HOST[:PORT]")
        return UdpDevice(host, int(port or DEFAULT_PORT), clock)
    raise ValueError(f"--device {spec}: expected sim, udp:HOST[:PORT] or fake")

