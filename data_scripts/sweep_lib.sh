# What the GPU sweeps (gpu_check.sh, compute_vs_dfb.sh) set up first, one
# copy: sourced after each defines die(), as . "$here/sweep_lib.sh".

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
