#!/bin/sh
# The bad-input battery (issue 18: never lose the user's data, never call
# garbage a success). Every case runs against every tool that takes that
# kind of input:
#   meshes     oitprep (convert), oitstream, oitbench, oitgen instances --input
#   part files oitprep info, verify, parts, oitstream, oitbench
# and each run is checked for
#   - its exit code (0 ok, 1 runtime, 2 usage, 3 bad input; 130/143 signals),
#   - a failure's stderr: exactly one line, naming the file (or option) and
#     the problem,
#   - nothing left behind: the run's output folder is empty again, and no
#     *.tmp / *.spill file exists anywhere under the scratch folder,
#   - the input unchanged (cksum before and after).
# Cases: outputs that are the input (same path, symlink, hard link), empty
# and garbage models (/etc/passwd as .obj, vertices only, no faces, all
# degenerate, all non-finite, binary bytes in a text format), UTF-8 BOMs,
# formats through assimp (truncated FBX, IFC without geometry, random .dae),
# gzip (named .gz or not: read; corrupt or truncated: refused naming gzip),
# VTK files (.vtp and legacy .vtk that VTK wrote: read; truncated, without
# geometry, only cells of a type not read, a dataset or file type that holds no surface,
# another format under their names: refused naming the file and the fault),
# STEP/IGES (truncated, random bytes named .igs, no geometry),
# corrupt part files (empty, text, truncated, flipped byte, gzip), usage
# errors (empty -o, unknown image extension, unwritable folder before the
# run, degenerate --view, --max-layers out of range), SIGINT/SIGTERM during
# oitprep and oitgen. It prints its table of cases.
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
need_every_tool
command -v gzip >/dev/null || skip "gzip not installed"
scratch bad_input
I="$T/in"
O="$T/out"
mkdir -p "$I" "$O" || exit 1
CASES=0
sum() { [ -n "$1" ] || { echo none; return; }; cksum <"$1" 2>/dev/null || echo missing; }
row() { printf '%-26s %-13s %5s %5s  %s\n' "$1" "$2" "$3" "$4" "$5"; }

# check NAME TOOL WANT INPUT NEEDLE OUTPUT: after a run ($rc, $T/err.txt).
# OUTPUT: what a success must have written ("" for nothing).
check() {
    name=$1 tool=$2 want=$3 input=$4 needle=$5 output=$6
    CASES=$((CASES + 1))
    verdict=
    [ "$rc" -eq "$want" ] || verdict="exit $rc, want $want"
    if [ "$want" -ne 0 ]; then
        lines=$(wc -l <"$T/err.txt")
        [ "$lines" -eq 1 ] || verdict="$verdict; $lines stderr lines"
        grep -qF -- "$needle" "$T/err.txt" || verdict="$verdict; stderr lacks '$needle'"
        [ -z "$(ls -A "$O")" ] || verdict="$verdict; left $(ls -A "$O" | tr '\n' ' ')"
    elif [ -n "$output" ] && [ ! -s "$output" ]; then
        verdict="$verdict; no $output"
    fi
    left=$(find "$T" -name '*.tmp' -o -name '*.spill' | head -n 3)
    [ -z "$left" ] || verdict="$verdict; left $left"
    [ -z "$input" ] || [ "$(sum "$input")" = "$before" ] || verdict="$verdict; input changed"
    verdict=${verdict#; }
    verdict=${verdict:-ok}
    row "$name" "$tool" "$want" "$rc" "$verdict"
    [ "$verdict" = ok ] || fail "$name / $tool: $verdict: $(head -c 300 "$T/err.txt")"
    rm -rf "$O" && mkdir -p "$O"
}

# run NAME TOOL WANT INPUT NEEDLE OUTPUT CMD...
run() {
    name=$1 tool=$2 want=$3 input=$4 needle=$5 output=$6
    shift 6
    before=$(sum "$input")
    "$@" >"$T/out.txt" 2>"$T/err.txt"
    rc=$?
    check "$name" "$tool" "$want" "$input" "$needle" "$output"
}

# mesh NAME WANT FILE [NEEDLE]: the case through every mesh tool.
mesh() {
    m=$1 want=$2 f=$3 needle=${4:-$(basename "$3")}
    run "$m" oitprep "$want" "$f" "$needle" "$O/x.oitp" "$P" "$f" -o "$O/x.oitp"
    run "$m" oitstream "$want" "$f" "$needle" "$O/x.png" \
        "$S" "$f" --size 16x16 --quiet --out "$O/x.png"
    run "$m" oitbench "$want" "$f" "$needle" "$O/b/results.csv" \
        "$BN" "$f" --methods dfb --orbit 1 --size 16x16 --frames 1 --warmup 0 --out "$O/b"
    run "$m" "oitgen inst" "$want" "$f" "$needle" "$O/x.ply" \
        "$G" instances --input "$f" --count 2 -o "$O/x.ply"
}

# part NAME WANT FILE [NEEDLE]: the case through every part-file tool.
part() {
    m=$1 want=$2 f=$3 needle=${4:-$(basename "$3")}
    run "$m" "prep info" "$want" "$f" "$needle" "" "$P" info "$f"
    run "$m" "prep verify" "$want" "$f" "$needle" "" \
        "$P" verify "$f" --directions 2 --viewpoints 1
    run "$m" "prep parts" "$want" "$f" "$needle" "$O/p.ply" "$P" parts "$f" -o "$O/p.ply"
    run "$m" oitstream "$want" "$f" "$needle" "$O/x.png" \
        "$S" "$f" --size 16x16 --quiet --out "$O/x.png"
    run "$m" oitbench "$want" "$f" "$needle" "$O/b/results.csv" \
        "$BN" "$f" --methods stream --orbit 1 --size 16x16 --frames 1 --warmup 0 --out "$O/b"
}

# ---- inputs ----
"$G" quads --count 4 -o "$I/good.ply" >/dev/null || die "oitgen quads"
tri='v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n'
printf "$tri" >"$I/good.obj"
cp /etc/passwd "$I/passwd.obj"
: >"$I/empty.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n' >"$I/vonly.obj"
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n' >"$I/degenerate.obj"
printf 'OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$I/nonfinite.off"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n' >"$I/nofaces.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$I/tri.ply"
printf '\357\273\277' >"$I/bom.obj" && printf "$tri" >>"$I/bom.obj"
printf '\357\273\277' >"$I/bom.ply" && cat "$I/tri.ply" >>"$I/bom.ply"
printf '\357\273\277OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$I/bom.off"
printf '\357\273\277solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' >"$I/bom.stl"
head -c 2048 "$G" >"$I/binary.obj"
head -c 2048 "$G" >"$I/binary.off"
gzip -9nc "$I/good.obj" >"$I/good.obj.gz"
cp "$I/good.obj.gz" "$I/gzip_named.obj"
gzip -9nc "$I/good.ply" >"$I/good.ply.gz"
gzip -9nc "$I/bom.stl" >"$I/ascii.stl.gz"
size=$(wc -c <"$I/good.ply.gz")
head -c $((size / 2)) "$I/good.ply.gz" >"$I/truncated.ply.gz"
cp "$I/good.ply.gz" "$I/corrupt.ply.gz"
printf '\377\377\377\377\377\377\377\377' |
    dd of="$I/corrupt.ply.gz" bs=1 seek=$((size / 3)) conv=notrunc 2>/dev/null
gzip -9nc "$I/empty.obj" >"$I/empty.obj.gz"
# VTK (tests/corpus: files VTK 9.1 wrote)
V=$(dirname "$0")/../corpus
cp "$V/vtp/poly_appended.vtp" "$V/vtk/poly_binary_51.vtk" "$V/vtk/ugrid_ascii_51.vtk" "$I/"
gzip -9nc "$I/poly_appended.vtp" >"$I/poly_appended.vtp.gz"
head -c 1500 "$I/poly_appended.vtp" >"$I/truncated.vtp"
head -c $(($(wc -c <"$I/poly_appended.vtp") - 200)) "$I/poly_appended.vtp" >"$I/cut_data.vtp"
head -c 400 "$I/poly_binary_51.vtk" >"$I/truncated.vtk"
printf '# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n' >"$I/points_only.vtk"
printf '# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\n' >"$I/empty.vtk"
printf '<VTKFile type="PolyData"><PolyData><Piece NumberOfPoints="0"></Piece></PolyData></VTKFile>\n' >"$I/empty.vtp"
printf '# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n' >"$I/image.vtk"
printf '<VTKFile type="UnstructuredGrid"><UnstructuredGrid></UnstructuredGrid></VTKFile>\n' >"$I/ugrid.vtp"
cp "$I/tri.ply" "$I/ply_named.vtp"
cp "$I/tri.ply" "$I/ply_named.vtk"
printf '# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n' >"$I/tetra.vtk"
sed 's/^10$/71/' "$I/tetra.vtk" >"$I/bezier.vtk" # a cell type the reader does not take
ln -s good.ply "$I/link.ply"
ln "$I/good.ply" "$I/hard.ply"
"$P" "$I/good.ply" -o "$I/good.oitp" >/dev/null 2>&1 || die "oitprep good.ply"
psize=$(wc -c <"$I/good.oitp")
: >"$I/empty.oitp"
printf 'hello, not a part file\n' >"$I/text.oitp"
head -c $((psize / 2)) "$I/good.oitp" >"$I/truncated.oitp"
cp "$I/good.oitp" "$I/flipped.oitp"
printf '\125' | dd of="$I/flipped.oitp" bs=1 seek=$((psize / 2)) conv=notrunc 2>/dev/null
gzip -9nc "$I/good.oitp" >"$I/gzip.oitp"
# formats read through assimp (issue 47): half an FBX, an IFC of a site
# without any product, binary bytes (a PNG: fixed, not /dev/urandom's)
# named .dae
AS=$(dirname "$0")/../corpus/assimp
head -c $(($(wc -c <"$AS/box.fbx") / 2)) "$AS/box.fbx" >"$I/truncated.fbx"
cp "$AS/empty_site.ifc" "$I/nogeometry.ifc"
cp "$(dirname "$0")/../corpus/image/small.png.bin" "$I/png.dae"
cp "$AS/crashes_assimp.ifc" "$I/crashes_assimp.ifc"
# STEP and IGES (Open CASCADE): cut mid-DATA, binary bytes (a PNG: fixed
# bytes, for /dev/urandom's sometimes parse as an IGES file holding
# nothing), no geometry, a file that crashes Open CASCADE
step_corpus=$(dirname "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}")/corpus/step
ssize=$(wc -c <"$step_corpus/parts.step")
head -c $((ssize / 2)) "$step_corpus/parts.step" >"$I/truncated.step"
cp "$(dirname "$step_corpus")/image/small.png.bin" "$I/png.igs"
cp "$step_corpus/nogeom.step" "$I/nogeom.step"
cp "$step_corpus/crashes_occt.step" "$I/crashes_occt.step"

row case tool want got verdict
row ---- ---- ---- --- -------

# ---- outputs that are the input: refused before any work, exit 2 ----
for f in good.ply link.ply hard.ply; do
    run "out=in ($f)" oitprep 2 "$I/good.ply" "would replace the input" "" \
        "$P" "$I/good.ply" -o "$I/$f"
    run "out=in ($f)" "oitgen inst" 2 "$I/good.ply" "would replace the input" "" \
        "$G" instances --input "$I/good.ply" -o "$I/$f"
done
run "stats=in" oitprep 2 "$I/good.ply" "would replace the input" "" \
    "$P" "$I/good.ply" -o "$O/x.oitp" --stats "$I/link.ply"
run "out=in" "prep parts" 2 "$I/good.oitp" "would replace the input" "" \
    "$P" parts "$I/good.oitp" -o "$I/good.oitp"
run "stats=in" oitstream 2 "$I/good.ply" "would replace the input" "" \
    "$S" "$I/good.ply" --size 16x16 --quiet --stats "$I/hard.ply"

# ---- models: good, garbage, empty ----
mesh "good ply" 0 "$I/good.ply"
mesh "passwd as obj" 3 "$I/passwd.obj" "passwd.obj: no vertices and no faces"
mesh "empty obj" 3 "$I/empty.obj" "empty.obj: no vertices and no faces"
mesh "vertices only obj" 3 "$I/vonly.obj" "vonly.obj: 3 vertices but no faces"
mesh "ply without faces" 3 "$I/nofaces.ply" "nofaces.ply: 3 vertices but no faces"
mesh "all degenerate obj" 3 "$I/degenerate.obj" "degenerate"
mesh "all non-finite off" 3 "$I/nonfinite.off" "non-finite"
mesh "binary named .obj" 3 "$I/binary.obj" "binary data, not a text OBJ"
mesh "binary named .off" 3 "$I/binary.off" "binary data, not a text OFF"
mesh "bom obj" 0 "$I/bom.obj"
mesh "bom ply" 0 "$I/bom.ply"
mesh "bom off" 0 "$I/bom.off"
mesh "bom ascii stl" 0 "$I/bom.stl"
mesh "gzip obj.gz" 0 "$I/good.obj.gz"
mesh "gzip named .obj" 0 "$I/gzip_named.obj"
mesh "gzip ply.gz" 0 "$I/good.ply.gz"
mesh "gzip ascii stl.gz" 0 "$I/ascii.stl.gz"
mesh "gzip truncated" 3 "$I/truncated.ply.gz" "gzip stream truncated"
mesh "gzip corrupt" 3 "$I/corrupt.ply.gz" "gzip"
mesh "gzip of empty obj" 3 "$I/empty.obj.gz" "no vertices and no faces"
mesh "vtp (VTK's default)" 0 "$I/poly_appended.vtp"
mesh "gzip vtp.gz" 0 "$I/poly_appended.vtp.gz"
mesh "binary vtk 5.1" 0 "$I/poly_binary_51.vtk"
mesh "unstructured vtk" 0 "$I/ugrid_ascii_51.vtk"
mesh "truncated vtp" 3 "$I/truncated.vtp" "truncated.vtp: byte offset"
mesh "vtp, data cut" 3 "$I/cut_data.vtp" "cut_data.vtp: byte offset"
mesh "truncated binary vtk" 3 "$I/truncated.vtk" "truncated.vtk: byte offset"
mesh "vtk points only" 3 "$I/points_only.vtk" "points_only.vtk: 3 vertices but no faces"
mesh "vtk no geometry" 3 "$I/empty.vtk" "empty.vtk: no vertices and no faces"
mesh "vtp no geometry" 3 "$I/empty.vtp" "empty.vtp: no vertices and no faces"
mesh "vtk tetrahedron (boundary)" 0 "$I/tetra.vtk"
mesh "vtk only unread cells" 3 "$I/bezier.vtk" "bezier.vtk: no surface cells and no volume cell"
mesh "vtk STRUCTURED_POINTS" 3 "$I/image.vtk" "DATASET STRUCTURED_POINTS is not supported"
mesh "vtp UnstructuredGrid" 3 "$I/ugrid.vtp" "VTKFile type 'UnstructuredGrid' is not supported"
mesh "ply named .vtp" 3 "$I/ply_named.vtp" "ply_named.vtp: byte offset 0: not an XML VTK file"
mesh "ply named .vtk" 3 "$I/ply_named.vtk" "ply_named.vtk: line 1: not a legacy VTK file"
mesh "truncated fbx" 3 "$I/truncated.fbx" "truncated.fbx: assimp cannot read it"
mesh "ifc without geometry" 3 "$I/nogeometry.ifc" "nogeometry.ifc: no geometry"
mesh "png named .dae" 3 "$I/png.dae" "png.dae: assimp cannot read it"
mesh "ifc that kills assimp" 3 "$I/crashes_assimp.ifc" "crashes_assimp.ifc: assimp crashed reading it"
mesh "truncated step" 3 "$I/truncated.step" "truncated.step: "
mesh "png named .igs" 3 "$I/png.igs" "png.igs: " # "not a readable IGES file", or under ASan "holds nothing": Open CASCADE reads what malloc left
mesh "step without geometry" 3 "$I/nogeom.step" "nogeom.step: "
mesh "step that kills Open CASCADE" 3 "$I/crashes_occt.step" "crashes_occt.step: Open CASCADE crashed reading it"
mesh "good step" 0 "$step_corpus/parts.step"

# ---- part files ----
part "good part file" 0 "$I/good.oitp"
part "empty part file" 3 "$I/empty.oitp"
part "text part file" 3 "$I/text.oitp"
part "truncated part file" 3 "$I/truncated.oitp"
part "flipped byte" 3 "$I/flipped.oitp"
part "gzip part file" 3 "$I/gzip.oitp"

# ---- usage errors, checked before the work ----
run "empty -o" oitprep 2 "$I/good.ply" "the path is empty" "" "$P" "$I/good.ply" -o ""
run "empty -o" "oitgen quads" 2 "" "the path is empty" "" "$G" quads -o ""
run "-o a folder" oitprep 2 "$I/good.ply" "is a folder" "" "$P" "$I/good.ply" -o "$O"
run "--out x.jpg" oitstream 2 "$I/good.ply" "unknown image extension '.jpg'" "" \
    "$S" "$I/good.ply" --size 16x16 --out "$O/x.jpg"
run "--out in /proc" oitbench 1 "$I/good.ply" "/proc/oit_no/such" "" \
    "$BN" "$I/good.ply" --methods dfb --out /proc/oit_no/such
run "-o in /proc" oitprep 1 "$I/good.ply" "/proc/oit_no/x.oitp: cannot create" "" \
    "$P" "$I/good.ply" -o /proc/oit_no/x.oitp
run "degenerate --view" oitstream 2 "$I/good.ply" "the eye and the target are the same" "" \
    "$S" "$I/good.ply" --size 16x16 --view 0,0,1,0,0,1,0,1,0,45 --out "$O/x.png"
run "--view :ortho=-1" oitstream 2 "$I/good.ply" "bad projection field" "" \
    "$S" "$I/good.ply" --size 16x16 --view 0,0,3,0,0,0,0,1,0,45:ortho=-1 --out "$O/x.png"
run "--view :ortho with :far=inf" oitstream 2 "$I/good.ply" "bad projection field" "" \
    "$S" "$I/good.ply" --size 16x16 --view 0,0,3,0,0,0,0,1,0,45:ortho=2:far=inf --out "$O/x.png"
run "--ortho 0" oitstream 2 "$I/good.ply" "a view height > 0, or fit" "" \
    "$S" "$I/good.ply" --size 16x16 --ortho 0 --out "$O/x.png"
run "--view :ortho=2" oitstream 0 "$I/good.ply" "" "$O/ortho.png" \
    "$S" "$I/good.ply" --size 16x16 --view 0,0,3,0,0,0,0,1,0,45:ortho=2 --out "$O/ortho.png" --quiet
run "--max-layers 66" oitprep 2 "$I/good.ply" "--max-layers '66': must be even, 2..64" "" \
    "$P" "$I/good.ply" -o "$O/x.oitp" --max-layers 66
run "--max-layers 64" oitprep 0 "$I/good.ply" "" "$O/k64.oitp" \
    "$P" "$I/good.ply" -o "$O/k64.oitp" --max-layers 64
"$P" "$I/good.ply" -o "$I/k64.oitp" --max-layers 64 >/dev/null 2>&1
run "K=64 part file" oitstream 0 "$I/k64.oitp" "" "$O/x.png" \
    "$S" "$I/k64.oitp" --size 16x16 --quiet --out "$O/x.png"
rm -f "$I/k64.oitp"
before=""
"$S" "$I/good.ply" --size 16x16 >"$T/out.txt" 2>"$T/err.txt"
rc=$?
grep -q "no --out given" "$T/err.txt" || rc=99
check "no --out says so" oitstream 0 "" "" ""

# ---- signals: the temporary output goes, a previous output stays ----
"$G" plant --triangles 600000 -o "$I/big.ply" >/dev/null 2>&1 || fail "oitgen plant"
# interrupt SIG CODE NAME TOOL OUTPUT CMD...: starts CMD, waits for OUTPUT.tmp,
# sends SIG; the run must exit CODE and leave OUTPUT as it was.
interrupt() {
    sig=$1 code=$2 name=$3 tool=$4 output=$5
    shift 5
    echo "previous output" >"$output"
    before=$(sum "$I/big.ply")
    prev=$(sum "$output")
    # no progress line, however long a loaded machine takes to reach the
    # signal: the one stderr line checked is the interruption's
    OIT_PROGRESS_PERIOD=86400 "$@" >"$T/out.txt" 2>"$T/err.txt" &
    pid=$!
    n=0
    while [ ! -e "$output.tmp" ] && [ $n -lt 200 ] && kill -0 $pid 2>/dev/null; do
        sleep 0.05
        n=$((n + 1))
    done
    kill -"$sig" $pid 2>/dev/null
    wait $pid
    rc=$?
    [ "$(sum "$output")" = "$prev" ] || rc=98 # the previous output changed
    rm -f "$output"
    check "$name" "$tool" "$code" "$I/big.ply" "interrupted by SIG$sig" ""
}
interrupt INT 130 "SIGINT converting" oitprep "$O/../sig.oitp" \
    "$P" "$I/big.ply" -o "$O/../sig.oitp" --threads 1
interrupt TERM 143 "SIGTERM converting" oitprep "$O/../sig.oitp" \
    "$P" "$I/big.ply" -o "$O/../sig.oitp" --threads 1
interrupt INT 130 "SIGINT generating" oitgen "$O/../sig.ply" \
    "$G" plant --triangles 3000000 -o "$O/../sig.ply"
interrupt TERM 143 "SIGTERM generating" oitgen "$O/../sig.ply" \
    "$G" instances --input "$I/big.ply" --count 8 -o "$O/../sig.ply"

echo "$CASES runs, $FAILS failed"
finish --clean "bad input"
