#!/usr/bin/python3
"""The density models side by side (issue 51): none, binary and continuous on the paper-scale
fixture and on a thin shell (MakeHuman short04 at the paper's 200 hairs/cm², 600 guides).

Every figure comes from the written files, not from the pipeline's own density grid: the strands'
density by bench/density_check.py (segments per 0.5 cm voxel: coefficient of variation and the
share of segments in voxels holding more than 4x the mean), the guide stage's CPU time from
report.json (the least of --repeats runs, the machine being shared), and whether 1 and 2 threads
write the same strand file byte for byte. It also draws the strands' density before and after
(segments per 0.25 cm column through a 2 cm mid-sagittal slab, one colour scale for the three
models) to --png.

    /usr/bin/python3 bench/density_models.py --hairfit build/hairfit --out /tmp/density_models \
        [--repeats 3] [--png docs/results/density-models.png]
"""
import argparse
import filecmp
import json
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import density_check  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = ["none", "binary", "continuous"]
# The weights of the density measurements (bench/results/density_guides.md): none gives F4's
# share to direction and boundary.
WEIGHTS = {"none": (0.4, 0.2, 0.4, 0.0), "binary": (0.35, 0.2, 0.35, 0.1), "continuous": (0.35, 0.2, 0.35, 0.1)}


def scene_for(base, model, changes):
    """The fixture's scene text with paths made absolute, the model and weights set, and `changes`
    (regex, replacement) applied."""
    folder = os.path.dirname(base)
    text = open(base).read()
    text = re.sub(r'"(\.\./[^"]*)"', lambda m: '"' + os.path.normpath(os.path.join(folder, m.group(1))) + '"', text)
    text = re.sub(r'(?m)^density = "(none|binary|continuous)".*$', "", text)
    text = re.sub(r"(?m)^\[effects\]$", f'[effects]\ndensity = "{model}"', text)
    text = re.sub(r"(?ms)^\[guides\.weights\].*?(?=^\[|\Z)", "", text)
    for pattern, replacement in changes:
        text, n = re.subn(pattern, replacement, text, flags=re.M)
        if n != 1:
            sys.exit(f"{base}: '{pattern}' matched {n} times")
    d, s, b, w = WEIGHTS[model]
    return text + f"\n[guides.weights]\ndirection = {d}\nsimilarity = {s}\nboundary = {b}\ndensity = {w}\n"


CASES = {
    "paper-scale": ("fixtures/paper-scale/scene.toml", []),
    "short04 shell": ("fixtures/makehuman-short04/scene.toml",
                      [(r"^density = 4 .*$", "density = 200"), (r"^guides = 120$", "guides = 600"),
                       (r"^renders = .*$", "renders = []")]),
}


def run(hairfit, scene, out, threads):
    subprocess.run([hairfit, "run", scene, "--out", out, "--threads", str(threads), "--no-cache", "--quiet"],
                   check=True, stdout=subprocess.DEVNULL)
    return json.load(open(os.path.join(out, "report.json")))["stages"]


def projection(path, axis, centre, slab, lower, cells, voxel):
    """Segments per column along `axis`, counting the midpoints within slab/2 of `centre`."""
    segments, xyz = density_check.read_hair(path)
    mid = density_check.segment_midpoints(segments, xyz)
    mid = mid[np.abs(mid[:, axis] - centre) < 0.5 * slab]
    keep = [a for a in range(3) if a != axis]
    ij = np.floor((mid[:, keep] - lower) / voxel).astype(int)
    inside = np.all((ij >= 0) & (ij < cells), axis=1)
    image = np.zeros(cells)
    np.add.at(image, (ij[inside, 0], ij[inside, 1]), 1)
    return image


def draw(panels, titles, png):
    from PIL import Image, ImageDraw
    top = max(p.max() for p in panels)
    tiles = []
    for p, title in zip(panels, titles):
        t = np.sqrt(p / top).T[::-1]  # up is +y: rows from the top
        rgb = np.stack([255 * (1 - t) + 40 * t, 255 * (1 - t) + 20 * t, 255 * (1 - 0.4 * t)], axis=-1)
        rgb[p.T[::-1] == 0] = 255
        tile = Image.fromarray(rgb.astype(np.uint8)).resize((3 * p.shape[0], 3 * p.shape[1]), Image.NEAREST)
        canvas = Image.new("RGB", (tile.width, tile.height + 18), "white")
        canvas.paste(tile, (0, 18))
        ImageDraw.Draw(canvas).text((4, 3), title, fill="black")
        tiles.append(canvas)
    sheet = Image.new("RGB", (sum(t.width for t in tiles) + 8 * (len(tiles) - 1), max(t.height for t in tiles)), "white")
    x = 0
    for t in tiles:
        sheet.paste(t, (x, 0))
        x += t.width + 8
    sheet.save(png)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hairfit", default=os.path.join(ROOT, "build", "hairfit"))
    ap.add_argument("--out", default="/tmp/density_models")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--png", default=None)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for case, (base, changes) in CASES.items():
        figures = {}
        for model in MODELS:
            tag = f"{case.split()[0]}_{model}"
            scene = os.path.join(args.out, tag + ".toml")
            open(scene, "w").write(scene_for(os.path.join(ROOT, base), model, changes))
            out = os.path.join(args.out, tag)
            cpu = []
            for _ in range(args.repeats):
                stages = run(args.hairfit, scene, out, 2)
                cpu.append((stages["guides"]["cpu_seconds"], stages["strands"]["cpu_seconds"]))
            stages = run(args.hairfit, scene, out + "_1", 1)
            same = filecmp.cmp(os.path.join(out, "strands.hair"), os.path.join(out + "_1", "strands.hair"), shallow=False)
            segments, xyz = density_check.read_hair(os.path.join(out, "strands.hair"))
            counts = density_check.voxel_counts(density_check.segment_midpoints(segments, xyz), 0.5)
            _, cv, crowded = density_check.statistics(counts, 4.0)
            figures[model] = dict(cv=cv, crowded=crowded, guides=min(c[0] for c in cpu), strands=min(c[1] for c in cpu),
                                  inside=stages["strands"]["inside_fraction"], same=same,
                                  hair=os.path.join(out, "strands.hair"))
        none = figures["none"]
        for model in MODELS:
            f = figures[model]
            rows.append(f"| {case} | {model} | {f['cv']:.3f} ({f['cv'] / none['cv']:.2f}×) | {f['crowded']:.4f} "
                        f"({f['crowded'] / none['crowded']:.2f}×) | {f['inside']:.5f} | {f['guides']:.2f} "
                        f"({f['guides'] / none['guides']:.2f}×) | {f['strands']:.2f} | "
                        f"{'yes' if f['same'] else 'NO'} |")
        if args.png and case == "paper-scale":
            xyz = density_check.read_hair(none["hair"])[1]
            lower, upper = xyz[:, 1:].min(axis=0), xyz[:, 1:].max(axis=0)  # project along x (left-right)
            cells = np.ceil((upper - lower) / 0.25).astype(int) + 1
            centre = 0.5 * (xyz[:, 0].min() + xyz[:, 0].max())
            panels = [projection(figures[m]["hair"], 0, centre, 2.0, lower, cells, 0.25) for m in MODELS]
            draw(panels, [f"{m}: CV {figures[m]['cv']:.3f}" for m in MODELS], args.png)
    print("| case | model | CV of segments per 0.5 cm voxel | share in voxels > 4× mean | strands inside | "
          "guide stage CPU s | strands stage CPU s | 1 = 2 threads |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
