/* Which reader takes which mesh extension, as the tools' --help prints it
 * (formats/read_mesh.c decides; this is its one description for users). */
#ifndef OIT_TOOLS_COMMON_MESH_FORMATS_H
#define OIT_TOOLS_COMMON_MESH_FORMATS_H

#define OIT_TOOL_MESH_FORMATS_HELP                                                          \
    "Mesh formats, by extension (case-insensitive; NAME.EXT.gz is inflated):\n"             \
    "  .ply .obj (with its .mtl) .off .stl   our streaming readers, memory bounded\n"       \
    "  .gltf .glb (Draco too)                our glTF reader\n"                             \
    "  .vtk .vtp                             our VTK readers (legacy; XML PolyData)\n"      \
    "  .step .stp .iges .igs                Open CASCADE (B-rep tessellated at\n"           \
    "    --deflection, oitprep only; XDE colours and transparency)\n"                       \
    "  every other extension assimp imports  assimp (.fbx .dae .3ds .3mf .ifc\n"            \
    "    .blend .x .lwo .ase .dxf ..., an unknown one's error lists them), the\n"           \
    "    whole scene in memory; points, lines skipped; diffuse colour, opacity\n"

#endif
