#!/usr/bin/env python3
"""Work-precision plot (log-log: error vs wall time) from the CSV of a wp_* program, as SVG.

Dependency-free (Python 3 standard library only). Generic: any CSV with a header; one curve per
distinct value of the label column, one panel per distinct prefix before the first '/' of that
label (e.g. 'sdof/exact_steps' -> panel 'sdof', curve 'exact_steps'); points joined in CSV order
(the order of the accuracy knob); legend in the lower left corner.

Usage:
  python3 scripts/plot_work_precision.py CSV OUT.svg [--x wall_time_s] [--y error]
      [--label method] [--title TITLE] [--panels sdof,pair12,shaft] [--floor 1e-17]
      [--panel-title sdof="SDOF Meissner"] ...

  CSV       output of e.g. ./build-rel/tests/benchmarks/wp_floquet (columns
            method,knob,wall_time_s,error,evaluations); '-' reads stdin.
  --x/--y   numeric columns for the axes (default wall_time_s and error); rows with a
            non-positive or non-numeric value are skipped (y values below --floor are raised to it
            so that exact results still show, marked hollow).
  --label   column naming the curve (default method).
  --panels  comma-separated panel order / selection (default: order of appearance).
  --panel-title NAME=TEXT  caption of a panel (repeatable).

Example (docs/benchmarks.md, Floquet section):
  ./build-floquet-rel/tests/benchmarks/wp_floquet > wp_floquet.csv
  python3 scripts/plot_work_precision.py wp_floquet.csv docs/images/floquet_work_precision.svg \\
      --title "Floquet work-precision" --panels sdof,pair12,shaft
"""

import argparse
import csv
import math
import sys
from xml.sax.saxutils import escape

PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b",
           "#e377c2", "#7f7f7f", "#bcbd22", "#000000", "#6b6ecf"]
MARKERS = ["circle", "square", "triangle", "diamond"]


def read_rows(path, xcol, ycol, label, floor):
    stream = sys.stdin if path == "-" else open(path, newline="")
    with stream:
        reader = csv.DictReader(stream)
        for col in (xcol, ycol, label):
            if col not in (reader.fieldnames or []):
                sys.exit(f"plot_work_precision: column '{col}' not in {reader.fieldnames}")
        panels = {}
        for row in reader:
            try:
                x, y = float(row[xcol]), float(row[ycol])
            except ValueError:
                continue
            if not (x > 0 and math.isfinite(x) and math.isfinite(y) and y >= 0):
                continue
            name = row[label]
            panel, _, curve = name.partition("/")
            if not curve:
                panel, curve = "", name
            floored = y < floor
            panels.setdefault(panel, {}).setdefault(curve, []).append((x, max(y, floor), floored))
    return panels


def decades(lo, hi):
    a, b = math.floor(math.log10(lo)), math.ceil(math.log10(hi))
    if a == b:
        b += 1
    return a, b


def fmt_pow(e):
    return f"1e{e}"


def marker(shape, x, y, color, hollow):
    fill = "white" if hollow else color
    r = 3.5
    if shape == "circle":
        return f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{r}" fill="{fill}" stroke="{color}"/>'
    if shape == "square":
        return (f'<rect x="{x - r:.1f}" y="{y - r:.1f}" width="{2 * r}" height="{2 * r}" '
                f'fill="{fill}" stroke="{color}"/>')
    if shape == "triangle":
        pts = f"{x:.1f},{y - r - 1:.1f} {x - r - 0.5:.1f},{y + r:.1f} {x + r + 0.5:.1f},{y + r:.1f}"
        return f'<polygon points="{pts}" fill="{fill}" stroke="{color}"/>'
    pts = f"{x:.1f},{y - r - 1:.1f} {x + r + 1:.1f},{y:.1f} {x:.1f},{y + r + 1:.1f} {x - r - 1:.1f},{y:.1f}"
    return f'<polygon points="{pts}" fill="{fill}" stroke="{color}"/>'


def panel_svg(ox, oy, w, h, title, curves, xlabel, ylabel):
    out = []
    left, right, top, bottom = 62, 10, 26, 42
    pw, ph = w - left - right, h - top - bottom
    xs = [p[0] for c in curves.values() for p in c]
    ys = [p[1] for c in curves.values() for p in c]
    xa, xb = decades(min(xs), max(xs))
    ya, yb = decades(min(ys), max(ys))

    def X(v):
        return ox + left + (math.log10(v) - xa) / (xb - xa) * pw

    def Y(v):
        return oy + top + (yb - math.log10(v)) / (yb - ya) * ph

    out.append(f'<text x="{ox + left + pw / 2:.1f}" y="{oy + 16}" text-anchor="middle" '
               f'font-weight="bold">{escape(title)}</text>')
    out.append(f'<rect x="{ox + left}" y="{oy + top}" width="{pw}" height="{ph}" fill="none" '
               f'stroke="#333"/>')
    ystep = max(1, (yb - ya) // 8)
    for e in range(xa, xb + 1):
        x = X(10.0 ** e)
        out.append(f'<line x1="{x:.1f}" y1="{oy + top}" x2="{x:.1f}" y2="{oy + top + ph}" '
                   f'stroke="#ddd"/>')
        out.append(f'<text x="{x:.1f}" y="{oy + top + ph + 14}" text-anchor="middle" '
                   f'font-size="10">{fmt_pow(e)}</text>')
    for e in range(ya, yb + 1, ystep):
        y = Y(10.0 ** e)
        out.append(f'<line x1="{ox + left}" y1="{y:.1f}" x2="{ox + left + pw}" y2="{y:.1f}" '
                   f'stroke="#ddd"/>')
        out.append(f'<text x="{ox + left - 4}" y="{y + 3:.1f}" text-anchor="end" '
                   f'font-size="10">{fmt_pow(e)}</text>')
    out.append(f'<text x="{ox + left + pw / 2:.1f}" y="{oy + h - 8}" text-anchor="middle" '
               f'font-size="11">{escape(xlabel)}</text>')
    cy = oy + top + ph / 2
    out.append(f'<text x="{ox + 14}" y="{cy:.1f}" text-anchor="middle" font-size="11" '
               f'transform="rotate(-90 {ox + 14} {cy:.1f})">{escape(ylabel)}</text>')
    for k, (name, pts) in enumerate(curves.items()):
        color = PALETTE[k % len(PALETTE)]
        shape = MARKERS[k % len(MARKERS)]
        if len(pts) > 1:
            path = " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y, _ in pts)
            out.append(f'<polyline points="{path}" fill="none" stroke="{color}" '
                       f'stroke-width="1.5"/>')
        for x, y, hollow in pts:
            out.append(marker(shape, X(x), Y(y), color, hollow))
        lx = ox + left + 10
        ly = oy + top + ph - 8 - 13 * (len(curves) - 1 - k)
        out.append(marker(shape, lx, ly - 3, color, False))
        out.append(f'<text x="{lx + 8}" y="{ly + 1}" font-size="10">{escape(name)}</text>')
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("out")
    ap.add_argument("--x", default="wall_time_s")
    ap.add_argument("--y", default="error")
    ap.add_argument("--label", default="method")
    ap.add_argument("--title", default="Work-precision")
    ap.add_argument("--panels", default="")
    ap.add_argument("--floor", type=float, default=1e-17)
    ap.add_argument("--panel-title", action="append", default=[])
    ap.add_argument("--xlabel", default="wall time per call [s]")
    ap.add_argument("--ylabel", default="max multiplier error [-]")
    args = ap.parse_args()
    panels = read_rows(args.csv, args.x, args.y, args.label, args.floor)
    order = [p for p in args.panels.split(",") if p] or list(panels)
    order = [p for p in order if p in panels]
    if not order:
        sys.exit("plot_work_precision: no data to plot")
    titles = dict(t.split("=", 1) for t in args.panel_title)
    pw, ph = 420, 340
    width, height = pw * len(order), ph + 30
    body = [f'<text x="{width / 2}" y="18" text-anchor="middle" font-size="14" '
            f'font-weight="bold">{escape(args.title)}</text>']
    for i, name in enumerate(order):
        body += panel_svg(i * pw, 30, pw, ph, titles.get(name, name or args.label),
                          panels[name], args.xlabel, args.ylabel)
    svg = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">\n'
           f'<rect width="100%" height="100%" fill="white"/>\n' + "\n".join(body) + "\n</svg>\n")
    with open(args.out, "w") as f:
        f.write(svg)


if __name__ == "__main__":
    main()
