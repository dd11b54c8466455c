/* avatar_node: the moving body as a ROS 1 node (glue only).
 *
 * Reads the URDF from robot_description as robot_state_publisher does, builds
 * an avatar (ssa_avatar.h): the body mesh from ~mesh (a file or package://
 * URI; empty: the URDF's own visual meshes) or, with ~avatar:=mannequin, the
 * built-in demo mannequin with ~tris triangles. Each joint_states message is
 * turned into a body pose by forward kinematics and linear blend skinning and
 * published on kinematic_mesh (skin_sim/SkinMesh) with the joint state's stamp,
 * the URDF's root link as frame_id and a topology_id that is a hash of the
 * body's triangles (stable across runs, so bags from different runs agree).
 *
 * joint_states: joints not named keep their last value (as in
 * robot_state_publisher); names the robot does not have are ignored and
 * counted (several publishers commonly share the topic). A message whose
 * arrays disagree, or with a NaN/Inf position, or naming no joint of the robot
 * is rejected with a throttled log line and counted. avatar_stats (SkinStats)
 * reports per message the posing time (total_ms) and the counters
 * (inputs_rejected: rejected messages; inputs_dropped: names ignored).
 * Values outside a joint's URDF limits are clamped (by the FK) with one
 * warning naming the joint and its limits, or with ~strict_limits the
 * message is rejected. Parameters of the wrong type or out of range stop the
 * node at start (exit 2) with one message naming the parameter. */
#include "node_params.h"
#include "rosc/rosc.h"
#include "skin_sim/ssa_avatar.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ERR_SZ 512

typedef struct node {
  ssa_avatar *av;
  const ssa_robot *robot;
  char frame[ROSC_FRAME_ID_MAX];
  uint32_t topology_id;
  double *q;          /* (njoint) last joint values */
  double *q_try;      /* (njoint) */
  double *pose;       /* (nvert x 3) */
  float *pos_out;     /* (nvert x 3) */
  uint32_t *tri_out;  /* (nface x 3) */
  rosc_pub *pub_mesh, *pub_stats;
  uint32_t rejected, unknown_names;
  unsigned long in, out;
  int strict_limits;      /* ~strict_limits: reject values outside the URDF limits */
  int limits_warned;      /* the clamping warning is given once */
  unsigned long clamped;  /* messages with values clamped to the limits */
  int queue;              /* ~queue_size */
} node;

static uint32_t hash_topology(int nvert, int nface, const int *faces)
{
  uint32_t h = 2166136261u; /* FNV-1a */
  uint32_t vals[2] = {(uint32_t)nvert, (uint32_t)nface};
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 4; k++) { h ^= (vals[i] >> (8 * k)) & 255u; h *= 16777619u; }
  for (size_t i = 0; i < 3 * (size_t)nface; i++)
    for (int k = 0; k < 4; k++) { h ^= ((uint32_t)faces[i] >> (8 * k)) & 255u; h *= 16777619u; }
  return h ? h : 1u;
}

static void reject(node *nd, const char *why)
{
  nd->rejected++;
  ROSC_WARN_THROTTLE(1.0, "rejected joint_states: %s (%u rejected so far)", why,
                     (unsigned)nd->rejected);
}

static void on_joints(const rosc_joint_state *m, void *user)
{
  node *nd = user;
  nd->in++;
  char why[ERR_SZ];
  if (m->n_position != m->n_name || (m->n_velocity && m->n_velocity != m->n_name) ||
      (m->n_effort && m->n_effort != m->n_name)) {
    snprintf(why, sizeof why, "arrays disagree (%zu names, %zu positions, %zu velocities, "
             "%zu efforts)", m->n_name, m->n_position, m->n_velocity, m->n_effort);
    reject(nd, why);
    return;
  }
  const ssa_robot *r = nd->robot;
  memcpy(nd->q_try, nd->q, (size_t)r->njoint * sizeof(double));
  size_t known = 0, unknown = 0;
  const char *first_unknown = NULL;
  for (size_t i = 0; i < m->n_name; i++) {
    int j = ssa_robot_joint_index(r, m->name[i]);
    if (j < 0) {
      unknown++;
      if (!first_unknown) first_unknown = m->name[i];
      continue;
    }
    if (!isfinite(m->position[i])) {
      snprintf(why, sizeof why, "joint '%s' has a non-finite position", m->name[i]);
      reject(nd, why);
      return;
    }
    nd->q_try[j] = m->position[i];
    known++;
  }
  if (known == 0 && m->n_name > 0) {
    snprintf(why, sizeof why, "none of its %zu joints is in the robot (first: '%s')", m->n_name,
             first_unknown);
    reject(nd, why);
    return;
  }
  if (unknown) {
    nd->unknown_names += (uint32_t)unknown;
    ROSC_WARN_THROTTLE(5.0, "joint_states names %zu joint(s) the robot does not have (first: "
                       "'%s'): ignored (%u names ignored so far)", unknown, first_unknown,
                       (unsigned)nd->unknown_names);
  }
  char lim[ERR_SZ];
  if (ssa_robot_check_limits(r, nd->q_try, lim, sizeof lim) > 0) {
    if (nd->strict_limits) {
      char why2[ERR_SZ + 32];
      snprintf(why2, sizeof why2, "%s (~strict_limits)", lim);
      reject(nd, why2);
      return;
    }
    nd->clamped++;
    if (!nd->limits_warned) {
      nd->limits_warned = 1;
      ROSC_WARN("joint_states: %s; clamped to the limits (said once; ~strict_limits:=true "
                "rejects such messages)", lim);
    }
  }
  memcpy(nd->q, nd->q_try, (size_t)r->njoint * sizeof(double));
  double t0 = 0, t1 = 0;
  rosc_wall_now_s(&t0);
  ssa_avatar_pose_joints(nd->av, nd->q, nd->pose);
  size_t n3 = 3 * (size_t)nd->av->nvert;
  for (size_t i = 0; i < n3; i++) nd->pos_out[i] = (float)nd->pose[i];
  rosc_wall_now_s(&t1);

  rosc_skin_mesh out;
  memset(&out, 0, sizeof out);
  out.header.stamp = m->header.stamp;
  if (out.header.stamp.sec == 0 && out.header.stamp.nsec == 0) rosc_now(&out.header.stamp);
  snprintf(out.header.frame_id, sizeof out.header.frame_id, "%s", nd->frame);
  out.topology_id = nd->topology_id;
  out.positions = nd->pos_out;
  out.n_positions = n3;
  out.triangles = nd->tri_out;
  out.n_triangles = 3 * (size_t)nd->av->nface;
  if (rosc_publish_skin_mesh(nd->pub_mesh, &out) == ROSC_OK) nd->out++;

  rosc_skin_stats s;
  memset(&s, 0, sizeof s);
  s.header = out.header;
  s.total_ms = (float)(1e3 * (t1 - t0));
  s.inputs_rejected = nd->rejected;
  s.inputs_dropped = nd->unknown_names;
  rosc_publish_skin_stats(nd->pub_stats, &s);
}

static void on_avatar_warning(void *user, const char *msg)
{
  (void)user;
  ROSC_WARN("%s", msg);
}

/* Loads the avatar: 0, or the exit status (1 it cannot be built, 2 a bad parameter). */
static int load_avatar(node *nd)
{
  char kind[64], mesh[1024], up[32], pkg[2048], err[ERR_SZ] = "";
  int tris = 5000, ok = 1;
  double edge = 0.02;
  ok &= param_ok(rosc_param_get_string("~avatar", kind, sizeof kind, "", NULL), "~avatar", "a string");
  ok &= param_ok(rosc_param_get_string("~mesh", mesh, sizeof mesh, "", NULL), "~mesh", "a string");
  ok &= param_ok(rosc_param_get_int("~tris", &tris, 5000, NULL), "~tris", "an int");
  ok &= param_ok(rosc_param_get_string("~package_path", pkg, sizeof pkg, "", NULL), "~package_path",
                 "a string");
  ok &= param_ok(rosc_param_get_bool("~strict_limits", &nd->strict_limits, 0, NULL),
                 "~strict_limits", "a bool");
  ok &= param_ok(rosc_param_get_string("~mesh_up_axis", up, sizeof up, "ignore", NULL),
                 "~mesh_up_axis", "a string");
  ok &= param_ok(rosc_param_get_double("~primitive_edge", &edge, 0.02, NULL), "~primitive_edge",
                 "a double (or an int)");
  if (ok && strcmp(up, "ignore") != 0 && strcmp(up, "file") != 0) {
    ROSC_ERROR("~mesh_up_axis: '%s' is neither 'ignore' (rviz's way) nor 'file'", up);
    ok = 0;
  }
  nd->queue = 2;
  ok &= param_ok(rosc_param_get_int("~queue_size", &nd->queue, 2, NULL), "~queue_size", "an int");
  if (ok && (nd->queue < 1 || nd->queue > 1000)) {
    ROSC_ERROR("~queue_size = %d is out of range [1, 1000]", nd->queue);
    ok = 0;
  }
  if (ok && !(edge >= 1e-4 && edge <= 10.0)) {
    ROSC_ERROR("~primitive_edge = %g m is out of range [0.0001, 10]", edge);
    ok = 0;
  }
  if (!ok) return 2;
  int st;
  if (strcmp(kind, "mannequin") == 0) {
    st = ssa_avatar_mannequin(&nd->av, tris, err, sizeof err);
    if (st != SS_OK) {
      ROSC_ERROR("mannequin: %s", err);
      return st == SS_E_ARG ? 2 : 1;
    }
  } else if (kind[0]) {
    ROSC_ERROR("~avatar: unknown built-in avatar '%s' (mannequin, or empty for the URDF)", kind);
    return 2;
  } else {
    char *urdf = NULL;
    if (rosc_robot_description(&urdf, NULL) != ROSC_OK) {
      ROSC_ERROR("robot_description is not set (load a URDF, or use ~avatar:=mannequin)");
      return 1;
    }
    ssa_robot *robot = NULL;
    st = ssa_robot_load_string(&robot, urdf, NULL, pkg[0] ? pkg : NULL, err, sizeof err);
    free(urdf);
    if (st != SS_OK) {
      ROSC_ERROR("robot_description: %s", err);
      return 1;
    }
    char path[4096];
    if (mesh[0]) {
      if (ssa_resolve_uri(mesh, NULL, pkg[0] ? pkg : NULL, path, sizeof path, err, sizeof err) !=
          SS_OK) {
        ROSC_ERROR("~mesh: %s", err);
        ssa_robot_destroy(robot);
        return 1;
      }
    }
    ssa_avatar_opts opts = ssa_avatar_default_opts();
    opts.package_path = pkg[0] ? pkg : NULL;
    opts.mesh_up_axis = strcmp(up, "file") == 0 ? SSA_UP_AXIS_FILE : SSA_UP_AXIS_IGNORE;
    opts.primitive_edge = edge;
    opts.warn = on_avatar_warning;
    st = ssa_avatar_from_robot(&nd->av, robot, mesh[0] ? path : NULL, &opts, err, sizeof err);
    if (st != SS_OK) {
      ROSC_ERROR("avatar: %s", err);
      return 1;
    }
  }
  nd->robot = nd->av->robot;
  snprintf(nd->frame, sizeof nd->frame, "%s", nd->robot->link_name[nd->robot->root_link]);
  return 0;
}

int main(int argc, char **argv)
{
  int st = rosc_init(&argc, argv, "avatar", 0, -1.0);
  if (st != ROSC_OK) {
    fprintf(stderr, "avatar_node: rosc_init: %s\n", rosc_strerror(st));
    return 1;
  }
  node nd;
  memset(&nd, 0, sizeof nd);
  int load = load_avatar(&nd);
  if (load != 0) {
    rosc_shutdown();
    return load;
  }
  const ssa_avatar *av = nd.av;
  nd.q = calloc((size_t)nd.robot->njoint + 1, sizeof(double));
  nd.q_try = calloc((size_t)nd.robot->njoint + 1, sizeof(double));
  nd.pose = malloc(3 * (size_t)av->nvert * sizeof(double));
  nd.pos_out = malloc(3 * (size_t)av->nvert * sizeof(float));
  nd.tri_out = malloc(3 * (size_t)av->nface * sizeof(uint32_t));
  if (!nd.q || !nd.q_try || !nd.pose || !nd.pos_out || !nd.tri_out) {
    ROSC_ERROR("out of memory");
    return 1;
  }
  for (size_t i = 0; i < 3 * (size_t)av->nface; i++) nd.tri_out[i] = (uint32_t)av->faces[i];
  nd.topology_id = hash_topology(av->nvert, av->nface, av->faces);
  rosc_sub *sub = NULL;
  if (rosc_pub_create(&nd.pub_mesh, ROSC_MSG_SKIN_MESH, "kinematic_mesh", 4, 0) != ROSC_OK ||
      rosc_pub_create(&nd.pub_stats, ROSC_MSG_SKIN_STATS, "avatar_stats", 10, 0) != ROSC_OK ||
      rosc_sub_joint_state(&sub, "joint_states", (unsigned)nd.queue, on_joints, &nd) != ROSC_OK) {
    ROSC_ERROR("cannot advertise or subscribe");
    rosc_shutdown();
    return 1;
  }
  ROSC_INFO("avatar '%s': %d vertices, %d triangles, %d joints, frame '%s', topology %u",
            nd.robot->name, av->nvert, av->nface, nd.robot->njoint, nd.frame,
            (unsigned)nd.topology_id);
  rosc_spin_for(-1.0);
  ROSC_INFO("avatar: %lu joint_states in, %lu meshes out, %u rejected, %u names ignored, %lu "
            "with values clamped to the joint limits", nd.in, nd.out, (unsigned)nd.rejected,
            (unsigned)nd.unknown_names, nd.clamped);
  rosc_sub_destroy(sub);
  rosc_pub_destroy(nd.pub_mesh);
  rosc_pub_destroy(nd.pub_stats);
  rosc_shutdown();
  free(nd.q); free(nd.q_try); free(nd.pose); free(nd.pos_out); free(nd.tri_out);
  ssa_avatar_destroy(nd.av);
  return 0;
}
