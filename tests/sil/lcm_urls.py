# SPDX-License-Identifier: Apache-2.0
"""A private LCM URL for an end-to-end test: a UDP port the kernel says is free and a multicast
group derived from the test's process id (the scheme `uvms run` uses, sil/cli/run_cmd.cpp), so
tests running side by side do not share a bus unless they mean to."""
import os
import socket


def private_url():
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("", 0))
    port = sock.getsockname()[1]
    sock.close()
    pid = os.getpid()
    return f"udpm://239.255.{pid >> 8 & 255}.{max(1, pid & 255)}:{port}?ttl=0"
