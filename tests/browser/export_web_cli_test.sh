#!/usr/bin/env bash
# `stochtex export-web` as a user meets it (docs/studio.md, "export-web"), without a browser: the
# files it writes (the page, the viewer byte for byte as in web/, each model's manifest, shader
# and data of the sizes the manifest says) and its refusals, each with exit code 1 or 2, one
# "stochtex: error:" line and nothing written.
#
# usage: export_web_cli_test.sh STOCHTEX_BINARY SOURCE_DIR
set -u

if [[ $# -ne 2 ]]; then
  echo "usage: $0 STOCHTEX_BINARY SOURCE_DIR" >&2
  exit 2
fi
stochtex=$1
source_dir=$2
exemplar=$source_dir/data/exemplars/grass_lawn_128.png
python=/usr/bin/python3

work=$(mktemp -d) || exit 2
trap 'rm -rf "$work"' EXIT
failed=0
fail() {
  echo "FAIL: $1"
  if [[ -s $work/stderr ]]; then sed 's/^/  stderr: /' "$work/stderr"; fi
  failed=$((failed + 1))
}
capture() {
  "$@" >"$work/stdout" 2>"$work/stderr"
  status=$?
}
# A refusal: its exit code, one error line mentioning $3, and the folder $4 as it was ($5: the
# listing of it before).
check_refusal() {
  local name=$1 code=$2 mention=$3 folder=$4 before=$5
  if [[ $status -ne $code ]]; then
    fail "$name: exit code $status, expected $code"
  elif [[ $(wc -l <"$work/stderr") -ne 1 ]] || ! grep -q '^stochtex: error: ' "$work/stderr"; then
    fail "$name: stderr is not one 'stochtex: error:' line"
  elif ! grep -qF -- "$mention" "$work/stderr"; then
    fail "$name: the message does not mention '$mention'"
  elif [[ $(find "$folder" 2>/dev/null | sort) != "$before" ]]; then
    fail "$name: the output folder changed"
  fi
}

mkdir -p "$work/a" "$work/b"
# Models of data: these checks are of the files and refusals (a srgb model's viewer is
# browser_test's), and a srgb model's measured removed deviations took 17 s more under the
# sanitizers.
for method in texton tiling lrp gabor; do
  "$stochtex" analyze "$exemplar" -m "$method" --colour-space data -o "$work/a/$method.stx" \
    2>/dev/null ||
    { echo "cannot analyse $exemplar with $method"; exit 1; }
done
cp "$work/a/texton.stx" "$work/b/texton.stx"

# The good path: every model in both variants, the page and the viewer.
site=$work/site
capture "$stochtex" export-web "$work"/a/{texton,tiling,lrp,gabor}.stx -o "$site"
if [[ $status -ne 0 ]]; then
  fail "export-web of four models: exit code $status"
else
  for file in index.html export/export.js export/export.css viewer/viewer.js viewer/group.js models.json; do
    [[ -f $site/$file ]] || fail "export-web wrote no $file"
  done
  cmp -s "$site/viewer/viewer.js" "$source_dir/web/viewer/viewer.js" ||
    fail "viewer/viewer.js is not web/viewer/viewer.js"
  cmp -s "$site/index.html" "$source_dir/web/export/index.html" ||
    fail "index.html is not web/export/index.html"
  # Every manifest names a shader calling its entry and data files of the sizes it gives.
  "$python" - "$site" <<'EOF' || fail "the models' files do not match models.json and manifests"
import json, os, sys
site = sys.argv[1]
listing = json.load(open(os.path.join(site, "models.json")))["models"]
assert [m["name"] for m in listing] == ["texton", "tiling", "lrp", "gabor"], listing
sizes = {"FLOAT": 4, "HALF_FLOAT": 2, "UNSIGNED_BYTE": 1}
for model in listing:
    assert model["variants"] == ["exact", "fast"], model
    for variant in model["variants"]:
        folder = os.path.join(site, "models", model["name"], variant)
        manifest = json.load(open(os.path.join(folder, "manifest.json")))
        assert manifest["format"] == "stochtex-web-export" and manifest["version"] == 1
        assert manifest["method"] == model["method"] == model["name"], manifest
        assert manifest["variant"] == variant and manifest["channels"] == 3, manifest
        expected = "fast" if model["name"] == "gabor" else variant
        assert manifest["shader_variant"] == expected, manifest
        assert ("note" in manifest) == (manifest["shader_variant"] != variant), manifest
        shader = open(os.path.join(folder, manifest["shader"])).read()
        assert "vec4 " + manifest["entry"] + "(" in shader
        files = {"manifest.json", manifest["shader"]}
        for texture in manifest["textures"]:
            assert "uniform highp sampler" in shader and texture["uniform"] in shader, texture
            count = (texture["width"] * texture["height"] * texture["depth"] *
                     texture["components"] * sizes[texture["type"]])
            assert os.path.getsize(os.path.join(folder, texture["file"])) == count, texture
            filtered = texture["filter"] != "nearest"
            assert texture["type"] == ("HALF_FLOAT" if filtered else "FLOAT"), texture
            assert texture["wrap"] in ("clamp_to_edge", "repeat"), texture
            files.add(texture["file"])
        assert set(os.listdir(folder)) == files, (folder, os.listdir(folder))
EOF
fi

# --variant fast alone; the same files again with --force, a foreign file kept.
capture "$stochtex" export-web "$work/a/texton.stx" -o "$work/fast" --variant fast
if [[ $status -ne 0 || -e $work/fast/models/texton/exact ||
  ! -f $work/fast/models/texton/fast/manifest.json ]]; then
  fail "export-web --variant fast: exit $status or the wrong folders"
fi
touch "$work/fast/mine.txt"
capture "$stochtex" export-web "$work/a/texton.stx" -o "$work/fast" --variant fast --force
if [[ $status -ne 0 || ! -f $work/fast/mine.txt ]]; then
  fail "export-web --force: exit $status or a foreign file removed"
fi

# Refusals: nothing written.
mkdir -p "$work/full" && touch "$work/full/mine.txt"
before=$(find "$work/full" | sort)
capture "$stochtex" export-web "$work/a/texton.stx" -o "$work/full"
check_refusal "a non-empty folder" 2 "--force" "$work/full" "$before"

capture "$stochtex" export-web "$work/a/texton.stx" "$work/b/texton.stx" -o "$work/new"
check_refusal "two models of one name" 2 "'texton'" "$work/new" ""

capture "$stochtex" export-web "$work/a/missing.stx" -o "$work/new"
check_refusal "a missing model" 1 "missing.stx" "$work/new" ""

echo "not a model" >"$work/a/corrupt.stx"
capture "$stochtex" export-web "$work/a/texton.stx" "$work/a/corrupt.stx" -o "$work/new"
check_refusal "a corrupt model" 1 "corrupt.stx" "$work/new" ""

touch "$work/plain_file"
capture "$stochtex" export-web "$work/a/texton.stx" -o "$work/plain_file"
check_refusal "an output that is a file" 2 "not a folder" "$work/new" ""

capture "$stochtex" export-web "$work/a/texton.stx" -o "$work/new" --variant best
check_refusal "an unknown variant" 2 "--variant" "$work/new" ""

if [[ $failed -ne 0 ]]; then
  echo "export_web_cli: $failed check(s) failed"
  exit 1
fi
echo "export_web_cli: all checks passed"
