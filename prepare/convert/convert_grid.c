/* The top grid's cells (convert_internal.h): their size, origin and count
 * from the model's bounds. Cubic cells whose edge is a power of two and an
 * origin on a multiple of it: every cell face and every kd midplane below
 * it is an exact float, so clipped geometry and the grid records agree bit
 * for bit. Apart as arithmetic on bounds alone; no pass over the input. */
#include "prepare/convert/convert_internal.h"

#include <math.h>

#define MAX_TOP_CELLS_PER_AXIS 1024u

/* The fast scheme's origin: a multiple of cell / 2^j, the coarsest that
 * gives fewest cells. A grid aligned to its own cell size always has a face
 * at 0, so a model around the origin is cut in two on every axis however
 * coarse the grid; a face at a multiple of a finer power of two is still an
 * exact float (the same argument as for the cell size). */
void oit_convert_shift_origin(const float mn[3], const float mx[3], oit_bin_grid *g)
{
    for (int k = 0; k < 3; k++)
        for (int j = 1; j <= 8; j++) {
            double a = g->cell / exp2(j), o = floor(mn[k] / a) * a;
            uint32_t dims = (uint32_t)floor((mx[k] - o) / g->cell) + 1;
            if (dims < g->dims[k]) {
                g->origin[k] = (float)o;
                g->dims[k] = dims;
            }
        }
}

/* Cells of edge `cell` from the face at or below mn, as many as reach mx. */
static void grid_at_cell(const float mn[3], const float mx[3], double cell, oit_bin_grid *g)
{
    g->cell = (float)cell;
    for (int k = 0; k < 3; k++) {
        double o = floor(mn[k] / cell) * cell;
        g->origin[k] = (float)o;
        g->dims[k] = (uint32_t)floor((mx[k] - o) / cell) + 1;
    }
}

void oit_convert_choose_grid(const float mn[3], const float mx[3], uint64_t triangles,
                             uint32_t want, double per_cell, oit_bin_grid *g)
{
    double ext[3], longest = 0;
    for (int k = 0; k < 3; k++) {
        ext[k] = (double)mx[k] - mn[k];
        longest = ext[k] > longest ? ext[k] : longest;
    }
    uint32_t n = want;
    if (!n) {
        double target = ceil(triangles / per_cell);
        for (n = 1; n < MAX_TOP_CELLS_PER_AXIS; n++) {
            double cells = 1;
            for (int k = 0; k < 3; k++)
                cells *= fmax(1.0, ceil(ext[k] / (longest / n)));
            if (cells >= target)
                break;
        }
    }
    grid_at_cell(mn, mx, longest > 0 ? exp2(ceil(log2(longest / n))) : 1.0, g);
}

static uint64_t cell_count(const oit_bin_grid *g)
{
    return (uint64_t)g->dims[0] * g->dims[1] * g->dims[2];
}

/* The fast scheme's grid, when the caller gave no grid: a model whose
 * extent is its power-of-two cell size, or that straddles a face of every
 * shift, still spans two cells an axis (a bounds maximum on a cell face
 * counts in the next cell), more than the `want` cells its triangles need,
 * and every face clips. A twice or four times larger cell that still gives
 * at least `want` has faces that are as exact, and costs the kd below
 * nothing: it splits by triangle counts, not by cell size. */
void oit_convert_fewest_cells(const float mn[3], const float mx[3], uint64_t want, oit_bin_grid *g)
{
    for (int d = 1; d <= 2; d++) {
        oit_bin_grid c;
        grid_at_cell(mn, mx, (double)g->cell * 2.0, &c);
        oit_convert_shift_origin(mn, mx, &c);
        if (cell_count(&c) < cell_count(g) && cell_count(&c) >= want)
            *g = c;
    }
}
