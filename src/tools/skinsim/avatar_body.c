/* skinsim: avatars as moving bodies (see avatar_body.h). */
#include "avatar_body.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int avatar_args_given(const avatar_args *a) {
  return a->avatar || a->urdf || a->mesh || a->motion || a->asset || a->anim || a->region ||
         a->strict_limits || a->mesh_up_axis || a->primitive_edge > 0.0;
}

#ifdef SS_HAVE_AVATAR
#include "skin_sim/ss_mesh.h"
#include "skin_sim/ssa_avatar.h"

#define AVATAR_FPS 30.0

struct avatar_body {
  ssa_avatar *av;
  int builtin;         /* built-in motion index, or -1 */
  ssa_motion *motion;  /* CSV motion, or NULL */
  int *map;            /* (motion njoint) robot joint of each column */
  double *q;           /* (robot njoint) */
  double *q_rest;      /* (robot njoint) the joints at frame 0 */
  int anim;            /* asset animation, or -1 */
  unsigned char *face_mask;
  int carried;         /* skin faces of pieces carried rigidly (not simulated) */
  uint32_t *part;      /* (nvert) what each body vertex moves with (ssa_avatar_rigid_parts) */
  double *rest;        /* (nvert x 3) the pose of frame 0: where the skin starts */
};


/* A robot's joint values at t seconds into q. */
static int joints_at(avatar_body *ab, double t, double *q) {
  const ssa_robot *robot = ab->av->robot;
  memset(q, 0, sizeof(double) * (size_t)robot->njoint);
  if (ab->builtin >= 0) return ssa_motion_builtin_eval(ab->builtin, t, robot, q);
  if (ab->motion) ssa_motion_sample(ab->motion, ab->map, t, q);
  return SS_OK;
}

static int pose(void *user, double frame, double *pos) {
  avatar_body *ab = user;
  const double t = frame / AVATAR_FPS;
  if (ab->anim >= 0) return ssa_avatar_pose_anim(ab->av, ab->anim, t, pos);
  int status = joints_at(ab, t, ab->q);
  return status ? status : ssa_avatar_pose_joints(ab->av, ab->q, pos);
}

/* ss_body.pose_toward_rest: in joint space (a robot) or in the bones' motion (an asset). */
static int pose_toward_rest(void *user, double frame, double w, double *pos) {
  avatar_body *ab = user;
  const double t = frame / AVATAR_FPS;
  if (ab->anim >= 0) return ssa_avatar_pose_anim_toward_rest(ab->av, ab->anim, t, w, pos);
  int status = joints_at(ab, t, ab->q);
  if (status) return status;
  ssa_joints_toward(ab->av->robot, ab->q, ab->q_rest, w, ab->q);
  return ssa_avatar_pose_joints(ab->av, ab->q, pos);
}

void avatar_body_close(avatar_body *ab) {
  if (!ab) return;
  ssa_avatar_destroy(ab->av);
  ssa_motion_destroy(ab->motion);
  free(ab->map);
  free(ab->q);
  free(ab->q_rest);
  free(ab->face_mask);
  free(ab->part);
  free(ab->rest);
  free(ab);
}

static void print_warning(void *user, const char *msg) {
  (void)user;
  fprintf(stderr, "skinsim: warning: %s\n", msg);
}

/* Joint values of the motion outside the robot's limits: one warning (they are
 * clamped), or with --strict-limits an error. */
static int check_limits(const ssa_motion *m, const int *map, const ssa_robot *robot,
                        const char *motion, int strict, char *err, int err_sz) {
  char msg[1024];
  if (ssa_motion_check_limits(m, map, robot, msg, sizeof msg) == 0) return SS_OK;
  if (strict) {
    snprintf(err, (size_t)err_sz, "motion '%s': %s (--strict-limits)", motion, msg);
    return SS_E_ARG;
  }
  fprintf(stderr, "skinsim: warning: motion '%s': %s; clamped to the limits (--strict-limits "
          "makes this an error)\n", motion, msg);
  return SS_OK;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The robot's motion: a built-in name or a CSV file. Sets *duration. */
static int open_motion(avatar_body *ab, const char *motion, int strict, double *duration,
                       char *err, int err_sz) {
  const ssa_robot *robot = ab->av->robot;
  ab->builtin = ssa_motion_builtin_index(motion);
  if (ab->builtin >= 0) {
    if (ssa_motion_builtin_coverage(ab->builtin, robot) == 0) {
      snprintf(err, (size_t)err_sz, "built-in motion '%s' moves joints of the mannequin "
               "(--avatar demo), and robot '%s' has none of them: give a CSV motion "
               "(time,<joint>,...) for its joints", motion, robot->name);
      return SS_E_ARG;
    }
    *duration = ssa_motion_builtin_period(ab->builtin);
    /* sampled at the frames, as the run will pose it */
    ssa_motion *table = NULL;
    int n = (int)(*duration * AVATAR_FPS + 0.5) + 1;
    int status = ssa_motion_from_builtin(&table, ab->builtin, robot, *duration, n < 2 ? 2 : n,
                                         err, err_sz);
    int *map = table ? malloc(sizeof(int) * (size_t)(table->njoint > 0 ? table->njoint : 1)) : NULL;
    if (!status && !map) status = SS_E_NOMEM;
    if (!status) status = ssa_motion_bind(table, robot, map, err, err_sz);
    if (!status) status = check_limits(table, map, robot, motion, strict, err, err_sz);
    free(map);
    ssa_motion_destroy(table);
    return status;
  }
  int status = ssa_motion_read_csv(&ab->motion, motion, err, err_sz);
  if (status) return status;
  ab->map = malloc(sizeof(int) * (size_t)(ab->motion->njoint > 0 ? ab->motion->njoint : 1));
  if (!ab->map) return SS_E_NOMEM;
  status = ssa_motion_bind(ab->motion, robot, ab->map, err, err_sz);
  if (status) return status;
  status = check_limits(ab->motion, ab->map, robot, motion, strict, err, err_sz);
  if (status) return status;
  *duration = ab->motion->time[ab->motion->nframe - 1];
  /* times in milliseconds read as seconds: rows seconds apart, a motion of minutes
     in which the robot seems to stand still */
  const ssa_motion *mo = ab->motion;
  if (mo->nframe >= 3 && *duration > 60.0) {
    double *gap = malloc(sizeof(double) * (size_t)(mo->nframe - 1));
    if (gap) {
      for (int i = 1; i < mo->nframe; i++) gap[i - 1] = mo->time[i] - mo->time[i - 1];
      qsort(gap, (size_t)(mo->nframe - 1), sizeof *gap, cmp_double);
      double med = gap[(mo->nframe - 1) / 2];
      if (med >= 5.0)
        fprintf(stderr, "skinsim: warning: motion file '%s', column 1 (time): rows %g s apart "
                "(median) over %g s: times in milliseconds? (the time column is seconds from "
                "the motion's start)\n", motion, med, *duration);
      free(gap);
    }
  }
  return SS_OK;
}

/* Skin faces in the region: those with at least two vertices whose dominant
 * link is listed. */
static int open_region(avatar_body *ab, const char *region, char *err, int err_sz) {
  char *copy = strdup(region);
  const int nv = ab->av->nvert, nf = ab->av->nface;
  unsigned char *vmask = malloc((size_t)nv);
  const char *names[256];
  int n = 0;
  ab->face_mask = malloc((size_t)nf);
  if (!copy || !vmask || !ab->face_mask) {
    free(copy);
    free(vmask);
    snprintf(err, (size_t)err_sz, "out of memory");
    return SS_E_NOMEM;
  }
  for (char *save = NULL, *tok = strtok_r(copy, ",", &save); tok && n < 256;
       tok = strtok_r(NULL, ",", &save))
    if (*tok) names[n++] = tok;
  int status = n ? SS_OK : SS_E_ARG;
  if (!n) snprintf(err, (size_t)err_sz, "--region lists no link");
  if (!status) {
    int marked = ssa_avatar_region_mask(ab->av, n, names, vmask, err, err_sz);
    if (marked < 0) status = marked;
    else if (marked == 0) {
      snprintf(err, (size_t)err_sz, "--region %s: no vertex of the body belongs to it", region);
      status = SS_E_ARG;
    }
  }
  if (!status) {
    const int *faces = ab->av->faces;
    for (int f = 0; f < nf; f++)
      ab->face_mask[f] =
          (unsigned char)(vmask[faces[3 * f]] + vmask[faces[3 * f + 1]] + vmask[faces[3 * f + 2]] >= 2);
  }
  free(copy);
  free(vmask);
  return status;
}

/* Skin pieces that move rigidly with one link or bone (a robot's visual
 * meshes) are carried with it instead of simulated (ss_mesh_rigid_pieces),
 * within --region's mask. */
static int carry_rigid(avatar_body *ab, char *err, int err_sz) {
  const int nv = ab->av->nvert, nf = ab->av->nface;
  uint32_t *part = ab->part = malloc(sizeof(uint32_t) * (size_t)nv);
  unsigned char *mask = ab->face_mask ? ab->face_mask : malloc((size_t)nf);
  ss_weld *weld = NULL;
  int status = part && mask ? SS_OK : SS_E_NOMEM;
  if (!ab->face_mask && mask) memset(mask, 1, (size_t)nf);
  if (!status && ssa_avatar_rigid_parts(ab->av, part) > 0) {
    status = ss_weld_create(&weld, nv, ab->rest, nf, ab->av->faces, -1.0, err, err_sz);
    ss_rigid_count count = {0, 0, 0};
    if (!status)
      status = ss_mesh_rigid_pieces(nv, nf, ab->av->faces, weld->vert_weld, part, mask, &count);
    ab->carried = count.nface_carried;
  }
  if (status == SS_E_NOMEM) snprintf(err, (size_t)err_sz, "out of memory");
  if (mask && !ab->face_mask) {
    if (!status && ab->carried > 0) ab->face_mask = mask;
    else free(mask);
  }
  ss_weld_destroy(weld);
  return status;
}

int avatar_body_carried(const avatar_body *ab) { return ab ? ab->carried : 0; }
const uint32_t *avatar_body_rigid_parts(const avatar_body *ab) { return ab ? ab->part : NULL; }

struct skin_file {
  ss_weld *weld;
  unsigned char *mask;
};

void skin_file_close(skin_file *sf) {
  if (!sf) return;
  ss_weld_destroy(sf->weld);
  free(sf->mask);
  free(sf);
}

int skin_file_open(skin_file **out, const char *path, const ss_body *body, const uint32_t *body_part,
                   double max_distance, ss_sim_mesh *skin, const unsigned char **face_mask,
                   int *carried, char *err, int err_sz) {
  *out = NULL;
  *face_mask = NULL;
  *carried = 0;
  skin_file *sf = calloc(1, sizeof *sf);
  ssa_asset *a = NULL;
  ssa_asset_opts opts = ssa_asset_default_opts();
  opts.z_up = 0;           /* the skin is in the body's frame: coordinates as written */
  opts.ignore_up_axis = 1;
  int status = sf ? ssa_asset_load(&a, path, &opts, err, err_sz) : SS_E_NOMEM;
  if (!status && (a->nvert <= 0 || a->nface <= 0)) {
    snprintf(err, (size_t)err_sz, "--skin %s: it has no triangles", path);
    status = SS_E_MESH;
  }
  if (!status)
    status = ss_weld_create(&sf->weld, a->nvert, a->rest_pos, a->nface, a->faces, -1.0, err, err_sz);
  ssa_asset_destroy(a);
  uint32_t *part = NULL;
  double *dist = NULL;
  if (!status) {
    const ss_weld *w = sf->weld;
    *skin = (ss_sim_mesh){w->nweld, w->pos, w->nface, w->faces};
    part = malloc(sizeof(uint32_t) * (size_t)w->nweld);
    dist = malloc(sizeof(double) * (size_t)w->nweld);
    status = part && dist ? SS_OK : SS_E_NOMEM;
    if (!status)
      status = ss_sim_skin_binding(body->nvert, body->rest, body->nface, body->faces, skin,
                                   body_part, part, dist, err, err_sz);
    int far = 0;
    for (int v = 1; !status && v < w->nweld; v++)
      if (dist[v] > dist[far]) far = v;
    if (!status && !(dist[far] <= max_distance)) {
      snprintf(err, (size_t)err_sz, "--skin %s: its vertex %d is %.4g m from the body, farther "
               "than --skin-max-distance %.4g m (is it in the body's frame and rest pose?)",
               path, w->weld_rep[far], dist[far], max_distance);
      status = SS_E_MESH;
    }
    if (!status && body_part) {
      sf->mask = malloc((size_t)w->nface);
      ss_rigid_count count = {0, 0, 0};
      status = sf->mask ? SS_OK : SS_E_NOMEM;
      if (!status) {
        memset(sf->mask, 1, (size_t)w->nface);
        status = ss_mesh_rigid_pieces(w->nweld, w->nface, w->faces, NULL, part, sf->mask, &count);
      }
      *carried = count.nface_carried;
    }
  } else if (status != SS_E_NOMEM) {
    char why[512];
    snprintf(why, sizeof why, "%s", err);
    snprintf(err, (size_t)err_sz, "--skin %s: %s", path, why);
  }
  if (status == SS_E_NOMEM) snprintf(err, (size_t)err_sz, "--skin %s: out of memory", path);
  free(part);
  free(dist);
  if (status) {
    skin_file_close(sf);
    return status;
  }
  *face_mask = *carried > 0 ? sf->mask : NULL;
  *out = sf;
  return SS_OK;
}

int avatar_body_open(avatar_body **out, const avatar_args *args, ss_body *body,
                     const unsigned char **face_mask, char *err, int err_sz) {
  *out = NULL;
  *face_mask = NULL;
  const int robot_kind = args->avatar || args->urdf;
  if (robot_kind + (args->asset != NULL) != 1 || (args->avatar && args->urdf)) {
    snprintf(err, (size_t)err_sz, "give exactly one body: --avatar demo, --urdf FILE [--mesh FILE] "
                                  "--motion M, or --asset FILE [--anim A]");
    return SS_E_ARG;
  }
  if (args->avatar && strcmp(args->avatar, "demo") != 0 && strcmp(args->avatar, "mannequin") != 0) {
    snprintf(err, (size_t)err_sz, "unknown avatar '%s' (the built-in one is 'demo')", args->avatar);
    return SS_E_ARG;
  }
  if (args->asset && (args->motion || args->mesh)) {
    snprintf(err, (size_t)err_sz, "--asset brings its own mesh and animation: no --mesh or --motion");
    return SS_E_ARG;
  }
  if (args->anim && !args->asset) {
    snprintf(err, (size_t)err_sz, "--anim selects an animation of an --asset");
    return SS_E_ARG;
  }
  if (args->urdf && !args->motion) {
    snprintf(err, (size_t)err_sz, "--urdf needs --motion FILE.csv (or a built-in motion name)");
    return SS_E_ARG;
  }
  avatar_body *ab = calloc(1, sizeof *ab);
  if (!ab) return SS_E_NOMEM;
  ab->builtin = -1;
  ab->anim = -1;
  ssa_avatar_opts opts = ssa_avatar_default_opts();
  opts.package_path = args->package_path;
  if (args->asset_scale > 0.0) opts.asset.scale = args->asset_scale;
  if (args->primitive_edge > 0.0) opts.primitive_edge = args->primitive_edge;
  if (args->max_file_mb > 0.0) opts.asset.max_file_mb = args->max_file_mb;
  if (args->import_timeout_s > 0.0) opts.asset.import_timeout_s = args->import_timeout_s;
  if (args->import_mem_mb > 0.0) opts.asset.import_mem_mb = args->import_mem_mb;
  opts.warn = print_warning;
  if (args->mesh_up_axis && strcmp(args->mesh_up_axis, "file") == 0)
    opts.mesh_up_axis = SSA_UP_AXIS_FILE;
  else if (args->mesh_up_axis && strcmp(args->mesh_up_axis, "ignore") != 0) {
    snprintf(err, (size_t)err_sz, "--mesh-up-axis expects ignore or file, got '%s'",
             args->mesh_up_axis);
    avatar_body_close(ab);
    return SS_E_ARG;
  }
  int status;
  double duration = 0.0;
  if (args->avatar)
    status = ssa_avatar_mannequin(&ab->av, args->avatar_tris, err, err_sz);
  else if (args->urdf)
    status = ssa_avatar_load_urdf(&ab->av, args->urdf, args->mesh, &opts, err, err_sz);
  else
    status = ssa_avatar_load_asset(&ab->av, args->asset, &opts, err, err_sz);
  if (!status && ab->av->robot) {
    const size_t nq = (size_t)(ab->av->robot->njoint > 0 ? ab->av->robot->njoint : 1);
    ab->q = calloc(nq, sizeof(double));
    ab->q_rest = calloc(nq, sizeof(double));
    if (!ab->q || !ab->q_rest) status = SS_E_NOMEM;
    if (!status) status = open_motion(ab, args->motion ? args->motion : "all", args->strict_limits,
                                        &duration, err, err_sz);
  } else if (!status) {
    const ssa_asset *asset = ab->av->asset;
    if (!asset || asset->nanim <= 0) {
      snprintf(err, (size_t)err_sz, "%s has no animation to drive the body", args->asset);
      status = SS_E_ARG;
    } else {
      const char *a = args->anim ? args->anim : "0";
      char *end = NULL;
      errno = 0;
      long idx = strtol(a, &end, 10);
      ab->anim = (*a && !*end && !errno) ? (int)idx : ssa_asset_anim_index(asset, a);
      if (ab->anim < 0 || ab->anim >= asset->nanim) {
        snprintf(err, (size_t)err_sz, "%s has no animation '%s' (it has %d)", args->asset, a,
                 asset->nanim);
        status = SS_E_ARG;
      } else {
        duration = asset->anim_duration[ab->anim];
      }
    }
  }
  if (!status && !(duration <= SSA_MOTION_MAX_S)) { /* an asset's animation (a CSV's is checked) */
    snprintf(err, (size_t)err_sz, "the motion lasts %g s, past the bound of %g s", duration,
             SSA_MOTION_MAX_S);
    status = SS_E_ARG;
  }
  if (!status && args->region) status = open_region(ab, args->region, err, err_sz);
  if (!status) {
    ab->rest = malloc(sizeof(double) * 3 * (size_t)ab->av->nvert);
    status = ab->rest ? pose(ab, 0.0, ab->rest) : SS_E_NOMEM;
    if (!status && ab->q_rest) status = joints_at(ab, 0.0, ab->q_rest); /* where the settle goes */
    if (status) snprintf(err, (size_t)err_sz, "posing the avatar at time 0 failed (%s)",
                         ss_status_string(status));
  }
  if (!status) status = carry_rigid(ab, err, err_sz);
  if (status) {
    avatar_body_close(ab);
    return status;
  }
  body->nvert = ab->av->nvert;
  body->nface = ab->av->nface;
  body->rest = ab->rest;
  body->faces = ab->av->faces;
  body->fps = AVATAR_FPS;
  /* duration is finite and at most SSA_MOTION_MAX_S (checked above): the count fits */
  body->frames = duration > 0.0 ? (int)(duration * AVATAR_FPS + 0.5) : 1;
  if (body->frames < 1) body->frames = 1;
  body->pose = pose;
  body->pose_toward_rest = pose_toward_rest;
  body->user = ab;
  *face_mask = ab->face_mask;
  *out = ab;
  return SS_OK;
}
#else /* built without the avatar layer (urdfdom, assimp) */

int avatar_body_open(avatar_body **out, const avatar_args *args, ss_body *body,
                     const unsigned char **face_mask, char *err, int err_sz) {
  (void)args, (void)body;
  *out = NULL;
  *face_mask = NULL;
  snprintf(err, (size_t)err_sz, "this skinsim was built without avatars (urdfdom, assimp)");
  return SS_E_UNSUPPORTED;
}
void avatar_body_close(avatar_body *ab) { (void)ab; }
int avatar_body_carried(const avatar_body *ab) { (void)ab; return 0; }
const uint32_t *avatar_body_rigid_parts(const avatar_body *ab) { (void)ab; return NULL; }
int skin_file_open(skin_file **out, const char *path, const ss_body *body, const uint32_t *body_part,
                   double max_distance, ss_sim_mesh *skin, const unsigned char **face_mask,
                   int *carried, char *err, int err_sz) {
  (void)path, (void)body, (void)body_part, (void)max_distance, (void)skin;
  *out = NULL;
  *face_mask = NULL;
  *carried = 0;
  snprintf(err, (size_t)err_sz, "this skinsim was built without mesh files (assimp)");
  return SS_E_UNSUPPORTED;
}
void skin_file_close(skin_file *sf) { (void)sf; }
#endif
