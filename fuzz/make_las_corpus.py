#!/usr/bin/env python3
"""Writes small LAS files for the fuzzer and the broken-file replay test (standard library only).

  python3 fuzz/make_las_corpus.py broken test/data/las_corpus   # every file must be rejected
  python3 fuzz/make_las_corpus.py seeds  /tmp/las_seeds          # valid seeds + the broken ones

Layouts follow the ASPRS LAS 1.4 R15 public header (227/235/375 bytes) and point formats 0-10.
"""
import os
import struct
import sys

RECORD = [20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67]


def las(minor=2, fmt=3, n=3, vlrs=(), record_length=None):
    """A valid LAS 1.<minor> file with n points of format fmt (bytearray)."""
    hs = {0: 227, 1: 227, 2: 227, 3: 235, 4: 375}[minor]
    rl = record_length or RECORD[fmt]
    vlr_bytes = b''.join(struct.pack('<H16sHH32s', 0, u, r, len(d), b'desc') + d for u, r, d in vlrs)
    off = hs + len(vlr_bytes)
    h = bytearray(hs)
    h[0:4] = b'LASF'
    h[24], h[25] = 1, minor
    h[26:34] = b'pcl_ls3d'
    struct.pack_into('<HIIBHI', h, 94, hs, off, len(vlrs), fmt, rl, 0 if (minor == 4 and fmt >= 6) else n)
    struct.pack_into('<5I', h, 111, n, 0, 0, 0, 0)
    struct.pack_into('<6d', h, 131, 0.01, 0.01, 0.01, 500000.0, 5000000.0, 0.0)
    struct.pack_into('<6d', h, 179, 500000.02, 500000.0, 5000000.02, 5000000.0, 0.02, 0.0)
    if minor == 4:
        struct.pack_into('<Q', h, 247, n)
        struct.pack_into('<Q', h, 255, n)
    pts = bytearray()
    for i in range(n):
        r = bytearray(rl)
        struct.pack_into('<iiiH', r, 0, i, i, i, 100 + i)
        if fmt >= 6:
            r[14], r[16] = 0x11, 2
            struct.pack_into('<Hd', r, 20, 7, 1.5 * i)
        else:
            r[14], r[15] = 0x09, 2
            struct.pack_into('<H', r, 18, 7)
            if fmt in (1, 3, 4, 5):
                struct.pack_into('<d', r, 20, 1.5 * i)
        pts += r
    return bytearray(h) + vlr_bytes + pts


def patched(data, offset, fmt, *values):
    data = bytearray(data)
    struct.pack_into(fmt, data, offset, *values)
    return data


def broken():
    base = las()
    b14 = las(minor=4, fmt=6)
    return {
        'empty.las': b'',
        'signature.las': b'LASX' + base[4:],
        'truncated_header.las': base[:150],
        'truncated_header_14.las': b14[:300],
        'truncated_points.las': base[:-10],
        'count_too_large.las': patched(base, 107, '<I', 1000),
        'count_huge.las': patched(base, 107, '<I', 0xFFFFFFFF),
        'count64_huge.las': patched(b14, 247, '<Q', 0xFFFFFFFFFFFFFFFF),
        'count_mismatch_14.las': patched(patched(b14, 107, '<I', 2), 247, '<Q', 3),
        'version_2_0.las': patched(base, 24, '<BB', 2, 0),
        'version_1_5.las': patched(base, 24, '<BB', 1, 5),
        'format_11.las': patched(base, 104, '<B', 11),
        'format_63.las': patched(base, 104, '<B', 63),
        'record_too_short.las': patched(base, 105, '<H', 20),
        'record_zero.las': patched(base, 105, '<H', 0),
        'offset_beyond_end.las': patched(base, 96, '<I', 100000),
        'offset_inside_header.las': patched(base, 96, '<I', 100),
        'header_size_small.las': patched(b14, 94, '<H', 227),
        'header_size_huge.las': patched(base, 94, '<H', 65535),
        'laz_bit7.las': patched(base, 104, '<B', 0x83),
        'laz_bit6.las': patched(base, 104, '<B', 0x43),
        'laszip_vlr.las': las(vlrs=[(b'laszip encoded', 22204, b'\0' * 34)]),
        'vlr_overrun.las': patched(las(vlrs=[(b'test', 1, b'abcd')]), 227 + 20, '<H', 5000),
        'vlr_count_huge.las': patched(base, 100, '<I', 0xFFFFFFFF),
        'scale_zero.las': patched(base, 131, '<d', 0.0),
        'scale_nan.las': patched(base, 139, '<d', float('nan')),
        'offset_inf.las': patched(base, 155, '<d', float('inf')),
        'no_points.las': patched(las(n=0), 107, '<I', 0),
    }


def seeds():
    out = dict(broken())
    for minor, fmts in ((0, (0, 1)), (2, (2, 3)), (3, (4, 5)), (4, range(11))):
        for f in fmts:
            out['valid_v1%d_pf%d.las' % (minor, f)] = las(minor=minor, fmt=f)
    out['valid_extra_bytes.las'] = las(fmt=1, record_length=33)
    out['valid_vlr.las'] = las(vlrs=[(b'LASF_Projection', 2112, b'PROJCS[]\0')])
    return out


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ('broken', 'seeds'):
        sys.exit(__doc__)
    files = broken() if sys.argv[1] == 'broken' else seeds()
    os.makedirs(sys.argv[2], exist_ok=True)
    for name, data in sorted(files.items()):
        with open(os.path.join(sys.argv[2], name), 'wb') as f:
            f.write(bytes(data))
    print('wrote %d files to %s' % (len(files), sys.argv[2]))


if __name__ == '__main__':
    main()
