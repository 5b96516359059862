#!/usr/bin/env python3
"""A stand-in for ff-sim with the same command line and UDP interface, for
the experiment's own tests where the real ff-sim is not the point (it answers
the protocol, renders the frictionmap band, 0.5 elsewhere). The end-to-end
test runs the real ff-sim."""
import argparse
import math
import os
import select
import signal
import socket
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from ffexp import geometry, protocol  # noqa: E402


def smooth5(u):
    u = min(max(u, 0.0), 1.0)
    return u * u * u * (u * (6 * u - 15) + 10)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--port", type=int, default=8888)
    ap.add_argument("--finger-port", type=int, default=8889)
    ap.add_argument("--speed", type=float, default=1.0)
    ap.add_argument("--trace")
    ap.add_argument("--quiet", action="store_true")
    ap.add_argument("--silent-after", type=float, default=math.inf, help="stop answering after this many simulated s")
    a = ap.parse_args()
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); sock.bind(("127.0.0.1", a.port))
    fing = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); fing.bind(("127.0.0.1", a.finger_port))
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    print(f"ff-sim ready port={a.port} finger-port={a.finger_port}", flush=True)
    start = time.monotonic()
    peer, cond, finger, streaming = None, None, None, False
    next_force, seq = 0.0, 0
    while True:
        now = (time.monotonic() - start) * a.speed
        ready, _, _ = select.select([sock, fing], [], [], 0.002)
        silent = now > a.silent_after
        for s in ready:
            data, addr = s.recvfrom(2048)
            if s is fing:
                parts = data.decode().split()
                finger = None if parts == ["up"] else (float(parts[0]), float(parts[1]), float(parts[2]))
                continue
            if silent:
                continue
            peer = addr
            try:
                t, sq, p = protocol.unframe(data)
            except protocol.ProtocolError:
                continue
            if t == protocol.SET_CONDITION:
                cond = protocol.decode_condition(p)
                sock.sendto(protocol.ack(sq, t), peer)
            elif t == protocol.QUERY_STATUS:
                sock.sendto(protocol.status(sq, 0x0200, force_mn=finger[2] * 1000 if finger else 0.0, faults=[0, 0, 0]), peer)
            elif t == protocol.QUERY_SENSOR_PROFILE:
                sock.sendto(protocol.sensor_profile(sq, protocol.SensorProfile()), peer)
            elif t == protocol.START_STREAM:
                streaming = True
                sock.sendto(protocol.ack(sq, t), peer)
        if silent or peer is None:
            continue
        if now >= next_force:
            next_force = now + 0.03
            seq = (seq + 1) & 0xFF
            sock.sendto(protocol.force(seq, int(now * 1e6) & 0xFFFFFFFF, finger[2] * 1000 if finger else 0.0), peer)
            if streaming:
                amp = 0.0
                if finger and cond and cond.kind == "frictionmap":
                    u = abs(finger[1] - float(geometry.path_y(finger[0], cond.target)))
                    amp = 0.5 + cond.strength * (smooth5((30 - u) / 20) - 0.5)
                elif finger and cond:
                    amp = 0.5
                sock.sendto(protocol.ticks(seq, [(int(now * 1e6) & 0xFFFFFFFF, amp, int(amp * 4095), finger is not None)]), peer)


if __name__ == "__main__":
    main()
