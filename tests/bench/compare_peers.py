#!/usr/bin/python3
"""Runs the project's benchmarks and the peer libraries in one session and prints the ratios.

Usage: tests/bench/compare_peers.py [--sculpt build/bin/sculpt] [--peers ../shared/bench/peers.py] [WORKLOAD ...]
Workloads: haar (issue 2), mc (issue 4), rot (issue 3), edt and sdf (issue 8), nurbs (issue 9,
against the paper's own figures: no peer library does this).
Needs Debian's python3 peer packages: scripts/install-deps.sh --peers
"""
import argparse, json, re, statistics, subprocess, sys, time


def sculpt_bench(sculpt, regex):
    out = subprocess.run([sculpt, "bench", "--json", "--filter", regex], check=True, capture_output=True, text=True).stdout
    results = {}
    for b in json.loads(out)["benchmarks"]:
        unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
        results[b["name"]] = b["real_time"] * unit
    return results


def peers(script, workload, sizes):
    out = subprocess.run(["/usr/bin/python3", script, workload, "--sizes", sizes], check=True, capture_output=True, text=True).stdout
    return out


def med(fn, reps=3):
    fn()
    ts = []
    for _ in range(reps):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def haar(args):
    ours = sculpt_bench(args.sculpt, "BM_Wavelet(Decompose|Reconstruct)(Noise)?/")
    text = peers(args.peers, "haar", "128,256")
    print(text.rstrip())
    # peers.py times only the decomposition; time pywt.waverecn here, same data, same session.
    sys.path.insert(0, str(__import__("pathlib").Path(args.peers).parent))
    import numpy as np, pywt
    from peers import sphere_density
    rows = []
    for n in (128, 256):
        m = re.search(rf"wavedecn 5 levels {n}\^3: ([0-9.]+) s", text)
        dec = float(m.group(1))
        f = sphere_density(n).astype(np.float32)
        coeffs = pywt.wavedecn(f, "haar", level=5)
        rec = med(lambda: pywt.waverecn(coeffs, "haar"))
        print(f"haar  pywt.waverecn 5 levels {n}^3: {rec:.4f} s")
        for threads, label in ((1, "1 thread"), (0, "all threads")):
            d = ours[f"BM_WaveletDecompose/{n}/{threads}"]
            r = ours[f"BM_WaveletReconstruct/{n}/{threads}"]
            rows.append((f"decompose {n}^3 ({label})", d, dec))
            rows.append((f"reconstruct {n}^3 ({label})", r, rec))
            if n == 256:  # worst case: noise, every brick detailed
                rows.append((f"decompose {n}^3 noise ({label})", ours[f"BM_WaveletDecomposeNoise/{n}/{threads}"], dec))
                rows.append((f"reconstruct {n}^3 noise ({label})", ours[f"BM_WaveletReconstructNoise/{n}/{threads}"], rec))
    print()
    print("| workload | sculpt | pywt | ratio |")
    print("|---|---:|---:|---:|")
    for name, o, p in rows:
        print(f"| {name} | {o * 1e3:.2f} ms | {p * 1e3:.1f} ms | {p / o:.0f}x |")


def best_of_rounds(args, run_once):
    """Runs run_once() (ours, then the peers) args.rounds times and keeps each figure's minimum.

    The machines are shared and noisy: noise only ever adds time, so the fastest of a few
    interleaved rounds is the fairest figure for both sides alike. Returns {name: seconds}."""
    best = {}
    for r in range(args.rounds):
        for name, t in run_once(first=(r == 0)).items():
            best[name] = min(t, best.get(name, t))
    return best


def mc(args):
    # peers.py runs VTK without normals; ours always computes gradient normals.
    # Time VTK doing the same work too (same data, same session).
    sys.path.insert(0, str(__import__("pathlib").Path(args.peers).parent))
    import vtk
    from vtk.util import numpy_support
    from peers import sphere_density
    filters = {}
    for n in (128, 256):
        img = vtk.vtkImageData()
        img.SetDimensions(n, n, n)
        img.GetPointData().SetScalars(numpy_support.numpy_to_vtk(sphere_density(n).ravel(), deep=True))
        fe = vtk.vtkFlyingEdges3D()
        fe.SetInputData(img)
        fe.SetValue(0, 127.5)
        fe.ComputeNormalsOn(); fe.ComputeGradientsOff(); fe.ComputeScalarsOff()
        filters[n] = (img, fe)
    threads = {}

    def once(first):
        t = {}
        # One process per size: the allocator's state after the 128^3 run changes
        # how much of the 256^3 run's fresh memory faults in (see the faults counter).
        ours = {}
        for n in (128, 256):
            ours.update(sculpt_bench(args.sculpt, f"BM_MeshExtract/n:{n}/threads:0/weld:0"))
        text = peers(args.peers, "mc", "128,256")
        if first:
            print(text.rstrip())
        for n in (128, 256):
            t[f"ours {n}"] = ours[f"BM_MeshExtract/n:{n}/threads:0/weld:0"]
            m = re.search(rf"vtkFlyingEdges3D {n}\^3 \(threads (\d+)\): ([0-9.]+) s", text)
            threads[n] = m.group(1)
            t[f"vtk {n}"] = float(m.group(2))
            fe = filters[n][1]
            t[f"vtk normals {n}"] = med(lambda: (fe.Modified(), fe.Update()))
        return t

    best = best_of_rounds(args, once)
    print()
    print(f"Fastest of {args.rounds} interleaved rounds (ours, peers.py, VTK with normals) for each figure.")
    print("| workload | sculpt (all threads, with normals) | vtkFlyingEdges3D (no normals) | ratio | VTK with normals | ratio |")
    print("|---|---:|---:|---:|---:|---:|")
    for n in (128, 256):
        o, v, vn = best[f"ours {n}"], best[f"vtk {n}"], best[f"vtk normals {n}"]
        print(f"| extraction {n}^3 (VTK threads {threads[n]}) | {o * 1e3:.1f} ms | {v * 1e3:.1f} ms | {v / o:.2f}x "
              f"| {vn * 1e3:.1f} ms | {vn / o:.2f}x |")


def rot(args):
    def once(first):
        t = {}
        ours = sculpt_bench(args.sculpt, "BM_ToolRotate/m:(16|32|64)/method:1/aa:[01]/angles:0")
        text = peers(args.peers, "rot", "128")
        if first:
            print(text.rstrip())
        for m_ in (16, 32, 64):
            m = re.search(rf"affine_transform {m_}\^3: nearest ([0-9.]+) ms, trilinear ([0-9.]+) ms", text)
            t[f"near {m_}"] = ours[f"BM_ToolRotate/m:{m_}/method:1/aa:0/angles:0"]
            t[f"tri {m_}"] = ours[f"BM_ToolRotate/m:{m_}/method:1/aa:1/angles:0"]
            t[f"scipy {m_}"] = float(m.group(2)) * 1e-3
        return t

    best = best_of_rounds(args, once)
    print()
    print(f"Fastest of {args.rounds} interleaved rounds (ours, then peers.py) for each figure.")
    print("| tool | sculpt nearest | sculpt trilinear | AA overhead | scipy order=1 | trilinear ratio |")
    print("|---|---:|---:|---:|---:|---:|")
    for m_ in (16, 32, 64):
        near, tri, sp = best[f"near {m_}"], best[f"tri {m_}"], best[f"scipy {m_}"]
        print(f"| {m_}^3 | {near * 1e6:.1f} us | {tri * 1e6:.1f} us | {100 * (tri / near - 1):+.0f}% | {sp * 1e3:.3f} ms | {sp / tri:.0f}x |")


def edt(args):
    ours = sculpt_bench(args.sculpt, "BM_DistanceEdt/n:(128|256)/threads:[01]")
    text = peers(args.peers, "edt", "128,256")
    print(text.rstrip())
    print()
    print("| workload | sculpt | scipy distance_transform_edt | ratio |")
    print("|---|---:|---:|---:|")
    for n in (128, 256):
        m = re.search(rf"edt   scipy distance_transform_edt {n}\^3: ([0-9.]+) s", text)
        sp = float(m.group(1))
        for threads, label in ((1, "1 thread"), (0, "all threads")):
            o = ours[f"BM_DistanceEdt/n:{n}/threads:{threads}"]
            print(f"| exact EDT of (sphere > 127) {n}^3 ({label}) | {o * 1e3:.1f} ms | {sp * 1e3:.0f} ms | {sp / o:.0f}x |")


def sdf(args):
    out = subprocess.run([args.sculpt, "bench", "--json", "--filter", "BM_DistanceSdfNarrowBand/"], check=True, capture_output=True, text=True).stdout
    text = peers(args.peers, "sdf", "128")
    print(text.rstrip())
    vdb = float(re.search(r"meshToLevelSet .*: ([0-9.]+) s", text).group(1))
    print()
    print("| workload | sculpt | OpenVDB meshToLevelSet | ratio | max error vs brute (voxels) |")
    print("|---|---:|---:|---:|---:|")
    for b in json.loads(out)["benchmarks"]:
        unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
        o = b["real_time"] * unit
        label = "1 thread" if "/threads:1" in b["name"] else "all threads"
        print(f"| narrow band 3, {int(b['triangles'])} triangles, 256^3 ({label}) | {o * 1e3:.0f} ms | {vdb * 1e3:.0f} ms | {vdb / o:.2f}x | {b['max_err_vs_brute']:.2g} |")


def nurbs(args):
    # No peer library implements the paper's path constraint: the reference is
    # the paper itself (PowerPC 1.33 GHz, 2007): Figure 14 80 steps 240 ms,
    # Figure 15 100 steps 420 ms, for the whole path.
    ours = sculpt_bench(args.sculpt, "BM_NurbsPath/")
    paper = {80: 0.240, 100: 0.420}
    print("| workload | sculpt | paper | ratio |")
    print("|---|---:|---:|---:|")
    for name, t in sorted(ours.items()):
        m = re.search(r"steps:(\d+)/star:(\d)/dense:(\d)", name)
        steps, star, dense = int(m.group(1)), m.group(2) == "1", m.group(3) == "1"
        label = f"{steps} steps, {'star' if star else 'circle'} zone, {'4 cells/refined span' if dense else '48x28 cells'}"
        print(f"| {label} | {t * 1e3:.2f} ms | {paper[steps] * 1e3:.0f} ms | {paper[steps] / t:.0f}x |")


WORKLOADS = {"haar": haar, "mc": mc, "rot": rot, "edt": edt, "sdf": sdf, "nurbs": nurbs}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sculpt", default="build/bin/sculpt")
    ap.add_argument("--peers", default="../shared/bench/peers.py")
    ap.add_argument("--rounds", type=int, default=3, help="interleaved rounds for mc and rot; the fastest of each figure is kept")
    ap.add_argument("workloads", nargs="*", default=list(WORKLOADS))
    args = ap.parse_args()
    for w in args.workloads:
        print(f"## {w}")
        WORKLOADS[w](args)


if __name__ == "__main__":
    main()
