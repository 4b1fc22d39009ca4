#!/usr/bin/env python3
"""Two attacks of issue 31 on a running simnode, measured from outside (loopback only).

  bench/hostile_clients.py control-flood SIMNODE NODES SECONDS
      simnode with NODES small nodes (scenarios/default.xml), images on /dev/shm; once they are
      initialized, 15 control clients pipeline `list` requests (64 KiB at a time) for SECONDS and
      never read. Meanwhile a hub client sends a Verify Node ID for one node every 100 ms and
      times the answer. Prints simnode's RSS before and at its peak, the round trips (p50, p99,
      max, missed) and how many control connections simnode closed.

  bench/hostile_clients.py idle-flood SIMNODE
      simnode's default scenario; 48 idle connections each from 127.0.0.2, .3 and .4 (each address
      under max-clients-per-address 48, together over max-clients 64), then after 2 s a client
      from 127.0.0.1 sends a global Verify Node ID. Prints whether it was answered and how many
      flood connections the hub closed.

Exits 1 when the measured behaviour is not the bounded one (the good client unanswered or
disconnected). Every simnode started here stops itself (--run-for).
"""
import os
import re
import socket
import subprocess
import sys
import tempfile
import threading
import time


def start_simnode(simnode, args, run_for):
    """Starts simnode; returns (process, hub port, control port or None, its output lines)."""
    proc = subprocess.Popen([simnode, *args, "--listen", "127.0.0.1:0", "--run-for", str(run_for)],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines, hub, ctl = [], None, None
    want_ctl = "--control" in args
    while hub is None or (want_ctl and ctl is None):
        line = proc.stdout.readline()
        if not line:
            sys.exit("simnode ended: " + "".join(lines[-5:]))
        lines.append(line)
        if m := re.search(r"listening on [^ ]*:(\d+)", line):
            hub = int(m.group(1))
        if m := re.search(r"control on [^ ]*:(\d+)", line):
            ctl = int(m.group(1))
    threading.Thread(target=lambda: lines.extend(proc.stdout), daemon=True).start()
    return proc, hub, ctl, lines


def rss_mib(pid):
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS"):
                return int(line.split()[1]) // 1024
    return 0


class VerifyClient:
    """A hub client that reads all the time and times Verified Node ID answers of one node."""

    def __init__(self, port, node_hex):
        self.sock = socket.create_connection(("127.0.0.1", port))
        self.node_hex = node_hex.encode()
        self.answers, self.closed = [], False
        self.cv = threading.Condition()
        threading.Thread(target=self._drain, daemon=True).start()

    def _drain(self):
        buf = b""
        while True:
            try:
                data = self.sock.recv(65536)
            except OSError:
                data = b""
            with self.cv:
                if not data:
                    self.closed = True
                    self.cv.notify_all()
                    return
                *complete, buf = (buf + data).split(b"\n")
                for line in complete:
                    if line.startswith(b":X19170") and line.endswith(b"N" + self.node_hex + b";"):
                        self.answers.append(time.time())
                self.cv.notify_all()

    def round_trip_ms(self, timeout=2.0):
        """ms until the answer, None when none came within timeout; raises when closed."""
        with self.cv:
            seen = len(self.answers)
            start = time.time()
            self.sock.sendall(b":X1949012AN" + self.node_hex + b";\n")
            self.cv.wait_for(lambda: len(self.answers) > seen or self.closed, timeout)
            if self.closed:
                raise ConnectionError("the hub closed the client")
            return (self.answers[-1] - start) * 1000 if len(self.answers) > seen else None


def control_flood(simnode, nodes, seconds):
    with tempfile.NamedTemporaryFile("w", suffix=".ini", dir="scenarios", delete=False) as ini:
        ini.write(f"[node.small]\nnode-id = 05.01.01.01.30.00\ncount = {nodes}\n"
                  "cdi = default.xml\nuser-name = Small node {n}\n")
    try:
        proc, hub, ctl, lines = start_simnode(
            simnode, ["--scenario", ini.name, "--control", "127.0.0.1:0",
                      "--image-dir", tempfile.mkdtemp(dir="/dev/shm")], int(seconds) + 120)
    finally:
        os.unlink(ini.name)
    while not any("initialized" in line for line in lines):
        time.sleep(0.2)
    verify = VerifyClient(hub, "050101013000")
    time.sleep(1)
    before = peak = rss_mib(proc.pid)
    flood = [socket.create_connection(("127.0.0.1", ctl)) for _ in range(15)]
    for sock in flood:
        sock.setblocking(False)
    requests = b'{"cmd":"list"}\n' * 4096
    end = time.time() + seconds

    def pump():
        while time.time() < end:
            for sock in flood:
                try:
                    sock.send(requests)
                except OSError:
                    pass
            time.sleep(0.05)

    threading.Thread(target=pump, daemon=True).start()
    trips, missed = [], 0
    while time.time() < end:
        rtt = verify.round_trip_ms()
        if rtt is None:
            missed += 1
        else:
            trips.append(rtt)
        peak = max(peak, rss_mib(proc.pid))
        time.sleep(0.1)
    proc.terminate()
    proc.wait()
    trips.sort()
    p99 = trips[max(0, int(len(trips) * 0.99) - 1)]
    closed = sum(1 for line in lines if "control: closed" in line)
    print(f"{nodes} nodes, {seconds:.0f} s: RSS {before} MiB before, {peak} MiB peak; "
          f"Verify n={len(trips)} missed={missed} p50={trips[len(trips) // 2]:.1f} ms "
          f"p99={p99:.1f} ms max={trips[-1]:.1f} ms; control connections closed: {closed} of 15")
    return 0 if missed == 0 else 1


def idle_flood(simnode):
    proc, hub, _, lines = start_simnode(
        simnode, ["--scenario", "scenarios/default.ini", "--image-dir", tempfile.mkdtemp()], 60)
    flood = []
    for address in ("127.0.0.2", "127.0.0.3", "127.0.0.4"):
        for _ in range(48):
            sock = socket.socket()
            sock.bind((address, 0))
            sock.connect(("127.0.0.1", hub))
            flood.append(sock)
    time.sleep(2)
    good = socket.create_connection(("127.0.0.1", hub))
    good.settimeout(3)
    start, text, answered = time.time(), b"", False
    good.sendall(b":X1949012AN;\n")
    try:
        while not answered and time.time() - start < 3:
            data = good.recv(4096)
            if not data:
                break
            text += data
            answered = b":X19170" in text
    except socket.timeout:
        pass
    closed = 0
    for sock in flood:
        sock.setblocking(False)
        try:
            closed += sock.recv(1) == b""
        except BlockingIOError:
            pass
        except OSError:
            closed += 1
    proc.terminate()
    proc.wait()
    evicted = sum(1 for line in lines if "the longest, to admit" in line)
    print(f"good client answered: {answered} in {time.time() - start:.3f} s; flood connections "
          f"closed by the hub: {closed} of {len(flood)} ({evicted} to admit a newcomer)")
    return 0 if answered else 1


if __name__ == "__main__":
    if len(sys.argv) == 5 and sys.argv[1] == "control-flood":
        sys.exit(control_flood(sys.argv[2], int(sys.argv[3]), float(sys.argv[4])))
    if len(sys.argv) == 3 and sys.argv[1] == "idle-flood":
        sys.exit(idle_flood(sys.argv[2]))
    sys.exit(__doc__)
