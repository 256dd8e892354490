/* The compute capture (OIT_CAPTURE_COMPUTE, capture.h): a batch rasterized,
 * ordered and composited in GL 4.5 compute shaders, no raster pipeline, no
 * per-pixel limit, bounded memory.
 *
 * Per batch (a visibility-ordered pack, or the whole mesh in core):
 *  1. binning: one invocation a triangle pulls its vertices from the
 *     buffers the meshes already live in (the streamer's ring or cache, a
 *     mesh's own), transforms them as the vertex stage does
 *     (oit_glsl_vertex_lib), writes a record (homogeneous edge functions,
 *     clip z and w, view-space vertices, normal, tie plane, prim, colours)
 *     and counts itself into each 16x16 tile its box touches within the
 *     batch rect; an exclusive scan of the tile counts (scan_glsl.h) gives
 *     each tile's list, which a scatter fills with record indices.
 *  2. sweep, one work group a tile, one invocation a pixel: coverage of
 *     the pixel centre by every triangle of the tile's list, then the
 *     fragment of frag_glsl.h's library (the same key, tie rule, shading,
 *     section planes and opaque tests as the fragment stage; its inputs
 *     interpolated here), kept in (key, prim, record) order.
 *  3. composite front to back (oit_composite) into the frame's per-pixel
 *     state (oit_glsl_state_io), the one the other captures carry.
 *
 * Order without a store: the sweep. Each pass over the tile's list keeps
 * the OIT_COMPUTE_SWEEP least fragments after the last one composited in
 * registers (an insertion into a sorted array), composites them, and
 * passes again while one was left out. No fragment is dropped and memory
 * does not grow with depth (a record a triangle, an index a (triangle,
 * tile)); time grows with depth / OIT_COMPUTE_SWEEP passes over the list,
 * which suits the deep pixels of a visibility-ordered pack poorly but
 * needs neither a count pass over the pixels nor a fragment store. The
 * record index is the third key, so that two fragments with the same key
 * and prim (pieces of one source triangle) are both composited.
 *
 * Fill rule: a pixel is covered where its centre is inside the triangle's
 * three homogeneous edge lines (Olano and Greer 1997; no clipping at the
 * eye plane, which that formulation makes unnecessary), then clipped to
 * GL's -w <= z <= w. On an edge's line the pixel goes to the side its
 * coefficients point to, and the neighbour across a shared edge holds the
 * exact negation (precise arithmetic), so a shared edge gives each centre
 * to one triangle: a top-left rule in spirit, not GL's snapped one, which
 * the spec leaves to the implementation anyway. Pixels whose centre lies
 * within a rounding of an edge may differ from a raster method's.
 *
 * Records past one binding: a batch cannot be cut where its records
 * outgrow one storage binding (its triangles are not in visibility
 * order; the sweep must see them all), so they span up to
 * OIT_COMPUTE_BLOCKS blocks of one buffer at consecutive binding points
 * (compute_blocks.h), the shaders picking a record's block by an
 * if-chain on its index.
 *
 * No read-back within a frame: the tile lists are sized from what the
 * host knows (4 entries a triangle, or the most a batch of an earlier
 * frame needed), a tile whose list overflowed sweeps every record of the
 * batch instead (exact, slower), and the entries needed are read back at
 * the next frame's begin to size the lists; the sweep's tiles are a work
 * list written on the GPU and dispatched indirectly.
 *
 * A driver that cuts long shader loops short (llvmpipe: 65535 iterations
 * an invocation, all loops together) gets the pixels it cut resumed in
 * further dispatches from their last composited fragment
 * (glsl/compute_tiles.glsl says how they notice), indirect, over the tiles with pending pixels,
 * read back once per chunk of rounds; a probe at creation tells whether
 * the driver cuts (where it says not and a pixel is pending all the same,
 * oit_capture_end fails and the next frames read back). A tile list too
 * long for even one sweep is refused with OIT_ERR_UNSUPPORTED rather than
 * rendered short.
 *
 * Early termination: with epsilon on (capture.h), a pre-pass marks the
 * tiles of the rect whose every pixel is below epsilon; binning skips them,
 * so a saturated tile costs its triangles nothing past set-up. A pixel
 * below epsilon in a live tile skips its sweep.
 *
 * The backend (OIT_CAPTURE_OPS, capture_backend.h): the frame's output
 * passes through the resume buffer at its end (a pixel's 16 bytes, idle
 * by then). Internal to view/render/capture/.
 */
#ifndef OIT_RENDER_CAPTURE_COMPUTE_H
#define OIT_RENDER_CAPTURE_COMPUTE_H

#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_mesh.h"
#include "view/render/gl/scan_glsl.h"
#include "view/render/capture/compute_glsl.h"

/* Where the driver cuts long shader loops (llvmpipe), a batch of several
 * meshes is captured in halves of them down to this many triangles, so that
 * one sweep of a tile's list finishes within the cut: a 300K-triangle pack
 * of the 1M plant at 48x48 did not (some of its tiles' lists held nearly
 * every triangle), and such a tile is refused, not rendered short. Exact:
 * a batch's meshes are in visibility order. One mesh alone is not split. */
#define OIT_COMPUTE_CUT_BATCH 65536

typedef struct oit_compute {
    GLuint prog[OIT_COMPUTE_PROGS]; /* the frame's view and opaque uniforms set by compute_uniforms */
    GLuint recs, tiles, list, dead, resume, pending, work[2], late;
    uint64_t recs_cap, tiles_cap, list_cap, dead_cap, resume_cap, pending_cap, work_cap[2],
        late_cap;
    /* The driver cuts long loops short (a probe at creation): the sweep's
     * rounds are read back after each chunk of them. Otherwise a batch
     * reads nothing back. */
    int cuts;
    int late_armed;      /* a frame wrote k->late since it was last read */
    uint32_t round;      /* the frame's sweep rounds so far (tile stamps) */
    uint32_t chunk;      /* rounds issued between read-backs where loops are cut */
    uint64_t list_seen;  /* the most tile-list entries a batch needed (late read-back) */
    unsigned test;       /* OIT_CAPTURE_TEST_COMPUTE_* of the capture's faults */
    oit_scan scan;
    uint64_t align; /* GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT */
    /* Storage blocks a batch's records may span (OIT_COMPUTE_BLOCKS or
     * fewer, as the driver's limits allow), and the shaders' define of it. */
    int blocks;
    char blocks_decl[32];
} oit_compute;

typedef struct oit_compute_frame {
    GLuint state;                /* the frame's per-pixel state */
    int width, height;
    uint64_t bind;               /* the most bytes one storage buffer may span */
    /* the most bytes its records and tile lists take (the slot budget;
     * 0: one binding each): a batch past it is captured in halves of its
     * meshes, its lists shortened (exact: overflowed tiles sweep every
     * record) */
    uint64_t budget;
    float epsilon;               /* what this batch tests (0: nothing) */
    struct oit_gpu_timer *timer; /* phases marked on it; NULL: none */
    oit_host_waits *waits;       /* the frame's waits on the GPU (view/render/gl/host_wait.h) */
} oit_compute_frame;

/* "#define CS_BLOCKS blocks\n" into buf: the storage blocks a batch's
 * records may span (1..OIT_COMPUTE_BLOCKS, compute_glsl.h), which the
 * programs that read or write records take first. */
void oit_compute_blocks_define(int blocks, char *buf, size_t size);
/* Captures meshes[0..n) over the GL rect r (bottom rows first, exclusive
 * ends) and composites them behind the state. The records span up to
 * k->blocks storage bindings of f->bind bytes each, so that one batch
 * holds k->blocks times what one binding does. A batch past that, or
 * with 4 list entries a triangle past f->budget, is captured in halves of
 * its meshes, in order, down to one mesh; OIT_ERR_UNSUPPORTED, with the
 * numbers, where one mesh's records alone exceed the blocks. */
oit_status oit_compute_batch(oit_compute *k, const oit_compute_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4],
                             oit_error *err);

#endif
