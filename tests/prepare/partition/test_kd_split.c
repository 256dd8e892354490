/* prepare/partition/kd_split.h: the split plane over piece boxes cuts no piece,
 * balances the halves' layers, falls on a subgrid boundary, and is not put
 * between coincident faces. */
#include <stdint.h>
#include <stdio.h>

#include "prepare/partition/kd.h"
#include "prepare/partition/kd_split.h"
#include "tests/lib/test_check.h"

/* Ten separate pieces along x: the chosen plane must cut none of them, leave
 * ceil(20/8) = 3 parts' worth, and be exactly a subgrid boundary. */
static void test_kd_split(void)
{
    oit_kd_piece_box b[10];
    for (int i = 0; i < 10; i++)
        b[i] = (oit_kd_piece_box){{(float)i, 0, 0}, {(float)i + 0.5f, 1, 1}, 2, 0, 0};
    float lo[3] = {0, 0, 0}, hi[3] = {16, 16, 16}, pos = 0, origin[3], cell[3];
    int axis = -1;
    CHECK(oit_kd_choose_split(b, 10, lo, hi, 8, &axis, &pos), "no split for 10 pieces");
    CHECK(axis == 0, "split on axis %d, want x", axis);
    uint32_t below = 0, above = 0;
    for (int i = 0; i < 10; i++) {
        CHECK(!(b[i].lo[0] < pos && b[i].hi[0] > pos), "split at %g cuts piece %d", pos, i);
        below += b[i].hi[0] <= pos ? 2 : 0;
        above += b[i].lo[0] >= pos ? 2 : 0;
    }
    CHECK((below + 7) / 8 + (above + 7) / 8 == 3, "split at %g leaves %u | %u layers", pos,
          below, above);
    CHECK(oit_kd_split_cells(lo, hi, 0, pos, origin, cell) && origin[0] + cell[0] == pos &&
              origin[0] <= lo[0] && origin[0] + 2 * cell[0] >= hi[0],
          "split at %g is not one subgrid boundary", pos);
    printf("kd split: 10 pieces -> x = %g, %u | %u layers, none cut\n", pos, below, above);
}

/* Every dyadic plane of [0, 16] falls inside some piece; only a plane at a
 * piece's own end or start (5.5 or 5.6) separates them without a cut. */
static void test_kd_split_events(void)
{
    static const float x[5][2] = {{0.5f, 5.5f}, {5.6f, 8.5f}, {8.6f, 11.5f}, {11.6f, 15.5f},
                                  {1.5f, 4.5f}};
    oit_kd_piece_box b[5];
    for (int i = 0; i < 5; i++)
        b[i] = (oit_kd_piece_box){{x[i][0], 0, 0}, {x[i][1], 1, 1}, 2, 0, 0};
    float lo[3] = {0, 0, 0}, hi[3] = {16, 16, 16}, pos = 0, origin[3], cell[3];
    int axis = -1;
    CHECK(oit_kd_choose_split(b, 5, lo, hi, 8, &axis, &pos) == 1, "no split for 5 pieces");
    CHECK(axis == 0 && pos >= 5.5f && pos <= 5.6f, "split on axis %d at %g, want x in "
          "[5.5, 5.6]", axis, pos);
    for (int i = 0; i < 5; i++)
        CHECK(!(b[i].lo[0] < pos && b[i].hi[0] > pos), "split at %g cuts piece %d", pos, i);
    CHECK(oit_kd_split_cells(lo, hi, 0, pos, origin, cell) && origin[0] + cell[0] == pos,
          "split at %.9g is not one subgrid boundary", pos);
    printf("kd split at piece bounds: x = %.9g, cell origin %.9g size %.9g, none cut\n", pos,
           origin[0], cell[0]);
}

/* Two pieces with faces in the plane x = 6 (a box standing on a slab): the
 * best plane by count and balance is x = 6, but there the two parts would
 * tie on coincident faces, so it must not be chosen; without the faces it
 * is (the check can fail). */
static void test_kd_split_touching(void)
{
    static const float x[5][2] = {{1, 6}, {6, 11}, {1, 6}, {6, 11}, {12, 15}};
    oit_kd_piece_box b[5];
    float lo[3] = {0, 0, 0}, hi[3] = {16, 16, 16}, pos[2] = {0, 0};
    int axis[2] = {-1, -1};
    for (int faces = 0; faces < 2; faces++) {
        for (int i = 0; i < 5; i++)
            b[i] = (oit_kd_piece_box){{x[i][0], 0, 0}, {x[i][1], 1, 1}, 2, 0, 0};
        b[0].face_hi = (uint8_t)faces;
        b[1].face_lo = (uint8_t)faces;
        CHECK(oit_kd_choose_split(b, 5, lo, hi, 8, &axis[faces], &pos[faces]) == 1,
              "no split for 5 pieces");
    }
    CHECK(axis[0] == 0 && pos[0] == 6.0f, "without faces: split on axis %d at %g, want x = 6",
          axis[0], pos[0]);
    CHECK(!(axis[1] == 0 && pos[1] == 6.0f), "split between coincident faces at x = 6");
    for (int i = 0; i < 5; i++)
        CHECK(!(axis[1] == 0 && b[i].lo[0] < pos[1] && b[i].hi[0] > pos[1]),
              "split at %g cuts piece %d", pos[1], i);
    printf("kd split with faces touching at x = 6: axis %d at %g instead\n", axis[1], pos[1]);
}

int main(void)
{
    test_kd_split();
    test_kd_split_events();
    test_kd_split_touching();
    return test_verdict();
}
