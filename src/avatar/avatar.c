/* Avatars: a body mesh, its skin binding (bones, bind matrices, weights) and
 * what drives it, a URDF robot (joint values -> FK) or an asset's animation.
 * Posing is target poses -> bone matrices -> linear blend skinning, into the
 * caller's array, without allocating.
 *
 * Binding a body to a URDF: the body at rest is taken to be the robot at
 * zero joint values, so each link's bind matrix is the inverse of its rest
 * pose (the file's own inverse bind matrices are not used: the file's bone
 * frames need not be the URDF's link frames; only the weights are). */
#include "skin_sim/ss_mesh.h"
#include "skin_sim/ssa_avatar.h"
#include "ssa_util.h"

#include <strings.h>

ssa_avatar_opts ssa_avatar_default_opts(void) {
  ssa_avatar_opts o;
  o.package_path = NULL;
  o.asset = ssa_asset_default_opts();
  o.weld_tol = -1.0;
  o.force_auto_weights = 0;
  o.autoweight = ssa_autoweight_default_opts();
  o.mesh_up_axis = SSA_UP_AXIS_IGNORE;
  o.primitive_edge = 0.02;
  o.warn = NULL;
  o.warn_user = NULL;
  return o;
}

void ssa_avatar_destroy(ssa_avatar *av) {
  if (!av) return;
  ssa_robot_destroy(av->robot);
  ssa_asset_destroy(av->asset);
  free(av->rest_pos);
  free(av->faces);
  free(av->vert_part);
  free(av->vert_src);
  free(av->vert_link);
  free(av->bone_target);
  free(av->bone_offset);
  free(av->bind_pos);
  free(av->w_start);
  free(av->w_bone);
  free(av->w_weight);
  free(av->target_world);
  free(av->bone_mat);
  free(av);
}

/* Allocates the per-vertex and per-bone arrays (weights: nw entries). */
static int alloc_body(ssa_avatar *av, int nvert, int nface, int nbone, int ntarget, int nw) {
  av->nvert = nvert;
  av->nface = nface;
  av->nbone = nbone;
  av->ntarget = ntarget;
  av->rest_pos = malloc(sizeof(double) * 3 * (size_t)nvert);
  av->bind_pos = malloc(sizeof(double) * 3 * (size_t)nvert);
  av->faces = malloc(sizeof(int) * 3 * (size_t)nface);
  av->vert_part = calloc((size_t)nvert, sizeof(int));
  av->vert_src = calloc((size_t)nvert, sizeof(int));
  av->vert_link = calloc((size_t)nvert, sizeof(int));
  av->bone_target = calloc((size_t)(nbone > 0 ? nbone : 1), sizeof(int));
  av->bone_offset = calloc((size_t)(nbone > 0 ? nbone : 1) * 16, sizeof(double));
  av->bone_mat = calloc((size_t)(nbone > 0 ? nbone : 1) * 16, sizeof(double));
  av->target_world = calloc((size_t)(ntarget > 0 ? ntarget : 1) * 16, sizeof(double));
  av->w_start = calloc((size_t)nvert + 1, sizeof(int));
  if (nw >= 0) {
    av->w_bone = calloc((size_t)(nw > 0 ? nw : 1), sizeof(int));
    av->w_weight = calloc((size_t)(nw > 0 ? nw : 1), sizeof(double));
    if (!av->w_bone || !av->w_weight) return 0;
  }
  return av->rest_pos && av->bind_pos && av->faces && av->vert_part && av->vert_src &&
         av->vert_link && av->bone_target && av->bone_offset && av->bone_mat &&
         av->target_world && av->w_start;
}

/* vert_link: the target of each vertex's largest weight. */
static void set_dominant(ssa_avatar *av) {
  for (int v = 0; v < av->nvert; v++) {
    double best = -1;
    int bt = 0;
    for (int k = av->w_start[v]; k < av->w_start[v + 1]; k++)
      if (av->w_weight[k] > best) {
        best = av->w_weight[k];
        bt = av->bone_target[av->w_bone[k]];
      }
    av->vert_link[v] = bt;
  }
}

int ssa_avatar_rigid_parts(const ssa_avatar *av, uint32_t *part) {
  if (!av || !part) return SS_E_ARG;
  int n = 0;
  for (int v = 0; v < av->nvert; v++) {
    int target = -1, one = 1;
    for (int k = av->w_start[v]; k < av->w_start[v + 1] && one; k++) {
      if (!(av->w_weight[k] > 0.0)) continue;
      int t = av->bone_target[av->w_bone[k]];
      if (target < 0) target = t;
      else one = t == target;
    }
    part[v] = one && target >= 0 ? (uint32_t)target + 1u : 0u;
    n += part[v] != 0;
  }
  return n;
}

int ssa_avatar_pose_joints_at(ssa_avatar *av, const double *root_pose, const double *q,
                              double *out) {
  if (!av || !out || av->kind != SSA_AVATAR_ROBOT || !av->robot) return SS_E_ARG;
  if (root_pose)
    for (int i = 0; i < 16; i++)
      if (!isfinite(root_pose[i])) return SS_E_NONFINITE;
  ssa_robot_fk(av->robot, q, av->target_world);
  for (int b = 0; b < av->nbone; b++) {
    const double *tw = av->target_world + 16 * av->bone_target[b];
    if (root_pose) {
      double m[16];
      m4_mul(root_pose, tw, m);
      m4_mul(m, av->bone_offset + 16 * b, av->bone_mat + 16 * b);
    } else {
      m4_mul(tw, av->bone_offset + 16 * b, av->bone_mat + 16 * b);
    }
  }
  ssa_lbs(av->nvert, av->bind_pos, av->w_start, av->w_bone, av->w_weight, av->bone_mat, out);
  return SS_OK;
}

int ssa_avatar_pose_joints(ssa_avatar *av, const double *q, double *out) {
  return ssa_avatar_pose_joints_at(av, NULL, q, out);
}

int ssa_avatar_pose_anim(ssa_avatar *av, int anim, double t, double *out) {
  return ssa_avatar_pose_anim_toward_rest(av, anim, t, 0.0, out);
}

int ssa_avatar_pose_anim_toward_rest(ssa_avatar *av, int anim, double t, double w, double *out) {
  if (!av || !out || av->kind != SSA_AVATAR_ASSET || !av->asset) return SS_E_ARG;
  if (anim < -1 || anim >= av->asset->nanim || !isfinite(t)) return SS_E_ARG;
  if (!(w >= 0.0 && w <= 1.0)) return SS_E_ARG;
  ssa_asset_node_world_toward_rest(av->asset, anim, t, w, av->target_world);
  for (int b = 0; b < av->nbone; b++)
    m4_mul(av->target_world + 16 * av->bone_target[b], av->bone_offset + 16 * b, av->bone_mat + 16 * b);
  ssa_lbs(av->nvert, av->bind_pos, av->w_start, av->w_bone, av->w_weight, av->bone_mat, out);
  return SS_OK;
}

/* ---------------------------------------------------------------- asset avatars */

static void warn(const ssa_avatar_opts *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Files in centimetres or millimetres that say metres (glTF's unit; the
 * Khronos Fox is 155 units long): a body the size of a building, or of a
 * coin, with a skin whose density and stiffness are per square metre. One
 * warning naming the size and the flag that fixes it. */
static void check_size(const ssa_avatar_opts *o, const char *path, const ssa_avatar *av) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int v = 0; v < av->nvert; v++)
    for (int k = 0; k < 3; k++) {
      lo[k] = fmin(lo[k], av->rest_pos[3 * v + k]);
      hi[k] = fmax(hi[k], av->rest_pos[3 * v + k]);
    }
  const double size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
  if (size > SSA_ASSET_SIZE_MAX || (size > 0.0 && size < SSA_ASSET_SIZE_MIN)) {
    const double *r = av->asset->root_fix; /* its first column: the scale times a rotation */
    warn(o, "asset '%s' is %.3g m across read at %.3g m per file unit: a file in %s? (skinsim "
         "--asset-scale sets the metres per unit)", path, size,
         sqrt(r[0] * r[0] + r[4] * r[4] + r[8] * r[8]),
         size > SSA_ASSET_SIZE_MAX ? "centimetres or millimetres" : "kilometres");
  }
}

int ssa_avatar_load_asset(ssa_avatar **out, const char *asset_path, const ssa_avatar_opts *opts,
                          char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  *out = NULL;
  ssa_avatar_opts o = opts ? *opts : ssa_avatar_default_opts();
  ssa_asset *a = NULL;
  int st = ssa_asset_load(&a, asset_path, &o.asset, err, err_sz);
  if (st != SS_OK) return st;
  ssa_avatar *av = calloc(1, sizeof *av);
  int nw = a->w_start[a->nvert];
  if (!av || !alloc_body(av, a->nvert, a->nface, a->nbone, a->nnode, nw)) {
    ssa_avatar_destroy(av);
    ssa_asset_destroy(a);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for asset '%s'", asset_path);
  }
  av->kind = SSA_AVATAR_ASSET;
  av->weight_source = SSA_WEIGHTS_FILE;
  av->asset = a;
  memcpy(av->rest_pos, a->rest_pos, sizeof(double) * 3 * (size_t)a->nvert);
  memcpy(av->bind_pos, a->bind_pos, sizeof(double) * 3 * (size_t)a->nvert);
  memcpy(av->faces, a->faces, sizeof(int) * 3 * (size_t)a->nface);
  memcpy(av->vert_part, a->vert_part, sizeof(int) * (size_t)a->nvert);
  memcpy(av->vert_src, a->vert_src, sizeof(int) * (size_t)a->nvert);
  memcpy(av->bone_target, a->bone_node, sizeof(int) * (size_t)a->nbone);
  memcpy(av->bone_offset, a->bone_offset, sizeof(double) * 16 * (size_t)a->nbone);
  memcpy(av->w_start, a->w_start, sizeof(int) * ((size_t)a->nvert + 1));
  memcpy(av->w_bone, a->w_bone, sizeof(int) * (size_t)nw);
  memcpy(av->w_weight, a->w_weight, sizeof(double) * (size_t)nw);
  set_dominant(av);
  check_size(&o, asset_path, av);
  *out = av;
  return SS_OK;
}

/* ---------------------------------------------------------------- robot avatars */

/* Link segments for automatic weights (see ssa_avatar_load_urdf). */
static int link_segments(const ssa_robot *r, const double *lw, double **seg, int **owner) {
  int nseg = 0;
  for (int l = 0; l < r->nlink; l++) {
    int nchild = 0;
    for (int c = 0; c < r->nlink; c++) nchild += r->link_parent[c] == l;
    nseg += nchild > 0 ? nchild : 1;
  }
  *seg = malloc(sizeof(double) * 6 * (size_t)nseg);
  *owner = malloc(sizeof(int) * (size_t)nseg);
  if (!*seg || !*owner) return -1;
  int k = 0;
  for (int l = 0; l < r->nlink; l++) {
    const double *o = lw + 16 * l;
    double a[3] = {o[3], o[7], o[11]};
    int nchild = 0;
    for (int c = 0; c < r->nlink; c++) {
      if (r->link_parent[c] != l) continue;
      const double *oc = lw + 16 * c;
      double *s = *seg + 6 * k;
      s[0] = a[0], s[1] = a[1], s[2] = a[2];
      s[3] = oc[3], s[4] = oc[7], s[5] = oc[11];
      (*owner)[k++] = l;
      nchild++;
    }
    if (nchild == 0) {
      double *s = *seg + 6 * k;
      s[0] = s[3] = a[0], s[1] = s[4] = a[1], s[2] = s[5] = a[2];
      int p = r->link_parent[l];
      if (p >= 0) {
        const double *op = lw + 16 * p;
        s[3] += a[0] - op[3];
        s[4] += a[1] - op[7];
        s[5] += a[2] - op[11];
      }
      (*owner)[k++] = l;
    }
  }
  return nseg;
}

/* Replaces the avatar's weights (CSR: w_start, w_bone, w_weight) by these,
 * freeing the old ones. */
static void set_weights(ssa_avatar *av, int *ws, int *wb, double *ww) {
  free(av->w_start);
  free(av->w_bone);
  free(av->w_weight);
  av->w_start = ws;
  av->w_bone = wb;
  av->w_weight = ww;
}

/* Bones: one per link, bind = inverse rest pose; weights from auto. */
static int bind_links_auto(ssa_avatar *av, const ssa_avatar_opts *o, const char *what, char *err,
                           int err_sz) {
  const ssa_robot *r = av->robot;
  double *seg = NULL;
  int *owner = NULL;
  int nseg = link_segments(r, av->target_world, &seg, &owner);
  if (nseg < 0) {
    free(seg);
    free(owner);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory binding %s", what);
  }
  set_weights(av, NULL, NULL, NULL);
  char why[512] = "";
  int st = ssa_auto_weights(av->nvert, av->rest_pos, av->nface, av->faces, o->weld_tol, nseg, seg,
                            owner, r->nlink, &o->autoweight, &av->w_start, &av->w_bone,
                            &av->w_weight, NULL, why, sizeof why);
  free(seg);
  free(owner);
  if (st != SS_OK) return ss_fail(err, err_sz, st, "%s: automatic weights failed: %s", what, why);
  av->weight_source = SSA_WEIGHTS_AUTO;
  return SS_OK;
}

static int setup_link_bones(ssa_avatar *av) {
  const ssa_robot *r = av->robot;
  for (int l = 0; l < r->nlink; l++) {
    av->bone_target[l] = l;
    if (!m4_affine_inverse(av->target_world + 16 * l, av->bone_offset + 16 * l)) return 0;
  }
  memcpy(av->bind_pos, av->rest_pos, sizeof(double) * 3 * (size_t)av->nvert);
  return 1;
}

/* Try the file's bones: each binds to the link named like its node or the
 * nearest ancestor node that is a link. Returns 1 if every vertex got weight. */
static int bind_links_from_file(ssa_avatar *av) {
  const ssa_robot *r = av->robot;
  const ssa_asset *a = av->asset;
  int *bone_link = malloc(sizeof(int) * (size_t)(a->nbone > 0 ? a->nbone : 1));
  double *acc = calloc((size_t)r->nlink, sizeof(double));
  int nw_max = a->w_start[a->nvert];
  int *wb = malloc(sizeof(int) * (size_t)(nw_max > 0 ? nw_max : 1));
  double *ww = malloc(sizeof(double) * (size_t)(nw_max > 0 ? nw_max : 1));
  int *ws = calloc((size_t)a->nvert + 1, sizeof(int));
  int ok = bone_link && acc && wb && ww && ws && a->nbone_file > 0;
  int matched_file_bone = 0;
  for (int b = 0; ok && b < a->nbone; b++) {
    int n = a->bone_node[b], l = -1;
    while (n >= 0 && l < 0) {
      l = ssa_robot_link_index(r, a->node_name[n]);
      n = a->node_parent[n];
    }
    bone_link[b] = l;
    if (l >= 0 && b < a->nbone_file) matched_file_bone = 1;
  }
  ok = ok && matched_file_bone;
  int nw = 0;
  for (int v = 0; ok && v < a->nvert; v++) {
    for (int k = a->w_start[v]; k < a->w_start[v + 1]; k++) {
      int l = bone_link[a->w_bone[k]];
      if (l >= 0) acc[l] += a->w_weight[k];
    }
    double sum = 0;
    int first = nw;
    for (int l = 0; l < r->nlink; l++)
      if (acc[l] > 0) {
        wb[nw] = l;
        ww[nw] = acc[l];
        sum += acc[l];
        nw++;
        acc[l] = 0;
      }
    if (!(sum > 0)) ok = 0;
    for (int k = first; k < nw; k++) ww[k] /= sum;
    ws[v + 1] = nw;
  }
  if (ok) {
    set_weights(av, ws, wb, ww);
    av->weight_source = SSA_WEIGHTS_FILE;
  } else {
    free(ws);
    free(wb);
    free(ww);
  }
  free(bone_link);
  free(acc);
  return ok;
}

static int finish_mesh_body(ssa_avatar *av, const ssa_avatar_opts *o, const char *what,
                            int try_file, char *err, int err_sz) {
  if (!setup_link_bones(av))
    return ss_fail(err, err_sz, SS_E_ARG, "%s: a link pose is singular", what);
  if (!(try_file && !o->force_auto_weights && bind_links_from_file(av))) {
    int st = bind_links_auto(av, o, what, err, err_sz);
    if (st != SS_OK) return st;
  }
  set_dominant(av);
  return SS_OK;
}

int ssa_collada_up_axis(const char *path) {
  size_t n = path ? strlen(path) : 0;
  if (n < 4 || strcasecmp(path + n - 4, ".dae") != 0) return -1;
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  char buf[65536];
  size_t got = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[got] = '\0';
  /* <asset> comes first in a COLLADA document; its <up_axis> is X_UP, Y_UP or Z_UP */
  const char *u = strstr(buf, "<up_axis>");
  if (!u) return 1;
  u += 9;
  while (*u == ' ' || *u == '\t' || *u == '\r' || *u == '\n') u++;
  if (strncmp(u, "X_UP", 4) == 0) return 0;
  if (strncmp(u, "Z_UP", 4) == 0) return 2;
  return 1;
}

static void warn(const ssa_avatar_opts *o, const char *fmt, ...) {
  if (!o->warn) return;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  o->warn(o->warn_user, msg);
}

/* One visual's triangles in its own frame: a mesh file (asset) or a tessellated primitive. */
typedef struct visual_part {
  ssa_asset *asset;
  double *prim_pos;
  int *prim_faces;
  int nvert, nface;
  const double *pos;
  const int *faces;
} visual_part;

static int body_from_visuals(ssa_avatar *av, const ssa_avatar_opts *o, char *err, int err_sz) {
  const ssa_robot *r = av->robot;
  const char *urdf = r->path && r->path[0] ? r->path : "(URDF text)";
  ssa_asset_opts ao = o->asset;
  ao.scale = 1.0;
  ao.z_up = 0;
  ao.ignore_up_axis = 1;
  visual_part *parts = calloc((size_t)(r->nvisual > 0 ? r->nvisual : 1), sizeof *parts);
  if (!parts) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for '%s'", urdf);
  int st = SS_OK, nv = 0, nf = 0, nb = 0, other_up = 0, first_up = -1;
  static const char *const up_names[3] = {"X_UP", "Y_UP", "Z_UP"};
  char base[4096];
  snprintf(base, sizeof base, "%s", r->path ? r->path : "");
  char *slash = strrchr(base, '/');
  if (slash) *slash = '\0'; else snprintf(base, sizeof base, ".");
  for (int i = 0; i < r->nvisual && st == SS_OK; i++) {
    visual_part *vp = parts + i;
    const char *link = r->link_name[r->visual_link[i]];
    const int kind = r->visual_kind[i];
    if (kind == SSA_VISUAL_BOX || kind == SSA_VISUAL_SPHERE || kind == SSA_VISUAL_CYLINDER) {
      char why[512] = "";
      st = ssa_primitive_mesh(kind, r->visual_size + 3 * i, o->primitive_edge, &vp->prim_pos,
                              &vp->nvert, &vp->prim_faces, &vp->nface, why, sizeof why);
      if (st != SS_OK) {
        ss_fail(err, err_sz, st, "URDF '%s', link '%s': %s", urdf, link, why);
        break;
      }
      vp->pos = vp->prim_pos;
      vp->faces = vp->prim_faces;
    } else if (kind == SSA_VISUAL_MESH) {
      if (!r->visual_path[i]) {
        char path[4096], why[1024] = "";
        ssa_resolve_uri(r->visual_uri[i], base, o->package_path, path, sizeof path, why,
                        sizeof why);
        st = ss_fail(err, err_sz, SS_E_IO, "URDF '%s', link '%s': %s", urdf, link, why);
        break;
      }
      ssa_asset_opts aoi = ao;
      const int up = ssa_collada_up_axis(r->visual_path[i]);
      if (up >= 0 && up != 2) {
        if (o->mesh_up_axis == SSA_UP_AXIS_FILE) {
          aoi.ignore_up_axis = 0; /* assimp turns the file Y-up, then Y-up becomes Z-up */
          aoi.z_up = 1;
        } else if (other_up++ == 0) {
          first_up = i;
        }
      }
      char why[1024] = "";
      st = ssa_asset_load(&vp->asset, r->visual_path[i], &aoi, why, sizeof why);
      if (st != SS_OK) {
        ss_fail(err, err_sz, st, "URDF '%s', link '%s': %s", urdf, link, why);
        break;
      }
      vp->nvert = vp->asset->nvert;
      vp->nface = vp->asset->nface;
      vp->pos = vp->asset->rest_pos;
      vp->faces = vp->asset->faces;
    } else {
      continue;
    }
    nv += vp->nvert;
    nf += vp->nface;
    nb++;
  }
  if (st == SS_OK && other_up > 0)
    warn(o, "URDF '%s': %d Collada mesh%s declare%s an up axis other than Z (first: '%s', %s) and "
         "%s read as written, as rviz draws %s (mesh up axis 'ignore'); if the robot comes out "
         "in rotated pieces, set the mesh up axis option to 'file' (skinsim --mesh-up-axis "
         "file, avatar_node ~mesh_up_axis:=file)",
         urdf, other_up, other_up == 1 ? "" : "es", other_up == 1 ? "s" : "",
         r->visual_path[first_up], up_names[ssa_collada_up_axis(r->visual_path[first_up])],
         other_up == 1 ? "is" : "are", other_up == 1 ? "it" : "them");
  /* meshes in millimetres or centimetres that the URDF reads as metres (no <mesh
     scale>): a robot the size of a building; one warning, naming the first */
  int nbig = 0, first_big = -1;
  double big_size = 0.0;
  for (int i = 0; st == SS_OK && i < r->nvisual; i++) {
    const visual_part *p = parts + i;
    if (!p->asset || !p->pos) continue;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int v = 0; v < p->nvert; v++)
      for (int k = 0; k < 3; k++) {
        double x = p->pos[3 * v + k] * r->visual_scale[3 * i + k];
        lo[k] = fmin(lo[k], x);
        hi[k] = fmax(hi[k], x);
      }
    double size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    if (size > SSA_ASSET_SIZE_MAX && nbig++ == 0) {
      first_big = i;
      big_size = size;
    }
  }
  if (nbig > 0)
    warn(o, "URDF '%s': %d mesh%s over %g m across (first: '%s' of link '%s', %.3g m at scale "
         "%g %g %g): a file in millimetres or centimetres? (<mesh scale='0.001 0.001 0.001'/> "
         "reads millimetres)", urdf, nbig, nbig == 1 ? "" : "es", SSA_ASSET_SIZE_MAX,
         r->visual_path[first_big], r->link_name[r->visual_link[first_big]], big_size,
         r->visual_scale[3 * first_big], r->visual_scale[3 * first_big + 1],
         r->visual_scale[3 * first_big + 2]);
  if (st == SS_OK && nf == 0)
    st = ss_fail(err, err_sz, SS_E_MESH, "URDF '%s' has no visual meshes or primitives to make a "
                 "body of", urdf);
  if (st == SS_OK && !alloc_body(av, nv, nf, nb, r->nlink, nv))
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for '%s'", urdf);
  if (st == SS_OK) {
    int v0 = 0, f0 = 0, b = 0;
    for (int i = 0; i < r->nvisual; i++) {
      const visual_part *p = parts + i;
      if (!p->pos) continue;
      double sc[16];
      m4_identity(sc);
      if (p->asset) { /* a mesh's scale; a primitive is tessellated at its size */
        sc[0] = r->visual_scale[3 * i];
        sc[5] = r->visual_scale[3 * i + 1];
        sc[10] = r->visual_scale[3 * i + 2];
      }
      av->bone_target[b] = r->visual_link[i];
      m4_mul(r->visual_origin + 16 * i, sc, av->bone_offset + 16 * b);
      memcpy(av->bind_pos + 3 * v0, p->pos, sizeof(double) * 3 * (size_t)p->nvert);
      for (int v = 0; v < p->nvert; v++) {
        av->vert_part[v0 + v] = i;
        av->vert_src[v0 + v] = v;
        av->w_start[v0 + v + 1] = v0 + v + 1;
        av->w_bone[v0 + v] = b;
        av->w_weight[v0 + v] = 1.0;
      }
      for (int f = 0; f < 3 * p->nface; f++) av->faces[3 * f0 + f] = p->faces[f] + v0;
      v0 += p->nvert;
      f0 += p->nface;
      b++;
    }
    av->weight_source = SSA_WEIGHTS_RIGID;
    ssa_avatar_pose_joints(av, NULL, av->rest_pos);
    set_dominant(av);
  }
  for (int i = 0; i < r->nvisual; i++) {
    ssa_asset_destroy(parts[i].asset);
    free(parts[i].prim_pos);
    free(parts[i].prim_faces);
  }
  free(parts);
  return st;
}

int ssa_avatar_from_robot(ssa_avatar **out, ssa_robot *robot, const char *mesh_path,
                          const ssa_avatar_opts *opts, char *err, int err_sz) {
  if (!out) {
    ssa_robot_destroy(robot);
    return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  }
  *out = NULL;
  if (!robot) return ss_fail(err, err_sz, SS_E_ARG, "no robot given");
  ssa_avatar_opts o = opts ? *opts : ssa_avatar_default_opts();
  ssa_avatar *av = calloc(1, sizeof *av);
  if (!av) {
    ssa_robot_destroy(robot);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  }
  av->kind = SSA_AVATAR_ROBOT;
  av->robot = robot;
  int st;
  if (!mesh_path) {
    st = body_from_visuals(av, &o, err, err_sz);
  } else {
    st = ssa_asset_load(&av->asset, mesh_path, &o.asset, err, err_sz);
    if (st == SS_OK) {
      const ssa_asset *a = av->asset;
      if (!alloc_body(av, a->nvert, a->nface, robot->nlink, robot->nlink, -1)) {
        st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for '%s'", mesh_path);
      } else {
        memcpy(av->rest_pos, a->rest_pos, sizeof(double) * 3 * (size_t)a->nvert);
        memcpy(av->faces, a->faces, sizeof(int) * 3 * (size_t)a->nface);
        memcpy(av->vert_part, a->vert_part, sizeof(int) * (size_t)a->nvert);
        memcpy(av->vert_src, a->vert_src, sizeof(int) * (size_t)a->nvert);
        ssa_robot_fk(robot, NULL, av->target_world);
        char what[4200];
        snprintf(what, sizeof what, "mesh file '%s'", mesh_path);
        st = finish_mesh_body(av, &o, what, 1, err, err_sz);
      }
    }
  }
  if (st != SS_OK) {
    ssa_avatar_destroy(av);
    return st;
  }
  *out = av;
  return SS_OK;
}

int ssa_avatar_from_robot_mesh(ssa_avatar **out, ssa_robot *robot, int nvert, const double *pos,
                               int nface, const int *faces, const ssa_avatar_opts *opts,
                               char *err, int err_sz) {
  if (!out) {
    ssa_robot_destroy(robot);
    return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  }
  *out = NULL;
  if (!robot) return ss_fail(err, err_sz, SS_E_ARG, "no robot given");
  char why[512] = "";
  int st = ss_mesh_check(nvert, pos, nface, faces, why, sizeof why);
  if (st != SS_OK) {
    ssa_robot_destroy(robot);
    return ss_fail(err, err_sz, st, "body mesh: %s", why);
  }
  ssa_avatar_opts o = opts ? *opts : ssa_avatar_default_opts();
  ssa_avatar *av = calloc(1, sizeof *av);
  if (!av || !alloc_body(av, nvert, nface, robot->nlink, robot->nlink, -1)) {
    if (av) av->robot = robot; else ssa_robot_destroy(robot);
    ssa_avatar_destroy(av);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the body mesh");
  }
  av->kind = SSA_AVATAR_ROBOT;
  av->robot = robot;
  memcpy(av->rest_pos, pos, sizeof(double) * 3 * (size_t)nvert);
  memcpy(av->faces, faces, sizeof(int) * 3 * (size_t)nface);
  for (int v = 0; v < nvert; v++) av->vert_src[v] = v;
  ssa_robot_fk(robot, NULL, av->target_world);
  st = finish_mesh_body(av, &o, "body mesh", 0, err, err_sz);
  if (st != SS_OK) {
    ssa_avatar_destroy(av);
    return st;
  }
  *out = av;
  return SS_OK;
}

int ssa_avatar_load_urdf(ssa_avatar **out, const char *urdf_path, const char *mesh_path,
                         const ssa_avatar_opts *opts, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  *out = NULL;
  ssa_robot *r = NULL;
  int st = ssa_robot_load(&r, urdf_path, opts ? opts->package_path : NULL, err, err_sz);
  if (st != SS_OK) return st;
  return ssa_avatar_from_robot(out, r, mesh_path, opts, err, err_sz);
}

int ssa_avatar_region_mask(const ssa_avatar *av, int n, const char *const *names,
                           unsigned char *mask, char *err, int err_sz) {
  if (!av || !mask || n < 0 || (n > 0 && !names))
    return ss_fail(err, err_sz, SS_E_ARG, "region: missing arguments");
  memset(mask, 0, (size_t)av->nvert);
  unsigned char *pick = calloc((size_t)(av->ntarget > 0 ? av->ntarget : 1), 1);
  if (!pick) return ss_fail(err, err_sz, SS_E_NOMEM, "region: out of memory");
  for (int i = 0; i < n; i++) {
    int t = av->kind == SSA_AVATAR_ROBOT ? ssa_robot_link_index(av->robot, names[i])
                                         : ssa_asset_node_index(av->asset, names[i]);
    if (t < 0) {
      free(pick);
      return ss_fail(err, err_sz, SS_E_ARG, "region: '%s' is no %s of this avatar",
                     names[i] ? names[i] : "(null)",
                     av->kind == SSA_AVATAR_ROBOT ? "link" : "node");
    }
    pick[t] = 1;
  }
  int count = 0;
  for (int v = 0; v < av->nvert; v++) {
    mask[v] = pick[av->vert_link[v]];
    count += mask[v];
  }
  free(pick);
  return count;
}
