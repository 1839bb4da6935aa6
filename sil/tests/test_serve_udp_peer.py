"""serve --mavlink udpout: only the configured peer is heard (issue 33 item 9).

On main a 1-byte datagram from any local port redirected all telemetry to its
sender (UdpLink.receive learned the peer from any datagram). These drive the
link's socket directly, no simulation: a few milliseconds."""
from __future__ import annotations

import socket
import time

from helical_sil.live.serve import UdpLink, parse_endpoint


def _udp() -> socket.socket:
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    s.settimeout(1.0)
    return s


def _drain(link: UdpLink) -> list[bytes]:
    got: list[bytes] = []
    deadline = time.monotonic() + 0.5
    while time.monotonic() < deadline:
        if link.wait(0.05):
            got.extend(link.receive())
            if got:
                break
    return got


def test_udpout_hears_only_its_peer_and_keeps_sending_to_it() -> None:
    gcs, intruder = _udp(), _udp()
    link = UdpLink(parse_endpoint(f"udpout:127.0.0.1:{gcs.getsockname()[1]}"))
    try:
        link.send(b"hb1")
        data, link_addr = gcs.recvfrom(100)
        assert data == b"hb1"
        intruder.sendto(b"x", link_addr)  # the 1-byte datagram
        assert _drain(link) == []
        assert link.stats.datagrams_foreign == 1 and link.stats.datagrams_in == 0
        link.send(b"hb2")  # still to the configured peer, not the intruder
        assert gcs.recvfrom(100)[0] == b"hb2"
        intruder.settimeout(0.2)
        try:
            stolen = intruder.recvfrom(100)
        except socket.timeout:
            stolen = None
        assert stolen is None
        gcs.sendto(b"cmd", link_addr)  # the peer itself is heard
        assert _drain(link) == [b"cmd"]
        assert link.stats.datagrams_in == 1
    finally:
        link.close()
        gcs.close()
        intruder.close()


def test_udpin_answers_whoever_spoke_last() -> None:
    """udpin is the listening side: the ground station is whoever sends (docs/mavlink.md)."""
    probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    probe.bind(("127.0.0.1", 0))
    port = probe.getsockname()[1]
    probe.close()
    link = UdpLink(parse_endpoint(f"udpin:127.0.0.1:{port}"))
    gcs = _udp()
    try:
        gcs.sendto(b"hello", ("127.0.0.1", port))
        assert _drain(link) == [b"hello"]
        link.send(b"answer")
        assert gcs.recvfrom(100)[0] == b"answer"
    finally:
        link.close()
        gcs.close()
