#!/usr/bin/env python3
"""Writes the synthetic indoor map the benchmarks and the soak use, deterministically.

    python3 scripts/dev/make_synthetic_map.py OUT_DIR [--size 4000] [--resolution 0.05]

OUT_DIR gets synthetic_indoor_<size>.pgm and .yaml (map_server format, trinary). The map is a grid of
rooms with 3-cell walls, a door in each wall, furniture blocks and rooms never explored (unknown):
about 8 % occupied and 18 % unknown cells at the default size, like a scanned office floor. The same
arguments always give the same bytes (a seeded Mersenne Twister from Python's standard library).
"""
import argparse
import os
import random

FREE, OCCUPIED, UNKNOWN = 254, 0, 205


def draw(size, seed=4000):
    rng = random.Random(seed)
    img = bytearray([FREE]) * (size * size)

    def fill(x0, y0, x1, y1, value):
        x0, y0, x1, y1 = max(0, x0), max(0, y0), min(size, x1), min(size, y1)
        if x0 >= x1:
            return
        row = bytes([value]) * (x1 - x0)
        for y in range(y0, y1):
            img[y * size + x0:y * size + x1] = row

    pitch = 190  # cells between room walls: 9.5 m rooms at 0.05 m, 21 x 21 = 441 rooms on 4000 cells
    wall = 3
    rooms = range(0, size, pitch)
    for ry in rooms:
        for rx in rooms:
            if rng.random() < 0.18:  # never explored
                fill(rx, ry, rx + pitch, ry + pitch, UNKNOWN)
                continue
            for _ in range(rng.randint(2, 6)):  # furniture
                w, h = rng.randint(8, 40), rng.randint(8, 40)
                x, y = rx + rng.randint(wall + 10, pitch - w - 10), ry + rng.randint(wall + 10, pitch - h - 10)
                fill(x, y, x + w, y + h, OCCUPIED)
    for r in rooms:  # walls along every room edge, each with a door
        fill(0, r, size, r + wall, OCCUPIED)
        fill(r, 0, r + wall, size, OCCUPIED)
    for ry in rooms:
        for rx in rooms:
            d = rng.randint(30, pitch - 50)
            fill(rx + d, ry, rx + d + 20, ry + wall, FREE)  # door in the bottom wall
            d = rng.randint(30, pitch - 50)
            fill(rx, ry + d, rx + wall, ry + d + 20, FREE)  # door in the left wall
    fill(0, 0, size, wall, OCCUPIED)  # outer walls
    fill(0, size - wall, size, size, OCCUPIED)
    fill(0, 0, wall, size, OCCUPIED)
    fill(size - wall, 0, size, size, OCCUPIED)
    return img


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    ap.add_argument("--size", type=int, default=4000, help="cells per side (default 4000)")
    ap.add_argument("--resolution", type=float, default=0.05, help="[m/cell] (default 0.05)")
    args = ap.parse_args()
    if not 200 <= args.size <= 20000:
        ap.error("--size must be in [200, 20000], got %d" % args.size)
    if not 1e-3 <= args.resolution <= 10.0:
        ap.error("--resolution must be in [0.001, 10], got %g" % args.resolution)
    os.makedirs(args.out_dir, exist_ok=True)
    name = "synthetic_indoor_%d" % args.size
    img = draw(args.size)
    with open(os.path.join(args.out_dir, name + ".pgm"), "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (args.size, args.size))
        f.write(img)
    half = args.size * args.resolution / 2.0
    with open(os.path.join(args.out_dir, name + ".yaml"), "w") as f:
        f.write("image: %s.pgm\nmode: trinary\nresolution: %g\norigin: [%g, %g, 0.0]\n"
                "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.25\n" % (name, args.resolution, -half, -half))
    occupied = img.count(OCCUPIED) / len(img)
    unknown = img.count(UNKNOWN) / len(img)
    print("make_synthetic_map: %s/%s.yaml: %dx%d at %g m, %.1f %% occupied, %.1f %% unknown"
          % (args.out_dir, name, args.size, args.size, args.resolution, 100 * occupied, 100 * unknown))


if __name__ == "__main__":
    main()
