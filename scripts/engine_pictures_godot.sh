#!/usr/bin/env bash
# Regenerates docs/images/engines/godot_*.png: screenshots of `export-shader --language godot` in
# Debian's Godot 3.2.3, headless under Xvfb (docs/engines.md, "Godot"). A tiling model of the
# shipped moss_ground_512.png (CC0, data/exemplars/ATTRIBUTION.md) is exported (fast variant, the
# engine's choice), copied into a Godot project and imported by Godot's editor with the exported
# .import files; the project then renders
#   godot_plane.png  the spatial shader on a 24 m ground plane, lit by a sun, seen in perspective;
#   godot_scene.png  the export's own scene (its ColorRect and canvas shader), 256 x 256;
# and `stochtex render` writes godot_cpu.png, the same 256 x 256 pixels on the CPU.
# Needs godot3, xvfb and xauth (scripts/install-deps.sh). Usage:
#   bash scripts/engine_pictures_godot.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
out="$root/docs/images/engines"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel 2 --target stochtex
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
project=$work/project
mkdir -p "$project/shots" "$out"
stochtex=$build/stochtex
"$stochtex" analyze "$root/data/exemplars/moss_ground_512.png" -m tiling -o "$work/moss.stx"
"$stochtex" export-shader "$work/moss.stx" -o "$project/moss" --variant fast --language godot
"$stochtex" render "$work/moss.stx" -o "$out/godot_cpu.png" --size 256x256 --seed 0

cat >"$project/project.godot" <<'EOF'
config_version=4

[application]

config/name="stochtex pictures"
run/main_scene="res://main.tscn"

[rendering]

quality/driver/driver_name="GLES3"
EOF
cat >"$project/main.tscn" <<'EOF'
[gd_scene load_steps=2 format=2]

[ext_resource path="res://main.gd" type="Script" id=1]

[node name="main" type="Node"]
script = ExtResource( 1 )
EOF
cat >"$project/main.gd" <<'EOF'
extends Node
# The ground plane in 3-D and the export's scene in 2-D, each in a viewport saved as a PNG.

func _textures(material):
	for name in ["tiling_exemplar", "tiling_lut"]:
		material.set_shader_param("stochtex_" + name, load("res://moss/" + name + ".exr"))

func _ready():
	var world = Viewport.new()
	world.size = Vector2(768, 432)
	world.own_world = true
	world.msaa = Viewport.MSAA_4X
	world.render_target_v_flip = true
	world.render_target_update_mode = Viewport.UPDATE_ALWAYS
	add_child(world)
	var environment = Environment.new()
	environment.background_mode = Environment.BG_COLOR
	environment.background_color = Color(0.62, 0.72, 0.86)
	environment.ambient_light_color = Color(0.75, 0.82, 1.0)
	environment.ambient_light_energy = 0.45
	var world_environment = WorldEnvironment.new()
	world_environment.environment = environment
	world.add_child(world_environment)
	var camera = Camera.new()
	camera.fov = 55
	camera.translation = Vector3(0, 1.7, 6)
	camera.rotation_degrees = Vector3(-16, 0, 0)
	world.add_child(camera)
	var sun = DirectionalLight.new()
	sun.rotation_degrees = Vector3(-40, 35, 0)
	world.add_child(sun)
	var ground = MeshInstance.new()
	ground.mesh = PlaneMesh.new()
	ground.mesh.size = Vector2(24, 24)
	var material = ShaderMaterial.new()
	material.shader = load("res://moss/stochtex_tiling.shader")
	_textures(material)
	# 24 m of plane, one exemplar (512 pixels) every 2 m.
	material.set_shader_param("stochtex_texture_scale", 12.0 * 512.0)
	ground.material_override = material
	world.add_child(ground)

	var flat = Viewport.new()
	flat.size = Vector2(256, 256)
	flat.usage = Viewport.USAGE_2D
	flat.render_target_v_flip = true
	flat.render_target_update_mode = Viewport.UPDATE_ALWAYS
	add_child(flat)
	var scene = load("res://moss/stochtex_tiling.tscn").instance()
	scene.rect_size = Vector2(256, 256)
	scene.material = scene.material.duplicate()
	scene.material.set_shader_param("stochtex_size", Vector2(256, 256))
	flat.add_child(scene)

	for i in range(3):
		yield(VisualServer, "frame_post_draw")
	world.get_texture().get_data().save_png("res://shots/godot_plane.png")
	flat.get_texture().get_data().save_png("res://shots/godot_scene.png")
	get_tree().quit()
EOF

# The editor imports the data with the exported .import files, then the project runs; the
# helpers of tests/godot/godot_test.py run Godot (and end its editor once the import is done).
/usr/bin/python3 - "$root" "$project" <<'EOF'
import os, sys
sys.path.insert(0, os.path.join(sys.argv[1], "tests", "godot"))
import godot_test
project = sys.argv[2]
godot_test.godot(["--editor"], project, os.path.join(project, "import.log"), 120,
                 lambda: not godot_test.imported(project, ["moss"]))
missing = godot_test.imported(project, ["moss"])
if missing:
    sys.exit(f"not imported: {missing}")
code, _ = godot_test.godot([], project, os.path.join(project, "run.log"), 120)
if code != 0:
    sys.exit(f"Godot exited with {code}: {open(os.path.join(project, 'run.log')).read()}")
EOF
cp "$project/shots/godot_plane.png" "$project/shots/godot_scene.png" "$out/"
echo "wrote $out/godot_plane.png, godot_scene.png, godot_cpu.png"
