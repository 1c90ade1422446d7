#!/usr/bin/env python3
"""Writes fuzz seeds for the PCD, PLY and XYZ readers and the loadCloud dispatcher (standard
library only). Each seed is a small valid file of one layout the readers must handle, plus a few
broken ones (headers claiming more than the data, truncations).

  python3 fuzz/make_corpus.py pcd  DIR
  python3 fuzz/make_corpus.py ply  DIR
  python3 fuzz/make_corpus.py xyz  DIR
  python3 fuzz/make_corpus.py load DIR   # first byte = extension chooser of load_cloud_fuzzer.cpp

load_cloud_fuzzer.cpp maps the first byte (mod 8) to .las .pcd .ply .xyz .txt .csv .dat .laz.
"""
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_las_corpus  # noqa: E402

PCD_TYPES = {'F4': 'f', 'F8': 'd', 'U1': 'B', 'U2': 'H', 'U4': 'I', 'I1': 'b', 'I2': 'h',
             'I4': 'i', 'U8': 'Q', 'I8': 'q'}


def lzf_literals(data):
    """Valid LZF made of literal runs only (control byte n-1, then n <= 32 bytes)."""
    out = bytearray()
    for i in range(0, len(data), 32):
        chunk = data[i:i + 32]
        out.append(len(chunk) - 1)
        out += chunk
    return bytes(out)


def lzf_with_backref(data):
    """LZF of `data`: 4 literal bytes, then one back reference repeating them (needs len >= 12)."""
    return bytes([3]) + data[:4] + bytes([(6 << 5) | 0, 3]) + lzf_literals(data[12:]) \
        if data[4:12] == data[:4] * 2 else lzf_literals(data)


def points(n, nan_every=0):
    pts = []
    for i in range(n):
        x, y, z = 0.5 * i, math.sin(i) * 3.0, 0.25 * i - 1.0
        if nan_every and i % nan_every == nan_every - 1:
            x = float('nan')
        pts.append((x, y, z, 10 * i % 65536, i % 7, i % 3 + 1))
    return pts


def pcd(fields, n=6, data='binary', width=None, height=1, nan_every=0, crlf=False, pad=False,
        count_line=True, viewpoint=True):
    """fields: list of (name, 'F4'|'U2'|..., count)."""
    if pad:
        fields = fields + [('_', 'U1', 4)]
    width = n if width is None else width
    head = ['# .PCD v0.7 - Point Cloud Data file format', 'VERSION 0.7',
            'FIELDS ' + ' '.join(f[0] for f in fields),
            'SIZE ' + ' '.join(f[1][1] for f in fields),
            'TYPE ' + ' '.join(f[1][0] for f in fields)]
    if count_line:
        head.append('COUNT ' + ' '.join(str(f[2]) for f in fields))
    head += ['WIDTH %d' % width, 'HEIGHT %d' % height]
    if viewpoint:
        head.append('VIEWPOINT 0 0 0 1 0 0 0')
    head += ['POINTS %d' % (width * height), 'DATA ' + data]
    eol = '\r\n' if crlf else '\n'
    text = (eol.join(head) + eol).encode()
    pts = points(width * height, nan_every)

    def values(p, name, kind, count):
        base = {'x': p[0], 'y': p[1], 'z': p[2], 'intensity': p[3], 'label': p[4],
                'classification': p[4], 'return_number': p[5]}.get(name, 1)
        if kind[0] != 'F':
            base = 0 if base != base else int(abs(base)) % (1 << (8 * int(kind[1]) - 1))
        return [base] * count

    if data == 'ascii':
        lines = []
        for p in pts:
            row = []
            for name, kind, count in fields:
                row += ['nan' if v != v else ('%.9g' % v if kind[0] == 'F' else str(v))
                        for v in values(p, name, kind, count)]
            lines.append(' '.join(row))
        return text + (eol.join(lines) + eol).encode()
    if data == 'binary':
        body = bytearray()
        for p in pts:
            for name, kind, count in fields:
                body += struct.pack('<%d%s' % (count, PCD_TYPES[kind]), *values(p, name, kind, count))
        return text + bytes(body)
    body = bytearray()  # binary_compressed: field after field, "_" padding not stored
    for name, kind, count in fields:
        if name == '_':
            continue
        for p in pts:
            body += struct.pack('<%d%s' % (count, PCD_TYPES[kind]), *values(p, name, kind, count))
    packed = lzf_with_backref(bytes(body))
    return text + struct.pack('<II', len(packed), len(body)) + packed


def pcd_seeds():
    xyz = [('x', 'F4', 1), ('y', 'F4', 1), ('z', 'F4', 1)]
    rich = [('x', 'F8', 1), ('y', 'F8', 1), ('z', 'F8', 1), ('intensity', 'U2', 1),
            ('label', 'U4', 1), ('normal', 'F4', 3), ('return_number', 'U1', 1)]
    seeds = {}
    for data in ('ascii', 'binary', 'binary_compressed'):
        seeds['xyz_%s.pcd' % data] = pcd(xyz, data=data)
        seeds['rich_%s.pcd' % data] = pcd(rich, data=data, nan_every=4)
        seeds['organized_%s.pcd' % data] = pcd(xyz, data=data, width=4, height=3, nan_every=3)
        seeds['padded_%s.pcd' % data] = pcd(xyz + [('rgb', 'F4', 1)], data=data, pad=True)
    seeds['crlf_ascii.pcd'] = pcd(xyz, data='ascii', crlf=True)
    seeds['v06_no_count.pcd'] = pcd(xyz, data='ascii', count_line=False, viewpoint=False)
    seeds['ints_binary.pcd'] = pcd([('x', 'I2', 1), ('y', 'I4', 1), ('z', 'I8', 1),
                                    ('classification', 'U1', 1)], data='binary')
    seeds['empty_binary.pcd'] = pcd(xyz, n=0, data='binary')
    seeds['claims_more.pcd'] = pcd(xyz, data='binary')[:-20]
    seeds['repeated_lzf.pcd'] = pcd([('flag', 'U4', 1)] + xyz, n=12, data='binary_compressed')
    return seeds


PLY_TYPES = {'float': 'f', 'double': 'd', 'uchar': 'B', 'char': 'b', 'ushort': 'H',
             'short': 'h', 'uint': 'I', 'int': 'i', 'int32': 'i', 'float32': 'f', 'uint8': 'B'}


def ply(fmt='ascii', props=(('float', 'x'), ('float', 'y'), ('float', 'z')), n=5, lists=False,
        faces=0, grid=False, before=False):
    endian = '>' if fmt == 'binary_big_endian' else '<'
    head = ['ply', 'format %s 1.0' % fmt, 'comment pcl_ls3d fuzz seed']
    if grid:
        head += ['obj_info num_cols 3', 'obj_info num_rows %d' % ((n + 2) // 3 * 2)]
    if before:
        head += ['element camera 1', 'property float view_px', 'property list uchar int ids']
    head.append('element vertex %d' % n)
    head += ['property %s %s' % p for p in props]
    if lists:
        head.append('property list uchar float extras')
    if faces:
        head += ['element face %d' % faces, 'property list uchar int vertex_indices']
    if grid:
        head += ['element range_grid %d' % ((n + 2) // 3 * 6), 'property list uchar int vertex_indices']
    head.append('end_header')
    out = ('\n'.join(head) + '\n').encode()
    pts = points(n)
    ascii = fmt == 'ascii'
    if before:
        out += b'1.5 2 7 8\n' if ascii else struct.pack(endian + 'fBii', 1.5, 2, 7, 8)
    for i, p in enumerate(pts):
        vals = [p[0], p[1], p[2], p[3], p[4], p[5]][:len(props)]
        if ascii:
            row = ['%.9g' % v if t in ('float', 'double', 'float32') else str(int(v) % 128)
                   for (t, _), v in zip(props, vals)]
            if lists:
                row += ['2', '0.5', '1.5'] if i % 2 else ['0']
            out += (' '.join(row) + '\n').encode()
        else:
            for (t, _), v in zip(props, vals):
                out += struct.pack(endian + PLY_TYPES[t],
                                   v if t in ('float', 'double', 'float32') else int(v) % 128)
            if lists:
                out += struct.pack(endian + 'Bff', 2, 0.5, 1.5) if i % 2 else b'\x00'
    for f in range(faces):
        out += b'3 0 1 2\n' if ascii else struct.pack(endian + 'Biii', 3, 0, 1, 2)
    if grid:
        for c in range((n + 2) // 3 * 6):
            has = c % 2 == 0 and c // 2 < n
            if ascii:
                out += ('1 %d\n' % (c // 2) if has else '0\n').encode()
            else:
                out += struct.pack(endian + 'Bi', 1, c // 2) if has else b'\x00'
    return out


def ply_seeds():
    rich = (('double', 'x'), ('double', 'y'), ('double', 'z'), ('ushort', 'intensity'),
            ('uchar', 'classification'), ('uchar', 'return_number'))
    seeds = {}
    for fmt in ('ascii', 'binary_little_endian', 'binary_big_endian'):
        seeds['xyz_%s.ply' % fmt] = ply(fmt)
        seeds['rich_%s.ply' % fmt] = ply(fmt, rich, lists=True)
        seeds['mesh_%s.ply' % fmt] = ply(fmt, faces=2)
        seeds['stanford_%s.ply' % fmt] = ply(fmt, grid=True)
        seeds['camera_first_%s.ply' % fmt] = ply(fmt, before=True)
    seeds['empty.ply'] = ply('ascii', n=0)
    seeds['claims_more.ply'] = ply('binary_little_endian')[:-7]
    return seeds


def xyz_seeds():
    return {
        'plain.xyz': b'1 2 3\n4 5 6\n7.5 8.25 -9\n',
        'utm.xyz': b'512345.678 5412345.123 321.5\n512346.001 5412346.999 322.25\n',
        'header.csv': b'X,Y,Z,Intensity,Classification\n1,2,3,100,2\n4,5,6,200,6\n',
        'cloudcompare.txt': b'//X,Y,Z,R,G,B\n1;2;3;255;0;0\n4;5;6;0;255;0\n',
        'comments.xyz': b'# x y z gps_time point_source_id return_number number_of_returns\n'
                        b'\n1 2 3 1.5 7 1 2\n// comment\n4 5 6 2.5 8 2 2\r\n',
        'nan_rows.xyz': b'1 2 3\nnan 2 3\n4 inf 6\n7 8 9\n',
        'mixed_separators.txt': b'1\t2,3;4\n5 6\t7 8\n',
        'skip_columns.xyz': b'x _ y z label\n1 9 2 3 4\n5 9 6 7 8\n',
        'short_row.xyz': b'1 2 3\n4 5\n',
        'garbage.xyz': b'1 2 3\n4 5 abcdefghijklmnopqrstuvwxyz0123456789abcdefghijklmnop\n',
    }


def load_seeds():
    ext = {'.las': 0, '.pcd': 1, '.ply': 2, '.xyz': 3, '.txt': 4, '.csv': 5}
    seeds = {}
    for name, data in list(pcd_seeds().items()) + list(ply_seeds().items()) + \
            list(xyz_seeds().items()):
        seeds['load_' + name] = bytes([ext[os.path.splitext(name)[1]]]) + data
    for i, (minor, fmt) in enumerate([(2, 3), (4, 6), (0, 1)]):
        seeds['load_%d.las' % i] = bytes([0]) + bytes(make_las_corpus.las(minor, fmt))
    seeds['load_sniff.dat'] = bytes([6]) + pcd_seeds()['xyz_ascii.pcd']
    seeds['load_laz.laz'] = bytes([7]) + bytes(make_las_corpus.las())
    return seeds


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ('pcd', 'ply', 'xyz', 'load'):
        sys.exit(__doc__)
    seeds = {'pcd': pcd_seeds, 'ply': ply_seeds, 'xyz': xyz_seeds, 'load': load_seeds}[sys.argv[1]]()
    os.makedirs(sys.argv[2], exist_ok=True)
    for name, data in seeds.items():
        with open(os.path.join(sys.argv[2], name), 'wb') as f:
            f.write(data)
    print('wrote %d seeds to %s' % (len(seeds), sys.argv[2]))


if __name__ == '__main__':
    main()
