/* Internal: procedural mesh building blocks and joint rotations for the
 * built-in scenes (scene.c). Meshes are grown in an ss_mb builder; every
 * generator emits faces counter-clockwise seen from outside. */
#ifndef SKIN_SIM_SCENE_GEOM_H
#define SKIN_SIM_SCENE_GEOM_H

#define SS_PI 3.14159265358979323846

#include "ss_mesh_build.h" /* ss_mb: the growable mesh */

/* Capsule of radius r around a cylinder of half-length hc, as a latitude-
 * longitude mesh: two poles, nring rings of nseg vertices (every other ring
 * turned half a segment, so triangles are near equilateral), 2 nseg nring faces.
 * Its axis runs along world axis `axis` (0 x, 2 z) through center. */
void ss_mb_capsule(ss_mb *mb, const double center[3], int axis, double r, double hc, int nseg,
                   int nring);
/* Rings and segments giving edges of about h on a capsule (at least 1 and 6). */
int ss_capsule_rings(double r, double hc, double h);
int ss_capsule_segs(double r, double h);

/* A closed thin plate: top grid at z = +t/2 and bottom grid at z = -t/2 over
 * [x0, x0 + lx] x [-ly/2, ly/2] with nx x ny cells each, joined by a rim strip.
 * 4 nx ny + 4 (nx + ny) faces. */
void ss_mb_plate(ss_mb *mb, double x0, double lx, double ly, double t, int nx, int ny);

/* An open grid sheet in the plane z = 0 (normal +z) over the coordinates
 * xs[0..nx] x ys[0..ny]. Cells flagged in tflag[j nx + c] (may be NULL) get a T-junction: a
 * vertex in the middle of their left edge and a zero-area face (exactly
 * collinear corners) closing it against the left neighbour. */
void ss_mb_sheet(ss_mb *mb, const double *xs, int nx, const double *ys, int ny,
                 const unsigned char *tflag);

/* An open sheet in the plane z = 0 (normal +z) over [x0, x0 + lx] x [y0, y0 + ly]
 * as a near-equilateral lattice: ny + 1 rows, odd rows shifted half of the
 * lx / nx spacing (with corner vertices at both ends). ny (2 nx + 1) faces. */
void ss_mb_lattice(ss_mb *mb, double x0, double lx, double y0, double ly, int nx, int ny);

/* Smoothstep of u clamped to [0, 1]: 0 below, 1 above, C1. */
double ss_smooth(double u);
/* Rotates p in place about the axis parallel to world axis `axis` through c by
 * angle a (right-handed). a == 0 leaves p bit-identical. */
void ss_rotate(double p[3], int axis, const double c[3], double a);

#endif
