/* The records in up to OIT_COMPUTE_BLOCKS (8) storage blocks, CS_BLOCKS of
 * them (the program's first lines define it: as many as the driver lets a
 * stage bind), u_block_recs records each, so that a batch is not limited
 * to what one binding spans. Block i holds records [i, i + 1) *
 * u_block_recs. GLSL 4.5 indexes an array of blocks only with a
 * dynamically uniform index, and a tile's records may lie in any block, so
 * the block is picked by an if-chain on the record's index; a batch within
 * one binding takes its first branch.
 *
 * Each block is named once, here: CS_RECS_EACH(X) is X(binding, block,
 * array) for each of the CS_BLOCKS blocks in order, and the pieces that
 * read or write records (compute_recs_read.glsl, compute_recs_write.glsl)
 * declare the blocks and walk the chain with it. */
uniform uint u_block_recs;
#define CS_RECS_0(X) X(OIT_BIND_FRAGS, Recs0, recs0)
#define CS_RECS_1(X) CS_RECS_0(X) X(OIT_BIND_RECS1, Recs1, recs1)
#define CS_RECS_2(X) CS_RECS_1(X) X(OIT_BIND_RECS2, Recs2, recs2)
#define CS_RECS_3(X) CS_RECS_2(X) X(OIT_BIND_RECS3, Recs3, recs3)
#define CS_RECS_4(X) CS_RECS_3(X) X(OIT_BIND_RECS4, Recs4, recs4)
#define CS_RECS_5(X) CS_RECS_4(X) X(OIT_BIND_RECS5, Recs5, recs5)
#define CS_RECS_6(X) CS_RECS_5(X) X(OIT_BIND_RECS6, Recs6, recs6)
#define CS_RECS_7(X) CS_RECS_6(X) X(OIT_BIND_RECS7, Recs7, recs7)
#if CS_BLOCKS == 1
#define CS_RECS_EACH CS_RECS_0
#elif CS_BLOCKS == 2
#define CS_RECS_EACH CS_RECS_1
#elif CS_BLOCKS == 3
#define CS_RECS_EACH CS_RECS_2
#elif CS_BLOCKS == 4
#define CS_RECS_EACH CS_RECS_3
#elif CS_BLOCKS == 5
#define CS_RECS_EACH CS_RECS_4
#elif CS_BLOCKS == 6
#define CS_RECS_EACH CS_RECS_5
#elif CS_BLOCKS == 7
#define CS_RECS_EACH CS_RECS_6
#else
#define CS_RECS_EACH CS_RECS_7
#endif
