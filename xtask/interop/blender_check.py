"""Blender's own projections of the scenes `cargo xtask interop` exported, Cycles' own
rays for the panoramas, Cycles' pictures of a lens with blades, and Blender's glTF for
the importer to read.

Usage: python blender_check.py JOB.json RESULT.json   (python with the bpy module)

JOB: {"cases": [{"name", "script" | "gltf", "size": [W, H], "points": [[x, y, z]...],
                 "render": bool, "export_glb": path | null,
                 "bokeh": {"samples": N, "path": exr} | absent}]}
RESULT: {name: {"points": [[x, y] | null...], "directions": [[dx, dy, dz]...] (row by
        row from the top, for "render"), "intensity": [..] (row by row from the top,
        for "bokeh"), "size": [W, H]}}
Points are image coordinates (x from the left, y from the top, in pixels) from
bpy_extras.object_utils.world_to_camera_view, Blender's own camera projection (sensor
fit, shift, pixel aspect, orthographic scale). A glTF file is imported with Blender's
importer, which turns glTF's +y up into Blender's +z up: points are turned the same way.
"""
import json
import sys
import time

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector


def project(scene, camera, points, to_blender):
    width = scene.render.resolution_x
    height = scene.render.resolution_y
    out = []
    for p in points:
        co = world_to_camera_view(scene, camera, Vector(to_blender(p)))
        if co.z <= 0.0:
            out.append(None)
        else:
            out.append([co.x * width, (1.0 - co.y) * height])
    return out


def render_directions(scene, path):
    """Renders the world with its colour set to the ray direction, one sample per pixel
    through Cycles' narrowest pixel filter, and reads the directions back."""
    for obj in list(scene.objects):
        if obj != scene.camera:
            bpy.data.objects.remove(obj, do_unlink=True)
    world = bpy.data.worlds.new("directions")
    world.use_nodes = True
    nodes = world.node_tree.nodes
    links = world.node_tree.links
    coords = nodes.new("ShaderNodeTexCoord")
    encode = nodes.new("ShaderNodeVectorMath")
    encode.operation = "MULTIPLY_ADD"
    encode.inputs[1].default_value = (0.5, 0.5, 0.5)
    encode.inputs[2].default_value = (0.5, 0.5, 0.5)
    links.new(coords.outputs["Generated"], encode.inputs[0])
    links.new(encode.outputs[0], nodes["Background"].inputs["Color"])
    nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.cycles.filter_width = 0.01
    scene.cycles.use_adaptive_sampling = False
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = list(image.pixels)
    out = []
    for row in range(height):
        source = height - 1 - row  # Blender images are stored bottom row first
        for col in range(width):
            i = 4 * (source * width + col)
            out.append([2.0 * pixels[i + c] - 1.0 for c in range(3)])
    return out


def render_bokeh(scene, job):
    """Renders the scene with every material as pure emission of its colour (strength 1)
    on its black world, with Cycles: many samples, no denoising, no adaptive sampling,
    its narrowest pixel filter, no bounces (the camera sees the lamps directly). Returns
    each pixel's intensity, the mean of red, green and blue, row by row from the top."""
    for material in bpy.data.materials:
        material.use_nodes = True
        nodes = material.node_tree.nodes
        nodes.clear()
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = material.diffuse_color
        emission.inputs["Strength"].default_value = 1.0
        output = nodes.new("ShaderNodeOutputMaterial")
        material.node_tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = job["samples"]
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.filter_width = 0.01
    scene.cycles.max_bounces = 0
    scene.cycles.seed = 0
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = job["path"]
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(job["path"])
    width, height = image.size
    pixels = list(image.pixels)
    out = []
    for row in range(height):
        source = height - 1 - row  # Blender images are stored bottom row first
        for col in range(width):
            i = 4 * (source * width + col)
            out.append(sum(pixels[i + c] for c in range(3)) / 3.0)
    return out


def main():
    job = json.load(open(sys.argv[1]))
    result = {}
    for case in job["cases"]:
        started = time.time()
        bpy.ops.wm.read_factory_settings(use_empty=True)
        print('factory', case['name'], time.time() - started, file=sys.stderr)
        if "script" in case:
            exec(compile(open(case["script"]).read(), case["script"], "exec"), {"__name__": "__main__"})
            to_blender = lambda p: p
        else:
            bpy.ops.import_scene.gltf(filepath=case["gltf"])
            scene = bpy.context.scene
            cameras = [o for o in scene.objects if o.type == "CAMERA"]
            scene.camera = cameras[0]
            scene.render.resolution_x, scene.render.resolution_y = case["size"]
            scene.render.resolution_percentage = 100
            scene.render.pixel_aspect_x, scene.render.pixel_aspect_y = case.get("pixel_aspect", [1.0, 1.0])
            to_blender = lambda p: (p[0], -p[2], p[1])
        scene = bpy.context.scene
        camera = scene.camera
        entry = {
            "points": project(scene, camera, case["points"], to_blender),
            "size": [scene.render.resolution_x, scene.render.resolution_y],
        }
        if case.get("export_glb"):
            bpy.ops.export_scene.gltf(
                filepath=case["export_glb"], export_format="GLB", export_cameras=True,
                export_yup=False,
            )
        if case.get("render"):
            entry["directions"] = render_directions(scene, case["render_path"])
        if case.get("bokeh"):
            entry["intensity"] = render_bokeh(scene, case["bokeh"])
        result[case["name"]] = entry
        print('case', case['name'], time.time() - started, file=sys.stderr)
    json.dump(result, open(sys.argv[2], "w"))


main()
