#!/usr/bin/env bash
# `antcd view` refuses malformed or mismatched inputs up front: exit code 2, exactly one line
# "error: ..." naming the problem, and no page (nor a temporary file) left behind. Runs without the
# viewer bundle: inputs are checked before the bundle is looked for.
# Usage: bad_inputs_test.sh ANTCD WORKDIR
set -euo pipefail
antcd="$1"
work="$2"
rm -rf "$work"
mkdir -p "$work/scene/meshes" "$work/other/meshes"
cd "$work"

# A tetrahedron, two objects using it, three frames; and a second scene elsewhere.
cat >scene/meshes/tet.obj <<'EOF'
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
EOF
cp scene/meshes/tet.obj other/meshes/tet.obj
scene_json='{ "format": "antcd-scene/1", "frames": 3, "objects": [
  { "name": "a", "mesh": "meshes/tet.obj", "poses": [ { "translation": [0, 0, 0] } ] },
  { "name": "b", "mesh": "meshes/tet.obj", "poses": [
    { "translation": [0.2, 0.2, 0.2] }, { "translation": [5, 0, 0] }, { "translation": [0.5, 0, 0] } ] } ] }'
printf '%s\n' "$scene_json" >scene/scene.json
printf '%s\n' "$scene_json" >other/scene.json

result() {  # result FILE SCENE-NAME FRAMES-JSON
  printf '{ "method": "exact", "scene": "%s", "build_ms": 1, "total_ms": 1, "frames": %s }\n' "$2" "$3" >"$1"
}
good_frames='[ { "frame": 0, "pairs": [["a", "b"]], "time_ms": 0.1 }, { "frame": 1, "pairs": [], "time_ms": 0.1 },
               { "frame": 2, "pairs": [["a", "b"]], "time_ms": 0.1 } ]'
result good.json scene/scene.json "$good_frames"
result other.json other/scene.json "$good_frames"
result range.json scene/scene.json '[ { "frame": 3, "pairs": [], "time_ms": 0.1 } ]'
result twice.json scene/scene.json '[ { "frame": 1, "pairs": [], "time_ms": 0.1 }, { "frame": 1, "pairs": [], "time_ms": 0.1 } ]'
result unknown.json scene/scene.json '[ { "frame": 0, "pairs": [["a", "crane_07"]], "time_ms": 0.1 } ]'
printf '{ "method": "exact", "frames": [ { "frame": 0, "pairs": [["a"' >truncated.json
sed 's/"build_ms": 1,/"delta": -1, "build_ms": 1,/' good.json >negative_delta.json
mkdir nomesh
sed 's#meshes/tet.obj#meshes/gone.obj#' scene/scene.json >nomesh/scene.json
printf '%s\n' '{ "format": "antcd-scene/1", "frames": 2, "objects": [ { "name": "a" } ] }' >bad_scene.json
mkdir out_dir

failures=0
# expect_refusal PATTERN ARGS...: exit 2, one stderr line "error: ..." matching PATTERN, no page.
expect_refusal() {
  local pattern="$1"
  shift
  rm -f view.html
  local code=0
  "$antcd" view "$@" >stdout.txt 2>stderr.txt || code=$?
  local lines
  lines=$(wc -l <stderr.txt)
  if [ "$code" -ne 2 ] || [ "$lines" -ne 1 ] || ! grep -q '^error: ' stderr.txt ||
    ! grep -qE -- "$pattern" stderr.txt || [ -e view.html ] ||
    [ -n "$(find . -maxdepth 1 -name '*.tmp*' -print -quit)" ]; then
    echo "FAIL: antcd view $* (exit $code, expected 2 and one error line matching '$pattern'):"
    cat stderr.txt
    failures=$((failures + 1))
  else
    echo "ok: $(cat stderr.txt)"
  fi
}

expect_refusal 'other/scene.json.*another scene|another scene' scene/scene.json --result other.json --out view.html
expect_refusal 'range.json: frame 3 out of range' scene/scene.json --result range.json --out view.html
expect_refusal 'twice.json: frame 1 listed twice' scene/scene.json --result twice.json --out view.html
expect_refusal "unknown.json: frame 0: .*no object 'crane_07'" scene/scene.json --result unknown.json --out view.html
expect_refusal 'negative_delta.json: delta' scene/scene.json --result negative_delta.json --out view.html
expect_refusal 'truncated.json' scene/scene.json --result truncated.json --out view.html
expect_refusal 'missing.json' scene/scene.json --result missing.json --out view.html
expect_refusal "object 'a'.*gone.obj" nomesh/scene.json --out view.html
expect_refusal 'bad_scene.json' bad_scene.json --out view.html
expect_refusal 'no-such-scene.json' no-such-scene.json --out view.html
expect_refusal 'at most|compares two' scene/scene.json --result good.json --result good.json --result good.json --out view.html
expect_refusal 'choose one' scene/scene.json --out view.html --serve
expect_refusal 'required' scene/scene.json --result good.json
expect_refusal 'out_dir.*folder' scene/scene.json --out out_dir
ANTCD_VIEWER_JS="$work/none.js" expect_refusal 'ANTCD_VIEWER_JS=.*none.js' scene/scene.json --result good.json --out view.html
ANTCD_LIVE_JS="$work/none.js" expect_refusal 'ANTCD_LIVE_JS=.*none.js' scene/scene.json --live --out live.html
# The result of the same scene given by another path (relative to the result's folder) is fine.
mkdir -p sub
result sub/rel.json ../scene/scene.json "$good_frames"
code=0
ANTCD_VIEWER_JS="$work/none.js" "$antcd" view scene/scene.json --result sub/rel.json --out view.html 2>stderr.txt || code=$?
if ! grep -q 'ANTCD_VIEWER_JS' stderr.txt; then
  echo "FAIL: a result naming the scene relative to its own folder was refused:"
  cat stderr.txt
  failures=$((failures + 1))
fi

if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all refusals as expected"
