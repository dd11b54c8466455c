/* Internal: the `quadruped` built-in scene (scene_quadruped.c), a raccoon-
 * scale four-legged body galloping so fast that its hind legs pass through its
 * belly. scene.c owns the scene list and calls these three functions. */
#ifndef SKIN_SIM_SCENE_QUADRUPED_H
#define SKIN_SIM_SCENE_QUADRUPED_H

#include "scene_geom.h"

enum { SS_QUAD_LEGS = 4 };

/* Where each part's vertices lie in the mesh (first vertex, one past last). */
typedef struct ss_quad {
  int torso[2], neck[2], head[2], tail[2];
  int leg[SS_QUAD_LEGS][2]; /* left hind, right hind, left front, right front */
} ss_quad;

/* Triangles of the body at resolution n (segments around the torso, >= 6). */
long long ss_quad_faces(int n);
/* Appends the body at resolution n to mb and records its parts in q. */
void ss_quad_build(ss_mb *mb, int n, ss_quad *q);
/* The gallop at frame t > 0 (finite), its every angle times amount (1: the
 * gallop; 0: rest): writes pos (nvert x 3) from rest, which pos must already
 * hold. Allocates nothing. */
void ss_quad_pose(const ss_quad *q, const double *rest, double t, double amount, double *pos);

#endif
