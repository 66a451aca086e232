# Blender side of scripts/compare-cycles.sh: renders an OBJ + MTL scene with Cycles the way Lueur renders it with
# `--blinn-k 1 --smooth-normals off` and every pass at weight 1 (Le + L1 + L2, and ln beyond one bounce), and writes
# a linear PFM.
#
#   blender -b --factory-startup -P render_cycles.py -- --obj S.obj --out I.pfm --camera "ex ey ez tx ty tz fovy" \
#       --size 256x256 --spp 64 [--seed 1] [--up "0 1 0"] [--threads 0] [--bounces 1]
#
# What "the same" means here:
#  - materials are Lambertian with the MTL's Kd, Ks ignored (the driver drops it from the BRDF materials' copies);
#    the ray-traced illumination models as Lueur reads them (README, "Materials"): illum 3 and 5 a sharp mirror of
#    reflectance Ks, illum 4, 6 and 7 smooth glass of index Ni (1.5 when missing) whose Fresnel reflection is white
#    and whose refraction Tf tints, each beside a Lambert base of the MTL's Kd, shared out as Lueur shares them;
#  - an emitter (Ke > 0) shines from the side its vertices wind counter-clockwise and is black from behind, as in
#    Lueur, and still reflects light with its Kd;
#  - `--bounces N` scattering events at most, of every kind (Lueur's --max-bounces N); caustics on, no glossy blur;
#    1 is Le + L1 + L2: paths camera - p - light and camera - p - q - light, plus what the camera sees;
#  - a box filter one pixel wide (Lueur's uniform jitter), no denoising, no adaptive sampling, no clamping, a black
#    world, the Standard view transform and linear 32-bit output.
# Prints "cycles_render_seconds T": the time of the render call alone (scene sync, Cycles' BVH and the samples),
# not Blender's start-up nor the file written afterwards.
import argparse
import array
import math
import os
import sys
import time

import bpy
from mathutils import Matrix, Vector


def parse_arguments():
    parser = argparse.ArgumentParser(prog="render_cycles.py")
    parser.add_argument("--obj", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--camera", required=True, help="ex ey ez tx ty tz fovy_degrees")
    parser.add_argument("--up", default="0 1 0")
    parser.add_argument("--size", default="256x256")
    parser.add_argument("--spp", type=int, required=True)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--threads", type=int, default=0, help="0: all")
    parser.add_argument("--bounces", type=int, default=1, help="0: Le + L1 only; 1: Le + L1 + L2; N: every bounce up to N")
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])


def default_material():
    return {"Kd": (0.8, 0.8, 0.8), "Ke": (0.0, 0.0, 0.0), "Ks": (0.0, 0.0, 0.0), "Tf": (1.0, 1.0, 1.0), "Ni": 1.5,
            "illum": 2}


def read_materials(mtl_path):
    """name -> its Kd, Ke, Ks, Tf, Ni and illum; a missing file gives none (every face then takes Lueur's grey)."""
    materials, name = {}, None
    if not os.path.isfile(mtl_path):
        return materials
    with open(mtl_path, encoding="utf-8", errors="replace") as f:
        for raw in f:
            words = raw.split("#", 1)[0].split()
            if not words:
                continue
            if words[0] == "newmtl" and len(words) > 1:
                name = words[1]
                materials[name] = default_material()
            elif name is None or len(words) < 2:
                continue
            elif words[0] in ("Kd", "Ke", "Ks", "Tf"):
                values = [float(w) for w in words[1:4]]
                materials[name][words[0]] = tuple(values) if len(values) == 3 else (values[0],) * 3
            elif words[0] == "Ni":
                materials[name]["Ni"] = float(words[1]) if float(words[1]) > 0.0 else 1.5
            elif words[0] == "illum":
                materials[name]["illum"] = int(float(words[1]))
    return materials


def read_obj(obj_path):
    """Vertices, triangles (fans of each face), each triangle's material name, the file's normals and each
    triangle's three normal indices (None where a corner has none)."""
    vertices, triangles, names, materials, current = [], [], [], {}, None
    normals, corner_normals = [], []
    folder = os.path.dirname(obj_path)
    with open(obj_path, encoding="utf-8", errors="replace") as f:
        for raw in f:
            words = raw.split("#", 1)[0].split()
            if not words:
                continue
            if words[0] == "v":
                vertices.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == "vn":
                normals.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == "mtllib":
                for library in words[1:]:
                    materials.update(read_materials(os.path.join(folder, library)))
            elif words[0] == "usemtl":
                current = words[1] if len(words) > 1 else None
            elif words[0] == "f":
                corners, corner_normal = [], []
                for word in words[1:]:
                    parts = word.split("/")
                    index = int(parts[0])
                    corners.append(index - 1 if index > 0 else len(vertices) + index)
                    n = int(parts[2]) if len(parts) > 2 and parts[2] else None
                    corner_normal.append(None if n is None else (n - 1 if n > 0 else len(normals) + n))
                for k in range(1, len(corners) - 1):
                    triangles.append((corners[0], corners[k], corners[k + 1]))
                    corner_normals.append((corner_normal[0], corner_normal[k], corner_normal[k + 1]))
                    names.append(current)
    return vertices, triangles, names, materials, normals, corner_normals


def without_twins(triangles, names, corner_normals):
    """Drops exact duplicates (the same three vertices): CornellBox-Original has some. Cycles, which does not offset
    ray origins, would shadow a face with its own twin; Lueur lights it."""
    seen, kept_triangles, kept_names, kept_normals = set(), [], [], []
    for triangle, name, normal in zip(triangles, names, corner_normals):
        key = frozenset(triangle)
        if len(key) < 3 or key in seen:
            continue
        seen.add(key)
        kept_triangles.append(triangle)
        kept_names.append(name)
        kept_normals.append(normal)
    return kept_triangles, kept_names, kept_normals


def sharp(nodes, kind, colour):
    """A perfectly specular BSDF node of this colour."""
    node = nodes.new(kind)
    node.inputs["Color"].default_value = (*colour, 1.0)
    node.inputs["Roughness"].default_value = 0.0
    if hasattr(node, "distribution"):
        node.distribution = "SHARP"
    return node


def add(nodes, links, a, b):
    node = nodes.new("ShaderNodeAddShader")
    links.new(a, node.inputs[0])
    links.new(b, node.inputs[1])
    return node.outputs["Shader"]


def surface_shader(nodes, links, m):
    """The scattering of one material as Lueur reads it (integrator/specular.cpp): Lambert, or a mirror or glass
    beside a Lambert base."""
    kd, illum = m["Kd"], m["illum"]
    if illum in (3, 5):  # a mirror: Kd + Ks scaled down together where a channel passes 1
        ks = m["Ks"]
        total = max(1.0, *(kd[c] + ks[c] for c in range(3)))
        base = tuple(v / total for v in kd)
        mirror = sharp(nodes, "ShaderNodeBsdfGlossy", tuple(v / total for v in ks))
        specular = mirror.outputs["BSDF"]
    elif illum in (4, 6, 7):  # glass: the base Kd, the dielectric the rest, its refraction tinted by Tf
        base = tuple(min(max(v, 0.0), 1.0) for v in kd)
        rest = tuple(1.0 - v for v in base)
        tf = tuple(min(max(v, 0.0), 1.0) for v in m["Tf"])
        reflection = sharp(nodes, "ShaderNodeBsdfGlossy", rest)
        refraction = sharp(nodes, "ShaderNodeBsdfRefraction", tuple(rest[c] * tf[c] for c in range(3)))
        refraction.inputs["IOR"].default_value = min(m["Ni"], 10.0)
        fresnel = nodes.new("ShaderNodeFresnel")
        fresnel.inputs["IOR"].default_value = min(m["Ni"], 10.0)
        mix = nodes.new("ShaderNodeMixShader")
        links.new(fresnel.outputs["Fac"], mix.inputs["Fac"])
        links.new(refraction.outputs["BSDF"], mix.inputs[1])
        links.new(reflection.outputs["BSDF"], mix.inputs[2])
        specular = mix.outputs["Shader"]
    else:
        base, specular = kd, None
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*base, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0
    if specular is None:
        return diffuse.outputs["BSDF"]
    return add(nodes, links, diffuse.outputs["BSDF"], specular)


def make_material(name, m):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    surface = surface_shader(nodes, links, m)
    ke = m["Ke"]
    if max(ke) <= 0.0:
        links.new(surface, output.inputs["Surface"])
        return material
    # One-sided emission: strength 1 - backfacing, so 1 in front and 0 behind.
    geometry = nodes.new("ShaderNodeNewGeometry")
    front = nodes.new("ShaderNodeMath")
    front.operation = "SUBTRACT"
    front.inputs[0].default_value = 1.0
    links.new(geometry.outputs["Backfacing"], front.inputs[1])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*ke, 1.0)
    links.new(front.outputs["Value"], emission.inputs["Strength"])
    links.new(add(nodes, links, emission.outputs["Emission"], surface), output.inputs["Surface"])
    return material


def look_at(camera_object, eye, target, up, fovy_degrees):
    """Blender cameras look down their local -Z with +Y up: the rotation's columns are right, up and -forward."""
    forward = (target - eye).normalized()
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    rotation = Matrix((right, true_up, -forward)).transposed()
    camera_object.location = eye
    camera_object.rotation_euler = rotation.to_euler()
    camera_object.data.sensor_fit = "VERTICAL"
    camera_object.data.angle_y = math.radians(fovy_degrees)


def main():
    args = parse_arguments()
    width, height = (int(v) for v in args.size.lower().split("x"))
    camera = [float(v) for v in args.camera.split()]
    up = Vector([float(v) for v in args.up.split()])

    vertices, triangles, names, materials, normals, corner_normals = read_obj(args.obj)
    triangles, names, corner_normals = without_twins(triangles, names, corner_normals)
    print("render_cycles: %d vertices, %d triangles" % (len(vertices), len(triangles)))

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    mesh = bpy.data.meshes.new("lueur-scene")
    mesh.from_pydata(vertices, [], triangles)
    slots = sorted({n or "" for n in names})
    for slot in slots:
        mesh.materials.append(make_material(slot or "default", materials.get(slot, default_material())))
    slot_of = {slot: i for i, slot in enumerate(slots)}
    mesh.polygons.foreach_set("material_index", [slot_of[n or ""] for n in names])
    mesh.update()
    # The file's normals where every corner has one, as Lueur shades with them (mirrors and glass reflect and
    # refract about them): Blender's custom split normals, one per corner in the triangles' order.
    if normals and all(n is not None for corners in corner_normals for n in corners):
        mesh.use_auto_smooth = True
        mesh.polygons.foreach_set("use_smooth", [True] * len(triangles))
        mesh.normals_split_custom_set([normals[n] for corners in corner_normals for n in corners])
        mesh.update()
    scene.collection.objects.link(bpy.data.objects.new("lueur-scene", mesh))

    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world

    camera_object = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera_object)
    scene.camera = camera_object
    eye = Vector(camera[0:3])
    look_at(camera_object, eye, Vector(camera[3:6]), up, camera[6])
    # Blender clips at 0.1 and 100 units by default; scenes in millimetres reach past that.
    farthest = max(((Vector(v) - eye).length for v in vertices), default=1.0)
    camera_object.data.clip_start = 1e-5 * farthest
    camera_object.data.clip_end = 2.0 * farthest

    render = scene.render
    render.engine = "CYCLES"
    render.resolution_x, render.resolution_y, render.resolution_percentage = width, height, 100
    render.film_transparent = False
    if args.threads > 0:
        render.threads_mode = "FIXED"
        render.threads = args.threads
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = args.spp
    cycles.seed = args.seed
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.max_bounces = args.bounces
    cycles.diffuse_bounces = args.bounces
    cycles.glossy_bounces = args.bounces
    cycles.transmission_bounces = args.bounces
    cycles.volume_bounces = 0
    cycles.transparent_max_bounces = 0
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.caustics_reflective = True
    cycles.caustics_refractive = True
    cycles.blur_glossy = 0.0
    cycles.pixel_filter_type = "BOX"
    cycles.filter_width = 1.0
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0

    start = time.perf_counter()
    bpy.ops.render.render()
    seconds = time.perf_counter() - start
    print("cycles_render_seconds %.4f" % seconds)

    # The render result holds linear radiance; saved as EXR, read back, written as PFM (rows bottom to top, which is
    # also Blender's order).
    exr = args.out + ".exr"
    render.image_settings.file_format = "OPEN_EXR"
    render.image_settings.color_depth = "32"
    bpy.data.images["Render Result"].save_render(exr, scene=scene)
    image = bpy.data.images.load(exr)
    rgba = array.array("f", bytes(4 * 4 * width * height))
    image.pixels.foreach_get(rgba)
    rgb = array.array("f", (rgba[i] for i in range(len(rgba)) if i % 4 != 3))
    if sys.byteorder != "little":
        rgb.byteswap()
    partial = args.out + ".partial"
    with open(partial, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        f.write(rgb.tobytes())
    os.replace(partial, args.out)
    os.remove(exr)


main()
