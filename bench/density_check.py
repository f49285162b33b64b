#!/usr/bin/python3
"""Independent density measurement of a written strand file (cyHair .hair), for issue 51.

Reads the file itself (not the pipeline's density grid), bins every segment by its midpoint into
cubic voxels of edge --voxel cm (cells aligned at the origin), and prints, over the occupied voxels:
the coefficient of variation (population std / mean) of segments per voxel, and the share of all
segments that lie in voxels holding more than --crowd × the mean. bench/density_models.py runs the
models side by side with it.

    /usr/bin/python3 bench/density_check.py out/hair.hair [--voxel 0.5] [--crowd 4]
"""
import argparse
import struct
import sys

import numpy as np


def read_hair(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"HAIR":
        sys.exit(f"{path}: not a cyHair file (no HAIR magic)")
    strands, points, bits, default_segments = struct.unpack_from("<4I", data, 4)
    offset = 128
    if bits & 1:
        segments = np.frombuffer(data, dtype="<u2", count=strands, offset=offset).astype(np.int64)
        offset += 2 * strands
    else:
        segments = np.full(strands, default_segments, dtype=np.int64)
    if not bits & 2:
        sys.exit(f"{path}: no points array")
    xyz = np.frombuffer(data, dtype="<f4", count=3 * points, offset=offset).reshape(points, 3).astype(np.float64)
    if segments.sum() + strands != points:
        sys.exit(f"{path}: segment counts do not add up to the point count")
    return segments, xyz


def segment_midpoints(segments, xyz):
    # Every point but the last of each strand starts a segment.
    ends = np.cumsum(segments + 1)  # one past each strand's last point
    starts = np.ones(len(xyz), dtype=bool)
    starts[ends - 1] = False
    first = np.nonzero(starts)[0]
    return 0.5 * (xyz[first] + xyz[first + 1])


def voxel_counts(mid, voxel):
    cells = np.floor(mid / voxel).astype(np.int64)
    _, counts = np.unique(cells, axis=0, return_counts=True)
    return counts


def statistics(counts, crowd):
    mean = counts.mean()
    cv = counts.std() / mean
    crowded = counts[counts > crowd * mean].sum() / counts.sum()
    return mean, cv, crowded


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("hair")
    ap.add_argument("--voxel", type=float, default=0.5)
    ap.add_argument("--crowd", type=float, default=4.0)
    args = ap.parse_args()
    segments, xyz = read_hair(args.hair)
    if not np.all(np.isfinite(xyz)):
        sys.exit(f"{args.hair}: non-finite point coordinates")
    counts = voxel_counts(segment_midpoints(segments, xyz), args.voxel)
    mean, cv, crowded = statistics(counts, args.crowd)
    print(f"{args.hair}: strands {len(segments)} segments {int(segments.sum())} occupied {len(counts)} "
          f"mean {mean:.3f} cv {cv:.3f} crowded_share {crowded:.4f} max {counts.max()}")


if __name__ == "__main__":
    main()
