#!/usr/bin/env python3
"""Writes the small hand-made inputs of tests/corpus/data (run from anywhere; the files are committed).

The meshes are tiny on purpose, so each file can be read and its fault seen: `cube.obj` is a closed,
outward-oriented hair volume [-12, 12]^3 cm and `cap.obj` a six-triangle scalp (a low hexagonal
pyramid around (0, 5, 0), normals up) that lies inside it. Every other mesh is one of these two with a
single fault. The PNGs are encoded by hand so their exact header (size, depth, colour type) is known.
"""
import math
import os
import struct
import zlib

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def obj(vertices, faces, comment):
    lines = ["# " + comment]
    lines += ["v %.9g %.9g %.9g" % v for v in vertices]
    lines += ["f " + " ".join(str(i) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


# The cube: 8 corners, 12 triangles, counter-clockwise seen from outside.
CUBE_V = [(x, y, z) for x in (-12, 12) for y in (-12, 12) for z in (-12, 12)]
CUBE_F = [(1, 2, 4), (1, 4, 3), (5, 7, 8), (5, 8, 6), (1, 5, 6), (1, 6, 2),
          (3, 4, 8), (3, 8, 7), (1, 3, 7), (1, 7, 5), (2, 6, 8), (2, 8, 4)]
# The cap: apex 1, ring 2..7 of radius 2 at height 5; (apex, next, this) turns counter-clockwise from above.
CAP_V = [(0, 5.5, 0)] + [(2 * math.cos(k * math.pi / 3), 5, 2 * math.sin(k * math.pi / 3)) for k in range(6)]
CAP_F = [(1, 2 + (k + 1) % 6, 2 + k) for k in range(6)]


def flipped(faces):
    return [(a, c, b) for a, b, c in faces]


def png_chunk(kind, payload):
    return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload))


def png(width, height, depth, colour_type, rows, empty_idat_first=False):
    """rows: list of bytes (one scanline each, without the filter byte)."""
    raw = b"".join(b"\0" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, 0))
            + (png_chunk(b"IDAT", b"") if empty_idat_first else b"")
            + png_chunk(b"IDAT", zlib.compress(raw)) + png_chunk(b"IEND", b""))


def main():
    write("cube.obj", obj(CUBE_V, CUBE_F, "a closed, outward-oriented hair volume [-12, 12]^3"))
    write("cap.obj", obj(CAP_V, CAP_F, "a six-triangle scalp inside cube.obj, normals up"))
    write("cap_flipped.obj", obj(CAP_V, flipped(CAP_F), "cap.obj with every triangle turned over (normals down)"))
    write("cube_inward.obj", obj(CUBE_V, flipped(CUBE_F), "cube.obj with every triangle turned over (normals inward)"))
    write("cube_small.obj", obj([(v[0] / 12, 5 + v[1] / 12, v[2] / 12) for v in CUBE_V], CUBE_F,
                                "a 2 cm cube around the cap's apex: it holds the apex but not the ring"))
    write("cap_outside.obj", obj([(x, y + 40, z) for x, y, z in CAP_V], CAP_F, "cap.obj moved 40 cm up, out of cube.obj"))
    write("cap_nonmanifold.obj", obj(CAP_V + [(0, 7, 0)], CAP_F + [(1, 2, 8)],
                                     "cap.obj plus a fin: edge 1-2 is shared by three triangles"))
    write("cube_nonmanifold.obj", obj(CUBE_V + [(0, 0, 20)], CUBE_F + [(2, 4, 9)],
                                      "cube.obj plus a fin: edge 2-4 is shared by three triangles"))
    write("cap_inconsistent.obj", obj(CAP_V, CAP_F[:5] + flipped(CAP_F[5:]), "cap.obj with its last triangle turned over"))
    write("cube_open.obj", obj(CUBE_V, CUBE_F[:11], "cube.obj without its last triangle: a hole"))
    write("cube_inconsistent.obj", obj(CUBE_V, CUBE_F[:11] + flipped(CUBE_F[11:]),
                                       "cube.obj with its last triangle turned over"))
    write("cap_inf.obj", obj(CAP_V, CAP_F, "cap.obj with an infinite coordinate").replace("v 2 5 0", "v 2 inf 0"))
    write("cap_enormous.obj", obj([(1e30 * x, 1e30 * y, 1e30 * z) for x, y, z in CAP_V], CAP_F,
                                  "cap.obj scaled by 1e30"))
    write("cap_bad_index.obj", obj(CAP_V, CAP_F + [(1, 7, 9)], "cap.obj with a face naming vertex 9 of 7"))
    write("empty.obj", b"")
    write("binary.obj", png(2, 2, 8, 0, [b"\x00\x80", b"\x80\xff"]))
    write("empty.png", b"")
    write("zero_width.png", png(0, 1, 8, 0, [b""]))
    write("one_pixel.png", png(1, 1, 8, 0, [b"\x80"]))
    # 16 bit: 0, 12345 and 65535 in one row.
    write("deep.png", png(3, 1, 16, 0, [struct.pack(">HHH", 0, 12345, 65535)]))
    # RGB: grey pixels except (1, 0), which is red.
    write("colour.png", png(2, 2, 8, 2, [b"\x40\x40\x40\xff\x00\x00", b"\x80\x80\x80\xc0\xc0\xc0"]))
    # RGB whose every pixel is grey: accepted as a grey map.
    write("grey_rgb.png", png(2, 1, 8, 2, [b"\x40\x40\x40\xc0\xc0\xc0"]))
    # A zero-length IDAT before the data (valid PNG, found by the PNG fuzz target: stb_image's
    # memcpy into a null buffer); loaded as the same pixels as without it.
    write("empty_idat.png", png(2, 1, 8, 0, [b"\x40\xc0"], empty_idat_first=True))


if __name__ == "__main__":
    main()
