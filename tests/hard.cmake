# Numerical hard cases (issue 8): each `oitgen hard --case` scene through
# oitprep, verify and every exact method (tests/test_hard.sh), in the
# default fast scheme (hard_CASE) and in Wang & Xie's (hard_CASE_guaranteed).
foreach(case coplanar rings sticks moebius degenerate nearflat far tiny thin nonmanifold
        stack dense coplanar_tiny coplanar_far decal touching)
  oit_add_test(NAME hard_${case} LABELS integration TIMEOUT 240
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_hard.sh ${case} fast $<TARGET_FILE:png_figures>)
  oit_add_test(NAME hard_${case}_guaranteed LABELS integration TIMEOUT 240
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_hard.sh ${case} guaranteed $<TARGET_FILE:png_figures>)
endforeach()

# Tie flicker over a 0.25-degree orbit (issue 20, tests/test_tie_orbit.sh).
oit_add_test(NAME tie_orbit LABELS integration TIMEOUT 240
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_tie_orbit.sh)
