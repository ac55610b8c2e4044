"""Blender opens `rouge export gltf`'s file: the same view from Rouge and from Blender's Cycles,
side by side, with the CIEDE2000 between them (docs/images/gltf_blender.png, docs/FORMATS.md).

The scene is the one `rouge render --lights front --subsurface none` draws: one white
directional light of irradiance π from the camera, no environment, no subsurface scattering
(what the export's baked base colour stands for). Rouge's camera and light are read from
`rouge export mitsuba` of the same options (scene.xml: lookat, fov, the light's direction and
irradiance) and set in Blender; the .glb is imported with Blender's own glTF importer and
rendered with Cycles, direct light only (Rouge has no light between surfaces), into linear EXR.
ΔE2000 (colour-science) is taken between the two linear images where Blender's alpha covers the
pixel; the image shows Rouge, Blender and the ΔE2000 map.

Two interpreters: this script under one with colour-science and Pillow (the repo's .venv), and
Blender's `bpy` module (PyPI `bpy` 5.0.1 needs CPython 3.11) in a separate venv outside the repo,
which this script runs as `--blender-python` for the Blender stage:

    python3.11 -m venv /work/venv-bpy && /work/venv-bpy/bin/pip install bpy==5.0.1
    .venv/bin/python python/blender_check.py --rouge target/release/rouge \\
        --blender-python /work/venv-bpy/bin/python [--out docs/images/gltf_blender.png]
"""

import argparse
import json
import math
import pathlib
import subprocess
import tempfile
import xml.etree.ElementTree as ET

SCENE = ["--lights", "front"]


def floats(text):
    return [float(v) for v in text.replace(",", " ").split()]


def rouge_camera_and_light(scene_xml: pathlib.Path) -> dict:
    """The camera (mm, Rouge's Y-up world) and the directional light of a Mitsuba scene."""
    root = ET.parse(scene_xml).getroot()
    sensor = root.find("sensor")
    fov = float(sensor.find("float[@name='fov']").get("value"))
    look = sensor.find("transform/lookat")
    film = sensor.find("film")
    size = {i.get("name"): int(i.get("value")) for i in film.findall("integer")}
    emitter = root.find("emitter[@type='directional']")
    return {
        "fov_y_deg": fov,
        "origin_mm": floats(look.get("origin")),
        "target_mm": floats(look.get("target")),
        "width": size["width"],
        "height": size["height"],
        "light_direction": floats(emitter.find("vector[@name='direction']").get("value")),
        "irradiance": floats(emitter.find("rgb[@name='irradiance']").get("value")),
    }


def blender_stage(glb: str, view_json: str, rouge_exr: str, out_npz: str, samples: int) -> None:
    """Runs inside the bpy interpreter: import, light, camera, Cycles render, both images out."""
    import bpy
    import mathutils
    import numpy as np

    view = json.loads(pathlib.Path(view_json).read_text())
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=glb)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0  # direct light only, as Rouge
    scene.render.resolution_x, scene.render.resolution_y = view["width"], view["height"]
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.render.filter_size = 0.01  # box-like pixels, as Rouge's one sample per pixel
    scene.view_settings.view_transform = "Standard"
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world

    # glTF's importer turns glTF's Y-up metres into Blender's Z-up: (x, y, z) -> (x, -z, y).
    def to_blender(v_mm, scale=1e-3):
        x, y, z = (c * scale for c in v_mm)
        return mathutils.Vector((x, -z, y))

    cam_data = bpy.data.cameras.new("rouge")
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(view["fov_y_deg"])
    cam_data.clip_start, cam_data.clip_end = 0.01, 100.0
    cam = bpy.data.objects.new("rouge", cam_data)
    scene.collection.objects.link(cam)
    origin, target = to_blender(view["origin_mm"]), to_blender(view["target_mm"])
    cam.location = origin
    cam.rotation_euler = (target - origin).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam

    sun_data = bpy.data.lights.new("rouge", "SUN")
    irradiance = view["irradiance"]
    sun_data.energy = max(irradiance)  # W/m²: a white Lambertian facing it has radiance E/π
    sun_data.color = [c / max(irradiance) for c in irradiance]
    sun_data.angle = 0.0
    sun = bpy.data.objects.new("rouge", sun_data)
    scene.collection.objects.link(sun)
    sun.rotation_euler = to_blender(view["light_direction"], 1.0).to_track_quat("-Z", "Y").to_euler()

    out_exr = str(pathlib.Path(out_npz).with_name("blender.exr"))
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = out_exr
    bpy.ops.render.render(write_still=True)

    def pixels(path):
        img = bpy.data.images.load(path)
        w, h = img.size
        return np.array(img.pixels[:], dtype=np.float32).reshape(h, w, 4)[::-1]

    np.savez(out_npz, blender=pixels(out_exr), rouge=pixels(rouge_exr))


def run(cmd):
    print("$", " ".join(map(str, cmd)), flush=True)
    subprocess.run([str(c) for c in cmd], check=True)


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rouge", default="target/release/rouge")
    parser.add_argument("--blender-python", default="/work/venv-bpy/bin/python")
    parser.add_argument("--out", default="docs/images/gltf_blender.png")
    parser.add_argument("--width", type=int, default=400)
    parser.add_argument("--height", type=int, default=300)
    parser.add_argument("--samples", type=int, default=64)
    parser.add_argument("--textures", default="2048")
    parser.add_argument("--blender-stage", nargs=4, metavar=("GLB", "VIEW", "ROUGE_EXR", "OUT_NPZ"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.blender_stage:
        blender_stage(*args.blender_stage, samples=args.samples)
        return {}

    import colour
    import numpy as np
    from PIL import Image
    from side_by_side import heat, write_sheet

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        size = ["--width", str(args.width), "--height", str(args.height)]
        run([args.rouge, "export", "gltf", *SCENE, "--textures", args.textures, "--out", tmp / "face.glb"])
        run([args.rouge, "export", "mitsuba", *SCENE, *size, "--interior", "lambert", "--flat-skin", "--out", tmp / "mitsuba"])
        run([args.rouge, "render", *SCENE, *size, "--subsurface", "none", "--out", tmp / "rouge.exr"])
        run([args.rouge, "render", *SCENE, *size, "--out", tmp / "rouge_sss.exr"])
        view = rouge_camera_and_light(tmp / "mitsuba" / "scene.xml")
        (tmp / "view.json").write_text(json.dumps(view))
        run([args.blender_python, __file__, "--samples", str(args.samples), "--blender-stage",
             tmp / "face.glb", tmp / "view.json", tmp / "rouge.exr", tmp / "rouge.npz"])
        data = np.load(tmp / "rouge.npz")
        blender, rouge = data["blender"], data["rouge"]
        # Rouge's default frame (screen-space subsurface scattering) against the same Blender frame.
        sss = read_exr_rgb(args.blender_python, tmp / "rouge_sss.exr", tmp / "rouge_sss.npy")

    mask = blender[..., 3] >= 0.999
    lab = lambda rgb: colour.XYZ_to_Lab(colour.RGB_to_XYZ(np.clip(rgb, 0, None), "sRGB", apply_cctf_decoding=False))
    de = colour.delta_E(lab(rouge[..., :3]), lab(blender[..., :3]), method="CIE 2000")
    de_sss = colour.delta_E(lab(sss[..., :3]), lab(blender[..., :3]), method="CIE 2000")
    stats = {
        "pixels": int(mask.sum()),
        "delta_e_mean": float(de[mask].mean()),
        "delta_e_median": float(np.median(de[mask])),
        "delta_e_p95": float(np.percentile(de[mask], 95)),
        "delta_e_mean_vs_rouge_screen_space_sss": float(de_sss[mask].mean()),
        "delta_e_p95_vs_rouge_screen_space_sss": float(np.percentile(de_sss[mask], 95)),
        "samples": args.samples,
        "textures": args.textures,
    }
    print(json.dumps(stats, indent=1))

    def display(rgb):
        v = np.clip(rgb[..., :3], 0, 1)
        v = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
        return Image.fromarray((v * 255 + 0.5).astype(np.uint8))

    rouge_bg = np.where(mask[..., None], rouge[..., :3], 0)
    panels = [("Rouge (--subsurface none)", display(rouge_bg)), ("Blender Cycles (the .glb)", display(blender)),
              ("dE2000 (blue 0, red 10 or more)", heat(de, mask))]
    write_sheet(panels, stats, args.out)
    return stats


def read_exr_rgb(blender_python, exr, out_npy):
    """A linear EXR's pixels (rows top first) read by Blender's image loader."""
    code = ("import bpy, numpy as np, sys; img = bpy.data.images.load(sys.argv[1]); w, h = img.size; "
            "np.save(sys.argv[2], np.array(img.pixels[:], dtype=np.float32).reshape(h, w, 4)[::-1])")
    run([blender_python, "-c", code, exr, out_npy])
    import numpy as np
    return np.load(out_npy)


if __name__ == "__main__":
    main()
