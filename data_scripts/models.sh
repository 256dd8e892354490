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
