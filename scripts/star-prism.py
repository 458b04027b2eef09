#!/usr/bin/env python3
"""Writes a prism over a non-convex star polygon as one OFF file: N sides, radius 10 and
7 alternating, height 1, caps as single polygons. For the loading benchmark:

    python3 scripts/star-prism.py 100000 /tmp/star && apart check /tmp/star
"""
import math
import os
import sys


def main() -> None:
    n, out = int(sys.argv[1]), sys.argv[2]
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "star.off"), "w") as f:
        f.write("OFF\n%d %d 0\n" % (2 * n, n + 2))
        for z in (0, 1):
            for k in range(n):
                a, r = 2 * math.pi * k / n, (10 if k % 2 == 0 else 7)
                f.write("%.17g %.17g %d\n" % (r * math.cos(a), r * math.sin(a), z))
        f.write("%d %s\n" % (n, " ".join(str(i) for i in reversed(range(n)))))
        f.write("%d %s\n" % (n, " ".join(str(n + i) for i in range(n))))
        for k in range(n):
            j = (k + 1) % n
            f.write("4 %d %d %d %d\n" % (k, j, n + j, n + k))


if __name__ == "__main__":
    main()
