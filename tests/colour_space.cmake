# Linear-light compositing (--colour-space linear, render/shade.h "Colour
# space"): DFB and the stream against the Embree reference on a hard case
# with vertex colours and on a fetched mesh (default colour; skipped without
# it), and PFM output in linear light (tests/test_colour_space.sh).
oit_add_test(NAME colour_space_hard LABELS integration TIMEOUT 240
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_colour_space.sh hard coplanar $<TARGET_FILE:png_figures>)
oit_add_test(NAME colour_space_mesh LABELS integration TIMEOUT 240
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_colour_space.sh mesh bunny00.off $<TARGET_FILE:png_figures>)
