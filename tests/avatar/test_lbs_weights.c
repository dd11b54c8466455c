/* Linear blend skinning and automatic (heat diffusion) weights on a tube
 * bent by a two-link arm: weights are a smooth partition of unity, each
 * vertex is dominated by its nearest link and far ends are rigid; the rest
 * pose is reproduced; a single joint's rotation rotates the rigid part
 * exactly; ssa_lbs blends matrices linearly. */
#include <string.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

#define NR 41 /* rings along x in [0, 2] */
#define NS 16 /* vertices around */
#define RAD 0.1

static const char *arm_urdf =
    "<robot name='arm'><link name='upper'/><link name='lower'/>"
    "<joint name='elbow' type='revolute'><parent link='upper'/><child link='lower'/>"
    "<origin xyz='1 0 0'/><axis xyz='0 0 1'/>"
    "<limit lower='-3' upper='3' effort='1' velocity='1'/></joint></robot>";

/* A closed tube: NR rings of NS vertices, two cap centres; outward CCW. */
static void make_tube(double *pos, int *faces, int *nv, int *nf) {
  int v = 0, f = 0;
  for (int i = 0; i < NR; i++)
    for (int j = 0; j < NS; j++) {
      double a = 2 * 3.14159265358979323846 * j / NS;
      pos[3 * v] = 2.0 * i / (NR - 1);
      pos[3 * v + 1] = RAD * cos(a);
      pos[3 * v + 2] = RAD * sin(a);
      v++;
    }
  int c0 = v++, c1 = v++;
  pos[3 * c0] = 0, pos[3 * c0 + 1] = 0, pos[3 * c0 + 2] = 0;
  pos[3 * c1] = 2, pos[3 * c1 + 1] = 0, pos[3 * c1 + 2] = 0;
  for (int i = 0; i + 1 < NR; i++)
    for (int j = 0; j < NS; j++) {
      int a = i * NS + j, b = i * NS + (j + 1) % NS, c = (i + 1) * NS + j,
          d = (i + 1) * NS + (j + 1) % NS;
      faces[3 * f] = a, faces[3 * f + 1] = b, faces[3 * f + 2] = d, f++;
      faces[3 * f] = a, faces[3 * f + 1] = d, faces[3 * f + 2] = c, f++;
    }
  for (int j = 0; j < NS; j++) {
    faces[3 * f] = c0, faces[3 * f + 1] = (j + 1) % NS, faces[3 * f + 2] = j, f++;
    int o = (NR - 1) * NS;
    faces[3 * f] = c1, faces[3 * f + 1] = o + j, faces[3 * f + 2] = o + (j + 1) % NS, f++;
  }
  *nv = v;
  *nf = f;
}

static double weight_of(const ssa_avatar *av, int v, int bone) {
  for (int k = av->w_start[v]; k < av->w_start[v + 1]; k++)
    if (av->w_bone[k] == bone) return av->w_weight[k];
  return 0.0;
}

static void test_lbs_direct(void) {
  /* bone 0 identity, bone 1 rotation by 0.7 about z through (1, 0, 0), bone 2 a translation */
  double M[3 * 16] = {0};
  double c = cos(0.7), s = sin(0.7);
  double rot[16] = {c, -s, 0, 1 - c, s, c, 0, -s, 0, 0, 1, 0, 0, 0, 0, 1};
  double tra[16] = {1, 0, 0, 0.5, 0, 1, 0, -2, 0, 0, 1, 3, 0, 0, 0, 1};
  M[0] = M[5] = M[10] = M[15] = 1;
  memcpy(M + 16, rot, sizeof rot);
  memcpy(M + 32, tra, sizeof tra);
  double p[9] = {2, 0, 0, 2, 0, 0, 1, 1, 1};
  int ws[4] = {0, 1, 3, 5}, wb[5] = {1, 0, 1, 1, 2};
  double ww[5] = {1.0, 0.5, 0.5, 0.25, 0.75};
  double out[9];
  ssa_lbs(3, p, ws, wb, ww, M, out);
  CHECK_NEAR(out[0], 1 + c, 1e-15); /* (2,0,0) rotated by 0.7 about (1,0,0) */
  CHECK_NEAR(out[1], s, 1e-15);
  CHECK_NEAR(out[2], 0, 1e-15);
  CHECK_NEAR(out[3], 0.5 * (2 + 1 + c), 1e-15); /* half identity, half rotation */
  CHECK_NEAR(out[4], 0.5 * s, 1e-15);
  CHECK_NEAR(out[6], 0.25 * (c * 1 - s * 1 + 1 - c) + 0.75 * 1.5, 1e-15);
  CHECK_NEAR(out[7], 0.25 * (s + c - s) + 0.75 * -1.0, 1e-15);
  CHECK_NEAR(out[8], 0.25 * 1 + 0.75 * 4, 1e-15);
}

/* A closed tube around the z axis shifted to (cx, 0): nr rings in [z0, z1], NS around. */
static void add_tube(double *pos, int *faces, int *nv, int *nf, double cx, double r, double z0,
                     double z1, int nr) {
  int b = *nv, f = *nf;
  for (int i = 0; i < nr; i++)
    for (int j = 0; j < NS; j++) {
      double a = 2 * 3.14159265358979323846 * j / NS;
      double *p = pos + 3 * (b + i * NS + j);
      p[0] = cx + r * cos(a), p[1] = r * sin(a), p[2] = z0 + (z1 - z0) * i / (nr - 1);
    }
  int c0 = b + nr * NS, c1 = c0 + 1;
  pos[3 * c0] = cx, pos[3 * c0 + 1] = 0, pos[3 * c0 + 2] = z0;
  pos[3 * c1] = cx, pos[3 * c1 + 1] = 0, pos[3 * c1 + 2] = z1;
  for (int i = 0; i + 1 < nr; i++)
    for (int j = 0; j < NS; j++) {
      int a = b + i * NS + j, bb = b + i * NS + (j + 1) % NS, c = b + (i + 1) * NS + j,
          d = b + (i + 1) * NS + (j + 1) % NS;
      faces[3 * f] = a, faces[3 * f + 1] = bb, faces[3 * f + 2] = d, f++;
      faces[3 * f] = a, faces[3 * f + 1] = d, faces[3 * f + 2] = c, f++;
    }
  for (int j = 0; j < NS; j++) {
    faces[3 * f] = c0, faces[3 * f + 1] = b + (j + 1) % NS, faces[3 * f + 2] = b + j, f++;
    int o = b + (nr - 1) * NS;
    faces[3 * f] = c1, faces[3 * f + 1] = o + j, faces[3 * f + 2] = o + (j + 1) % NS, f++;
  }
  *nv = c1 + 1;
  *nf = f;
}

/* An arm hanging beside a torso, 5 cm apart: the torso's side is nearer to the
   arm's bone than to its own, but cannot see it through the arm. */
static void test_visibility(void) {
  static double pos[3 * 2 * (21 * NS + 2)];
  static int faces[3 * 2 * (2 * 20 * NS + 2 * NS)];
  int nv = 0, nf = 0;
  add_tube(pos, faces, &nv, &nf, 0.0, 0.15, 0.0, 1.0, 21);
  int ntorso = nv;
  add_tube(pos, faces, &nv, &nf, 0.24, 0.04, 0.1, 0.9, 17);
  double segs[12] = {0, 0, 0, 0, 0, 1, 0.24, 0, 0.1, 0.24, 0, 0.9};
  int owners[2] = {0, 1};
  char err[256] = "";
  for (int vis = 0; vis < 2; vis++) {
    ssa_autoweight_opts o = ssa_autoweight_default_opts();
    o.visibility = vis;
    int *ws = NULL, *wb = NULL, *dom = malloc(sizeof(int) * (size_t)nv);
    double *ww = NULL;
    CHECK_EQ_INT(ssa_auto_weights(nv, pos, nf, faces, -1, 2, segs, owners, 2, &o, &ws, &wb, &ww,
                                  dom, err, sizeof err),
                 SS_OK);
    int torso_to_arm = 0, arm_to_torso = 0;
    for (int v = 0; v < nv; v++) {
      if (v < ntorso) torso_to_arm += dom[v] == 1;
      else arm_to_torso += dom[v] == 0;
    }
    if (vis) {
      CHECK_EQ_INT(torso_to_arm, 0);
      CHECK_EQ_INT(arm_to_torso, 0);
    } else {
      CHECK_MSG(torso_to_arm > 0, "without visibility the torso's side should go to the arm");
    }
    printf("visibility %d: %d torso vertices bound to the arm, %d arm vertices to the torso\n",
           vis, torso_to_arm, arm_to_torso);
    free(ws);
    free(wb);
    free(ww);
    free(dom);
  }
}

int main(void) {
  test_lbs_direct();
  test_visibility();
  static double pos[3 * (NR * NS + 2)];
  static int faces[3 * (2 * (NR - 1) * NS + 2 * NS)];
  int nv, nf;
  make_tube(pos, faces, &nv, &nf);
  char err[512] = "";
  ssa_robot *r = NULL;
  CHECK_EQ_INT(ssa_robot_load_string(&r, arm_urdf, NULL, NULL, err, sizeof err), SS_OK);
  if (!r) return 1;
  int up = ssa_robot_link_index(r, "upper"), lo = ssa_robot_link_index(r, "lower");
  ssa_avatar *av = NULL;
  CHECK_EQ_INT(ssa_avatar_from_robot_mesh(&av, r, nv, pos, nf, faces, NULL, err, sizeof err), SS_OK);
  if (!av) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  CHECK_EQ_INT(av->weight_source, SSA_WEIGHTS_AUTO);
  CHECK_EQ_INT(av->nbone, 2);
  /* partition of unity, non-negative */
  for (int v = 0; v < nv; v++) {
    double sum = 0;
    for (int k = av->w_start[v]; k < av->w_start[v + 1]; k++) {
      CHECK(av->w_weight[k] > 0 && av->w_weight[k] <= 1);
      sum += av->w_weight[k];
    }
    CHECK_NEAR(sum, 1.0, 1e-12);
  }
  /* nearest link dominates, far parts are rigid, smooth and monotone along x, ~1/2 at the joint */
  for (int j = 0; j < NS; j++) {
    double prev = -1;
    for (int i = 0; i < NR; i++) {
      int v = i * NS + j;
      double x = pos[3 * v], w1 = weight_of(av, v, lo);
      if (x < 0.8) CHECK_EQ_INT(av->vert_link[v], up);
      if (x > 1.2) CHECK_EQ_INT(av->vert_link[v], lo);
      if (x < 0.7) CHECK(w1 == 0.0);
      if (x > 1.3) CHECK(w1 == 1.0);
      if (fabs(x - 1.0) < 1e-9) CHECK_MSG(fabs(w1 - 0.5) < 0.15, "weight %g at the joint", w1);
      if (prev >= 0) {
        CHECK_MSG(w1 >= prev - 1e-9, "not monotone at x %g: %g after %g", x, w1, prev);
        CHECK_MSG(w1 - prev < 0.25, "a jump of %g at x %g", w1 - prev, x);
      }
      /* symmetric about the joint */
      int vm = (NR - 1 - i) * NS + j;
      CHECK_NEAR(w1, 1.0 - weight_of(av, vm, lo), 0.1);
      prev = w1;
    }
  }
  /* rest pose reproduced */
  double *out = malloc(sizeof(double) * 3 * (size_t)nv);
  CHECK_EQ_INT(ssa_avatar_pose_joints(av, NULL, out), SS_OK);
  for (int i = 0; i < 3 * nv; i++) CHECK_NEAR(out[i], pos[i], 1e-12);
  /* one joint rotated: the rigid lower part rotates exactly about the joint, the upper stays */
  double q[1] = {1.0};
  CHECK_EQ_INT(ssa_avatar_pose_joints(av, q, out), SS_OK);
  double c = cos(1.0), s = sin(1.0);
  for (int v = 0; v < nv; v++) {
    const double *p = pos + 3 * v;
    if (p[0] > 1.3) {
      CHECK_NEAR(out[3 * v], 1 + c * (p[0] - 1) - s * p[1], 1e-12);
      CHECK_NEAR(out[3 * v + 1], s * (p[0] - 1) + c * p[1], 1e-12);
      CHECK_NEAR(out[3 * v + 2], p[2], 1e-12);
    } else if (p[0] < 0.7) {
      for (int k = 0; k < 3; k++) CHECK_NEAR(out[3 * v + k], p[k], 1e-12);
    }
    for (int k = 0; k < 3; k++) CHECK(isfinite(out[3 * v + k]));
  }
  /* bad segment owners are refused */
  int *ws = NULL, *wb = NULL;
  double *ww = NULL;
  double seg[6] = {0, 0, 0, 1, 0, 0};
  int owner = 5;
  CHECK_EQ_INT(ssa_auto_weights(nv, pos, nf, faces, -1, 1, seg, &owner, 2, NULL, &ws, &wb, &ww,
                                NULL, err, sizeof err),
               SS_E_ARG);
  CHECK(ws == NULL);
  /* the pure function: dominant owners out */
  int *dom = malloc(sizeof(int) * (size_t)(nv + 1));
  double segs[12] = {0, 0, 0, 1, 0, 0, 1, 0, 0, 2, 0, 0};
  int owners[2] = {0, 1};
  CHECK_EQ_INT(ssa_auto_weights(nv, pos, nf, faces, -1, 2, segs, owners, 2, NULL, &ws, &wb, &ww,
                                dom, err, sizeof err),
               SS_OK);
  for (int v = 0; v < nv; v++) CHECK(dom[v] == (pos[3 * v] < 1.0 ? 0 : 1) || fabs(pos[3 * v] - 1) < 1e-9);
  free(ws);
  free(wb);
  free(ww);
  /* a vertex in no face (files have them) takes its nearest owner, the solve stays regular */
  static double pos2[3 * (NR * NS + 3)];
  memcpy(pos2, pos, sizeof(double) * 3 * (size_t)nv);
  pos2[3 * nv] = 1.8, pos2[3 * nv + 1] = 0.5, pos2[3 * nv + 2] = 0.0;
  CHECK_EQ_INT(ssa_auto_weights(nv + 1, pos2, nf, faces, -1, 2, segs, owners, 2, NULL, &ws, &wb,
                                &ww, dom, err, sizeof err),
               SS_OK);
  if (ws) {
    CHECK_EQ_INT(ws[nv + 1] - ws[nv], 1);
    CHECK_EQ_INT(wb[ws[nv]], 1);
  }
  free(ws);
  free(wb);
  free(ww);
  free(dom);
  free(out);
  ssa_avatar_destroy(av);
  return ss_test_finish("test_lbs_weights");
}
