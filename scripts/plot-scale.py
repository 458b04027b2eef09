#!/usr/bin/env python3
"""Plots the CSV of scripts/bench-scale.sh: time and peak memory of `apart sequence`
against the part count, for each kind of assembly, this build beside the baseline, as
one SVG (log-log axes). Standard library only.

    python3 scripts/plot-scale.py results.csv docs/scale.svg
"""
import csv
import math
import sys


def main():
    src, out = sys.argv[1], sys.argv[2]
    rows = [r for r in csv.DictReader(open(src)) if r["command"] == "sequence"]
    kinds = sorted({r["kind"] for r in rows})
    panels = [(k, m) for m in ("seconds", "peak_mib") for k in kinds]
    w, h, pad = 360, 260, 52
    svg = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w * len(kinds)}" '
        f'height="{h * 2}" font-family="DejaVu Sans, sans-serif" font-size="11">',
        f'<rect width="{w * len(kinds)}" height="{h * 2}" fill="white"/>',
    ]
    colors = {"new": "#1f77b4", "baseline": "#d62728"}
    for p, (kind, metric) in enumerate(panels):
        ox, oy = (p % len(kinds)) * w, (p // len(kinds)) * h
        pts = [r for r in rows if r["kind"] == kind]
        xs = [int(r["parts"]) for r in pts]
        ys = [float(r[metric]) for r in pts if float(r[metric]) > 0]
        if not xs or not ys:
            continue
        x0, x1 = math.log10(min(xs)), math.log10(max(xs))
        y0, y1 = math.log10(min(ys)), math.log10(max(ys))
        x1, y1 = max(x1, x0 + 0.5), max(y1, y0 + 0.5)
        y0, y1 = math.floor(y0), math.ceil(y1)
        sx = lambda x: ox + pad + (math.log10(x) - x0) / (x1 - x0) * (w - 1.5 * pad)
        sy = lambda y: oy + h - pad - (math.log10(y) - y0) / (y1 - y0) * (h - 1.5 * pad)
        svg.append(f'<rect x="{ox + pad}" y="{oy + pad / 2}" width="{w - 1.5 * pad}" '
                   f'height="{h - 1.5 * pad}" fill="none" stroke="#999"/>')
        unit = "seconds" if metric == "seconds" else "peak MiB"
        svg.append(f'<text x="{ox + w / 2}" y="{oy + 16}" text-anchor="middle">'
                   f'{kind}: {unit} of sequence against parts</text>')
        for e in range(int(y0), int(y1) + 1):
            y = sy(10 ** e)
            svg.append(f'<line x1="{ox + pad - 4}" x2="{ox + w - pad / 2}" y1="{y:.1f}" '
                       f'y2="{y:.1f}" stroke="#eee"/>')
            svg.append(f'<text x="{ox + pad - 6}" y="{y + 4:.1f}" text-anchor="end">'
                       f'{10 ** e:g}</text>')
        for x in sorted(set(xs)):
            svg.append(f'<text x="{sx(x):.1f}" y="{oy + h - pad + 14}" '
                       f'text-anchor="middle">{x}</text>')
        for label, color in colors.items():
            line = [(int(r["parts"]), float(r[metric]), r["status"])
                    for r in pts if r["binary"] == label and float(r[metric]) > 0]
            line.sort()
            if not line:
                continue
            path = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y, _ in line)
            svg.append(f'<polyline points="{path}" fill="none" stroke="{color}" '
                       f'stroke-width="2"/>')
            for x, y, status in line:
                filled = color if status == "ok" else "white"
                svg.append(f'<circle cx="{sx(x):.1f}" cy="{sy(y):.1f}" r="3.5" '
                           f'fill="{filled}" stroke="{color}"/>')
        ly = oy + pad / 2 + 14
        for k, (label, color) in enumerate(colors.items()):
            svg.append(f'<text x="{ox + pad + 8}" y="{ly + 14 * k}" fill="{color}">'
                       f'{"this build" if label == "new" else "before"}</text>')
    svg.append('<text x="8" y="{}" fill="#555">open circles: stopped by the timeout or the '
               'memory limit (the true value is higher)</text>'.format(h * 2 - 6))
    svg.append("</svg>")
    open(out, "w").write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
