/* A body for the core's contact tests: its topology, bounding volume tree
 * and frame records at one pose, made and checked in one call. */
#ifndef SKIN_SIM_TEST_BODY_H
#define SKIN_SIM_TEST_BODY_H

#include "bvh.h"
#include "ss_test.h"
#include "walk.h"

typedef struct test_body {
  ss_topo *topo;
  ss_bvh *bvh;
  ss_frames *fr;
} test_body;

static inline void test_body_destroy(test_body *b) {
  ss_frames_destroy(b->fr);
  ss_bvh_destroy(b->bvh);
  ss_topo_destroy(b->topo);
  b->fr = NULL, b->bvh = NULL, b->topo = NULL;
}

/* The body of nface faces over nvert vertices at pos (read only while this
 * runs); 1 if made, else 0 and nothing held. */
static inline int test_body_create(test_body *b, int nvert, const double *pos, int nface, const int *faces) {
  char err[256] = "";
  b->topo = NULL, b->bvh = NULL, b->fr = NULL;
  CHECK_MSG(ss_topo_create(&b->topo, nvert, pos, nface, faces, -1.0, err, sizeof err) == SS_OK, "%s", err);
  if (b->topo) CHECK_EQ_INT(ss_bvh_create(&b->bvh, b->topo), SS_OK);
  CHECK_EQ_INT(ss_frames_create(&b->fr, nface), SS_OK);
  if (!b->topo || !b->bvh || !b->fr) {
    test_body_destroy(b);
    return 0;
  }
  ss_bvh_refit(b->bvh, pos);
  ss_frames_update(b->fr, b->topo, pos);
  return 1;
}

#endif
