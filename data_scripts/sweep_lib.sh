# What the GPU sweeps (gpu_check.sh, compute_vs_dfb.sh) set up first, one
# copy: sourced after each defines die(), as . "$here/sweep_lib.sh".
# probe_renderer and model_mesh read $bin, $work (make_work's) and $cache.

# Both sweep the fetched meshes (in $here/cache unless OIT_MESH_CACHE says)
# and render headless.
cache=${OIT_MESH_CACHE:-$here/cache}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}

# need_bins BIN TOOL...: dies unless each TOOL is built in BIN.
need_bins() {
    _b=$1 && shift
    for _t in "$@"; do
        [ -x "$_b/$_t" ] || die "$_b/$_t: missing (build with: make build)"
    done
}

# make_work NAME: $work, a fresh folder /tmp/NAME.XXXXXX removed at exit;
# an interrupt or a kill exits 130 or 143 (so that the EXIT trap runs).
make_work() {
    work=$(mktemp -d "/tmp/$1.XXXXXX") || die "mktemp failed"
    trap 'rm -rf "$work"' EXIT
    trap 'exit 130' INT
    trap 'exit 143' TERM
}

# renderer_of STATS.json: the GL renderer an oitstream --stats file names
# (empty when none).
renderer_of() {
    sed -n 's/.*"renderer": "\([^"]*\)".*/\1/p' "$1" | head -n 1
}

# renderer_tag RENDERER: it as a file-name tag (lower case, runs of other
# characters one dash, 40 characters at most).
renderer_tag() {
    echo "$1" | tr 'A-Z' 'a-z' | sed 's/[^a-z0-9]\{1,\}/-/g; s/^-//; s/-$//' | cut -c1-40
}

# probe_renderer [OITSTREAM OPTION...]: writes the demo to $work/demo.ply
# and renders it at 8x8 with the options; sets renderer (the GL renderer,
# empty when the stats name none), tag (it as a file-name tag, "unknown"
# for none) and def12 (0 on llvmpipe, whose sweeps leave the 12M plant out
# by default, else 1). Returns 1 when the frame fails, $work/err.txt saying
# why.
probe_renderer() {
    "$bin/oitgen" demo -o "$work/demo.ply" >/dev/null || die "oitgen demo failed"
    "$bin/oitstream" "$work/demo.ply" "$@" --size 8x8 --out "$work/probe.png" \
        --stats "$work/probe.json" --quiet 2>"$work/err.txt" || return 1
    renderer=$(renderer_of "$work/probe.json")
    tag=$(renderer_tag "${renderer:-unknown}")
    case $renderer in *llvmpipe*) def12=0 ;; *) def12=1 ;; esac
}

# model_mesh MODEL: sets mesh to MODEL's file: demo is probe_renderer's,
# plantN[M|K] an `oitgen plant` of N (millions, thousands) triangles
# written to $work, any other name a file of $cache; dies when there is
# none.
model_mesh() {
    case $1 in
    demo) mesh=$work/demo.ply ;;
    plant*)
        _n=$(echo "${1#plant}" | sed 's/M$/000000/; s/K$/000/')
        mesh=$work/$1.ply
        "$bin/oitgen" plant --triangles "$_n" -o "$mesh" >/dev/null || die "$1: oitgen failed" ;;
    *) mesh=$cache/$1; [ -f "$mesh" ] || die "$1: not in $cache" ;;
    esac
}
