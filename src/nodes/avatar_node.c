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
 * node at start (exit 2) with one message naming the parameter.
 *
 * Mesh files are read behind the avatar layer's guards (safe_import.h): files
 * over ~max_file_mb are refused, and each import runs in a child process
 * stopped after ~import_timeout seconds or ~import_mem_mb more megabytes.
 * The ~reload service (std_srvs/Empty) reads the body parameters,
 * robot_description and ~mesh again and swaps the body in (joint values kept
 * by name); if that load fails or a file is refused, the call fails, one error
 * names the file, and the node keeps publishing its last good body. At start
 * there is no good body yet: a failed load ends the node (exit 1, or 2 for a
 * bad parameter). */
#include "node_log.h"
#include "node_msg.h"
#include "node_params.h"
#include "rosc/rosc.h"
#include "ss_input.h"
#include "skin_sim/ssa_avatar.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ERR_SZ 512

/* One loaded body and its buffers: swapped whole by ~reload. */
typedef struct body {
  ssa_avatar *av;
  const ssa_robot *robot;
  char frame[SS_MSG_FRAME_ID_MAX];
  uint32_t topology_id;
  double *q;          /* (njoint) last joint values */
  double *q_try;      /* (njoint) */
  double *pose;       /* (nvert x 3) */
  float *pos_out;     /* (nvert x 3) */
  uint32_t *tri_out;  /* (nface x 3) */
  uint32_t *rigid_out; /* (nvert) what each vertex moves with (ssa_avatar_rigid_parts) */
} body;

typedef struct node {
  body b;             /* the last good body */
  msg_pub *pub_mesh, *pub_stats;
  unsigned long reloads, reload_failures;
  uint32_t rejected, unknown_names;
  unsigned long in, out;
  int strict_limits;      /* ~strict_limits: reject values outside the URDF limits */
  int limits_warned;      /* the clamping warning is given once */
  unsigned long clamped;  /* messages with values clamped to the limits */
  int queue;              /* ~queue_size */
} node;

static void reject(node *nd, const char *why)
{
  nd->rejected++;
  NODE_WARN_THROTTLE(1.0, "rejected joint_states: %s (%u rejected so far)", why,
                     (unsigned)nd->rejected);
}

static void on_joints(const void *msg, void *user)
{
  const ss_msg_joint_state *m = msg;
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
  body *b = &nd->b;
  const ssa_robot *r = b->robot;
  memcpy(b->q_try, b->q, (size_t)r->njoint * sizeof(double));
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
    b->q_try[j] = m->position[i];
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
    NODE_WARN_THROTTLE(5.0, "joint_states names %zu joint(s) the robot does not have (first: "
                       "'%s'): ignored (%u names ignored so far)", unknown, first_unknown,
                       (unsigned)nd->unknown_names);
  }
  char lim[ERR_SZ];
  if (ssa_robot_check_limits(r, b->q_try, lim, sizeof lim) > 0) {
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
  memcpy(b->q, b->q_try, (size_t)r->njoint * sizeof(double));
  double t0 = 0, t1 = 0;
  rosc_wall_now_s(&t0);
  ssa_avatar_pose_joints(b->av, b->q, b->pose);
  size_t n3 = 3 * (size_t)b->av->nvert;
  for (size_t i = 0; i < n3; i++) b->pos_out[i] = (float)b->pose[i];
  rosc_wall_now_s(&t1);

  ss_msg_skin_mesh out;
  memset(&out, 0, sizeof out);
  out.header.stamp = m->header.stamp;
  if (out.header.stamp.sec == 0 && out.header.stamp.nsec == 0) out.header.stamp = msg_now();
  snprintf(out.header.frame_id, sizeof out.header.frame_id, "%s", b->frame);
  out.topology_id = b->topology_id;
  out.positions = b->pos_out;
  out.n_positions = n3;
  out.triangles = b->tri_out;
  out.n_triangles = 3 * (size_t)b->av->nface;
  out.rigid_part = b->rigid_out;
  out.n_rigid_part = (size_t)b->av->nvert;
  if (msg_publish(nd->pub_mesh, SS_MSG_SKIN_MESH, &out) == ROSC_OK) nd->out++;

  ss_msg_skin_stats s;
  memset(&s, 0, sizeof s);
  s.header = out.header;
  s.total_ms = (float)(1e3 * (t1 - t0));
  s.inputs_rejected = nd->rejected;
  s.inputs_dropped = nd->unknown_names;
  msg_publish(nd->pub_stats, SS_MSG_SKIN_STATS, &s);
}

static void on_avatar_warning(void *user, const char *msg)
{
  (void)user;
  ROSC_WARN("%s", msg);
}

static void body_free(body *b)
{
  free(b->q); free(b->q_try); free(b->pose); free(b->pos_out); free(b->tri_out);
  free(b->rigid_out);
  ssa_avatar_destroy(b->av);
  memset(b, 0, sizeof *b);
}

/* The buffers of a loaded body; joint values of `old` (may be NULL) kept by name. */
static int body_finish(body *b, const body *old)
{
  const ssa_avatar *av = b->av;
  b->robot = av->robot;
  snprintf(b->frame, sizeof b->frame, "%s", b->robot->link_name[b->robot->root_link]);
  b->q = calloc((size_t)b->robot->njoint + 1, sizeof(double));
  b->q_try = calloc((size_t)b->robot->njoint + 1, sizeof(double));
  b->pose = malloc(3 * (size_t)av->nvert * sizeof(double));
  b->pos_out = malloc(3 * (size_t)av->nvert * sizeof(float));
  b->tri_out = malloc(3 * (size_t)av->nface * sizeof(uint32_t));
  b->rigid_out = malloc((size_t)av->nvert * sizeof(uint32_t));
  if (!b->q || !b->q_try || !b->pose || !b->pos_out || !b->tri_out || !b->rigid_out) return 0;
  for (size_t i = 0; i < 3 * (size_t)av->nface; i++) b->tri_out[i] = (uint32_t)av->faces[i];
  ssa_avatar_rigid_parts(av, b->rigid_out);
  /* what moves rigidly is part of the topology: the skin node carries those pieces */
  b->topology_id = ss_input_topology_id(av->nvert, av->nface, av->faces, b->rigid_out);
  if (old && old->robot)
    for (int j = 0; j < b->robot->njoint; j++) {
      int k = ssa_robot_joint_index(old->robot, b->robot->joint_name[j]);
      if (k >= 0) b->q[j] = old->q[k];
    }
  return 1;
}

/* Reads a double parameter within [lo, hi]; 0 (with one error) if it is not one. */
static int get_ranged(const char *name, double *v, double def, double lo, double hi,
                      const char *unit)
{
  if (!get_double(name, v, def)) return 0;
  if (*v >= lo && *v <= hi) return 1;
  ROSC_ERROR("%s = %g %s is out of range [%g, %g]", name, *v, unit, lo, hi);
  return 0;
}

/* Loads a body from the parameters (~avatar, ~mesh, robot_description, ...) into
 * *b: 0, or 1 it cannot be built, 2 a bad parameter (each with one error). */
static int load_body(body *b, const body *old)
{
  char kind[64], mesh[1024], up[32], pkg[2048], err[ERR_SZ] = "";
  int tris = 5000, ok = 1;
  double edge = 0.02, max_mb = 256.0, timeout_s = 60.0, mem_mb = 4096.0;
  memset(b, 0, sizeof *b);
  ok &= param_ok(rosc_param_get_string("~avatar", kind, sizeof kind, "", NULL), "~avatar", "a string");
  ok &= param_ok(rosc_param_get_string("~mesh", mesh, sizeof mesh, "", NULL), "~mesh", "a string");
  ok &= param_ok(rosc_param_get_int("~tris", &tris, 5000, NULL), "~tris", "an int");
  ok &= param_ok(rosc_param_get_string("~package_path", pkg, sizeof pkg, "", NULL), "~package_path",
                 "a string");
  ok &= param_ok(rosc_param_get_string("~mesh_up_axis", up, sizeof up, "ignore", NULL),
                 "~mesh_up_axis", "a string");
  ok &= param_ok(rosc_param_get_double("~primitive_edge", &edge, 0.02, NULL), "~primitive_edge",
                 "a double (or an int)");
  ok &= get_ranged("~max_file_mb", &max_mb, 256.0, 1e-6, 1048576.0, "MB");
  ok &= get_ranged("~import_timeout", &timeout_s, 60.0, 0.1, 86400.0, "s");
  ok &= get_ranged("~import_mem_mb", &mem_mb, 4096.0, 16.0, 1048576.0, "MB");
  if (ok && strcmp(up, "ignore") != 0 && strcmp(up, "file") != 0) {
    ROSC_ERROR("~mesh_up_axis: '%s' is neither 'ignore' (rviz's way) nor 'file'", up);
    ok = 0;
  }
  if (ok && !(edge >= 1e-4 && edge <= 10.0)) {
    ROSC_ERROR("~primitive_edge = %g m is out of range [0.0001, 10]", edge);
    ok = 0;
  }
  if (!ok) return 2;
  int st;
  if (strcmp(kind, "mannequin") == 0) {
    st = ssa_avatar_mannequin(&b->av, tris, err, sizeof err);
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
    opts.asset.max_file_mb = max_mb;
    opts.asset.import_timeout_s = timeout_s;
    opts.asset.import_mem_mb = mem_mb;
    opts.warn = on_avatar_warning;
    st = ssa_avatar_from_robot(&b->av, robot, mesh[0] ? path : NULL, &opts, err, sizeof err);
    if (st != SS_OK) {
      ROSC_ERROR("avatar: %s", err);
      return 1;
    }
  }
  if (!body_finish(b, old)) {
    ROSC_ERROR("avatar: out of memory for the body's buffers");
    body_free(b);
    return 1;
  }
  return 0;
}

static void log_body(const char *what, const body *b)
{
  ROSC_INFO("%s '%s': %d vertices, %d triangles, %d joints, frame '%s', topology %u", what,
            b->robot->name, b->av->nvert, b->av->nface, b->robot->njoint, b->frame,
            (unsigned)b->topology_id);
}

/* ~reload (std_srvs/Empty): a new body from the parameters, or the old one kept. */
static int on_reload(void *user)
{
  node *nd = user;
  body fresh;
  if (load_body(&fresh, &nd->b) != 0) {
    nd->reload_failures++;
    ROSC_ERROR("~reload failed (see the error above); still publishing the last good body "
               "('%s', %d vertices, topology %u)", nd->b.robot->name, nd->b.av->nvert,
               (unsigned)nd->b.topology_id);
    return 1;
  }
  body_free(&nd->b);
  nd->b = fresh;
  nd->reloads++;
  log_body("~reload: avatar", &nd->b);
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
  int ok = 1;
  nd.queue = 2;
  ok &= param_ok(rosc_param_get_bool("~strict_limits", &nd.strict_limits, 0, NULL),
                 "~strict_limits", "a bool");
  ok &= param_ok(rosc_param_get_int("~queue_size", &nd.queue, 2, NULL), "~queue_size", "an int");
  if (ok && (nd.queue < 1 || nd.queue > 1000)) {
    ROSC_ERROR("~queue_size = %d is out of range [1, 1000]", nd.queue);
    ok = 0;
  }
  int load = ok ? load_body(&nd.b, NULL) : 2;
  if (load != 0) {
    rosc_shutdown();
    return load;
  }
  msg_sub *sub = NULL;
  rosc_srv *srv_reload = NULL;
  int status = 0;
  if (msg_pub_create(&nd.pub_mesh, SS_MSG_SKIN_MESH, "kinematic_mesh", 4, 0) != ROSC_OK ||
      msg_pub_create(&nd.pub_stats, SS_MSG_SKIN_STATS, "avatar_stats", 10, 0) != ROSC_OK ||
      msg_subscribe(&sub, SS_MSG_JOINT_STATE, "joint_states", (unsigned)nd.queue, on_joints,
                    NULL, &nd) != ROSC_OK ||
      rosc_srv_empty(&srv_reload, "~reload", on_reload, &nd) != ROSC_OK) {
    /* a SIGINT during set-up makes roscpp refuse new publishers: a clean stop */
    if (rosc_ok()) {
      ROSC_ERROR("cannot advertise or subscribe");
      status = 1;
    }
  } else {
    log_body("avatar", &nd.b);
    rosc_spin_for(-1.0);
    ROSC_INFO("avatar: %lu joint_states in, %lu meshes out, %u rejected, %u names ignored, %lu "
              "with values clamped to the joint limits, %lu reloads (%lu failed)", nd.in, nd.out,
              (unsigned)nd.rejected, (unsigned)nd.unknown_names, nd.clamped, nd.reloads,
              nd.reload_failures);
  }
  rosc_srv_destroy(srv_reload);
  msg_sub_destroy(sub);
  msg_pub_destroy(nd.pub_mesh);
  msg_pub_destroy(nd.pub_stats);
  rosc_shutdown();
  body_free(&nd.b);
  return status;
}
