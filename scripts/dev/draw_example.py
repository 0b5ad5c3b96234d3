#!/usr/bin/env python3
"""Draws the bundled example: a small warehouse (16 m x 10 m at 0.05 m) with its keepout, speed, binary and
lanes masks, as map_server PGM + YAML files in example/. Deterministic: re-running it gives the same
bytes. The masks use mode raw, so a pixel value is the occupancy value itself (255 reads as -1)."""
import os
import sys

RES = 0.05
W, H = 320, 200  # cells: 16 m x 10 m


def cells(x0, y0, x1, y1):
    """World rectangle [m] -> the cells whose centres lie inside it."""
    for j in range(H):
        y = (j + 0.5) * RES
        if not (y0 <= y < y1):
            continue
        for i in range(W):
            x = (i + 0.5) * RES
            if x0 <= x < x1:
                yield i, j


def write_pgm(path, grid):
    """grid[j][i] with j = 0 the lowest row; PGM rows go top-down."""
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (W, H))
        for j in reversed(range(H)):
            f.write(bytes(grid[j]))


def write_yaml(path, image, mode, comment):
    with open(path, "w") as f:
        f.write(f"# {comment}\n")
        f.write(f"image: {image}\nresolution: {RES}\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n")
        f.write(f"occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: {mode}\n")


def fill(grid, rect, value):
    for i, j in cells(*rect):
        grid[j][i] = value


def main(out):
    os.makedirs(out, exist_ok=True)
    # The map (trinary: 0 black = occupied, 254 white = free, 205 grey = unknown).
    m = [[254] * W for _ in range(H)]
    for rect in [(0, 0, 16, 0.2), (0, 9.8, 16, 10), (0, 0, 0.2, 10), (15.8, 0, 16, 10)]:
        fill(m, rect, 0)  # outer walls
    for x0 in (2.0, 6.0, 10.0):
        fill(m, (x0, 7.0, x0 + 3.0, 7.6), 0)  # racks along the top
    fill(m, (13.5, 4.0, 14.5, 5.0), 0)  # a pillar
    fill(m, (0.2, 8.6, 1.6, 9.8), 205)  # an unmapped corner
    write_pgm(os.path.join(out, "warehouse.pgm"), m)
    write_yaml(os.path.join(out, "warehouse.yaml"), "warehouse.pgm", "trinary", "the example warehouse map")

    # Keepout mask (raw): 100 = virtual wall, 50 = costly but passable, 0 = nothing.
    k = [[0] * W for _ in range(H)]
    fill(k, (12.0, 7.0, 15.8, 9.8), 100)  # a loading dock nobody may enter
    fill(k, (13.0, 0.2, 15.8, 2.6), 50)  # a wet floor: avoid if possible
    write_pgm(os.path.join(out, "keepout_mask.pgm"), k)
    write_yaml(os.path.join(out, "keepout_mask.yaml"), "keepout_mask.pgm", "raw",
               "keepout mask: 100 lethal, 50 costly, 0 nothing")

    # Speed mask (raw): area ids; 0 = in no area, 255 (-1) = keep the last limit.
    s = [[0] * W for _ in range(H)]
    fill(s, (4.0, 0.2, 7.0, 3.0), 1)  # area 1: a pedestrian crossing
    fill(s, (9.0, 0.2, 12.0, 3.0), 2)  # area 2: a narrow passage
    fill(s, (7.0, 0.2, 7.5, 3.0), 255)  # between them: keep whatever was in force
    write_pgm(os.path.join(out, "speed_mask.pgm"), s)
    write_yaml(os.path.join(out, "speed_mask.yaml"), "speed_mask.pgm", "raw", "speed mask: cell value = area id")
    with open(os.path.join(out, "speed_limits.yaml"), "w") as f:
        f.write("# max_speed [m/s] of each area id of speed_mask\n")
        f.write("limits:\n  - {area_id: 1, max_speed: 0.3}\n  - {area_id: 2, max_speed: 0.6}\n")

    # Lanes mask (raw) over the aisle region: 0 = lane, 100 = forbidden, 255 (-1) = no opinion.
    lanes = [[255] * W for _ in range(H)]
    fill(lanes, (1.0, 3.6, 12.5, 6.6), 100)
    fill(lanes, (1.0, 4.6, 12.5, 5.6), 0)  # the main lane, 1 m wide
    fill(lanes, (5.5, 3.6, 6.5, 6.6), 0)  # a crossing lane
    fill(lanes, (11.0, 3.6, 12.0, 6.6), 0)  # the lane that joins the lower aisle
    write_pgm(os.path.join(out, "lanes_mask.pgm"), lanes)
    write_yaml(os.path.join(out, "lanes_mask.yaml"), "lanes_mask.pgm", "raw",
               "lanes mask: 0 lane, 100 forbidden, -1 no opinion")

    # Binary mask (raw): 100 = a private office along the main lane (the cameras must be off there).
    b = [[0] * W for _ in range(H)]
    fill(b, (3.0, 4.4, 8.0, 5.8), 100)
    write_pgm(os.path.join(out, "binary_mask.pgm"), b)
    write_yaml(os.path.join(out, "binary_mask.yaml"), "binary_mask.pgm", "raw",
               "binary mask: 100 flips the state (above flip_threshold 50), 0 default_state")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "example"))
