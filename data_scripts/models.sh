# The fetched meshes (data_scripts/fetch_meshes.sh) that the benchmark
# scripts run on: one list, sourced by each (. "$here/models.sh").
OIT_FETCHED_MODELS="bunny00.off armadillo.off refined_elephant.off ChineseDragon-10kv.off \
fandisk.off turbine.off Wuson.ply spider.obj Spider_binary.stl head.stl propeller.stl \
2CylinderEngine.glb"
# The same glTF with Draco-compressed buffers, for the scripts that cover
# every reader.
OIT_FETCHED_DRACO="2CylinderEngine-draco.gltf"

# fetched_paths CACHE [NAME...]: the path of each model of the list (then of
# each NAME) that CACHE holds, space-separated; missing ones are left out.
fetched_paths() {
    _c=$1 && shift
    for _m in $OIT_FETCHED_MODELS "$@"; do
        [ -f "$_c/$_m" ] && printf ' %s' "$_c/$_m"
    done
    return 0
}

# check_models CACHE WITH12M: the GPU checks' model names: demo, each fetched
# mesh (and the Draco glTF) that CACHE holds, plant1M, and plant12M unless
# WITH12M is 0; space-separated.
check_models() {
    printf 'demo'
    for _m in $OIT_FETCHED_MODELS $OIT_FETCHED_DRACO; do
        [ -f "$1/$_m" ] && printf ' %s' "$_m"
    done
    printf ' plant1M'
    [ "$2" = 0 ] || printf ' plant12M'
}

# generated_paths BIN WORK [N...]: writes `oitgen demo` to WORK/demo.ply and
# one `oitgen plant --triangles N` to WORK/plantN.ply a size, and prints
# their paths, space-separated; fails when oitgen does.
generated_paths() {
    _b=$1 _w=$2 && shift 2
    "$_b/oitgen" demo -o "$_w/demo.ply" >/dev/null || return 1
    printf ' %s' "$_w/demo.ply"
    for _n in "$@"; do
        "$_b/oitgen" plant --triangles "$_n" -o "$_w/plant$_n.ply" >/dev/null || return 1
        printf ' %s' "$_w/plant$_n.ply"
    done
}

# two_builds OLD_BIN NEW_BIN: for the scripts that compare two builds (before
# and after a change): sets old and new to their binary folders (absolute),
# work to a scratch folder removed on exit, and renders headless.
two_builds() {
    old=$(cd "$1" && pwd) && new=$(cd "$2" && pwd) || return 1
    work=$(mktemp -d) || return 1
    trap 'rm -rf "$work"' EXIT
    export EGL_PLATFORM=surfaceless
}
