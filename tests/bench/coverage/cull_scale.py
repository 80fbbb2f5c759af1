#!/usr/bin/python3
"""The culling service at scale, as the web page meets it: for a few views
of a scene, what the page loads (the top K) against the totals and the
share of the view's covered pixels that set covers; the smallest top-K
set that reaches --share of them; /v1/cull latency with 1 and 8 clients
at once; the service's peak and current memory. Starts tessera-cull
itself (standard library only).

  cull_scale.py --cull build/default/bin/tessera-cull SCENE
                [--view NAME=PX,PY,PZ:TX,TY,TZ ...] [--k 256] [--share 0.95]
Without --view: the scene's own camera, and that camera carried 120 and
240 degrees around the scene's centre (about the vertical), looking at it.
"""
import argparse, concurrent.futures, json, math, statistics, subprocess, time, urllib.request


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--cull", required=True, help="the tessera-cull binary")
    ap.add_argument("--view", action="append", default=[], help="NAME=PX,PY,PZ:TX,TY,TZ")
    ap.add_argument("--k", type=int, default=256, help="objects the page loads (its default)")
    ap.add_argument("--share", type=float, default=0.95, help="share of the covered pixels to reach")
    ap.add_argument("--size", default="960x540", help="the view's pixels, WxH")
    ap.add_argument("--rounds", type=int, default=16, help="requests per client for the latency")
    a = ap.parse_args()
    width, height = (int(v) for v in a.size.split("x"))

    started = time.time()
    service = subprocess.Popen([a.cull, a.scene, "--listen", "127.0.0.1:0", "--max-objects", "100000",
                                "--previews", "0"], stdout=subprocess.PIPE, text=True)
    try:
        line = service.stdout.readline()
        if not line.startswith("listening on"):
            raise SystemExit(f"tessera-cull did not start: {line!r}")
        port = int(line.rsplit(":", 1)[1])
        print(f"{a.scene}: service up in {time.time() - started:.1f} s")
        base = f"http://127.0.0.1:{port}"
        scene = json.load(urllib.request.urlopen(base + "/v1/scene"))
        fov = scene["camera"]["fov"]

        def cull(position, target, k):
            body = json.dumps({"camera": {"position": position, "target": target, "fov": fov},
                               "width": width, "height": height, "max_objects": k}).encode()
            t = time.perf_counter()
            answer = json.load(urllib.request.urlopen(urllib.request.Request(base + "/v1/cull", data=body)))
            return answer, (time.perf_counter() - t) * 1000

        views = {}
        for v in a.view:
            name, pose = v.split("=")
            p, t = ([float(x) for x in part.split(",")] for part in pose.split(":"))
            views[name] = (p, t)
        if not views:
            p = scene["camera"]["position"]
            lo, hi = scene["bounds"]["min"], scene["bounds"]["max"]
            c = [(lo[i] + hi[i]) / 2 for i in range(3)]
            views["camera"] = (p, scene["camera"]["target"])
            d = [p[i] - c[i] for i in range(3)]
            for degrees in (120, 240):
                r = math.radians(degrees)
                turned = [d[0] * math.cos(r) + d[2] * math.sin(r), d[1], -d[0] * math.sin(r) + d[2] * math.cos(r)]
                views[f"orbit {degrees}"] = ([c[i] + turned[i] for i in range(3)], c)

        total_tri, total_obj = scene["total_triangles"], scene["total_objects"]
        print(f"totals: {total_obj} objects, {total_tri} triangles; views of {width}x{height}")
        print(f"{'view':<12} {'covered':>8} {'seen':>6} | {'top K':>6} {'tris':>10} {'% tris':>7} {'% px':>6} |"
              f" {'for ' + str(round(100 * a.share)) + '%: objs':>13} {'tris':>10} {'% tris':>7}")
        for name, (p, t) in views.items():
            answer, _ = cull(p, t, 100000)
            objects = answer["objects"]
            covered = sum(o["pixels"] for o in objects)
            top = objects[:a.k]
            top_tri = sum(o["triangles"] for o in top)
            top_px = sum(o["pixels"] for o in top) / covered if covered else 0
            acc = tri = n = 0
            for o in objects:
                if acc >= a.share * covered:
                    break
                acc += o["pixels"]
                tri += o["triangles"]
                n += 1
            print(f"{name:<12} {100 * answer['covered_fraction']:7.1f}% {len(objects):>6} | {len(top):>6} {top_tri:>10}"
                  f" {100 * top_tri / total_tri:6.2f}% {100 * top_px:5.1f}% | {n:>13} {tri:>10} {100 * tri / total_tri:6.2f}%")

        first = next(iter(views.values()))
        cull(*first, a.k)  # warm
        one = sorted(cull(*first, a.k)[1] for _ in range(a.rounds))
        print(f"1 client : median {statistics.median(one):6.1f} ms, p99 {percentile(one, 0.99):6.1f} ms"
              f" ({len(one)} requests, K = {a.k})")
        names = list(views.values())
        with concurrent.futures.ThreadPoolExecutor(8) as pool:
            eight = sorted(pool.map(lambda i: cull(*names[i % len(names)], a.k)[1], range(8 * a.rounds)))
        print(f"8 clients: median {statistics.median(eight):6.1f} ms, p99 {percentile(eight, 0.99):6.1f} ms"
              f" ({len(eight)} requests)")
        status = dict(l.split(":", 1) for l in open(f"/proc/{service.pid}/status") if ":" in l)
        print(f"memory: peak {status['VmHWM'].strip()}, now {status['VmRSS'].strip()}")
    finally:
        service.terminate()
        service.wait()


def percentile(sorted_values, q):
    return sorted_values[min(len(sorted_values) - 1, math.ceil(q * len(sorted_values)) - 1)]


if __name__ == "__main__":
    main()
