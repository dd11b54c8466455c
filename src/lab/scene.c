/* The built-in scenes: procedural bodies where anchor methods fail.
 *
 * Each scene is a body mesh generated here at any resolution (about `tris`
 * triangles) and a scripted motion, posed like a linear-blend-skinned
 * character: parts rotate rigidly about joints, and across a joint's blend
 * region the rotation angle ramps smoothly (a smoothstep of the rest
 * coordinate), which keeps limbs round where matrix blending would pinch them.
 * Capsules are latitude-longitude meshes with every other ring turned half a
 * segment (near-equilateral triangles; thin fans at the poles); the boundary
 * sheet is a near-equilateral lattice; fold and slivers are grids of right
 * triangles. Units are metres, 30 frames per second; frame 0
 * is the rest pose, bit for bit; poses are defined for any frame >= 0 (armpit
 * and elbow hold their end pose, twist keeps spinning, the rest oscillate).
 * The anchor tracking experiment (track.c) seeds anchors at every vertex and
 * face barycenter, lets them ride with the body, pulls each back towards where
 * it was a frame ago lifted 0.1 edge lengths off the surface (lagging skin) and
 * moves it by walk or by Euclidean projection. Why each scene is hard:
 *
 *  armpit   A torso (capsule, radius 0.28 m) and an arm (capsule, radius
 *           0.075 m) hinged at the shoulder. The arm swings down from a
 *           T-pose by 97 degrees, past vertical, and presses into the torso:
 *           at the end the arm's inner side lies up to ~0.056 m (1.3 edges
 *           at the default size) inside the torso. The two parts are SEPARATE
 *           closed components of one mesh (arm not welded to the torso; its
 *           root cap sits 1 cm from the torso). Lagging points on the arm lie
 *           nearer the torso than their own sheet: projection jumps across
 *           (a snag); the walk stays on the arm.
 *  elbow    A capsule tube (radius 0.09 m) bent at its middle by 135 degrees
 *           about a hinge 0.8 radii towards the outer side, blended over
 *           +-1.5 radii: the inner side of the crease folds sharply (it
 *           inverts and passes through itself), the outer side stretches
 *           by at most ~25%. (A hinge on the axis stretches the outer side
 *           ~2x, and edge-path surface distances then overstate walks there.)
 *  fold     A closed thin flap (plate 0.8 x 0.5 m, thickness 0.4 grid
 *           spacings: its two sides are closer than one edge) hinged at its
 *           root, flapping +-0.5 rad every second: the tip moves several edge
 *           lengths per frame along its normal, so a point lagging behind on
 *           one side ends up nearer the other side. Projection snaps it
 *           through; the walk cannot leave its side.
 *  twist    A capsule (radius 0.15 m) spinning about its axis at 4.3 grid
 *           segments per frame after a short ramp: every anchor must cross
 *           many faces per frame (cost and step limits of the walk).
 *  slivers  An open wavy sheet of badly conditioned triangles: every fourth
 *           column is 1/300 of the row spacing wide (aspect ratio ~300) and
 *           T-junctions closed by exactly zero-area faces (three collinear
 *           corners; they stay collinear in every pose since the motion maps
 *           points by their x and z alone). Two joints bend it to and fro.
 *  boundary An open rectangular sheet (boundary edges all round) that slides
 *           and turns in its plane and bends at a joint: lagging anchors near
 *           its trailing border are pulled off the sheet and must stop on it.
 *  quadruped A raccoon-scale four-legged body (~19,000 triangles, the paper's
 *           Figure 1 raccoon had 18,929) in a fast gallop, 2.5 strides per
 *           second: the hind legs swing forward through the belly (the body
 *           mesh intersects itself), the front legs back under the chest, the
 *           spine flexes. Torso, neck, head, tail and legs are separate closed
 *           capsules overlapping where they join. Built and posed in
 *           scene_quadruped.c.
 */
#include "ss_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene_geom.h"
#include "scene_quadruped.h"
#include "ss_err.h"

enum { ARMPIT, ELBOW, FOLD, TWIST, SLIVERS, BOUNDARY, QUADRUPED, NSCENE }; /* append only */

static const struct scene_info {
  const char *name, *about;
  int default_tris, frames;
} scene_infos[NSCENE] = {
    {"armpit", "an arm swings down into the torso: the body mesh intersects itself", 4000, 72},
    {"elbow", "a tube bends 135 degrees at a joint: a sharp crease on the inner side", 3000, 70},
    {"fold", "a flap thinner than an edge flaps fast: lagging points near the other side", 3000,
     90},
    {"twist", "a capsule spins about its axis: anchors cross many faces per frame", 3000, 60},
    {"slivers", "a bending sheet of slivers (aspect ~300) and zero-area faces", 3000, 80},
    {"boundary", "an open sheet slides and bends: lagging anchors reach its border", 2500, 90},
    {"quadruped", "a raccoon-scale body gallops: the hind legs pass through the belly", 19000,
     90},
};

#define MIN_TRIS 100
#define MAX_TRIS 5000000

/* ---- geometry constants (metres, radians) ---- */
static const double ARM_TORSO_R = 0.28, ARM_TORSO_HC = 0.45; /* torso radius, half cylinder */
static const double ARM_R = 0.075, ARM_HC = 0.275;           /* arm radius, half cylinder */
static const double ARM_GAP = 0.01, ARM_SHOULDER_Z = 0.32;
static const double ARM_SWING = (97.0 / 180.0) * SS_PI, ARM_SWING_FRAMES = 45.0;
static const double ELBOW_R = 0.09, ELBOW_HC = 0.5;
static const double ELBOW_BLEND = 1.5, ELBOW_AXIS_Z = -0.8; /* blend half-width, axis offset: radii */
static const double ELBOW_BEND = (135.0 / 180.0) * SS_PI, ELBOW_FRAMES = 50.0;
static const double FOLD_L = 0.8, FOLD_W = 0.5, FOLD_THICK = 0.4; /* thickness in grid spacings */
static const double FOLD_X0 = 0.08, FOLD_X1 = 0.28;              /* hinge blend region */
static const double FOLD_AMP = 0.5, FOLD_PERIOD = 30.0;
static const double TWIST_R = 0.15, TWIST_HC = 0.35, TWIST_SEGS_PER_FRAME = 4.3;
static const double TWIST_RAMP = 10.0;
static const double SLIV_L = 1.0, SLIV_W = 0.6, SLIV_THIN = 1.0 / 300.0, SLIV_PERIOD = 80.0;
static const double BND_L = 1.0, BND_W = 0.6;

struct ss_scene {
  int kind;
  int nvert, nface;
  double *rest;
  int *faces;
  int arm_first;  /* armpit: first vertex of the arm */
  ss_quad quad;   /* quadruped: where its parts lie */
  double omega;   /* twist: peak angular speed, radians per frame */
};

/* ---- layout: counts from one resolution parameter n ---- */

typedef struct plan {
  double h;
  int a, b, c, d;   /* per scene: segments/rings, cells, ... */
} plan;

/* Slivers: n + 1 grid coordinates over len, plus a thin cell after every
 * period-th (none if period is 0); writes xs unless NULL; returns the cells. */
static int sliver_coords(int n, double h, double len, int period, double *xs) {
  int k = 0;
  for (int i = 0; i <= n; i++) {
    double x = -0.5 * len + len * i / n;
    if (xs) xs[k] = x;
    k++;
    if (period > 0 && i % period == period / 2 && i < n) {
      if (xs) xs[k] = x + SLIV_THIN * h;
      k++;
    }
  }
  return k - 1; /* cells */
}

static int sliver_tcell(int c, int j, const double *xs, const double *ys, double h) {
  return c >= 1 && xs[c + 1] - xs[c] > 0.5 * h && ys[j + 1] - ys[j] > 0.5 * h &&
         (3 * c + 5 * j) % 13 == 0;
}

static plan make_plan(int kind, int n) {
  plan p = {0};
  switch (kind) {
    case ARMPIT:
      p.h = 2.0 * SS_PI * ARM_TORSO_R / n;
      p.a = n;
      p.b = ss_capsule_rings(ARM_TORSO_R, ARM_TORSO_HC, p.h);
      p.c = ss_capsule_segs(ARM_R, p.h);
      p.d = ss_capsule_rings(ARM_R, ARM_HC, p.h);
      break;
    case ELBOW:
    case TWIST: {
      double r = kind == ELBOW ? ELBOW_R : TWIST_R, hc = kind == ELBOW ? ELBOW_HC : TWIST_HC;
      p.h = 2.0 * SS_PI * r / n;
      p.a = n;
      p.b = ss_capsule_rings(r, hc, p.h);
      break;
    }
    case FOLD:
    case SLIVERS:
    case BOUNDARY: {
      double len = kind == FOLD ? FOLD_L : kind == SLIVERS ? SLIV_L : BND_L;
      double wid = kind == FOLD ? FOLD_W : kind == SLIVERS ? SLIV_W : BND_W;
      p.h = wid / n; /* row spacing; boundary's lattice spaces columns 2/sqrt(3) wider */
      p.a = (int)lround(len / (kind == BOUNDARY ? 1.1547005383792515 * p.h
                               : kind == SLIVERS  ? 1.25 * p.h
                                                  : p.h));
      if (p.a < 2) p.a = 2;
      p.b = n;
      break;
    }
    case QUADRUPED:
      p.a = n; /* segments around the torso */
      break;
  }
  return p;
}

static long long plan_faces(int kind, const plan *p) {
  switch (kind) {
    case ARMPIT: return 2LL * p->a * p->b + 2LL * p->c * p->d;
    case ELBOW:
    case TWIST: return 2LL * p->a * p->b;
    case QUADRUPED: return ss_quad_faces(p->a);
    case FOLD: return 4LL * p->a * p->b + 4LL * (p->a + p->b);
    case BOUNDARY: return (2LL * p->a + 1) * p->b;
    case SLIVERS: { /* thin columns only: T-cells counted on column indices */
      int nx = sliver_coords(p->a, p->h, SLIV_L, 4, NULL);
      long long nt = 0;
      for (int i = 0, c = -1; i < p->a; i++) {
        c += (i % 4 == 2) ? 2 : 1; /* this normal column, after any thin one */
        for (int j = 0; j < p->b; j++) nt += c >= 1 && (3 * c + 5 * j) % 13 == 0;
      }
      return 2LL * nx * p->b + 2 * nt;
    }
  }
  return 0;
}

static int min_n(int kind) {
  if (kind == SLIVERS) return 3;
  return (kind == ARMPIT || kind == ELBOW || kind == TWIST || kind == QUADRUPED) ? 6 : 2;
}

/* The resolution whose face count is nearest to tris. */
static int choose_n(int kind, int tris) {
  int lo = min_n(kind), hi = lo;
  for (;;) {
    plan p = make_plan(kind, hi);
    if (plan_faces(kind, &p) >= tris || hi > (1 << 20)) break;
    lo = hi;
    hi *= 2;
  }
  while (hi - lo > 1) { /* invariant: faces(hi) >= tris (or hi is the cap) */
    int mid = lo + (hi - lo) / 2;
    plan p = make_plan(kind, mid);
    if (plan_faces(kind, &p) >= tris)
      hi = mid;
    else
      lo = mid;
  }
  plan pl = make_plan(kind, lo), ph = make_plan(kind, hi);
  long long fl = plan_faces(kind, &pl), fh = plan_faces(kind, &ph);
  return llabs(fl - tris) < llabs(fh - tris) ? lo : hi;
}

/* ---- building ---- */

static int build(ss_scene *s, ss_mb *mb, int n) {
  plan p = make_plan(s->kind, n);
  switch (s->kind) {
    case ARMPIT: {
      const double torso[3] = {0.0, 0.0, 0.0};
      const double arm[3] = {ARM_TORSO_R + ARM_GAP + ARM_R + ARM_HC, 0.0, ARM_SHOULDER_Z};
      ss_mb_capsule(mb, torso, 2, ARM_TORSO_R, ARM_TORSO_HC, p.a, p.b);
      s->arm_first = mb->nv;
      ss_mb_capsule(mb, arm, 0, ARM_R, ARM_HC, p.c, p.d);
      break;
    }
    case ELBOW:
    case TWIST: {
      const double o[3] = {0.0, 0.0, 0.0};
      if (s->kind == ELBOW)
        ss_mb_capsule(mb, o, 0, ELBOW_R, ELBOW_HC, p.a, p.b);
      else
        ss_mb_capsule(mb, o, 0, TWIST_R, TWIST_HC, p.a, p.b);
      s->omega = TWIST_SEGS_PER_FRAME * 2.0 * SS_PI / p.a;
      break;
    }
    case QUADRUPED:
      ss_quad_build(mb, p.a, &s->quad);
      break;
    case FOLD:
      ss_mb_plate(mb, 0.0, FOLD_L, FOLD_W, FOLD_THICK * p.h, p.a, p.b);
      break;
    case BOUNDARY:
      ss_mb_lattice(mb, -0.5 * BND_L, BND_L, -0.5 * BND_W, BND_W, p.a, p.b);
      break;
    case SLIVERS: {
      int nx = sliver_coords(p.a, p.h, SLIV_L, 4, NULL);
      int ny = sliver_coords(p.b, p.h, SLIV_W, 0, NULL);
      double *xs = malloc(sizeof(double) * (size_t)(nx + 1));
      double *ys = malloc(sizeof(double) * (size_t)(ny + 1));
      unsigned char *tflag = calloc((size_t)nx * (size_t)ny, 1);
      if (!xs || !ys || !tflag) {
        free(xs);
        free(ys);
        free(tflag);
        return SS_E_NOMEM;
      }
      sliver_coords(p.a, p.h, SLIV_L, 4, xs);
      sliver_coords(p.b, p.h, SLIV_W, 0, ys);
      for (int j = 0; j < ny; j++)
        for (int c = 0; c < nx; c++)
          tflag[(size_t)j * nx + c] = (unsigned char)sliver_tcell(c, j, xs, ys, p.h);
      ss_mb_sheet(mb, xs, nx, ys, ny, tflag);
      free(xs);
      free(ys);
      free(tflag);
      break;
    }
  }
  return mb->failed ? SS_E_NOMEM : SS_OK;
}

/* ---- public API ---- */

int ss_scene_count(void) { return NSCENE; }

const char *ss_scene_name(int index) {
  return index >= 0 && index < NSCENE ? scene_infos[index].name : NULL;
}

const char *ss_scene_about(int index) {
  return index >= 0 && index < NSCENE ? scene_infos[index].about : NULL;
}

int ss_scene_create(ss_scene **out, const char *name, int tris, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "scene: NULL output pointer");
  *out = NULL;
  int kind = -1;
  for (int i = 0; name && i < NSCENE; i++)
    if (strcmp(name, scene_infos[i].name) == 0) kind = i;
  if (kind < 0)
    return ss_fail(err, err_sz, SS_E_ARG,
                   "unknown scene '%s' (valid: armpit, elbow, fold, twist, slivers, boundary, "
                   "quadruped)",
                   name ? name : "(null)");
  if (tris != 0 && (tris < MIN_TRIS || tris > MAX_TRIS))
    return ss_fail(err, err_sz, SS_E_ARG,
                   "scene %s: triangle count %d is out of range (0 for the default, or %d to %d)",
                   name, tris, MIN_TRIS, MAX_TRIS);
  if (tris == 0) tris = scene_infos[kind].default_tris;

  ss_scene *s = calloc(1, sizeof *s);
  if (!s) return ss_fail(err, err_sz, SS_E_NOMEM, "scene %s: out of memory", name);
  s->kind = kind;
  ss_mb mb = {0};
  int status = build(s, &mb, choose_n(kind, tris));
  if (status) {
    ss_mb_free(&mb);
    free(s);
    return ss_fail(err, err_sz, status, "scene %s: out of memory for %d triangles", name, tris);
  }
  s->nvert = mb.nv;
  s->nface = mb.nf;
  s->rest = mb.pos;
  s->faces = mb.tri;
  *out = s;
  return SS_OK;
}

void ss_scene_destroy(ss_scene *scene) {
  if (!scene) return;
  free(scene->rest);
  free(scene->faces);
  free(scene);
}

const char *ss_scene_get_name(const ss_scene *scene) { return scene_infos[scene->kind].name; }
int ss_scene_nvert(const ss_scene *scene) { return scene->nvert; }
int ss_scene_nface(const ss_scene *scene) { return scene->nface; }
const int *ss_scene_faces(const ss_scene *scene) { return scene->faces; }
const double *ss_scene_rest(const ss_scene *scene) { return scene->rest; }
int ss_scene_default_frames(const ss_scene *scene) { return scene_infos[scene->kind].frames; }
double ss_scene_fps(const ss_scene *scene) { return 30.0; }

/* ---- motion ---- */

/* Smooth periodic signal that starts at rest: sin ramped in over 8 frames. */
static double wave(double t, double period, double phase) {
  return sin(2.0 * SS_PI * t / period + phase) * ss_smooth(t / 8.0);
}

/* Rotates p about the y-parallel line through (x, 0, z) by a times the blend
 * weight of rest coordinate rx across [x - w, x + w]. */
static void joint_y(double p[3], double rx, double x, double z, double w, double a) {
  const double c[3] = {x, 0.0, z};
  ss_rotate(p, 1, c, a * ss_smooth((rx - (x - w)) / (2.0 * w)));
}

/* The pose of frame t > 0 with every joint angle and offset of the motion
 * times `amount` (1: the motion itself, bit for bit; 0: rest). The twist's
 * spin is first taken modulo a turn (the same pose), so that its way back
 * to rest is less than half a turn. */
static void pose_scaled(const ss_scene *s, double t, double amount, double *pos) {
  const int nv = s->nvert;
  const double *rest = s->rest;
  const double o[3] = {0.0, 0.0, 0.0};
  switch (s->kind) {
    case ARMPIT: {
      const double pivot[3] = {ARM_TORSO_R + ARM_GAP + ARM_R, 0.0, ARM_SHOULDER_Z};
      double a = amount * ARM_SWING * ss_smooth(t / ARM_SWING_FRAMES);
      for (int v = s->arm_first; v < nv; v++) ss_rotate(pos + 3 * v, 1, pivot, a);
      break;
    }
    case ELBOW: {
      double a = -amount * ELBOW_BEND * ss_smooth(t / ELBOW_FRAMES);
      for (int v = 0; v < nv; v++)
        joint_y(pos + 3 * v, rest[3 * v], 0.0, ELBOW_AXIS_Z * ELBOW_R, ELBOW_BLEND * ELBOW_R, a);
      break;
    }
    case FOLD: {
      double a = amount * FOLD_AMP * wave(t, FOLD_PERIOD, 0.0);
      double mid = 0.5 * (FOLD_X0 + FOLD_X1), half = 0.5 * (FOLD_X1 - FOLD_X0);
      for (int v = 0; v < nv; v++) joint_y(pos + 3 * v, rest[3 * v], mid, 0.0, half, a);
      break;
    }
    case TWIST: {
      /* angular speed ramps in smoothly (smoothstep), then stays constant */
      double u = t / TWIST_RAMP;
      double a = u < 1.0 ? s->omega * TWIST_RAMP * (u * u * u - 0.5 * u * u * u * u)
                         : s->omega * (0.5 * TWIST_RAMP + (t - TWIST_RAMP));
      if (amount != 1.0) a = amount * remainder(a, 2.0 * SS_PI);
      for (int v = 0; v < nv; v++) ss_rotate(pos + 3 * v, 0, o, a);
      break;
    }
    case SLIVERS: {
      double a1 = amount * 0.45 * wave(t, SLIV_PERIOD, 0.0);
      double a2 = amount * 0.6 * wave(t, SLIV_PERIOD, 1.0);
      for (int v = 0; v < nv; v++) { /* distal joint first, in rest space */
        joint_y(pos + 3 * v, rest[3 * v], 0.2, 0.0, 0.08, a2);
        joint_y(pos + 3 * v, rest[3 * v], -0.15, 0.0, 0.08, a1);
      }
      break;
    }
    case BOUNDARY: {
      double bend = amount * 0.7 * sin(SS_PI * t / 60.0) * sin(SS_PI * t / 60.0);
      double turn = amount * 0.3 * wave(t, 60.0, 0.0);
      double dx = amount * 0.15 * wave(t, 45.0, 0.0), dy = amount * 0.05 * wave(t, 30.0, 0.0);
      for (int v = 0; v < nv; v++) {
        double *p = pos + 3 * v;
        joint_y(p, rest[3 * v], 0.2, 0.0, 0.1, bend);
        ss_rotate(p, 2, o, turn);
        p[0] += dx;
        p[1] += dy;
      }
      break;
    }
    case QUADRUPED:
      ss_quad_pose(&s->quad, rest, t, amount, pos);
      break;
  }
}

void ss_scene_pose(const ss_scene *s, double frame, double *pos) {
  ss_scene_pose_toward_rest(s, frame, 0.0, pos);
}

void ss_scene_pose_toward_rest(const ss_scene *s, double frame, double w, double *pos) {
  memcpy(pos, s->rest, sizeof(double) * 3 * (size_t)s->nvert);
  double t = frame > 0.0 ? frame : 0.0; /* NaN and negatives: rest */
  if (t > 1e6) t = 1e6;
  if (!(w < 1.0) || t == 0.0) return; /* w NaN: rest */
  pose_scaled(s, t, w > 0.0 ? 1.0 - w : 1.0, pos);
}
