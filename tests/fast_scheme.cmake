# oitprep --scheme fast (issue 17) on every hard case, the demo and two
# fetched meshes: convert, info, verify (no order violations), stream equal
# to DFB on the file, triangles out <= 1.10x in (tests/test_fast_scheme.sh).
foreach(case coplanar rings sticks moebius degenerate nearflat far tiny thin nonmanifold
        stack dense coplanar_tiny coplanar_far decal touching demo mesh:fandisk.off mesh:head.stl)
  string(REPLACE "mesh:" "mesh_" tname "${case}")
  string(REPLACE "." "_" tname "${tname}")
  oit_add_test(NAME fast_${tname} LABELS integration TIMEOUT 240
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_fast_scheme.sh ${case})
endforeach()
