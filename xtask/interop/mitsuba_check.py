"""Mitsuba 3's own rays for the scenes `cargo xtask interop` exported, and Mitsuba-written
scenes for the importer to read.

Usage: python mitsuba_check.py JOB.json RESULT.json

JOB: {"cases": [{"name", "file", "pixels": [[x, y]...], "lens": [[a, b]...] | null,
                 "coverage": [W, H] | null}],
      "written": [{"name", "dict": {...}, "out": "file.xml", "pixels": [[x, y]...]}]}
RESULT: {"cases": {name: {"rays": [[o, d]...], "lens_rays": [[o, d]...],
                          "coverage": "0101..."}},
         "written": {name: {"rays": [[o, d]...]}}}
Rays are Mitsuba's `sensor.sample_ray` at film positions x / W, y / H (continuous image
coordinates); a lens sample (a, b) of viewray's is Mitsuba's aperture sample (1 - a, b),
because Mitsuba's sensor x axis points left.
"""
import json
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")


def rays(sensor, pixels, lens=None):
    width, height = sensor.film().size()
    out = []
    for i, (x, y) in enumerate(pixels):
        aperture = mi.Point2f(0.5, 0.5)
        if lens is not None:
            a, b = lens[i]
            aperture = mi.Point2f(1.0 - a, b)
        ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f(x / width, y / height), aperture)
        out.append([list(ray.o), list(ray.d)])
    return out


def coverage(scene, sensor, size):
    width, height = size
    bits = []
    for row in range(height):
        for col in range(width):
            ray, _ = sensor.sample_ray(
                0.0, 0.5, mi.Point2f((col + 0.5) / width, (row + 0.5) / height), mi.Point2f(0.5, 0.5)
            )
            bits.append("1" if scene.ray_intersect(ray).is_valid() else "0")
    return "".join(bits)


def main():
    job = json.load(open(sys.argv[1]))
    result = {"cases": {}, "written": {}}
    for case in job["cases"]:
        scene = mi.load_file(case["file"])
        sensor = scene.sensors()[0]
        entry = {"rays": rays(sensor, case["pixels"])}
        if case.get("lens"):
            entry["lens_rays"] = rays(sensor, case["pixels"], case["lens"])
        if case.get("coverage"):
            entry["coverage"] = coverage(scene, sensor, case["coverage"])
        result["cases"][case["name"]] = entry
    for written in job.get("written", []):
        d = dict(written["dict"])
        to_world = d["sensor"].pop("look_at", None)
        if to_world is not None:
            origin, target, up = to_world
            d["sensor"]["to_world"] = mi.ScalarTransform4f().look_at(origin=origin, target=target, up=up)
        scale = d["sensor"].pop("scale", None)
        if scale is not None:
            d["sensor"]["to_world"] = d["sensor"]["to_world"] @ mi.ScalarTransform4f().scale(scale)
        state = mi.parser.parse_dict(mi.parser.ParserConfig("scalar_rgb"), d)
        mi.parser.write_file(state, written["out"])
        scene = mi.load_file(written["out"])
        result["written"][written["name"]] = {"rays": rays(scene.sensors()[0], written["pixels"])}
    json.dump(result, open(sys.argv[2], "w"))


main()
