/* The per-draw record that the vertex stage's one input, OIT_IN_DRAW
 * (frag_glsl.h), reads: for the single draws of gpu_mesh.c and the
 * multi-draws of gpu_mesh_many.c alike, from a buffer through a vertex
 * array attribute with divisor 1, so that a draw's baseInstance picks its
 * record. No draw reads the attribute's current value (glVertexAttribI*):
 * GL leaves it undefined after a draw that sourced the attribute from an
 * array, a driver may latch it lazily, and a vertex array with no array
 * enabled is where drivers differ most. */
#ifndef OIT_RENDER_GPU_DRAW_RECORD_H
#define OIT_RENDER_GPU_DRAW_RECORD_H

#include "view/render/gl/frag_glsl.h"

/* (the draw's first vertex in its OIT_BIND_VERTS binding, the prim of its
 * first triangle or 0x80000000 | the word index of its first prim in its
 * OIT_BIND_PRIMS binding) */
typedef struct oit_draw_rec {
    GLuint first_vertex, first_prim;
} oit_draw_rec;

/* Makes vao's OIT_IN_DRAW read record baseInstance + instance of records
 * (binding 0, divisor 1). Called again whenever records names another
 * buffer: a vertex array holds the buffer it was given. */
static inline void oit_draw_records_attach(GLuint vao, GLuint records)
{
    glEnableVertexArrayAttrib(vao, OIT_IN_DRAW);
    glVertexArrayAttribIFormat(vao, OIT_IN_DRAW, 2, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(vao, OIT_IN_DRAW, 0);
    glVertexArrayVertexBuffer(vao, 0, records, 0, sizeof(oit_draw_rec));
    glVertexArrayBindingDivisor(vao, 0, 1);
}

#endif
