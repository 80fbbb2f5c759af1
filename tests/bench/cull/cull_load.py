#!/usr/bin/python3
"""tessera-cull under load, on loopback (standard library only; run it
after `ulimit -n 65536`). Starts the service itself and reads its memory
from /proc.

  cull_load.py crowd --cull BIN SCENE [--crowd 1000] [--seconds 30] [--dribble 3] [--addresses 1]
      CROWD connections from 127.0.0.1 (or spread over ADDRESSES addresses
      127.0.1.N, so that no per-address limit applies) that send nothing or one byte of a
      request every DRIBBLE seconds, reconnecting when closed; meanwhile a
      client from 127.0.0.2 asks GET /v1/scene every 0.2 s. Prints the good
      client's worst and p99 latency, how the crowd's connections ended
      (429, closed at the deadline and after how long), and the service's
      memory idle and at its peak.
  cull_load.py culls --cull BIN SCENE [--clients 64] [--requests 20] [--size 960x540]
      CLIENTS clients, each from its own address 127.0.1.N, each sending
      REQUESTS POST /v1/cull for different views (orbiting the scene's
      centre): answered count, errors, latency median / p95 / p99 / max,
      the service's peak memory. With --give-up S each client closes its
      connection after S seconds without an answer (counted as given up):
      /v1/status then shows how many rankings the service dropped unranked.
"""
import argparse, errno, json, math, os, selectors, socket, statistics, subprocess, sys, threading, time


def start(binary, scene, extra):
    service = subprocess.Popen([binary, scene, "--listen", "127.0.0.1:0", "--previews", "0"] + extra,
                               stdout=subprocess.PIPE, text=True)
    line = service.stdout.readline()
    if not line.startswith("listening on"):
        raise SystemExit(f"tessera-cull did not start: {line!r}")
    return service, int(line.rsplit(":", 1)[1])


def memory(pid):
    """(current RSS, peak RSS) in MiB."""
    fields = dict(l.split(":", 1) for l in open(f"/proc/{pid}/status"))
    return int(fields["VmRSS"].split()[0]) / 1024, int(fields["VmHWM"].split()[0]) / 1024


def http(port, method, target, body=b"", source="127.0.0.2", timeout=30):
    """One request on its own connection: (status, body, seconds)."""
    t = time.perf_counter()
    s = socket.socket()
    s.settimeout(timeout)
    s.bind((source, 0))
    s.connect(("127.0.0.1", port))
    head = f"{method} {target} HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: {len(body)}\r\n\r\n"
    s.sendall(head.encode() + body)
    data = b""
    while chunk := s.recv(65536):
        data += chunk
    s.close()
    status = int(data[9:12]) if data.startswith(b"HTTP/1.1 ") else 0
    return status, data.split(b"\r\n\r\n", 1)[-1], time.perf_counter() - t


def pct(values, p):
    v = sorted(values)
    return v[min(len(v) - 1, int(math.ceil(p / 100 * len(v))) - 1)]


def crowd(a):
    service, port = start(a.cull, a.scene, a.service)
    try:
        time.sleep(1.0)
        idle = memory(service.pid)[0]
        good, failures, stop = [], [], threading.Event()

        def probe():
            while not stop.is_set():
                try:
                    status, _, seconds = http(port, "GET", "/v1/scene", timeout=10)
                    good.append(seconds) if status == 200 else failures.append(status)
                except OSError as e:
                    failures.append(str(e))
                time.sleep(0.2)

        sel = selectors.DefaultSelector()
        opened, ended = {}, {"429": 0, "503": 0, "closed": 0, "reset": 0, "other": 0}
        closedAfter = []

        sources = ["127.0.0.1"] if a.addresses == 1 else [f"127.0.1.{i + 1}" for i in range(a.addresses)]
        serial = [0]

        def connect():
            s = socket.socket()
            s.bind((sources[serial[0] % len(sources)], 0))
            serial[0] += 1
            s.setblocking(False)
            try:
                s.connect(("127.0.0.1", port))
            except BlockingIOError:
                pass
            sel.register(s, selectors.EVENT_READ)
            opened[s] = [time.monotonic(), b"", 0]  # opened at, what came back, bytes sent

        request = b"GET / HTTP/1.1\r\nHost: x\r\n\r\n"
        for _ in range(a.crowd):
            connect()
        thread = threading.Thread(target=probe)
        thread.start()
        peak, deadline, nextDribble = 0.0, time.monotonic() + a.seconds, time.monotonic() + a.dribble
        while time.monotonic() < deadline:
            for key, _ in sel.select(timeout=0.2):
                s = key.fileobj
                try:
                    chunk = s.recv(4096)
                except ConnectionResetError:
                    chunk, reset = b"", True
                else:
                    reset = False
                if chunk:
                    opened[s][1] += chunk
                    continue
                at, text, _ = opened.pop(s)
                sel.unregister(s)
                s.close()
                if reset:
                    ended["reset"] += 1
                elif text.startswith(b"HTTP/1.1 429"):
                    ended["429"] += 1
                elif text.startswith(b"HTTP/1.1 503"):
                    ended["503"] += 1
                elif not text:
                    ended["closed"] += 1
                    closedAfter.append(time.monotonic() - at)
                else:
                    ended["other"] += 1
                connect()  # the crowd keeps its size
            if time.monotonic() >= nextDribble:
                nextDribble += a.dribble
                for i, (s, state) in enumerate(list(opened.items())):
                    if i % 2 == 0 or state[2] >= len(request):
                        continue  # half the crowd stays silent
                    try:
                        s.send(request[state[2]:state[2] + 1])
                        state[2] += 1
                    except OSError:
                        pass
            peak = max(peak, memory(service.pid)[0])
        stop.set()
        thread.join()
        print(f"crowd of {a.crowd} from {len(sources)} address(es) for {a.seconds} s (half silent, half a byte every {a.dribble} s)")
        print(f"  good client (127.0.0.2, GET /v1/scene every 0.2 s): {len(good)} answered, {len(failures)} failed "
              f"{failures[:3]}" + (f"; latency p50 {statistics.median(good) * 1000:.1f} ms, "
                                   f"p99 {pct(good, 99) * 1000:.1f} ms, max {max(good) * 1000:.1f} ms" if good else ""))
        print(f"  crowd connections ended: {ended}")
        if closedAfter:
            print(f"  closed at the deadline after {min(closedAfter):.2f}..{max(closedAfter):.2f} s")
        print(f"  service memory: idle {idle:.1f} MiB, peak during the crowd {peak:.1f} MiB "
              f"(+{peak - idle:.1f} MiB)")
        print("  status:", http(port, "GET", "/v1/status")[1].decode())
    finally:
        service.kill()


def culls(a):
    service, port = start(a.cull, a.scene, a.service)
    try:
        scene = json.loads(http(port, "GET", "/v1/scene")[1])
        lo, hi = scene["bounds"]["min"], scene["bounds"]["max"]
        centre = [(lo[i] + hi[i]) / 2 for i in range(3)]
        p = scene["camera"]["position"]
        radius = math.hypot(p[0] - centre[0], p[2] - centre[2]) or 1.0
        width, height = (int(v) for v in a.size.split("x"))
        idle = memory(service.pid)[0]
        latencies, errors = [], []
        lock = threading.Lock()

        def client(c):
            for r in range(a.requests):
                angle = 2 * math.pi * (c * a.requests + r) / (a.clients * a.requests)
                position = [centre[0] + radius * math.sin(angle), p[1], centre[2] + radius * math.cos(angle)]
                body = json.dumps({"camera": {"position": position, "target": centre, "fov": scene["camera"]["fov"]},
                                   "width": width, "height": height, "max_objects": a.k}).encode()
                try:
                    status, answer, seconds = http(port, "POST", "/v1/cull", body, source=f"127.0.1.{c + 1}",
                                                   timeout=a.give_up or 120)
                    ok = status == 200 and "objects" in json.loads(answer)
                except socket.timeout:
                    ok, status, seconds = False, "gave up", 0
                except (OSError, ValueError) as e:
                    ok, status, seconds = False, str(e), 0
                with lock:
                    latencies.append(seconds) if ok else errors.append(status)

        started = time.perf_counter()
        threads = [threading.Thread(target=client, args=(c,)) for c in range(a.clients)]
        for t in threads:
            t.start()
        peak = 0.0
        while any(t.is_alive() for t in threads):
            peak = max(peak, memory(service.pid)[0])
            time.sleep(0.1)
        wall = time.perf_counter() - started
        print(f"{a.clients} clients x {a.requests} POST /v1/cull ({a.size}, K={a.k}) on {a.scene}:")
        print(f"  answered {len(latencies)} of {a.clients * a.requests}, errors {len(errors)} {errors[:3]}, "
              f"{wall:.1f} s in all ({len(latencies) / wall:.1f} answers/s)")
        ms = [s * 1000 for s in latencies] or [0]
        print(f"  latency median {statistics.median(ms):.0f} ms, p95 {pct(ms, 95):.0f} ms, p99 {pct(ms, 99):.0f} ms, "
              f"max {max(ms):.0f} ms")
        print(f"  service memory: after start {idle:.0f} MiB, peak during the load {peak:.0f} MiB, "
              f"peak since start {memory(service.pid)[1]:.0f} MiB")
        time.sleep(1.0)  # the last given-up requests leave the queue
        print("  status:", http(port, "GET", "/v1/status")[1].decode())
    finally:
        service.kill()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=["crowd", "culls"])
    ap.add_argument("scene")
    ap.add_argument("--cull", required=True, help="the tessera-cull binary")
    ap.add_argument("--crowd", type=int, default=1000)
    ap.add_argument("--seconds", type=float, default=30)
    ap.add_argument("--dribble", type=float, default=3)
    ap.add_argument("--addresses", type=int, default=1, help="crowd source addresses (1: 127.0.0.1)")
    ap.add_argument("--clients", type=int, default=64)
    ap.add_argument("--requests", type=int, default=20)
    ap.add_argument("--size", default="960x540")
    ap.add_argument("--k", type=int, default=256)
    ap.add_argument("--give-up", type=float, default=0, help="seconds a client waits for an answer (0: 120)")
    ap.add_argument("--service", nargs=argparse.REMAINDER, default=[], help="more tessera-cull options (last)")
    a = ap.parse_args()
    crowd(a) if a.mode == "crowd" else culls(a)


if __name__ == "__main__":
    main()
