#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets into test/fuzz/corpus/<target>/.

Each binary seed follows the byte layout the target's decoder reads (test/fuzz/fuzz_decoder.hpp and
the target's LLVMFuzzerTestOneInput); keep both in step. Seeds are small well-formed inputs plus a
few with the special values (0, NaN, inf, mismatched lengths) the fuzzer should start near.
Run: python3 test/fuzz/make_seeds.py   (rewrites the corpus folders; commit the result)
"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


# ---- the FuzzDecoder encoding -------------------------------------------------------------------
def u8(v): return struct.pack('<B', v & 0xFF)
def u16(v): return struct.pack('<H', v & 0xFFFF)
def u32(v): return struct.pack('<I', v & 0xFFFFFFFF)
def i16(v): return struct.pack('<h', v)
def flag(b): return u8(1 if b else 0)
def small(v, lo): return u8(v - lo)          # FuzzDecoder::small(lo, hi) with v in [lo, hi]
def size(n): return u8(n) if n < 255 else u8(255) + u32(n)
def string(s): return u8(len(s)) + s.encode()

ZERO, NAN, INF, NINF, HUGE, TINY = b'\x01', b'\x02', b'\x03', b'\x04', b'\x05', b'\x07'


def real(v):
    """A double as FuzzDecoder::real reads it: int16/256 when exact, else int32/1000, else raw."""
    if isinstance(v, bytes):
        return v
    if v == 0:
        return ZERO
    if abs(v) < 128 and round(v * 256) == v * 256:
        return u8(10) + i16(int(v * 256))
    if abs(v) < 2e6:
        return u8(13) + struct.pack('<i', int(round(v * 1000)))
    return u8(0) + struct.pack('<d', v)


def grid_values(values, how=0, explicit=None):
    """gridValues(): how 0 = exact, 1 = one short, 2 = one long, 3 = empty, 4 = explicit length."""
    out = u8(how)
    if how == 4:
        out += size(explicit)
    return out + bytes(v & 0xFF for v in values)


def geometry(w=10, h=10, res=0.25, ox=0.0, oy=0.0):
    return small(w, 1) + small(h, 1) + u8(int(res * 64) - 1) + i16(int(ox * 256)) + i16(int(oy * 256))


def pose(x=0.0, y=0.0, yaw=0.0):
    return real(x) + real(y) + real(yaw)


def sensor_pose(x=0.0, y=0.0, z=0.3):
    return real(x) + real(y) + real(z) + i16(0) + i16(0) + i16(0) + i16(32767)


def write(target, name, data):
    folder = os.path.join(HERE, 'corpus', target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), 'wb') as f:
        f.write(data)


def clean(target):
    folder = os.path.join(HERE, 'corpus', target)
    if os.path.isdir(folder):
        for f in os.listdir(folder):
            os.remove(os.path.join(folder, f))


# ---- fuzz_mask ----------------------------------------------------------------------------------
def mask_grid(w, h, res, ox, oy, yaw=0.0, values=None, frame_odom=False, how=0):
    values = values if values is not None else [(k * 37) % 101 for k in range(w * h)]
    return (flag(frame_odom) + size(w) + size(h) + real(res) + real(ox) + real(oy) + real(yaw) +
            grid_values(values, how))


def seeds_mask():
    for kind, params in ((0, b''),
                         (1, real(0.5) + u8(1) + flag(False) + real(10.0)),
                         (2, real(1.0) + flag(False) + flag(True) + real(0.0) + real(0.01))):
        head = u8(kind) + params + geometry(16, 16, 0.25) + flag(False) + flag(False) + pose(1.0, 2.0, 0.5)
        lanes = [0 if (k % 8) in (3, 4) else 100 for k in range(64)]
        write('mask', f'k{kind}_aligned', head + u8(0) + mask_grid(8, 8, 0.5, 0.0, 0.0, values=lanes) +
              u8(2) + pose(2.0, 2.0))
        write('mask', f'k{kind}_offset', head + u8(0) + mask_grid(8, 8, 0.25, 0.5, 0.5) + u8(2) + pose())
        write('mask', f'k{kind}_rotated_odom', head + u8(0) +
              mask_grid(6, 5, 0.3, -1.0, 0.25, yaw=0.75, frame_odom=True) + u8(2) + pose() + u8(3) + flag(False) +
              u8(2) + pose())
        write('mask', f'k{kind}_replace_and_reject', head + u8(0) + mask_grid(4, 4, 1.0, 0.0, 0.0) + u8(2) + pose() +
              u8(0) + mask_grid(4, 4, NAN, 0.0, 0.0) + u8(0) + mask_grid(3, 3, 0.5, 1.0, 1.0, how=1) +
              u8(0) + mask_grid(2, 2, 0.125, 3.0, 3.0) + u8(2) + pose())
    rolling = u8(0) + geometry(12, 12, 0.5) + flag(True) + flag(True) + pose()
    write('mask', 'rolling_keepout', rolling + u8(0) + mask_grid(10, 10, 0.5, -2.0, -2.0) + u8(2) + pose(1.5, -0.75) +
          u8(2) + pose(30.0, 30.0))
    write('mask', 'special_values', u8(0) + geometry() + flag(False) + flag(False) + pose() +
          u8(0) + mask_grid(3, 3, INF, 0.0, 0.0) + u8(0) + mask_grid(3, 3, TINY, 0.0, 0.0) +
          u8(0) + mask_grid(3, 3, 1.0, HUGE, 0.0) + u8(0) + mask_grid(0, 3, 1.0, 0.0, 0.0) + u8(2) + pose())


# ---- fuzz_static_map ----------------------------------------------------------------------------
def update(x, y, w, h, values=None, how=0):
    values = values if values is not None else [100] * (w * h)
    return (size(abs(x)) + flag(x < 0) + size(abs(y)) + flag(y < 0) + size(w) + size(h) + grid_values(values, how))


def seeds_static_map():
    for bits in (0, 1, 4 | 8, 16, 32, 64, 32 | 64, 128 | 16):
        head = u8(bits) + u8(100) + u8(0xFF) + geometry(8, 8, 0.5) + pose()
        if bits & 64:
            head += u8(9) + u8(40)
        body = (u8(0) + mask_grid(12, 10, 0.25, -1.0, -1.0, values=[(k * 7) % 101 - 1 for k in range(120)]) +
                u8(2) + pose(0.5, 0.5) + u8(1) + update(2, 3, 4, 2) + u8(1) + update(-1, 0, 2, 2) +
                u8(1) + update(10, 9, 3, 3) + u8(2) + pose(1.0, 0.0))
        write('static_map', f'bits{bits}', head + body)
    write('static_map', 'reject_then_accept', u8(0) + u8(100) + u8(0xFF) + geometry() + pose() +
          u8(0) + mask_grid(4, 4, 0.0, 0.0, 0.0) + u8(0) + mask_grid(5, 4, 0.5, 0.0, 0.0, how=2) +
          u8(0) + mask_grid(5, 4, 0.5, 0.0, 0.0, frame_odom=True) + u8(3) + pose() +
          u8(1) + update(0, 0, 5, 4, how=1) + u8(3) + pose())


# ---- fuzz_speed_limits --------------------------------------------------------------------------
def limits(entries):
    out = small(len(entries), 0)
    for area, speed in entries:
        out += size(area) + real(speed)
    return out


def seeds_speed_limits():
    mask = small(4, 1) + small(4, 1) + u8(31) + i16(0) + i16(0) + grid_values([0, 1, 2, 3, 50, 100, -1, 7] * 2)
    for pct in (False, True):
        for nav2 in (False, True):
            head = real(2.0) + flag(pct) + flag(nav2) + real(0.0) + real(1.0 if not nav2 else 0.01) + geometry()
            ops = (u8(0) + limits([(1, 0.5), (2, 50.0), (3, 1.0), (0, 1.0), (101, 1.0), (2, NAN), (7, INF)]) +
                   u8(3) + pose(0.5, 0.5) + u8(3) + pose(1.5, 0.5) + u8(3) + pose(2.5, 0.5) + u8(2) + flag(False) +
                   u8(3) + pose(0.5, 2.5) + u8(2) + flag(True) + u8(3) + pose(3.5, 3.5))
            write('speed_limits', f'pct{int(pct)}_nav2{int(nav2)}', head + mask + ops)
    yaml = 'limits:\n  - {area_id: 1, max_speed: 0.5}\n  - {area_id: 2, max_speed: .inf}\n  - {area_id: 3}\n'
    write('speed_limits', 'features_yaml', real(1.0) + flag(False) + flag(False) + real(0.0) + real(1.0) + geometry() +
          mask + u8(1) + u8(len(yaml)) + yaml.encode() + u8(3) + pose(0.5, 0.5))


# ---- sensors ------------------------------------------------------------------------------------
def sensor_params(bits=2, voxel=False):
    out = (u8(bits) + i16(-256) + i16(512) + u8(20) + u8(24) + u8(0) + u8(0) + small(1, 0) + i16(512))
    if voxel:
        out += i16(0) + u8(12) + small(10, 1) + u8(15) + u8(0)
    return out


def scan(n, amin, amax, ranges, rmin=0.05, rmax=4.0, per_beam=False):
    inc = (amax - amin) / (n - 1) if n > 1 else 0.01
    out = real(amin) + real(amax) + real(inc) + real(0.0) + real(0.1) + real(rmin) + real(rmax) + size(n)
    if per_beam:
        out += flag(True) + b''.join(real(r) for r in ranges)
    else:
        out += flag(False) + small(len(ranges), 1) + b''.join(real(r) for r in ranges)
    return out + small(0, 0)


def seeds_laser_scan():
    for kind in (0, 1, 2, 3):
        voxel = bool(kind & 1)
        head = u8(kind) + sensor_params(2 | 4, voxel) + geometry(20, 20, 0.25, -2.5, -2.5)
        write('laser_scan', f'kind{kind}', head + u8(1) + scan(90, -1.5, 1.5, [1.0, 2.0, INF, NAN, 0.01]) +
              sensor_pose(0.0, 0.0, 0.3) + u8(0) + pose(0.25, 0.0) + u8(1) +
              scan(5, 0.0, 0.5, [1.0, 1.5, 2.0, 2.5, 3.0], per_beam=True) + sensor_pose(0.5, 0.5, 0.3) +
              u8(0) + pose(0.5, 0.5))
    write('laser_scan', 'bad_scans', u8(0) + sensor_params() + geometry() + u8(1) +
          real(0.0) + real(1.0) + real(0.0) + real(0) + real(0) + real(0.1) + real(4.0) + size(3) + flag(False) +
          small(1, 1) + real(1.0) + small(0, 0) + sensor_pose() + u8(1) +
          real(NAN) + real(1.0) + real(0.1) + real(0) + real(0) + real(0.1) + real(4.0) + size(11) + flag(False) +
          small(1, 1) + real(1.0) + small(0, 0) + sensor_pose() + u8(0) + pose())


def cloud(points, big_endian=False, float64=False, extra_field=True, how=0):
    fmt = ('>' if big_endian else '<') + ('d' if float64 else 'f')
    sz = 8 if float64 else 4
    dtype = 8 if float64 else 7
    names = [(0, 0), (1, sz), (2, 2 * sz)] + ([(3, 3 * sz)] if extra_field else [])
    step = sz * len(names)
    out = size(1) + size(len(points)) + small(len(names), 0)
    for idx, off in names:
        out += u8(idx) + size(off) + u8(dtype) + size(1)
    out += flag(big_endian) + flag(False) + size(step) + flag(True) + u8(how)
    for p in points:
        out += b''.join(struct.pack(fmt, v) for v in (list(p) + [0.0] * (len(names) - 3)))
    return out


def seeds_pointcloud2():
    pts = [(1.0, 0.0, 0.5), (1.5, 0.5, 0.2), (0.5, -1.0, 1.0), (float('nan'), 0.0, 0.0)]
    for kind in (0, 1, 2, 3):
        head = u8(kind) + sensor_params(2, bool(kind & 1)) + geometry(20, 20, 0.25, -2.5, -2.5)
        write('pointcloud2', f'kind{kind}', head + u8(1) + cloud(pts) + sensor_pose() + u8(0) + pose() +
              u8(1) + cloud(pts, big_endian=True, float64=True) + sensor_pose(0.5, 0.0) + u8(0) + pose(0.5, 0.0))
    write('pointcloud2', 'short_data', u8(0) + sensor_params() + geometry() + u8(1) + cloud(pts, how=1) +
          sensor_pose() + u8(1) + cloud(pts[:2], extra_field=False, how=2) + sensor_pose() + u8(0) + pose())


def seeds_range():
    reading = lambda fov, rmin, rmax, r, kind=0: u8(kind) + real(fov) + real(rmin) + real(rmax) + real(r)
    for bits, typ in ((0, 0), (1, 1), (4, 2), (2 | 8, 0)):
        head = (u8(bits) + real(1.2) + u8(255) + u8(51) + u8(204) + u8(typ) + geometry(20, 20, 0.125, -1.25, -1.25))
        write('range', f'bits{bits}_type{typ}', head + u8(1) + reading(0.5, 0.1, 2.0, 1.0) + sensor_pose(0, 0, 0.1) +
              u8(1) + reading(0.5, 0.1, 2.0, 2.0) + sensor_pose(0.25, 0, 0.1) +
              u8(1) + reading(0.3, 0.2, 0.2, NINF, 1) + sensor_pose(0, 0.25, 0.1) +
              u8(1) + reading(0.3, 0.2, 0.2, INF, 1) + sensor_pose(0, 0.25, 0.1) + u8(0) + pose() + u32(10 ** 8))
    write('range', 'bad_readings', u8(0) + real(1.2) + u8(255) + u8(51) + u8(204) + u8(0) + geometry() +
          u8(1) + reading(NAN, 0.1, 2.0, 1.0) + sensor_pose() + u8(1) + reading(4.0, 0.1, 2.0, 1.0) + sensor_pose() +
          u8(1) + reading(0.5, 2.0, 0.1, 1.0) + sensor_pose() + u8(1) + reading(0.5, 0.0, HUGE, 1e6) + sensor_pose() +
          u8(0) + pose() + u32(0))


# ---- fuzz_map_file ------------------------------------------------------------------------------
def png(width, height, color_type, bit_depth, rows, palette=None, trns=None):
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xFFFFFFFF)
    out = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, bit_depth, color_type, 0, 0, 0))
    if palette:
        out += chunk(b'PLTE', bytes(palette))
    if trns:
        out += chunk(b'tRNS', bytes(trns))
    out += chunk(b'IDAT', zlib.compress(b''.join(b'\x00' + r for r in rows)))
    return out + chunk(b'IEND', b'')


def seeds_map_file():
    yaml = (b'image: map.pgm\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\n'
            b'occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n')
    yaml_scale = yaml.replace(b'trinary', b'scale').replace(b'negate: 0', b'negate: true')
    grey = bytes([0, 127, 128, 205, 254, 255, 64, 192, 10, 250, 100, 200])
    pgm5 = b'P5\n# comment\n4 3\n255\n' + grey
    pgm2 = b'P2\n4 3\n15\n' + b' '.join(str(v % 16).encode() for v in grey) + b'\n'
    pgm16 = b'P5 2 2 65535\n' + b'\x00\x00\xff\xff\x80\x00\x7f\xff'
    ppm6 = b'P6\n2 2\n255\n' + bytes(range(0, 240, 20))
    ppm3 = b'P3 2 1 255 0 0 0 255 255 255\n'
    png_grey = png(4, 3, 0, 8, [grey[0:4], grey[4:8], grey[8:12]])
    png_rgba = png(2, 2, 6, 8, [bytes([0, 0, 0, 255, 255, 255, 255, 0]), bytes([128, 128, 128, 255, 9, 9, 9, 128])])
    png_pal = png(3, 1, 3, 8, [bytes([0, 1, 2])], palette=[0, 0, 0, 255, 255, 255, 128, 128, 128], trns=[255, 0])
    png_1bit = png(9, 2, 0, 1, [bytes([0b10101010, 0b10000000]), bytes([0xFF, 0])])
    png_16 = png(2, 1, 4, 16, [bytes([0, 0, 255, 255, 255, 255, 0, 0])])
    images = {'pgm5': pgm5, 'pgm2': pgm2, 'pgm16': pgm16, 'ppm6': ppm6, 'ppm3': ppm3, 'png_grey': png_grey,
              'png_rgba': png_rgba, 'png_palette': png_pal, 'png_1bit': png_1bit, 'png_16bit': png_16}
    for name, img in images.items():
        write('map_file', name, u8(1) + u16(len(yaml)) + yaml + img)
    for mode in range(4):
        write('map_file', f'mode{mode}_pgm', u8(2 | (mode << 2)) + u16(0) + pgm5)
        write('map_file', f'mode{mode}_png_rgba', u8(2 | (mode << 2)) + u16(0) + png_rgba)
    write('map_file', 'scale_negate', u8(1) + u16(len(yaml_scale)) + yaml_scale + pgm5)
    write('map_file', 'truncated_pgm', u8(0) + u16(0) + pgm5[:-3])
    write('map_file', 'truncated_png', u8(0) + u16(0) + png_grey[:-20])
    bad_yaml = b'image: map.pgm\nresolution: .nan\norigin: [0, 0]\nnegate: maybe\noccupied_thresh: 2\n'
    write('map_file', 'bad_yaml', u8(1) + u16(len(bad_yaml)) + bad_yaml + pgm5)


# ---- fuzz_params --------------------------------------------------------------------------------
def seeds_params():
    for name in sorted(os.listdir(os.path.join(ROOT, 'params'))):
        if name.endswith('.yaml'):
            with open(os.path.join(ROOT, 'params', name), 'rb') as f:
                write('params', name, f.read())
    small_docs = {
        'footprint_string.yaml': 'costmap:\n  footprint: "[[0.5, 0.3], [-0.5, 0.3], [-0.5, -0.3], [0.5, -0.3]]"\n'
                                 '  footprint_padding: 0.02\n  width: 4\n  height: 4\n  resolution: 0.1\n'
                                 '  plugins:\n    - {name: g, type: costmap_layers/GradientLayer}\n'
                                 '    - {name: inflation, type: costmap_layers/InflationLayer}\n'
                                 '  g: {gradient_size: 3}\n  inflation: {inflation_radius: 0.5}\n',
        'footprint_list.yaml': 'costmap:\n  footprint: [[0.4, 0.2], [-0.4, 0.2], [-0.4, -0.2], [0.4, -0.2]]\n'
                               '  robot_radius: 0.3\n  rolling_window: true\n  width: 3\n  height: 3\n'
                               '  resolution: 0.05\n  track_unknown_space: true\n'
                               '  plugins: [obstacles, range]\n  obstacles: {plugin: costmap_layers/VoxelLayer, '
                               'observation_sources: "scan cloud", scan: {data_type: LaserScan}, cloud: {}}\n'
                               '  range: {plugin: costmap_layers/RangeSensorLayer, topics: [sonar]}\n',
        'nav2_foxy.yaml': 'local_costmap:\n  plugin_names: [static, keepout]\n'
                          '  plugin_types: ["costmap_layers::StaticLayer", "costmap_layers::KeepoutFilter"]\n'
                          '  filters: [speed, lanes]\n  speed: {plugin: costmap_layers/SpeedFilter, '
                          'speed_limit_in_percent: true, default_max_speed: 1.0}\n'
                          '  lanes: {plugin: costmap_layers/LanesFilter, cost_profile: exponential}\n',
        'wrong_types.yaml': 'costmap:\n  footprint: 12\n  robot_radius: "big"\n  width: [1, 2]\n  resolution: .nan\n'
                            '  plugins: {name: x}\n  global_frame: ""\n',
        'bad_footprint.yaml': 'costmap:\n  footprint: "[[0, 0], [1, .inf]]"\n  plugins:\n'
                              '    - {name: a, type: costmap_layers/GradientLayer}\n'
                              '    - {name: a, type: costmap_layers/GradientLayer}\n',
        'anchors.yaml': 'base: &b {resolution: 0.5, width: 2, height: 2}\ncostmap:\n  <<: *b\n  origin_x: -1e3\n'
                        '  plugins: [{name: s, type: costmap_layers/StaticLayer}]\n  s: {first_map_only: yes}\n',
    }
    for name, text in small_docs.items():
        write('params', name, text.encode())


if __name__ == '__main__':
    for target, fn in (('mask', seeds_mask), ('static_map', seeds_static_map), ('speed_limits', seeds_speed_limits),
                       ('laser_scan', seeds_laser_scan), ('pointcloud2', seeds_pointcloud2), ('range', seeds_range),
                       ('map_file', seeds_map_file), ('params', seeds_params)):
        clean(target)
        fn()
    print('seeds written to', os.path.join(HERE, 'corpus'))
