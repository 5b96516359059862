"""The UDP device client against a peer in the test that sends it frames
built with the codec: what it keeps, what it refuses and how it says so."""
import socket
import threading

import pytest

from ffexp import device, protocol


@pytest.fixture
def peer():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    s.settimeout(2.0)
    yield s
    s.close()


def _client(peer):
    dev = device.UdpDevice("127.0.0.1", peer.getsockname()[1])
    dev._send(protocol.query_status)  # binds the client's socket; the peer learns its address
    _, address = peer.recvfrom(2048)
    return dev, address


def test_refused_datagrams_and_unasked_errors_are_kept_and_counted(peer):
    dev, address = _client(peer)
    good = protocol.force(1, 1000, 250.0)
    bad_crc = good[:-1] + bytes([good[-1] ^ 1])
    for data in (bad_crc, protocol.frame(protocol.ERROR, 2, bytes([8, 0x01])), bad_crc,
                 protocol.frame(protocol.SAMPLES, 3, bytes([0, 0])), good):
        peer.sendto(data, address)
    dev._receive(1.0)
    dev._receive(0.2)  # whatever came after the first wait
    assert dev.force_n == pytest.approx(0.25)
    assert dev.take_errors() == {"datagram refused: bad CRC": 2, "device error: busy (message type 0x01)": 1}
    assert dev.take_errors() == {}  # taken once
    dev.close()


def test_an_error_in_reply_to_a_request_is_a_refusal_with_its_text(peer):
    dev, _ = _client(peer)

    def answer():
        data, address = peer.recvfrom(2048)
        t, seq, _ = protocol.unframe(data)
        peer.sendto(protocol.frame(protocol.ERROR, seq, bytes([7, t])), address)

    answering = threading.Thread(target=answer)
    answering.start()
    with pytest.raises(device.DeviceRefused, match=r"device error: malformed \(message type 0x01\)"):
        dev.set_condition(protocol.Condition("heightmap", "top", 0.5))
    answering.join()
    assert dev.take_errors() == {}  # answered the request: not an unasked error
    dev.close()
