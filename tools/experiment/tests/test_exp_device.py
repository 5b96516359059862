"""The device clients against peers in the test: a UDP socket that sends
frames built with the codec, the ff-sim stand-in as a child process, and
the in-Python fake. What each keeps, refuses, and how it says so."""
import os
import signal
import socket
import stat
import subprocess
import sys
import threading
import time

import pytest

from ffexp import device, geometry, protocol

HERE = os.path.dirname(os.path.abspath(__file__))
STANDIN = os.path.join(HERE, "standin_ff_sim.py")


@pytest.fixture
def peer():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    s.settimeout(2.0)
    yield s
    s.close()


class Clock:
    def __init__(self):
        self.now = 0.0

    def __call__(self):
        return self.now


def _client(peer, clock=time.monotonic):
    dev = device.UdpDevice("127.0.0.1", peer.getsockname()[1], clock)
    dev._send(protocol.query_status)  # binds the client's socket; the peer learns its address
    _, address = peer.recvfrom(2048)
    return dev, address


def _answer(peer, reply):
    """A thread answering the next request with reply(type, sequence)."""
    def run():
        data, address = peer.recvfrom(2048)
        t, seq, _ = protocol.unframe(data)
        peer.sendto(reply(t, seq), address)
    thread = threading.Thread(target=run)
    thread.start()
    return thread


def test_a_new_client_knows_nothing_yet(peer):
    dev = device.UdpDevice("127.0.0.1", peer.getsockname()[1])
    assert dev.name == f"udp:127.0.0.1:{peer.getsockname()[1]}" and dev.time_scale == 1.0
    assert dev.force_n != dev.force_n and dev.amplitude != dev.amplitude  # NaN until the device says
    assert dev.status is None and dev.sensor_profile is None and dev.counters == {}
    assert not dev.lost() and not dev.sock.getblocking()
    dev.close()
    assert dev.sock.fileno() == -1


def test_refused_datagrams_and_unasked_errors_are_kept_and_counted(peer):
    dev, address = _client(peer)
    good = protocol.force(1, 1000, 250.0)
    bad_crc = good[:-1] + bytes([good[-1] ^ 1])
    for data in (bad_crc, protocol.frame(protocol.ERROR, 2, bytes([8, 0x01])), bad_crc,
                 protocol.frame(protocol.SAMPLES, 3, bytes([0, 0])), good):
        peer.sendto(data, address)
    time.sleep(0.05)
    dev._receive(1.0)
    assert dev.force_n == pytest.approx(0.25)
    assert dev.take_errors() == {"datagram refused: bad CRC": 2, "device error: busy (message type 0x01)": 1}
    assert dev.take_errors() == {}  # taken once
    dev.close()


def test_a_receive_waits_up_to_its_timeout_for_the_first_datagram(peer):
    dev, address = _client(peer)
    late = threading.Timer(0.2, lambda: peer.sendto(protocol.force(1, 1000, 100.0), address))
    late.start()
    dev._receive(2.0)
    late.join()
    assert dev.force_n == pytest.approx(0.1)
    dev.close()


def test_a_receive_returns_once_the_first_datagrams_are_handled(peer):
    dev, address = _client(peer)
    peer.sendto(protocol.force(1, 1000, 100.0), address)
    start = time.monotonic()
    dev._receive(2.0)
    assert time.monotonic() - start < 1.0 and dev.force_n == pytest.approx(0.1)
    dev.close()


def test_poll_keeps_ticks_status_and_silence_and_asks_status_once_a_second(peer):
    clock = Clock()
    dev, address = _client(peer, clock)
    wall = [100.0]
    dev.wall = lambda: wall[0]
    dev.last_heard = wall[0]
    assert dev.poll() == {}
    assert protocol.unframe(peer.recvfrom(2048)[0])[0] == protocol.QUERY_STATUS  # the first poll asks
    clock.now = 0.5
    dev.poll()  # within the second: does not ask again
    peer.settimeout(0.1)
    with pytest.raises(socket.timeout):
        peer.recvfrom(2048)
    peer.settimeout(2.0)
    peer.sendto(protocol.ticks(5, [(10, 0.25, 1023, True), (510, 0.75, 3071, True)]), address)
    peer.sendto(protocol.status(6, faults=[0, 3]), address)
    time.sleep(0.05)
    clock.now = 1.0
    wall[0] = 100.4
    assert dev.poll() == {"protocol_errors": 0, "watchdog_trips": 0, "stream_overruns": 0,
                          "non_finite_coordinate": 0, "off_screen": 3}
    assert dev.amplitude == 0.75 and dev.take_amplitudes() == [(1.0, 0.25), (1.0, 0.75)]
    assert dev.status.faults == [0, 3]
    assert protocol.unframe(peer.recvfrom(2048)[0])[0] == protocol.QUERY_STATUS  # a second on
    peer.sendto(protocol.status(7, faults=[0, 3]), address)
    time.sleep(0.05)
    wall[0] = 100.8
    assert dev.poll() == {}  # the same counters again: nothing changed
    assert not dev.lost()  # heard at 100.8
    wall[0] = 101.31
    assert dev.lost()
    dev.close()


def test_requests_take_only_their_own_reply(peer):
    dev, _ = _client(peer)
    dev.replies[2] = protocol.Ack(protocol.SET_CONDITION, True, 0)  # stale, from a sequence wrapped round

    def answer():  # a Force first, so the client looks for its reply before the reply is there
        data, address = peer.recvfrom(2048)
        seq = protocol.unframe(data)[1]
        peer.sendto(protocol.force(9, 0, 0.0), address)
        time.sleep(0.1)
        peer.sendto(protocol.status(seq, faults=[4]), address)
    answering = threading.Thread(target=answer)
    answering.start()
    status = dev.query_status()
    answering.join()
    assert status.faults == [4] and dev.sequence == 2 and dev.replies == {}
    # a late duplicate after the request ended is no reply any more; an Error about it is news
    dev._send(protocol.query_status)
    data, address = peer.recvfrom(2048)
    peer.sendto(protocol.frame(protocol.ERROR, 2, bytes([8, 0x02])), address)
    time.sleep(0.05)
    dev._receive(0.5)
    assert dev.replies == {} and dev.take_errors() == {"device error: busy (message type 0x02)": 1}
    dev.close()


def test_an_unanswered_request_is_tried_four_times_then_the_device_is_lost(peer, monkeypatch):
    monkeypatch.setattr(device, "REPLY_TIMEOUT_S", 0.05)
    dev, _ = _client(peer)
    with pytest.raises(device.DeviceLost, match=r"does not answer QueryStatus \(4 tries, 50 ms each\)"):
        dev.query_status()
    sequences = [protocol.unframe(peer.recvfrom(2048)[0])[1] for _ in range(4)]
    assert sequences == [2, 3, 4, 5] and dev.pending == {}
    dev.close()


def test_the_sequence_wraps_at_256(peer):
    dev, _ = _client(peer)
    dev.sequence = 254
    assert [dev._send(protocol.query_status) for _ in range(3)] == [255, 0, 1]
    dev.close()


def test_a_send_that_fails_is_a_lost_device(peer):
    dev, _ = _client(peer)
    dev.sock.close()
    with pytest.raises(device.DeviceLost, match=f"cannot send to udp:127.0.0.1:{peer.getsockname()[1]}: "):
        dev._send(protocol.query_status)


@pytest.mark.parametrize("call, reply", [
    (lambda d: d.query_status(), "error"),
    (lambda d: d.set_condition(protocol.Condition("heightmap", "top", 0.5)), "error"),
    (lambda d: d.query_condition(), "error"),
    (lambda d: d.query_sensor_profile(), "error"),
    (lambda d: d.set_condition(protocol.Condition("heightmap", "top", 0.5)), "refused"),
], ids=["status", "condition", "query-condition", "sensor-profile", "ack-refused"])
def test_an_error_or_a_refusal_in_reply_is_device_refused(peer, call, reply):
    dev, _ = _client(peer)
    if reply == "error":
        build, why = (lambda t, seq: protocol.frame(protocol.ERROR, seq, bytes([7, t]))), r"device error: malformed"
    else:
        build, why = (lambda t, seq: protocol.ack(seq, t, ok=False, detail=3)), r"condition refused \(prepare status 3\)"
    answering = _answer(peer, build)
    with pytest.raises(device.DeviceRefused, match=why):
        call(dev)
    answering.join()
    assert dev.take_errors() == {}  # a reply to the request: not an unasked error
    dev.close()


def test_open_reads_status_counters_and_sensor_profile_and_replies_are_returned(peer):
    dev, address = _client(peer)
    profile = protocol.SensorProfile(2.0, 0.5, 30.0, 0.0, 100.0, 150.0, 2000, 0.0)
    replies = iter([lambda t, seq: protocol.status(seq, faults=[0, 1]),
                    lambda t, seq: protocol.sensor_profile(seq, profile)])

    def answer_two():
        for reply in replies:
            data, address = peer.recvfrom(2048)
            t, seq, _ = protocol.unframe(data)
            peer.sendto(reply(t, seq), address)
    answering = threading.Thread(target=answer_two)
    answering.start()
    status = dev.open()
    answering.join()
    assert status.faults == [0, 1] and dev.status is status and dev.counters["off_screen"] == 1
    peer.sendto(protocol.status(9, faults=[0, 1]), address)
    assert dev._receive(1.0) == {}  # the counters it opened with are not news
    assert dev.sensor_profile == profile
    payload = protocol.Condition("frictionmap", "bottom", 0.66).payload()
    answering = _answer(peer, lambda t, seq: protocol.frame(protocol.CONDITION, seq, payload))
    assert dev.query_condition() == payload
    answering.join()
    answering = _answer(peer, lambda t, seq: protocol.ack(seq, t))
    assert dev.set_condition(protocol.Condition("frictionmap", "bottom", 0.66)).ok
    answering.join()
    dev.start_stream()
    t, _, p = protocol.unframe(peer.recvfrom(2048)[0])
    assert (t, p) == (protocol.START_STREAM, bytes([device.TICK_DECIMATION]))
    dev.close()


@pytest.fixture
def closing():
    """Devices to close whatever the test's outcome (no stand-in outlives its test)."""
    opened = []
    yield opened.append
    for dev in opened:
        dev.close()


def test_the_simulator_runs_reports_the_finger_and_stops(tmp_path, closing):
    dev = device.SimDevice(STANDIN, speed=2.0, trace=str(tmp_path / "trace.csv"))
    closing(dev)
    assert dev.ready.startswith("ff-sim ready") and dev.name == "sim:standin_ff_sim.py speed 2"
    assert dev.proc.args[-2:] == ["--trace", str(tmp_path / "trace.csv")] and dev.time_scale == 2.0
    dev.open()
    dev.set_condition(protocol.Condition("heightmap", "top", 1.0))
    dev.finger(300.0, 240.0, 0.4)
    deadline = time.monotonic() + 3.0
    while time.monotonic() < deadline and not (dev.force_n == pytest.approx(0.4) and dev.amplitude == 0.5):
        dev.poll()
        time.sleep(0.01)
    assert dev.force_n == pytest.approx(0.4) and dev.amplitude == 0.5  # streaming: the stand-in renders 0.5 here
    dev.finger_up()
    deadline = time.monotonic() + 3.0
    while time.monotonic() < deadline and dev.force_n != 0.0:
        dev.poll()
        time.sleep(0.01)
    assert dev.force_n == 0.0
    dev.close()
    assert dev.proc.returncode == 0 and dev.sock.fileno() == -1  # SIGTERM: the stand-in's clean exit


def _script(tmp_path, body):
    path = tmp_path / "fake-ff-sim"
    path.write_text("#!/bin/sh\n" + body + "\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return str(path)


def test_a_simulator_that_is_missing_or_does_not_start_says_why(tmp_path):
    with pytest.raises(device.DeviceLost, match=r"ff-sim not found at .*nothing: build it \(cmake --build"):
        device.SimDevice(str(tmp_path / "nothing"))
    with pytest.raises(device.DeviceLost, match="ff-sim not found at None"):
        device.SimDevice(None)
    with pytest.raises(device.DeviceLost, match="ff-sim did not start: cannot bind port"):
        device.SimDevice(_script(tmp_path, "echo 'cannot bind port' >&2"))
    start = time.monotonic()
    with pytest.raises(device.DeviceLost, match="ff-sim did not start: hello"):
        device.SimDevice(_script(tmp_path, "echo hello; exec sleep 30"))
    assert time.monotonic() - start < 10  # killed, not waited for


def test_a_simulator_that_ignores_sigterm_is_killed(tmp_path, monkeypatch, closing):
    dev = device.SimDevice(_script(tmp_path, "trap '' TERM; echo 'ff-sim ready'; while true; do sleep 0.05; done"))
    closing(dev)
    real_wait = dev.proc.wait

    def short_wait(timeout=None):
        return real_wait(timeout=None if timeout is None else 0.3)
    monkeypatch.setattr(dev.proc, "wait", short_wait)
    dev.close()
    assert real_wait(timeout=5) == -9


def _gone(pid):
    """No such process, or one that has exited and waits to be reaped (a zombie)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
def test_the_simulator_dies_with_a_killed_study():
    # a study that started ff-sim (the stand-in) and is then SIGKILLed: no close() runs
    here = os.path.dirname(os.path.abspath(__file__))
    code = (f"import sys, time; sys.path[:0] = [{os.path.join(here, '..')!r}, {os.path.join(here, '..', '..', 'common')!r}]\n"
            f"from ffexp import device\n"
            f"dev = device.SimDevice({STANDIN!r})\n"
            f"print(dev.proc.pid, flush=True)\n"
            f"time.sleep(60)\n")
    study = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    sim = int(study.stdout.readline())
    try:
        assert not _gone(sim)
        study.kill()
        study.wait()
        deadline = time.monotonic() + 1.0
        while time.monotonic() < deadline and not _gone(sim):
            time.sleep(0.02)
        assert _gone(sim)
    finally:
        if not _gone(sim):
            os.kill(sim, signal.SIGKILL)


def test_find_ff_sim_and_free_ports(tmp_path):
    assert device.find_ff_sim(str(tmp_path)) is None
    sim = tmp_path / "build" / "native" / "tools" / "sim"
    sim.mkdir(parents=True)
    (sim / "ff-sim").write_text("")
    assert device.find_ff_sim(str(tmp_path)) is None  # not executable
    (sim / "ff-sim").chmod(0o755)
    assert device.find_ff_sim(str(tmp_path)) == str(sim / "ff-sim")
    port = device._free_udp_port()
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", port))  # free: the probe let go of it
    s.close()


def test_open_device_reads_the_spec(tmp_path, monkeypatch, closing):
    fake = device.open_device("fake", str(tmp_path), 1.0, time.monotonic)
    assert isinstance(fake, device.FakeDevice) and fake.name == "fake"
    udp = device.open_device("udp:10.0.0.7:9000", str(tmp_path), 1.0, time.monotonic)
    assert udp.address == ("10.0.0.7", 9000)
    udp.close()
    udp = device.open_device("udp:10.0.0.7", str(tmp_path), 1.0, time.monotonic)
    assert udp.address == ("10.0.0.7", device.DEFAULT_PORT)
    udp.close()
    for bad in ("udp:", "udp:host:port", "udp::9000"):
        with pytest.raises(ValueError, match=f"--device {bad}: expected udp:HOST\\[:PORT\\]"):
            device.open_device(bad, str(tmp_path), 1.0, time.monotonic)
    with pytest.raises(ValueError, match=r"--device usb: expected sim, udp:HOST\[:PORT\] or fake"):
        device.open_device("usb", str(tmp_path), 1.0, time.monotonic)
    monkeypatch.setenv("FF_SIM", STANDIN)
    sim = device.open_device("sim", str(tmp_path), 3.0, time.monotonic, trace=str(tmp_path / "t.csv"))
    closing(sim)
    assert sim.name == "sim:standin_ff_sim.py speed 3" and "--trace" in sim.proc.args
    sim.close()
    monkeypatch.delenv("FF_SIM")
    with pytest.raises(device.DeviceLost, match=f"ff-sim not found at {tmp_path}/build/native/tools/sim/ff-sim"):
        device.open_device("sim", str(tmp_path), 1.0, time.monotonic)


def test_the_fake_device_acks_refuses_falls_silent_and_renders_the_band():
    opened = device.FakeDevice()
    opened.open()
    assert opened.poll() == {}  # the counters it opened with are not news
    wall = [51.0]
    opened.wall, opened.last_heard = (lambda: wall[0]), 50.0
    assert opened.lost()
    opened.poll()
    assert not opened.lost()  # a poll hears from it
    fake = device.FakeDevice(force_n=0.2)
    assert fake.query_status().force_mn == pytest.approx(200.0) and fake.finger_at is None
    assert fake.poll() == {"protocol_errors": 0, "watchdog_trips": 0, "stream_overruns": 0,
                           "non_finite_coordinate": 0, "off_screen": 0, "non_increasing_time": 0, "jump_rejected": 0}
    fake.fault_counts[1] = 2
    assert fake.poll() == {"off_screen": 2}
    assert fake.set_condition(protocol.Condition("frictionmap", "top", 1.0)).ok
    fake.finger(400.0, float(geometry.path_y(400.0, "top")), 0.3)
    assert fake.finger_at[0] == 400.0 and fake.amplitude == 1.0
    fake.finger(400.0, 470.0, 0.3)
    assert fake.amplitude == 0.0 and [a for _, a in fake.take_amplitudes()] == [1.0, 0.0]
    fake.refuse = True
    with pytest.raises(device.DeviceRefused, match="prepare status 3"):
        fake.set_condition(protocol.Condition("heightmap"))
    fake.silent = True
    assert fake.poll() == {}
    for call in (fake.query_status, fake.query_sensor_profile, lambda: fake.set_condition(protocol.Condition())):
        with pytest.raises(device.DeviceLost, match="fake device silent"):
            call()
