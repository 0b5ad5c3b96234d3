#!/usr/bin/env python3
"""Writes the small maps of the move_base rostest (deterministic; the files are committed):
room.pgm  a 6 m x 4 m room at 0.05 m/cell, walls two cells thick (trinary: black = occupied);
keepout.pgm  raw mask: 100 in a band x in [2.8, 3.2) m, y in [0, 3.0) m (a wall with a gap at the top);
speed.pgm  raw mask: 30 in the square x, y in [0.5, 1.5) m around the start (1.0, 1.0), 0 elsewhere.
PGM rows run from the top (highest y) down."""
import os

W, H, RES = 120, 80, 0.05
HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, value_at):
    rows = []
    for r in range(H):
        j = H - 1 - r  # map row (0 = lowest y)
        rows.append(bytes(value_at(i, j) for i in range(W)))
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (W, H))
        f.write(b"".join(rows))


def inside(i, j, x0, x1, y0, y1):
    x, y = (i + 0.5) * RES, (j + 0.5) * RES
    return x0 <= x < x1 and y0 <= y < y1


write("room.pgm", lambda i, j: 0 if i < 2 or j < 2 or i >= W - 2 or j >= H - 2 else 254)
write("keepout.pgm", lambda i, j: 100 if inside(i, j, 2.8, 3.2, 0.0, 3.0) else 0)
write("speed.pgm", lambda i, j: 30 if inside(i, j, 0.5, 1.5, 0.5, 1.5) else 0)
