#!/bin/sh
# Issue 17's benchmark: the stream (oitprep's default scheme, oitstream's
# default options, --epsilon 0) against what a user would run instead on the
# same source mesh: DFB in core (`oitstream MESH --method dfb`), the unsorted
# floor (`--method unsorted`), and the peer users pick today, VTK 9.1 dual
# depth peeling (data_scripts/vtk_ddp.py under Xvfb) with exact settings
# (1000 peels, occlusion ratio 0) and with VTK's default of 4 peels.
#
# Per model, in one run and with the same views: an orbit of CMP_VIEWS views
# (default 5; CMP_BIG_VIEWS, default 3, for models of more than CMP_BIG_TRIS
# triangles, default 5M: the 12M plant, as issue 17's table did), elevation
# 20, as oitstream frames the source mesh, written once to one walk file that
# every method reads, each view twice: the second (warm) frame is timed, as a
# viewer sees a still view; ms = median of the warm frames.
#
# Columns: the scheme, triangles in/out, parts (oitprep --stats), conversion s and
# input triangles/s, peak host RSS of the conversion and of the stream
# (/usr/bin/time -v), GPU bytes at peak (stream; DFB with its mesh, and the
# mesh's part), overflow pixels (sum
# over all frames), second-pass pixels and packs (stats keys
# second_pass_pixels / second_pass_packs, worst frame; '-' when this build's
# oitstream does not write them), ms of each method, stream/DFB and
# view/stream/unsorted, and "off %": the worst view's share of pixels off by more
# than 1/255 between a method and DFB on the source mesh, with the largest
# absolute difference (in 1/255) beside it.
#
# Usage: data_scripts/stream_vs_dfb.sh [BINDIR] [OUT.md] [WxH]
#   defaults: build/bin, bench/stream-vs-dfb-$(hostname).md, 1024x1024
# Models: demo (oitgen demo), plant1M and plant12M (oitgen plant), and every
# fetched mesh of data_scripts/cache (OIT_MESH_CACHE) that exists.
# Knobs (environment):
#   CMP_MODELS="demo plant1M fandisk.off"  these instead of all (plantN: a
#                                 plant of N triangles, e.g. plant100000)
#   CMP_12M=0                     leave the 12M plant out
#   CMP_VTK=0                     leave VTK out (its columns print "skipped")
#   CMP_VTK_SKIP="plant12M"       models VTK is not run on
#   CMP_VIEWS, CMP_BIG_VIEWS, CMP_BIG_TRIS  as above
#   CMP_PEELS="1000 4"            the two VTK peel counts (exact, default)
#   CMP_PYTHON=/usr/bin/python3   the Python with python3-vtk9 (Debian's)
#   CMP_KEEP=DIR                  keep frames and stats per model in DIR
#   CMP_COMPUTE=0                 leave out the compute capture's columns: in
#                                 core (`--method compute`) and streamed
#                                 (`--capture compute`), issue 39
# Needs: the tools in BINDIR, /usr/bin/time; for VTK: python3-vtk9, xvfb-run
# (setup/install-deps.sh setup/bench-packages.txt installs them; the script
# runs it when they are missing). Big files go to a folder under /tmp that is
# removed at the end (the 12M plant: 0.26 GB of PLY, 1.3 GB of part file).
# Exits non-zero, naming the model and step, when a tool is missing or any
# render, conversion or comparison fails: no row is printed for it.
# Duration on a loaded 2-core llvmpipe machine at 1024x1024: demo ~1 min,
# 1M plant ~5 min (VTK exact DDP ~20 s a frame); the 12M plant's conversion
# ~90 s and stream ~25 s a frame, and VTK on it likely tens of minutes
# (CMP_VTK_SKIP=plant12M leaves it out).
set -eu
. "$(dirname "$0")/models.sh"
bin=${1:-build/bin} size=${3:-1024x1024}
out=${2:-bench/stream-vs-dfb-$(hostname).md}
here=$(cd "$(dirname "$0")" && pwd)
cache=${OIT_MESH_CACHE:-$here/cache}
views=${CMP_VIEWS:-5} big_views=${CMP_BIG_VIEWS:-3} big_tris=${CMP_BIG_TRIS:-5000000}
peels=${CMP_PEELS:-1000 4}
py=${CMP_PYTHON:-/usr/bin/python3}
use_vtk=${CMP_VTK:-1}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
cmdline="$0 $*"

# Fails loudly: the rows finished so far go to stderr, none to OUT.
die() {
    echo "stream_vs_dfb: $*" >&2
    if [ -s "${work:-/nonexistent}/rows1" ]; then
        echo "stream_vs_dfb: rows finished before the failure (not written to $out):" >&2
        cat "$work/rows1" "$work/rows2" >&2
    fi
    exit 1
}
case $size in *x*) ;; *) die "size '$size': expected WxH" ;; esac
w=${size%x*} h=${size#*x}

# ---- tools -------------------------------------------------------------
for t in oitgen oitprep oitstream; do
    [ -x "$bin/$t" ] || die "$bin/$t: missing (build with: nice make build)"
done
[ -x /usr/bin/time ] || die "/usr/bin/time: missing (apt-get install time)"
if [ "$use_vtk" != 0 ]; then
    if ! "$py" -c 'import vtkmodules.vtkRenderingOpenGL2' 2>/dev/null ||
        ! command -v xvfb-run >/dev/null 2>&1; then
        echo "stream_vs_dfb: installing setup/bench-packages.txt (python3-vtk9, xvfb)" >&2
        "$here/../setup/install-deps.sh" "$here/../setup/bench-packages.txt" ||
            die "setup/install-deps.sh setup/bench-packages.txt failed"
    fi
    "$py" -c 'import vtkmodules.vtkRenderingOpenGL2' ||
        die "$py: no VTK (python3-vtk9; or set CMP_PYTHON, or CMP_VTK=0)"
    command -v xvfb-run >/dev/null 2>&1 || die "xvfb-run: missing (xvfb)"
    [ -f "$here/vtk_ddp.py" ] || die "$here/vtk_ddp.py: missing"
fi

work=$(mktemp -d /tmp/stream_vs_dfb.XXXXXX)
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# ---- helpers -----------------------------------------------------------
num() { sed -n "s/.*\"$1\": *\([-0-9.e+]*\).*/\1/p" "$2" | head -n 1; }
# Median of the warm (2nd, 4th, ...) frames' ms of a stats file.
warm_ms() {
    grep -o '"ms": [-0-9.]*' "$1" | sed 's/.*: //' | awk 'NR % 2 == 0' | sort -g |
        awk '{ v[NR] = $1 } END { if (NR == 0) exit 1;
                                   if (NR % 2) printf "%.1f\n", v[(NR + 1) / 2];
                                   else printf "%.1f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
# Sum / max over all frames of an integer key; "-" when no frame has it.
key_sum() {
    grep -o "\"$1\": [0-9]*" "$2" | sed 's/.*: //' |
        awk '{ s += $1; n++ } END { if (n) print s; else print "-" }'
}
key_max() {
    grep -o "\"$1\": [0-9]*" "$2" | sed 's/.*: //' |
        awk '{ if ($1 > m) m = $1; n++ } END { if (n) print m + 0; else print "-" }'
}
rss_mb() { sed -n 's/.*Maximum resident set size (kbytes): *\([0-9]*\).*/\1/p' "$1" |
    awk '{ printf "%.0f\n", $1 / 1024 }'; }
mb() { case $1 in -) echo - ;; *) awk -v b="$1" 'BEGIN { printf "%.1f", b / 1e6 }' ;; esac; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
# Checks a stats file has one frame a walk line and a median.
check_frames() { # stats label
    cf_n=$(grep -c '"ms":' "$1" || true)
    [ "$cf_n" = "$nframes" ] || die "$name: $2: $cf_n frames in $1, expected $nframes"
    warm_ms "$1" >/dev/null || die "$name: $2: no frame times in $1"
}
# Runs oitstream along the walk: render FILE STATS DIR TIMEFILE [options].
render() {
    f=$1 st=$2 dir=$3 tv=$4 label=$5; shift 5
    mkdir -p "$dir"
    nice -n 10 /usr/bin/time -v -o "$tv" "$bin/oitstream" "$f" --walk "$work/walk.txt" \
        --size "$size" "$@" --out "$dir/" --stats "$st" --quiet ||
        die "$name: $label: oitstream $f $* failed"
    check_frames "$st" "$label"
}
# Worst view's pct over 1/255 and max abs (in 1/255) of DIR_A against DIR_B
# over the warm frames: prints "PCT MAXABS255".
compare_dirs() {
    worst=0 maxabs=0 i=1
    while [ "$i" -lt "$nframes" ]; do
        fr=$(printf 'frame_%03d.png' "$i")
        [ -s "$1/$fr" ] || die "$name: $3: $1/$fr missing"
        [ -s "$2/$fr" ] || die "$name: $3: $2/$fr missing"
        j=$("$bin/oitstream" --compare "$1/$fr" "$2/$fr" --json) ||
            die "$name: $3: oitstream --compare $1/$fr $2/$fr failed"
        cp_pct=$(echo "$j" | sed -n 's/.*"pct_over_1_255": *\([-0-9.e+]*\).*/\1/p')
        cp_max=$(echo "$j" | sed -n 's/.*"max_abs": *\([-0-9.e+]*\).*/\1/p')
        [ -n "$cp_pct" ] && [ -n "$cp_max" ] || die "$name: $3: no figures in compare output: $j"
        worst=$(awk -v a="$worst" -v b="$cp_pct" 'BEGIN { print (b > a ? b : a) }')
        maxabs=$(awk -v a="$maxabs" -v b="$cp_max" 'BEGIN { print (b > a ? b : a) }')
        i=$((i + 2))
    done
    awk -v p="$worst" -v m="$maxabs" 'BEGIN { printf "%.3f %.0f\n", p, m * 255 }'
}

# ---- models ------------------------------------------------------------
all="demo plant1M"
for m in $OIT_FETCHED_MODELS $OIT_FETCHED_DRACO; do
    [ -f "$cache/$m" ] && all="$all $m"
done
[ "${CMP_12M:-1}" = 0 ] || all="$all plant12M" # last: the longest
models=${CMP_MODELS:-$all}
if [ "${CMP_12M:-1}" = 0 ]; then
    models=$(echo "$models" | tr ' ' '\n' | grep -vx 'plant12M\|plant12000000' | tr '\n' ' ')
fi
[ -n "$(echo "$models" | tr -d ' ')" ] || die "no models"

# ---- header ------------------------------------------------------------
mkdir -p "$(dirname "$out")"
commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo '?')
git -C "$here" diff --quiet HEAD -- 2>/dev/null || commit="$commit (+ uncommitted changes)"
t1="| model | scheme | views | tris in | tris out | out/in | parts | conv s | in tris/s | conv RSS MB | stream RSS MB | stream GPU MB | DFB GPU MB | of it DFB's mesh MB | overflow | 2nd-pass px | 2nd-pass packs |"
s1="|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
t2="| model | stream ms | DFB mesh ms | unsorted ms | stream / DFB | stream / unsorted | stream off % (max) | compute ms | compute / DFB | compute off % (max) | stream --capture compute ms | its / DFB | its off % (max) |"
s2="|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for p in $peels; do
    t2="$t2 VTK DDP $p ms | VTK $p off % (max) |"
    s2="$s2---|---|"
done
: >"$work/rows1"
: >"$work/rows2"
: >"$work/notes"

vtk_renderer=""
gl_renderer=""
have_draco=""
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
for model in $models; do
    name=$model
    echo "== $name" >&2
    # The input: generated into the work folder, or the fetched file.
    case $model in
    demo)
        "$bin/oitgen" demo -o "$work/demo.ply" >/dev/null || die "demo: oitgen demo failed"
        m=$work/demo.ply ;;
    plant*)
        n=$(echo "${model#plant}" | sed 's/M$/000000/; s/K$/000/')
        case $n in '' | *[!0-9]*) die "$model: expected plantN, plant1M, plant12M" ;; esac
        nice -n 10 "$bin/oitgen" plant --triangles "$n" -o "$work/$model.ply" >/dev/null ||
            die "$model: oitgen plant --triangles $n failed"
        m=$work/$model.ply ;;
    *)
        m=$cache/$model
        [ -f "$m" ] || die "$model: not in $cache (data_scripts/fetch_meshes.sh fetches it)" ;;
    esac

    # The views: an orbit as oitstream frames the source mesh, each twice.
    nice -n 10 "$bin/oitstream" "$m" --method unsorted --orbit "$views" --size 16x16 \
        --out "$work/v/" --stats "$work/v.json" --quiet || die "$name: framing the views failed"
    tin=$(num triangles "$work/v.json")
    nv=$views
    if [ "$tin" -gt "$big_tris" ]; then
        nv=$big_views
        nice -n 10 "$bin/oitstream" "$m" --method unsorted --orbit "$nv" --size 16x16 \
            --out "$work/v/" --stats "$work/v.json" --quiet || die "$name: framing the views failed"
    fi
    sed -n 's/.*"view": "\([^"]*\)".*/\1/p' "$work/v.json" | awk '{ print; print }' >"$work/walk.txt"
    nframes=$((2 * nv))
    [ "$(wc -l <"$work/walk.txt")" = "$nframes" ] || die "$name: walk has not $nframes lines"
    rm -rf "$work/v"

    # Conversion (oitprep's defaults) and the stream.
    nice -n 10 /usr/bin/time -v -o "$work/prep.time" "$bin/oitprep" "$m" -o "$work/m.oitp" \
        --stats "$work/prep.json" >"$work/prep.log" 2>&1 ||
        { cat "$work/prep.log" >&2; die "$name: oitprep failed"; }
    render "$work/m.oitp" "$work/s.json" "$work/s" "$work/s.time" stream --epsilon 0
    [ "${CMP_COMPUTE:-1}" = 0 ] || render "$work/m.oitp" "$work/sc.json" "$work/sc" \
        "$work/sc.time" "stream --capture compute" --epsilon 0 --capture compute
    rm -f "$work/m.oitp"
    # The alternatives on the source mesh.
    render "$m" "$work/d.json" "$work/d" "$work/d.time" dfb --method dfb
    render "$m" "$work/u.json" "$work/u" "$work/u.time" unsorted --method unsorted
    [ "${CMP_COMPUTE:-1}" = 0 ] ||
        render "$m" "$work/c.json" "$work/c" "$work/c.time" compute --method compute
    [ -n "$gl_renderer" ] || gl_renderer=$(sed -n 's/.*"renderer": "\([^"]*\)".*/\1/p' "$work/d.json" | head -n 1)

    conv=$(num total "$work/prep.json")
    tout=$(num triangles_out "$work/prep.json")
    [ -n "$conv" ] && [ -n "$tout" ] || die "$name: oitprep --stats has no total/triangles_out"
    sms=$(warm_ms "$work/s.json") dms=$(warm_ms "$work/d.json") ums=$(warm_ms "$work/u.json")
    dcap=$(key_max gpu_bytes_peak "$work/d.json")
    [ "$dcap" != - ] || die "$name: dfb: no gpu_bytes_peak in $work/d.json"
    r=$(compare_dirs "$work/s" "$work/d" "stream vs dfb")
    off="${r% *} (${r#* })"
    scheme=$(sed -n 's/.*"scheme": *"\([^"]*\)".*/\1/p' "$work/prep.json" | head -n 1)
    echo "| $name | ${scheme:-?} | $nv | $tin | $tout | $(ratio "$tout" "$tin") | $(num parts "$work/prep.json") |" \
        "$conv | $(awk -v n="$tin" -v s="$conv" 'BEGIN { printf "%.0f", (s > 0 ? n / s : 0) }') |" \
        "$(rss_mb "$work/prep.time") | $(rss_mb "$work/s.time") |" \
        "$(mb "$(key_max gpu_bytes_peak "$work/s.json")") | $(mb "$dcap") | $(mb "$(key_max gpu_mesh_bytes "$work/d.json")") |" \
        "$(key_sum overflow_pixels "$work/s.json") | $(key_max second_pass_pixels "$work/s.json") |" \
        "$(key_max second_pass_packs "$work/s.json") |" >>"$work/rows1"
    row="| $name | $sms | $dms | $ums | $(ratio "$sms" "$dms") | $(ratio "$sms" "$ums") | $off |"
    if [ "${CMP_COMPUTE:-1}" = 0 ]; then
        row="$row skipped (CMP_COMPUTE=0) | - | - | skipped | - | - |"
    else
        for x in c sc; do
            xms=$(warm_ms "$work/$x.json")
            r=$(compare_dirs "$work/$x" "$work/d" "$x vs dfb")
            row="$row $xms | $(ratio "$xms" "$dms") | ${r% *} (${r#* }) |"
        done
    fi

    # VTK dual depth peeling on the same walk.
    skip=""
    if [ "$use_vtk" = 0 ]; then
        skip="skipped (CMP_VTK=0)"
    elif echo " ${CMP_VTK_SKIP:-} " | grep -q " $model "; then
        skip="skipped (CMP_VTK_SKIP)"
    else
        case $m in *.gltf | *.glb)
            ! grep -aq KHR_draco_mesh_compression "$m" || { skip="not run (Draco: see notes)"; have_draco=1; } ;;
        esac
    fi
    for p in $peels; do
        if [ -n "$skip" ]; then
            row="$row $skip | - |"
            continue
        fi
        rm -rf "$work/k"
        sw=$((w > 1280 ? w : 1280)) sh=$((h > 1024 ? h : 1024))
        nice -n 10 xvfb-run -a -s "-screen 0 ${sw}x${sh}x24" "$py" "$here/vtk_ddp.py" "$m" \
            --walk "$work/walk.txt" --size "$size" --peels "$p" --out "$work/k/" \
            --stats "$work/k.json" 2>"$work/k.log" ||
            { tail -n 20 "$work/k.log" >&2; die "$name: VTK DDP ($p peels) failed"; }
        check_frames "$work/k.json" "VTK DDP $p peels"
        [ -n "$vtk_renderer" ] || vtk_renderer=$(sed -n 's/.*"renderer": "\([^"]*\)".*/\1/p' "$work/k.json" | head -n 1)
        conv_note=$(tr -d '\n' <"$work/k.json" | sed -n 's/.*"conversion": \({[^}]*}\).*/\1/p' | tr -s ' ')
        [ -n "$conv_note" ] && ! grep -qF "$name:" "$work/notes" &&
            echo "- $name: VTK read a PLY converted by vtk_ddp.py: $conv_note" >>"$work/notes"
        r=$(compare_dirs "$work/k" "$work/d" "VTK $p peels vs dfb")
        kms=$(warm_ms "$work/k.json")
        row="$row $kms | ${r% *} (${r#* }) |"
        if [ -n "${CMP_KEEP:-}" ]; then
            mkdir -p "$CMP_KEEP/$name" && cp -r "$work/k" "$CMP_KEEP/$name/vtk$p" &&
                cp "$work/k.json" "$CMP_KEEP/$name/vtk$p.json"
        fi
    done
    echo "$row" >>"$work/rows2"
    if [ -n "${CMP_KEEP:-}" ]; then
        mkdir -p "$CMP_KEEP/$name"
        for x in s d u c sc; do
            [ -d "$work/$x" ] || continue
            cp -r "$work/$x" "$CMP_KEEP/$name/$x" && cp "$work/$x.json" "$CMP_KEEP/$name/$x.json"
        done
        cp "$work/prep.json" "$work/walk.txt" "$CMP_KEEP/$name/"
    fi
    tail -n 1 "$work/rows1" >&2
    tail -n 1 "$work/rows2" >&2
    rm -rf "$work/s" "$work/d" "$work/u" "$work/k" "$work/c" "$work/sc"
    case $m in "$work"/*) rm -f "$m" ;; esac
done

{
    echo "# The stream against DFB on the source mesh, unsorted and VTK dual depth peeling"
    echo
    echo "Machine: $(uname -m), $(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1),"
    echo "$(awk '/MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo) RAM; load average at the start $load_start, at the end $(cut -d' ' -f1-3 /proc/loadavg) (shared machine: timings are noisy)."
    echo "GL (oitstream, EGL): $gl_renderer."
    [ "$use_vtk" = 0 ] || echo "GL (VTK $("$py" -c 'import vtkmodules.vtkCommonCore as c; print(c.vtkVersion.GetVTKVersion())'), GLX under Xvfb): ${vtk_renderer:-not run}."
    echo "Commit (this checkout): $commit; tools from $bin. Size $size."
    echo "Command: \`$cmdline\`"
    env | grep '^CMP_' | sed 's/^/  env: /; s/$//' || true
    echo
    echo "Views: an orbit of $views views at elevation 20 (framing the source mesh; $big_views for models over $big_tris triangles),"
    echo "each rendered twice; ms = median of the warm (second) frames. All methods read the same walk file."
    echo "stream: \`oitprep MESH -o M.oitp\` (default scheme, named in the scheme column, and options), \`oitstream M.oitp --epsilon 0\` (default options);"
    echo "DFB / unsorted / compute: \`oitstream MESH --method dfb|unsorted|compute\` on the source mesh;"
    echo "stream --capture compute: the same part file, \`oitstream M.oitp --epsilon 0 --capture compute\`."
    echo "VTK DDP: data_scripts/vtk_ddp.py (vtkDualDepthPeelingPass, occlusion ratio 0, multisampling off, offscreen under Xvfb)"
    echo "at ${peels% *} peels (exact) and ${peels#* } (VTK's default); same cameras and shading (positional light at the eye,"
    echo "flat, ambient 0.3, diffuse 0.7, alpha 0.35): what differs is listed in vtk_ddp.py and its stats."
    echo "off % = worst view's share of pixels off by more than 1/255 against DFB on the source mesh; (max) = largest"
    echo "absolute difference in 1/255. overflow = sum over all frames; 2nd-pass px / packs = worst frame"
    echo "(stats keys second_pass_pixels / second_pass_packs, '-' where this oitstream does not write them);"
    echo "RSS = peak host resident set (/usr/bin/time -v); GPU MB = gpu_bytes_peak, worst frame (1 MB = 10^6 bytes):"
    echo "the stream's counts its ring, cache, capture and per-pixel state; DFB's its fragment buffers and the source"
    echo "mesh it holds, whose part is gpu_mesh_bytes ('-' from an oitstream before that key, whose DFB figure left it out)."
    echo
    echo "## Conversion and stream"
    echo
    echo "$t1"
    echo "$s1"
    cat "$work/rows1"
    echo
    echo "## Time and error against DFB on the source mesh"
    echo
    echo "$t2"
    echo "$s2"
    cat "$work/rows2"
    echo
    if [ -s "$work/notes" ] || [ -n "$have_draco" ]; then
        echo "Notes:"
        cat "$work/notes"
        [ -z "$have_draco" ] ||
            echo "- Draco-compressed glTF: no VTK figures: vtk_ddp.py's converter has no Draco decoder, and no project tool writes a mesh as it reads it (see the uncompressed .glb of the same model)."
    fi
} >"$out"
cat "$out"
echo "stream_vs_dfb: wrote $out" >&2
