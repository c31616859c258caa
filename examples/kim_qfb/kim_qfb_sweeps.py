#!/usr/bin/env python3
"""Kim et al. (2015) test case on the Kahraman-Blankenship rig: RMS DTE vs mesh frequency.

For each mean torque (default 100, 200, 300 N m) this script
  1. runs `geardyn simulate` stepped up and down sweeps of the rig with tooth-contact teeth,
     type A (teeth = "revolute") and type B (teeth = "bushing"), Kim's values (Tables 2-3):
     k = 39.3e6 N/mm^1.5, c = 1.0, m1 = 1.5, m2 = 1.0, m3 = 0.25 (the [mesh.contact] defaults),
     k_b = 11.5e6 N mm/rad, c_b = 0.2 N mm s/rad;
  2. traces the nonlinear harmonic balance (`geardyn hb --nonlinear`) of the slice model of the
     same pair, matched to the contact model (see MatchedSliceSets below);
  3. writes docs-ready SVG plots kim-<T>Nm.svg and the raw JSON into --out.

Usage: kim_qfb_sweeps.py --geardyn build/test/apps/geardyn --out docs/figures [--points 57]
       [--torques 100,200,300] [--teeth revolute,bushing] [--jobs 2] [--reuse] [--nhb-only]
"""
import argparse
import concurrent.futures
import json
import math
import os
import subprocess
import sys
import time

SCENE = "builtin:kahraman-blankenship-rig"
MESH = "mesh.pinion-wheel"
# Kim Table 3: root joint of every tooth, SI.
TEETH_SETS = [f"{MESH}.model=contact", f"{MESH}.contact.bending_stiffness=11.5e3",
              f"{MESH}.contact.bending_damping=2.0e-4"]
# Rig geometry (the scene): base radius, tip radius, centre distance, module, face width [m].
R_B, R_A, A, M, B = 0.070477, 0.078, 0.150, 0.003, 0.020
ALPHA = math.radians(20.0)
# Kim Eq. (12) law of the [mesh.contact] defaults (SI): k [N/m^1.5], c [N s/m^1.25], m3.
K_LAW, C_LAW, M3 = 1.24278e12, 5623.41, 0.25
# Scene-level modal damping: the slice model's translational modes (~10 kHz) are met by mesh
# harmonics and need it to be traced. The contact model needs it too: Kim's law damps the mesh
# mode by only ~0.7 % and the transverse bearing modes hardly at all (docs/benchmarks.md).
NHB_MODAL_RATIO = 0.01
# Damping the rig needs, in BOTH models (the scene's bearings have none): bearing dampers
# (zeta ~ 0.05 of the mesh mode through the rz entries, translations and tilts alike) and a soft
# torsional support of the wheel (1e4 N m/rad, a 180 Hz mode far below the sweep) so that the
# rigid-body rotation settles: without it the contact model's speed and mesh phase drift after
# every transient and no speed becomes steady (tests/apps/contact_dynamic_xcheck_test.cpp).
RIG_SETS = ["bearing.pinion-support.damping=[16600,16600,5260,63,63,24]",
            "bearing.wheel-support.damping=[16600,16600,5260,63,63,24]",
            "bearing.wheel-support.stiffness=[1e10,1e10,1e9,1e8,1e8,1e4]",
            f"damping.modal_ratio={NHB_MODAL_RATIO}"]


def contact_ratio():
    """Transverse contact ratio of the rig: g_alpha / p_b (closed form for a spur pair)."""
    g = 2.0 * math.sqrt(R_A**2 - R_B**2) - A * math.sin(ALPHA)
    return g / (math.pi * M * math.cos(ALPHA))


def run(cmd, out_json):
    print("+", " ".join(cmd), file=sys.stderr, flush=True)
    with open(out_json, "w") as f:
        rc = subprocess.run(cmd, stdout=f).returncode
    with open(out_json) as f:
        text = f.read()
    return rc, (json.loads(text) if text.strip() else None)


def sets(items):
    out = []
    for s in items:
        out += ["--set", s]
    return out


def matched_slice_sets(geardyn, torque, out):
    """Slice model matched to the type-A contact model at the operating load.

    Stiffness: the contact model's quasi-static mean mesh stiffness Kbar (`simulate
    --quasi-static`, Hertz law and tooth joints linearised at the load) = the slice model's
    k * b * eps_alpha (mean contact length of a spur pair), so the two have the same mean mesh
    stiffness and the same mesh resonance. Damping: Kim's damper c * delta^m3 * ddelta/dt per
    loaded pair at the mean per-pair load F/eps_alpha (Hertz indentation delta = (F/k)^(2/3)),
    times eps_alpha pairs on average = the slice model's mesh damping c_m [N s/m] (the contact
    damper is in series with the tooth springs there, so c_m is an upper bound of its effect).
    """
    eps = contact_ratio()
    rc, qs = run([geardyn, "simulate", SCENE] + sets(TEETH_SETS + [f"{MESH}.contact.teeth=revolute"]) +
                 ["--torque", str(torque), "--quasi-static", "--samples-per-period", "64", "--json"],
                 os.path.join(out, f"kim-qs-{torque:g}Nm.json"))
    if rc != 0 or qs is None or qs.get("status") != "success":
        sys.exit(f"quasi-static at {torque} N m failed (exit {rc})")
    kbar = qs["runs"][0]["meshes"][0]["mean_stiffness_n_per_m"]
    k_len = kbar / (B * eps)
    f_pair = torque / R_B / eps
    c_m = eps * C_LAW * (f_pair / K_LAW) ** (2.0 * M3 / 3.0)
    return kbar, k_len, c_m, [f"{MESH}.model=slices", f"{MESH}.stiffness_per_length={k_len:.6g}",
                              f"{MESH}.damping={c_m:.6g}"] + RIG_SETS


# Upper end of the RMS DTE axis [um]: Kim's figures end at 20 um; larger values (the slice
# model's superharmonic resonance with back-flank contact) are drawn clipped at the top.
Y_CLIP = 30.0


def polyline(xs, ys, sx, sy, color, dash=""):
    pts = " ".join(f"{sx(x):.1f},{sy(min(y, Y_CLIP)):.1f}" for x, y in zip(xs, ys) if math.isfinite(y))
    d = f' stroke-dasharray="{dash}"' if dash else ""
    return f'<polyline fill="none" stroke="{color}" stroke-width="1.5"{d} points="{pts}"/>'


def svg(path, torque, nhb, series, note):
    """RMS DTE [um] vs mesh frequency [Hz]; nhb = (f, rms) segments, series = label -> points."""
    W, H, L, R, T, Bm = 720, 440, 70, 20, 40, 60
    fmin, fmax = 700.0, 3500.0
    ymax = 1.0
    for _, ys in nhb:
        ymax = max([ymax] + [y for y in ys if math.isfinite(y)])
    for pts in series.values():
        ymax = max([ymax] + [p[1] for p in pts if math.isfinite(p[1])])
    ymax = min(math.ceil(ymax * 1.1), Y_CLIP)
    sx = lambda f: L + (f - fmin) / (fmax - fmin) * (W - L - R)
    sy = lambda y: H - Bm - y / ymax * (H - T - Bm)
    e = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
         f'<rect width="{W}" height="{H}" fill="white"/>',
         f'<text x="{W/2}" y="20" text-anchor="middle" font-size="14">Kahraman-Blankenship rig, {torque:g} N m: RMS DTE (Kim et al. 2015 test case)</text>']
    for i in range(8):
        f = 700 + 400 * i
        e.append(f'<line x1="{sx(f):.1f}" y1="{H-Bm}" x2="{sx(f):.1f}" y2="{T}" stroke="#ddd"/>')
        e.append(f'<text x="{sx(f):.1f}" y="{H-Bm+16}" text-anchor="middle">{f}</text>')
    step = max(1, int(ymax / 8))
    for y in range(0, int(ymax) + 1, step):
        e.append(f'<line x1="{L}" y1="{sy(y):.1f}" x2="{W-R}" y2="{sy(y):.1f}" stroke="#ddd"/>')
        e.append(f'<text x="{L-6}" y="{sy(y)+4:.1f}" text-anchor="end">{y}</text>')
    e.append(f'<text x="{(L+W-R)/2}" y="{H-Bm+34}" text-anchor="middle">mesh frequency [Hz]</text>')
    e.append(f'<text x="18" y="{(T+H-Bm)/2}" text-anchor="middle" transform="rotate(-90 18 {(T+H-Bm)/2})">RMS DTE [µm]</text>')
    for xs, ys in nhb:
        e.append(polyline(xs, ys, sx, sy, "black"))
    colors = {"type A up": "#1f77b4", "type A down": "#1f77b4", "type B up": "#d62728",
              "type B down": "#d62728", "type A": "#1f77b4", "type B": "#d62728"}
    legend = [("nonlinear HB, slice model (matched)", "black", "line")]
    for label, pts in series.items():
        c = colors.get(label, "#2ca02c")
        mark = "^" if "up" in label else ("v" if "down" in label else "o")
        for f, y in pts:
            if not math.isfinite(y):
                continue
            x0, y0 = sx(f), sy(min(y, Y_CLIP))
            if mark == "^":
                e.append(f'<path d="M{x0-4:.1f},{y0+3:.1f} L{x0+4:.1f},{y0+3:.1f} L{x0:.1f},{y0-4:.1f} Z" fill="none" stroke="{c}"/>')
            elif mark == "v":
                e.append(f'<path d="M{x0-4:.1f},{y0-3:.1f} L{x0+4:.1f},{y0-3:.1f} L{x0:.1f},{y0+4:.1f} Z" fill="{c}" stroke="{c}"/>')
            else:
                e.append(f'<circle cx="{x0:.1f}" cy="{y0:.1f}" r="4" fill="none" stroke="{c}"/>')
        legend.append((f"contact model, {label}", c, mark))
    for i, (text, c, kind) in enumerate(legend):
        y = T + 14 + 16 * i
        e.append(f'<text x="{W-R-10}" y="{y}" text-anchor="end" fill="{c}">{text} ({"—" if kind=="line" else kind})</text>')
    for i, line in enumerate(note.split("\n")):  # the note's lines at the bottom
        e.append(f'<text x="{L}" y="{H - 14 + 10 * i}" font-size="10">{line}</text>')
    e.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(e) + "\n")


def sweep_job(a, teeth, torque, branch):
    """One `simulate` stepped sweep (one tooth type, torque and branch) -> its JSON file."""
    cmd = ([a.geardyn, "simulate", SCENE] + sets(TEETH_SETS + [f"{MESH}.contact.teeth={teeth}"] +
                                                 a.contact_set) +
           ["--torque", f"{torque:g}", "--mesh-frequency", f"700:3500:{a.points}", "--sweep", branch,
            "--tolerance", a.tolerance, "--steady-tolerance", a.steady_tolerance, "--max-periods",
            a.max_periods, "--threads", "1", "--json"])
    path = os.path.join(a.out, f"kim-{teeth}-{torque:g}Nm-{branch}.json")
    t0 = time.time()
    if a.reuse:  # redraw only: a missing or empty branch file is left out
        if not os.path.exists(path) or os.path.getsize(path) == 0:
            return teeth, torque, branch, 0, None, 0.0
        with open(path) as f:
            return teeth, torque, branch, 0, json.load(f), 0.0
    rc, sim = run(cmd, path)
    return teeth, torque, branch, rc, sim, time.time() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--geardyn", default="build/test/apps/geardyn")
    ap.add_argument("--out", default="docs/figures")
    ap.add_argument("--torques", default="100,200,300")
    ap.add_argument("--teeth", default="revolute,bushing")
    ap.add_argument("--points", type=int, default=57, help="speeds per branch (700-3500 Hz)")
    ap.add_argument("--tolerance", default="1e-5")
    ap.add_argument("--steady-tolerance", default="1e-3")
    ap.add_argument("--max-periods", default="200",
                    help="mesh cycles per speed at most (the steady test is over one mesh cycle "
                         "with the tooth shift); a point not steady by then is kept and drawn")
    ap.add_argument("--contact-set", action="append", default=None,
                    help="extra --set of the contact runs (default: the rig damping RIG_SETS, "
                         "the same as the NHB model's)")
    ap.add_argument("--jobs", type=int, default=2, help="sweeps (tooth type x torque x branch) run "
                    "at once, one thread each")
    ap.add_argument("--reuse", action="store_true",
                    help="redraw from the branch JSON files in --out (missing ones left out), run no sweep")
    ap.add_argument("--nhb-only", action="store_true", help="only the NHB curves (fast)")
    ap.add_argument("--extra-json", action="append", default=[],
                    help="LABEL=FILE: single-speed `simulate --json` results to plot as points")
    a = ap.parse_args()
    if a.contact_set is None:
        a.contact_set = list(RIG_SETS)
    os.makedirs(a.out, exist_ok=True)
    names = {"revolute": "type A", "bushing": "type B"}
    torques = [float(t) for t in a.torques.split(",")]
    nhbs = {}
    for torque in torques:
        kbar, k_len, c_m, slice_sets = matched_slice_sets(a.geardyn, torque, a.out)
        print(f"{torque:g} N m: Kbar {kbar:.4g} N/m, slice k {k_len:.4g} N/m2, c_m {c_m:.4g} N s/m",
              file=sys.stderr)
        rc, nhb = run([a.geardyn, "hb", SCENE] + sets(slice_sets) +
                      ["--set", f"operating_point.torque={torque:g}",
                       "--set", f"load.brake.torque={torque:g}", "--nonlinear",
                       "--mesh-frequency", "700:3500:200", "--stability", "none", "--json"],
                      os.path.join(a.out, f"kim-nhb-{torque:g}Nm.json"))
        segs = {}
        for p in (nhb or {}).get("points", []):
            ok = p["status"] == "success" and p["meshes"]
            segs.setdefault((p.get("segment", 0), p.get("branch", 0)), ([], []))
            segs[(p.get("segment", 0), p.get("branch", 0))][0].append(p["mesh_frequency_hz"])
            segs[(p.get("segment", 0), p.get("branch", 0))][1].append(
                p["meshes"][0]["rms_dte_m"] * 1e6 if ok else float("nan"))
        nhbs[torque] = (kbar, k_len, c_m, segs)
    series = {t: {} for t in torques}
    counts = {t: [0, 0] for t in torques}  # steady, not steady
    if not a.nhb_only:
        jobs = [(teeth, t, b) for teeth in a.teeth.split(",") for t in torques for b in ("up", "down")]
        t0 = time.time()
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            for teeth, torque, branch, rc, sim, wall in pool.map(lambda j: sweep_job(a, *j), jobs):
                pts = (sim or {}).get("points", [])
                print(f"{names[teeth]} {torque:g} N m {branch}: {len(pts)} points, {wall:.1f} s wall, "
                      f"exit {rc}", file=sys.stderr, flush=True)
                for p in pts:
                    # A point not steady within --max-periods is still the branch (the sweep goes
                    # on from its state): drawn with its last period's RMS, counted apart.
                    good = p["status"] in ("success", "not_converged") and p.get("meshes")
                    y = p["meshes"][0]["rms_dte_m"] * 1e6 if good else float("nan")
                    counts[torque][0 if p["status"] == "success" else 1] += 1
                    series[torque].setdefault(f"{names[teeth]} {p['branch']}", []).append(
                        (p["mesh_frequency_hz"], y))
        print(f"all sweeps: {time.time() - t0:.1f} s wall, {a.jobs} jobs", file=sys.stderr)
    for torque in torques:
        kbar, k_len, c_m, segs = nhbs[torque]
        for item in a.extra_json:
            label, path = item.split("=", 1)
            with open(path) as f:
                sim = json.load(f)
            for p in sim.get("points", []):
                if abs(p["torque_nm"] - torque) < 1e-9:
                    series[torque].setdefault(label, []).append(
                        (p["mesh_frequency_hz"], p["meshes"][0]["rms_dte_m"] * 1e6))
        note = (f"slice model: k = {k_len:.3g} N/m² (contact K̄ = {kbar:.3g} N/m, type A), "
                f"c_m = {c_m:.3g} N·s/m;\nboth: bearing dampers, wheel rz 1e4 N·m/rad, modal ratio "
                f"{NHB_MODAL_RATIO}; contact tol {a.tolerance}, steady {a.steady_tolerance} "
                f"(steady {counts[torque][0]}, not steady {counts[torque][1]})")
        svg(os.path.join(a.out, f"kim-{torque:g}Nm.svg"), torque, list(segs.values()),
            series[torque], note)


if __name__ == "__main__":
    main()
