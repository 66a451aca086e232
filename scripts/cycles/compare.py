#!/usr/bin/env python3
"""Time to quality, Lueur against Blender's Cycles on the same scene, camera and light transport (issue 18).

For each Cycles sample count (16, 64, 256 by default) Cycles renders once and reports its own render time T (its
scene sync, BVH build and samples); Lueur then renders with its default settings within T and within T / 2, its
loading and BVH build counted: as many whole frames as fit in the budget (their count estimated from a first
render's time per frame, then lowered until the time Lueur used, loading plus tracing, is within the budget), and
every image's relMSE against a
long Cycles reference is printed: mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01). Lueur also renders
a long image of its own with another seed, whose relMSE against Cycles' reference is the floor Lueur's error can
reach (what still differs between the renderers, and the reference's own noise); Lueur's images are measured
against it too.

Both renderers see the same copy of the scene (Ks dropped from its BRDF materials, so that they are Lambertian;
mirrors and glass kept), every pass at weight 1, `--bounces N` scattering events at most (1 by default: Le + L1 + L2;
more adds Lueur's ln and Cycles' further bounces), a box filter and no denoising (see render_cycles.py). Needs `blender` (Debian's package); the build and
the tests never do. Usage: scripts/compare-cycles.sh [options] (--help lists them).
"""
import argparse
import hashlib
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))

# name -> (the scene, or "default" for Lueur's embedded one; its camera "ex ey ez tx ty tz fovy")
PRESETS = {
    "cornell-original": ("{shared}/scenes/cornell-original/CornellBox-Original.obj", "0 1 3.9 0 1 0 40"),
    "cornell-sphere": ("{shared}/scenes/cornell-sphere/CornellBox-Sphere.obj", "0 1 3.9 0 1 0 40"),
    "default": ("default", "278 273 -800 278 273 0 39.3077"),
}


def read_pfm(path):
    with open(path, "rb") as f:
        data = f.read()
    # Header: "PF", width height, scale (negative: little-endian), each on its own line.
    parts = data.split(b"\n", 3)
    if parts[0].strip() != b"PF":
        raise SystemExit("compare: %s is not a colour PFM" % path)
    width, height = (int(v) for v in parts[1].split())
    order = "<" if float(parts[2]) < 0 else ">"
    count = 3 * width * height
    return width, height, struct.unpack(order + "%df" % count, parts[3][: 4 * count])


def block_means(image, blocks=8):
    """The mean luminance of the whole image and of each of blocks x blocks equal blocks."""
    width, height, values = image
    sums = [[0.0] * blocks for _ in range(blocks)]
    total = 0.0
    for y in range(height):
        row = sums[y * blocks // height]
        for x in range(width):
            i = 3 * (y * width + x)
            luminance = 0.2126 * values[i] + 0.7152 * values[i + 1] + 0.0722 * values[i + 2]
            row[x * blocks // width] += luminance
            total += luminance
    area = (width // blocks) * (height // blocks)
    return total / (width * height), [v / area for row in sums for v in row]


def block_errors(image, reference):
    """The relative difference of the image means, and the root mean square of the blocks' relative differences
    (blocks darker than a hundredth of the reference's mean left out: their ratios are noise)."""
    mean, blocks = block_means(image)
    ref_mean, ref_blocks = block_means(reference)
    kept = [(b - r) / r for b, r in zip(blocks, ref_blocks) if r > 0.01 * ref_mean]
    return (mean - ref_mean) / ref_mean, (sum(e * e for e in kept) / max(len(kept), 1)) ** 0.5


def relative_mse(image, reference):
    if image[:2] != reference[:2]:
        raise SystemExit("compare: images of different sizes")
    total = 0.0
    for x, r in zip(image[2], reference[2]):
        total += (x - r) * (x - r) / (r * r + 0.01)
    return total / len(reference[2])


def run(command, what):
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        tail = "\n".join(result.stdout.splitlines()[-15:])
        raise SystemExit("compare: %s failed (status %d):\n%s" % (what, result.returncode, tail))
    return result.stdout


def without_highlights(lines):
    """An MTL's lines less the Ks of its BRDF materials (both renderers then see Kd only there); a mirror's Ks
    (illum 3 or 5) is its reflectance and stays."""
    materials, current = [], []
    for line in lines:
        if line.strip().startswith("newmtl"):
            materials.append(current)
            current = []
        current.append(line)
    materials.append(current)
    kept = []
    for material in materials:
        illum = [line.split()[1] for line in material if re.match(r"\s*illum\s+\S", line)]
        mirror = bool(illum) and illum[-1] in ("3", "5")
        kept += [line for line in material if mirror or not re.match(r"\s*Ks\s", line)]
    return kept


def lambert_copy(obj_path, folder):
    """Copies the OBJ and its MTL libraries into `folder`, the MTLs without the Ks of their BRDF materials."""
    os.makedirs(folder, exist_ok=True)
    source_folder = os.path.dirname(os.path.abspath(obj_path))
    target = os.path.join(folder, os.path.basename(obj_path))
    shutil.copyfile(obj_path, target)
    with open(obj_path, encoding="utf-8", errors="replace") as f:
        libraries = [w for line in f if line.startswith("mtllib") for w in line.split()[1:]]
    for library in libraries:
        source = os.path.join(source_folder, library)
        if not os.path.isfile(source):
            continue
        with open(source, encoding="utf-8", errors="replace") as f:
            kept = without_highlights(f.readlines())
        with open(os.path.join(folder, library), "w", encoding="utf-8") as f:
            f.writelines(kept)
    return target


def cycles_render(args, obj, spp, seed, out):
    output = run([args.blender, "-b", "--factory-startup", "-P", os.path.join(HERE, "render_cycles.py"), "--",
                  "--obj", obj, "--out", out, "--camera", args.camera, "--size", args.size, "--spp", str(spp),
                  "--seed", str(seed), "--threads", str(args.threads), "--bounces", str(args.bounces)],
                 "Cycles at %d samples" % spp)
    match = re.search(r"cycles_render_seconds ([0-9.]+)", output)
    if not match:
        raise SystemExit("compare: Cycles printed no render time")
    return float(match.group(1))


def lueur_render(args, obj, out, frames, seed=None):
    """Renders with Lueur; returns (frames, seconds used: loading and BVH build plus tracing, loading seconds)."""
    passes = "le,l1,l2" + (",ln" if args.bounces > 1 else "")
    command = [args.lueur, obj, "--headless", "--out", out, "--camera", args.camera, "--size", args.size,
               "--passes", passes, "--weights", "le=1,l1=1,l2=1,ln=1", "--max-bounces", str(args.bounces),
               "--blinn-k", "1", "--smooth-normals", "off",
               "--frames", str(frames), "--seed", str(args.seed if seed is None else seed)]
    if args.threads > 0:
        command += ["--threads", str(args.threads)]
    command += args.lueur_option
    output = run(command, "Lueur")
    match = re.search(r"(\d+) frames in ([0-9.]+) s", output)
    loaded = re.search(r"loaded in ([0-9.]+) s", output)
    if not match or not loaded:
        raise SystemExit("compare: Lueur printed no frame count or loading time")
    load = float(loaded.group(1))
    return int(match.group(1)), load + float(match.group(2)), load


def render_within(args, obj, path, budget, load_seconds, frame_seconds):
    """Renders the most whole frames whose time, loading included, stays within `budget` (at least one frame), the
    count found from each render's own time per frame; returns (frames, seconds used), the image left at `path`."""
    frames, best, tried = max(1, int((budget - load_seconds) / frame_seconds)), None, set()
    while frames not in tried:
        tried.add(frames)
        attempt = "%s.%d.pfm" % (path, frames)
        rendered, seconds, load = lueur_render(args, obj, attempt, frames=frames)
        fits = (budget - load) / max(seconds - load, 1e-6) * rendered  # frames at this render's pace
        if seconds <= budget or frames == 1:
            if best is None or rendered > best[0]:
                best = (rendered, seconds)
                shutil.copyfile(attempt, path)
            frames = max(frames, int(fits))
        else:
            frames = max(1, min(frames - 1, int(fits)))
        if best is not None and frames <= best[0]:
            break
    return best


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", help="a preset (%s) or an OBJ file (then give --camera)" % ", ".join(PRESETS))
    parser.add_argument("--camera", help="ex ey ez tx ty tz fovy (default: the preset's)")
    parser.add_argument("--size", default="256x256")
    parser.add_argument("--spp", default="16,64,256", help="Cycles sample counts, comma-separated")
    parser.add_argument("--reference-spp", type=int, default=4096)
    parser.add_argument("--lueur-reference-frames", type=int, default=1024,
                        help="frames of Lueur's own long render, with another seed (0: none)")
    parser.add_argument("--threads", type=int, default=0, help="both renderers (0: all cores)")
    parser.add_argument("--bounces", type=int, default=1,
                        help="scattering events at most, both renderers (1: Le + L1 + L2; more: Lueur's ln too)")
    parser.add_argument("--seed", type=int, default=1, help="Lueur's seed")
    parser.add_argument("--lueur", default=os.environ.get("LUEUR_EXE", "lueur"))
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--shared", default=os.path.join(HERE, "..", "..", "..", "shared"))
    parser.add_argument("--cache", default=os.path.join(os.path.expanduser("~"), ".cache", "lueur-cycles"),
                        help="where references are kept between runs")
    parser.add_argument("--json", help="also write the figures to this file")
    parser.add_argument("--lueur-option", action="append", default=[],
                        help="an extra option for Lueur (repeat for more), e.g. --lueur-option=--sampler=independent")
    return parser.parse_args()


def main():
    args = parse_arguments()
    if shutil.which(args.blender) is None:
        raise SystemExit("compare: no '%s' on PATH: install Debian's blender package to compare with Cycles"
                         % args.blender)
    work = tempfile.mkdtemp(prefix="lueur-cycles-")
    try:
        scene, preset_camera = PRESETS.get(args.scene, (args.scene, None))
        args.camera = args.camera or preset_camera
        if not args.camera:
            raise SystemExit("compare: give --camera for a scene file")
        if scene == "default":
            scene = os.path.join(work, "exported", "default.obj")
            os.makedirs(os.path.dirname(scene))
            run([args.lueur, "--export-default-scene", scene], "exporting the default scene")
        scene = scene.format(shared=os.path.abspath(args.shared))
        if not os.path.isfile(scene):
            raise SystemExit("compare: no scene file %s" % scene)
        obj = lambert_copy(scene, os.path.join(work, "lambert"))

        # The reference depends only on what Cycles sees: cached under a hash of it.
        key = hashlib.sha256()
        for name in sorted(os.listdir(os.path.dirname(obj))):
            with open(os.path.join(os.path.dirname(obj), name), "rb") as f:
                key.update(name.encode() + f.read())
        key.update(("%s|%s|%d|%d" % (args.camera, args.size, args.reference_spp, args.bounces)).encode())
        with open(os.path.join(HERE, "render_cycles.py"), "rb") as f:
            key.update(f.read())
        os.makedirs(args.cache, exist_ok=True)
        reference_path = os.path.join(args.cache, key.hexdigest()[:20] + ".pfm")
        if not os.path.isfile(reference_path):
            print("compare: Cycles reference, %d samples (minutes; kept in %s)" % (args.reference_spp, args.cache),
                  flush=True)
            seconds = cycles_render(args, obj, args.reference_spp, 7, reference_path)
            print("compare: reference took %.1f s" % seconds, flush=True)
        reference = read_pfm(reference_path)

        # Lueur's own long render, with another seed: its relMSE against Cycles' reference is the floor Lueur's
        # error can reach there (what still differs between the renderers, and the reference's own noise), and it
        # is the second reference Lueur's images are measured against.
        own = None
        if args.lueur_reference_frames > 0:
            path = os.path.join(work, "lueur-reference.pfm")
            frames, seconds, load_seconds = lueur_render(args, obj, path, frames=args.lueur_reference_frames,
                                                         seed=args.seed + 100)
            own_image = read_pfm(path)
            mean_error, block_rms = block_errors(own_image, reference)
            own = {"frames": frames, "seconds": seconds, "relmse": relative_mse(own_image, reference),
                   "mean_error": mean_error, "block_rms": block_rms}
            print("compare: Lueur's own reference: %d frames in %.1f s, relMSE %.6f against Cycles', mean %+.2f%%, "
                  "8x8 blocks %.2f%% rms" % (frames, seconds, own["relmse"], 100 * mean_error, 100 * block_rms),
                  flush=True)

        # The time a frame takes, from a short render: where the budgets' frame counts start.
        calibration_frames = 8
        _, seconds, load_seconds = lueur_render(args, obj, os.path.join(work, "lueur-calibration.pfm"),
                                                frames=calibration_frames)
        frame_seconds = max(seconds - load_seconds, 1e-6) / calibration_frames
        rows = []
        for spp in (int(s) for s in args.spp.split(",")):
            cycles_path = os.path.join(work, "cycles-%d.pfm" % spp)
            cycles_seconds = cycles_render(args, obj, spp, 1, cycles_path)
            cycles_image = read_pfm(cycles_path)
            mean_error, block_rms = block_errors(cycles_image, reference)
            row = {"spp": spp, "cycles_seconds": cycles_seconds,
                   "cycles_relmse": relative_mse(cycles_image, reference), "cycles_mean_error": mean_error,
                   "cycles_block_rms": block_rms}
            for label, budget in (("same", cycles_seconds), ("half", cycles_seconds / 2.0)):
                path = os.path.join(work, "lueur-%d-%s.pfm" % (spp, label))
                frames, seconds = render_within(args, obj, path, budget, load_seconds, frame_seconds)
                image = read_pfm(path)
                row[label] = {"frames": frames, "seconds": seconds, "relmse": relative_mse(image, reference),
                              "relmse_own": relative_mse(image, own_image) if own else None}
            rows.append(row)
            print("compare: %4d spp: Cycles %.2f s relMSE %.6f | Lueur in the same time: %d frames, %.6f | in half: "
                  "%d frames, %.6f" % (spp, cycles_seconds, row["cycles_relmse"], row["same"]["frames"],
                                       row["same"]["relmse"], row["half"]["frames"], row["half"]["relmse"]),
                  flush=True)

        def own_text(entry):
            return " (%.6f)" % entry["relmse_own"] if entry["relmse_own"] is not None else ""

        print()
        print("%s, %s, camera \"%s\", %d bounces; relMSE against Cycles at %d samples (in brackets: against Lueur's "
              "own reference)" % (args.scene, args.size, args.camera, args.bounces, args.reference_spp))
        print("Lueur's times: loading and BVH build plus tracing, as used: the most whole frames within the budget")
        print("| Cycles | time | relMSE | Lueur, same time | time | relMSE | Lueur, half the time | time | relMSE "
              "| half reaches |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
        for r in rows:
            print("| %d spp | %.2f s | %.6f | %d frames | %.2f s | %.6f%s | %d frames | %.2f s | %.6f%s | %s |" % (
                r["spp"], r["cycles_seconds"], r["cycles_relmse"], r["same"]["frames"], r["same"]["seconds"],
                r["same"]["relmse"], own_text(r["same"]), r["half"]["frames"], r["half"]["seconds"],
                r["half"]["relmse"], own_text(r["half"]), "yes" if r["half"]["relmse"] <= r["cycles_relmse"] else "no"))
        if own:
            print("Lueur's own reference: %d frames (%.1f s), relMSE %.6f against Cycles' (the floor); its mean %+.2f%% "
                  "of Cycles', its 8x8 blocks %.2f%% rms" % (own["frames"], own["seconds"], own["relmse"],
                                                             100 * own["mean_error"], 100 * own["block_rms"]))
        for r in rows:
            print("Cycles at %d spp against its reference: mean %+.2f%%, 8x8 blocks %.2f%% rms (its own noise)" % (
                r["spp"], 100 * r["cycles_mean_error"], 100 * r["cycles_block_rms"]))
        if args.json:
            partial = args.json + ".partial"
            with open(partial, "w") as f:
                json.dump({"scene": args.scene, "size": args.size, "camera": args.camera, "bounces": args.bounces,
                           "reference_spp": args.reference_spp, "rows": rows, "lueur_reference": own}, f, indent=2)
            os.replace(partial, args.json)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
