/* The `quadruped` built-in scene: a raccoon-scale four-legged body (the paper's
 * Figure 1 raccoon had 18,929 triangles; ours defaults to ~19,000) in a fast
 * gallop whose hind legs swing forward THROUGH the belly, so the body mesh
 * intersects itself as the raccoon's did in its fight scene.
 *
 * Geometry (metres; x forward, z up, y to the left). Eight closed capsules of
 * near-equilateral triangles, all with the same edge length h (the torso's
 * circumference over the resolution n): a torso (radius 0.12, 0.64 long), a
 * neck tilted 50 degrees up from the torso's front, a head with its snout
 * forward, a tail drooping back, and four legs (radius 0.04, 0.36 long,
 * hanging from hips/shoulders inside the torso down to the ground). The parts
 * are SEPARATE closed components of one mesh that overlap where they join
 * (each leg's top, the neck's and the tail's base lie inside the torso; the
 * head overlaps the neck), like the armpit scene's arm: no welding, so no
 * junction geometry to get wrong; each component is watertight and oriented
 * outward (counter-clockwise seen from outside).
 *
 * Motion, posed like a linear-blend-skinned character with smooth joint
 * blends (see scene.c): a rotary gallop of 2.5 strides per second (a stride
 * every 12 frames at 30 fps), ramped in over the first 6 frames so that frame
 * 0 is the rest pose, then periodic for ever. All joints turn about lateral
 * (y) axes. Each leg bends at its knee/elbow (a smoothstep blend of +-1.5 leg
 * radii about a hinge half a radius towards the outer side) and turns rigidly
 * at its hip/shoulder; the hind legs swing from 35 degrees back to 85 degrees
 * forward, where their upper halves lie inside the belly (the hips are 5 cm
 * below the spine); the front legs swing from 40 degrees forward to 50 back,
 * under the chest. Knees flex 0-60 degrees (hind, most while swinging
 * forward) and elbows 0-80 (front, most while reaching forward), the paw
 * going back. At the peak speed a paw moves ~0.17 m (15 edges) per frame. The spine flexes +-12 degrees at each half (arched when the
 * legs gather, extended when they stretch), blended over the middle 0.3 m;
 * legs follow the spine at their hips, the neck and head nod, the tail swings.
 * Left and right legs are out of phase as in a rotary gallop. */
#include "scene_quadruped.h"

#include <math.h>

#define DEG (SS_PI / 180.0)

/* ---- the body at rest ---- */

/* A capsule part: center, radius, half cylinder, axis (0 x, 2 z) and a tilt
 * about the y axis through its center (radians). */
typedef struct part {
  double c[3], r, hc;
  int axis;
  double tilt;
} part;

static const double TORSO_R = 0.12;
static const double LEG_R = 0.04, LEG_HC = 0.14, LEG_Y = 0.07, LEG_Z = -0.20;
static const double HIP_X = 0.18, HIP_Z = -0.05, KNEE_Z = -0.21;
static const double KNEE_W = 1.5, KNEE_OUT = 0.5; /* blend half-width, hinge offset: leg radii */
static const double SPINE_W = 0.15;               /* spine blend half-width */
static const double NECK_BASE[3] = {0.25, 0.0, 0.04}, TAIL_BASE[3] = {-0.27, 0.0, 0.04};

enum { TORSO, NECK, HEAD, TAIL, LEG0, NPART = LEG0 + SS_QUAD_LEGS };

/* Leg k: 0 left hind, 1 right hind, 2 left front, 3 right front. */
static double leg_x(int k) { return k < 2 ? -HIP_X : HIP_X; }
static double leg_y(int k) { return (k & 1) ? -LEG_Y : LEG_Y; }

static part get_part(int i) {
  const part fixed[LEG0] = {
      {{0.0, 0.0, 0.0}, TORSO_R, 0.20, 0, 0.0},         /* torso */
      {{0.30, 0.0, 0.10}, 0.055, 0.05, 0, -50.0 * DEG}, /* neck, front end up */
      {{0.41, 0.0, 0.19}, 0.065, 0.045, 0, 10.0 * DEG}, /* head, snout a little down */
      {{-0.41, 0.0, 0.0}, 0.035, 0.11, 0, -15.0 * DEG}, /* tail, far end down */
  };
  if (i < LEG0) return fixed[i];
  int k = i - LEG0;
  part p = {{leg_x(k), leg_y(k), LEG_Z}, LEG_R, LEG_HC, 2, 0.0};
  return p;
}

static double edge_h(int n) { return 2.0 * SS_PI * TORSO_R / n; }

long long ss_quad_faces(int n) {
  double h = edge_h(n);
  long long nf = 0;
  for (int i = 0; i < NPART; i++) {
    part p = get_part(i);
    nf += 2LL * ss_capsule_segs(p.r, h) * ss_capsule_rings(p.r, p.hc, h);
  }
  return nf;
}

void ss_quad_build(ss_mb *mb, int n, ss_quad *q) {
  double h = edge_h(n);
  for (int i = 0; i < NPART; i++) {
    part p = get_part(i);
    int first = mb->nv;
    const double o[3] = {0.0, 0.0, 0.0};
    /* built about the origin, tilted, then moved: rigid, so still outward */
    ss_mb_capsule(mb, o, p.axis, p.r, p.hc, ss_capsule_segs(p.r, h),
                  ss_capsule_rings(p.r, p.hc, h));
    for (int v = first; v < mb->nv && !mb->failed; v++) {
      double *x = mb->pos + 3 * v;
      ss_rotate(x, 1, o, p.tilt);
      for (int c = 0; c < 3; c++) x[c] += p.c[c];
    }
    int *range = i == TORSO ? q->torso
                 : i == NECK ? q->neck
                 : i == HEAD ? q->head
                 : i == TAIL ? q->tail
                             : q->leg[i - LEG0];
    range[0] = first;
    range[1] = mb->nv;
  }
}

/* ---- the gallop ---- */

static const double PERIOD = 12.0, RAMP = 6.0; /* frames */
static const double HIND_MID = -25.0 * DEG, HIND_AMP = 60.0 * DEG; /* + is backwards */
static const double FRONT_MID = 5.0 * DEG, FRONT_AMP = 45.0 * DEG;
static const double HIND_KNEE = 60.0 * DEG, FRONT_KNEE = 80.0 * DEG;
static const double SPINE = 12.0 * DEG, NOD = 10.0 * DEG, TAIL_SWING = 20.0 * DEG;
/* phase offsets of the legs (rotary gallop: left hind leads) */
static const double LEG_PHASE[SS_QUAD_LEGS] = {0.0, 0.6, -0.5, -1.1};

/* The spine's rotation at rest coordinate x: -a behind, +a in front. */
static double spine_angle(double x, double a) {
  return a * (2.0 * ss_smooth((x + SPINE_W) / (2.0 * SPINE_W)) - 1.0);
}

void ss_quad_pose(const ss_quad *q, const double *rest, double t, double amount, double *pos) {
  const double o[3] = {0.0, 0.0, 0.0};
  double g = amount * ss_smooth(t / RAMP); /* 0 at rest, 1 after the ramp */
  double ph = 2.0 * SS_PI * t / PERIOD;
  double spine = g * SPINE * sin(ph);

  for (int k = 0; k < SS_QUAD_LEGS; k++) {
    double s = sin(ph + LEG_PHASE[k]);
    double hip, knee;
    if (k < 2) { /* hind: forward (negative) when the legs gather (s = 1) */
      hip = g * (HIND_MID - HIND_AMP * s);
      knee = g * HIND_KNEE * (0.5 + 0.5 * sin(ph + LEG_PHASE[k] - 0.5));
    } else { /* front: back under the chest when the legs gather */
      hip = g * (FRONT_MID + FRONT_AMP * s);
      knee = g * FRONT_KNEE * (0.5 - 0.5 * s);
    }
    const double hip_c[3] = {leg_x(k), 0.0, HIP_Z};
    const double knee_c[3] = {leg_x(k) + KNEE_OUT * LEG_R, 0.0, KNEE_Z};
    double w = KNEE_W * LEG_R, a_spine = spine_angle(leg_x(k), spine);
    for (int v = q->leg[k][0]; v < q->leg[k][1]; v++) {
      double *p = pos + 3 * v;
      ss_rotate(p, 1, knee_c, knee * ss_smooth((KNEE_Z + w - rest[3 * v + 2]) / (2.0 * w)));
      ss_rotate(p, 1, hip_c, hip);
      ss_rotate(p, 1, o, a_spine);
    }
  }
  double nod = g * NOD * sin(ph + 1.0), wag = g * TAIL_SWING * sin(ph + 2.0);
  for (int v = q->neck[0]; v < q->head[1]; v++) ss_rotate(pos + 3 * v, 1, NECK_BASE, nod);
  for (int v = q->tail[0]; v < q->tail[1]; v++) ss_rotate(pos + 3 * v, 1, TAIL_BASE, wag);
  for (int v = q->torso[0]; v < q->tail[1]; v++) /* torso, neck, head, tail */
    ss_rotate(pos + 3 * v, 1, o, spine_angle(rest[3 * v], spine));
}
