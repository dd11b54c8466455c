/* Assets through assimp's C API: meshes triangulated and appended into one
 * body (each vertex remembers its source mesh and index), bones with their
 * weights and offset (inverse bind) matrices, the node hierarchy, and
 * animation clips sampled at any time.
 *
 * Skinning follows assimp's convention: a skinned vertex p (mesh space) goes
 * to sum_k w_k N[node_k] O_k p, N the node's world transform and O the bone's
 * offset; a mesh without bones follows its node rigidly (it gets one bone of
 * its own, offset identity), and so do the unweighted vertices of a skinned
 * mesh. On top of the file's root the asset applies root_fix: scale to metres
 * and the file's up axis turned into +Z (REP 103). assimp hands every format
 * over as Y-up (Collada's up axis is converted by assimp itself), except FBX,
 * whose metadata (UpAxis, UpAxisSign, UnitScaleFactor in cm) is read here. */
#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "skin_sim/ssa_avatar.h"
#include "safe_import.h"
#include "ssa_util.h"
#include "ss_free.h"

ssa_asset_opts ssa_asset_default_opts(void) {
  ssa_asset_opts o;
  o.scale = 0.0;
  o.z_up = 1;
  o.ignore_up_axis = 0;
  o.max_file_mb = o.import_timeout_s = o.import_mem_mb = 0.0; /* defaults: safe_import.h */
  return o;
}

void ssa_asset_destroy(ssa_asset *a) {
  if (!a) return;
  free(a->path);
  ssa_free_strs(a->node_name, a->nnode);
  free(a->node_parent);
  free(a->node_local);
  ssa_free_strs(a->part_name, a->npart);
  SS_FREE_ALL(a->part_node, a->bind_pos, a->rest_pos, a->faces, a->vert_part, a->vert_src);
  ssa_free_strs(a->bone_name, a->nbone);
  SS_FREE_ALL(a->bone_node, a->bone_part, a->bone_offset, a->w_start, a->w_bone, a->w_weight);
  ssa_free_strs(a->anim_name, a->nanim);
  SS_FREE_ALL(a->anim_duration, a->anim_chan_start, a->chan_node, a->chan_key_start, a->key_time,
              a->key_value, a->anim_node_chan, a->node_rest_trs, a);
}

int ssa_asset_node_index(const ssa_asset *a, const char *name) {
  if (!a || !name) return -1;
  for (int i = 0; i < a->nnode; i++)
    if (strcmp(a->node_name[i], name) == 0) return i;
  return -1;
}

int ssa_asset_anim_index(const ssa_asset *a, const char *name) {
  if (!a || !name) return -1;
  for (int i = 0; i < a->nanim; i++)
    if (strcmp(a->anim_name[i], name) == 0) return i;
  return -1;
}

static void mat_from_ai(const struct aiMatrix4x4 *m, double *o) {
  const ai_real *s = &m->a1;
  for (int i = 0; i < 16; i++) o[i] = (double)s[i];
}

static int count_nodes(const struct aiNode *n) {
  int c = 1;
  for (unsigned i = 0; i < n->mNumChildren; i++) c += count_nodes(n->mChildren[i]);
  return c;
}

static int add_nodes(ssa_asset *a, const struct aiNode *n, int parent, int *k,
                     const struct aiNode **nodes) {
  int me = (*k)++;
  nodes[me] = n;
  if (!(a->node_name[me] = ssa_strdup(n->mName.data))) return 0;
  a->node_parent[me] = parent;
  mat_from_ai(&n->mTransformation, a->node_local + 16 * me);
  for (unsigned i = 0; i < n->mNumChildren; i++)
    if (!add_nodes(a, n->mChildren[i], me, k, nodes)) return 0;
  return 1;
}

/* Rotation matrix (3x3 inside a 4x4) to a unit quaternion xyzw. */
static void quat_from_m4(const double *m, double *q) {
  double tr = m[0] + m[5] + m[10];
  if (tr > 0) {
    double s = sqrt(tr + 1.0) * 2;
    q[3] = 0.25 * s;
    q[0] = (m[9] - m[6]) / s;
    q[1] = (m[2] - m[8]) / s;
    q[2] = (m[4] - m[1]) / s;
  } else if (m[0] > m[5] && m[0] > m[10]) {
    double s = sqrt(1.0 + m[0] - m[5] - m[10]) * 2;
    q[3] = (m[9] - m[6]) / s;
    q[0] = 0.25 * s;
    q[1] = (m[1] + m[4]) / s;
    q[2] = (m[2] + m[8]) / s;
  } else if (m[5] > m[10]) {
    double s = sqrt(1.0 + m[5] - m[0] - m[10]) * 2;
    q[3] = (m[2] - m[8]) / s;
    q[0] = (m[1] + m[4]) / s;
    q[1] = 0.25 * s;
    q[2] = (m[6] + m[9]) / s;
  } else {
    double s = sqrt(1.0 + m[10] - m[0] - m[5]) * 2;
    q[3] = (m[4] - m[1]) / s;
    q[0] = (m[2] + m[8]) / s;
    q[1] = (m[6] + m[9]) / s;
    q[2] = 0.25 * s;
  }
  double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (int i = 0; i < 4; i++) q[i] = n > 0 ? q[i] / n : (i == 3);
}

/* Rest local transform as T, R (quaternion), S (no shear assumed). */
static void decompose(const double *m, double *trs) {
  trs[0] = m[3];
  trs[1] = m[7];
  trs[2] = m[11];
  double s[3], r[16];
  for (int c = 0; c < 3; c++) {
    s[c] = sqrt(m[c] * m[c] + m[4 + c] * m[4 + c] + m[8 + c] * m[8 + c]);
    if (!(s[c] > 0)) s[c] = 1.0;
  }
  double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
               m[2] * (m[4] * m[9] - m[5] * m[8]);
  if (det < 0) s[0] = -s[0];
  m4_identity(r);
  for (int i = 0; i < 3; i++)
    for (int c = 0; c < 3; c++) r[4 * i + c] = m[4 * i + c] / s[c];
  quat_from_m4(r, trs + 3);
  trs[7] = s[0];
  trs[8] = s[1];
  trs[9] = s[2];
}

static double meta_number(const struct aiMetadata *md, const char *key, double dflt, int *found) {
  if (found) *found = 0;
  if (!md) return dflt;
  for (unsigned i = 0; i < md->mNumProperties; i++) {
    if (strcmp(md->mKeys[i].data, key) != 0 || !md->mValues[i].mData) continue;
    const void *p = md->mValues[i].mData;
    double v = dflt;
    switch (md->mValues[i].mType) {
      case AI_INT32: v = *(const int32_t *)p; break;
      case AI_UINT64: v = (double)*(const uint64_t *)p; break;
      case AI_FLOAT: v = *(const float *)p; break;
      case AI_DOUBLE: v = *(const double *)p; break;
      default: continue;
    }
    if (found) *found = 1;
    return v;
  }
  return dflt;
}

/* The rotation taking the file's up axis (0 x, 1 y, 2 z; sign) onto +Z. */
static void up_to_z(int axis, int sign, double *m) {
  m4_identity(m);
  const double ux = axis == 0 ? 1 : 0, uy = axis == 1 ? 1 : 0;
  if (axis == 2 && sign > 0) return;
  if (axis == 2) { /* -Z: half turn about X */
    m[5] = -1;
    m[10] = -1;
    return;
  }
  double about[3] = {uy * sign, -ux * sign, 0.0}; /* u x e_z ... axis = u x z */
  double n = sqrt(about[0] * about[0] + about[1] * about[1]);
  about[0] /= n;
  about[1] /= n;
  m4_axis_angle(about, SSA_PI / 2, m);
}

static int load_scene(ssa_asset *a, const struct aiScene *sc, const ssa_asset_opts *o,
                      const char *path, char *err, int err_sz) {
  /* ---- root fix */
  int is_fbx = ssa_has_ext(path, ".fbx");
  double scale = o->scale;
  if (!(scale > 0)) {
    int found = 0;
    double usf = meta_number(sc->mMetaData, "UnitScaleFactor", 1.0, &found);
    scale = (is_fbx && found && usf > 0 && isfinite(usf)) ? usf / 100.0 : 1.0;
  }
  int up_axis = 1, up_sign = 1;
  if (is_fbx) {
    int f1 = 0, f2 = 0;
    double ax = meta_number(sc->mMetaData, "UpAxis", 1, &f1);
    double sg = meta_number(sc->mMetaData, "UpAxisSign", 1, &f2);
    if (f1 && ax >= 0 && ax <= 2) up_axis = (int)ax;
    if (f2 && sg < 0) up_sign = -1;
  }
  double rot[16], sc_m[16];
  if (o->z_up && !o->ignore_up_axis)
    up_to_z(up_axis, up_sign, rot);
  else
    m4_identity(rot);
  m4_identity(sc_m);
  sc_m[0] = sc_m[5] = sc_m[10] = scale;
  m4_mul(rot, sc_m, a->root_fix);

  /* ---- nodes */
  if (!sc->mRootNode) return ss_fail(err, err_sz, SS_E_MESH, "asset '%s' has no nodes", path);
  a->nnode = count_nodes(sc->mRootNode);
  const struct aiNode **nodes = calloc((size_t)a->nnode, sizeof *nodes);
  a->node_name = calloc((size_t)a->nnode, sizeof(char *));
  a->node_parent = calloc((size_t)a->nnode, sizeof(int));
  a->node_local = calloc((size_t)a->nnode * 16, sizeof(double));
  a->node_rest_trs = calloc((size_t)a->nnode * 10, sizeof(double));
  int k = 0;
  if (!nodes || !a->node_name || !a->node_parent || !a->node_local || !a->node_rest_trs ||
      !add_nodes(a, sc->mRootNode, -1, &k, nodes)) {
    free(nodes);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
  }
  for (int i = 0; i < a->nnode; i++) decompose(a->node_local + 16 * i, a->node_rest_trs + 10 * i);

  /* ---- parts: meshes with triangles */
  int npart = 0, nv = 0, nf = 0, nbone = 0, nweights = 0;
  for (unsigned m = 0; m < sc->mNumMeshes; m++) {
    const struct aiMesh *me = sc->mMeshes[m];
    int tris = 0;
    for (unsigned f = 0; f < me->mNumFaces; f++) tris += me->mFaces[f].mNumIndices == 3;
    if (!tris) continue;
    npart++;
    nv += (int)me->mNumVertices;
    nf += tris;
    nbone += (int)me->mNumBones + 1; /* the part's own rigid bone, used if needed */
    for (unsigned b = 0; b < me->mNumBones; b++) nweights += (int)me->mBones[b]->mNumWeights;
    nweights += (int)me->mNumVertices;
  }
  if (nf == 0) {
    free(nodes);
    return ss_fail(err, err_sz, SS_E_MESH, "asset '%s' contains no triangles", path);
  }
  a->npart = npart;
  a->nvert = nv;
  a->nface = nf;
  a->part_name = calloc((size_t)npart, sizeof(char *));
  a->part_node = calloc((size_t)npart, sizeof(int));
  a->bind_pos = malloc(sizeof(double) * 3 * (size_t)nv);
  a->rest_pos = malloc(sizeof(double) * 3 * (size_t)nv);
  a->faces = malloc(sizeof(int) * 3 * (size_t)nf);
  a->vert_part = malloc(sizeof(int) * (size_t)nv);
  a->vert_src = malloc(sizeof(int) * (size_t)nv);
  a->bone_name = calloc((size_t)nbone, sizeof(char *));
  a->nbone = a->bone_name ? nbone : 0; /* capacity until the bones are known: frees on error */
  a->bone_node = calloc((size_t)nbone, sizeof(int));
  a->bone_part = calloc((size_t)nbone, sizeof(int));
  a->bone_offset = calloc((size_t)nbone * 16, sizeof(double));
  a->w_start = calloc((size_t)nv + 1, sizeof(int));
  a->w_bone = calloc((size_t)nweights, sizeof(int));
  a->w_weight = calloc((size_t)nweights, sizeof(double));
  /* temporary per-vertex lists in COO form */
  int *coo_v = malloc(sizeof(int) * (size_t)nweights);
  if (!a->part_name || !a->part_node || !a->bind_pos || !a->rest_pos || !a->faces ||
      !a->vert_part || !a->vert_src || !a->bone_name || !a->bone_node || !a->bone_part ||
      !a->bone_offset || !a->w_start || !a->w_bone || !a->w_weight || !coo_v) {
    free(nodes);
    free(coo_v);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
  }
  /* file bones first, then the rigid bones of parts that need one */
  int p = 0, v0 = 0, f0 = 0, nb = 0, nw = 0;
  int *rigid_needed = calloc((size_t)npart, sizeof(int));
  int *part_mesh = calloc((size_t)npart, sizeof(int));
  int *part_v0 = calloc((size_t)npart, sizeof(int));
  if (!rigid_needed || !part_mesh || !part_v0) {
    SS_FREE_ALL(nodes, coo_v, rigid_needed, part_mesh, part_v0);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
  }
  int status = SS_OK;
  for (unsigned m = 0; m < sc->mNumMeshes && status == SS_OK; m++) {
    const struct aiMesh *me = sc->mMeshes[m];
    int tris = 0;
    for (unsigned f = 0; f < me->mNumFaces; f++) tris += me->mFaces[f].mNumIndices == 3;
    if (!tris) continue;
    part_mesh[p] = (int)m;
    part_v0[p] = v0;
    a->part_name[p] = ssa_strdup(me->mName.data);
    a->part_node[p] = 0;
    for (int i = 0; i < a->nnode; i++) {
      int hit = 0;
      for (unsigned q = 0; q < nodes[i]->mNumMeshes; q++) hit |= nodes[i]->mMeshes[q] == m;
      if (hit) {
        a->part_node[p] = i;
        break;
      }
    }
    for (unsigned i = 0; i < me->mNumVertices; i++) {
      double *d = a->bind_pos + 3 * (v0 + (int)i);
      d[0] = me->mVertices[i].x;
      d[1] = me->mVertices[i].y;
      d[2] = me->mVertices[i].z;
      if (!isfinite(d[0]) || !isfinite(d[1]) || !isfinite(d[2])) {
        status = ss_fail(err, err_sz, SS_E_NONFINITE,
                         "asset '%s': vertex %u of mesh %u ('%s') is not finite", path, i, m,
                         me->mName.data);
        break;
      }
      a->vert_part[v0 + (int)i] = p;
      a->vert_src[v0 + (int)i] = (int)i;
    }
    for (unsigned f = 0; f < me->mNumFaces; f++) {
      if (me->mFaces[f].mNumIndices != 3) continue;
      for (int c = 0; c < 3; c++) {
        unsigned idx = me->mFaces[f].mIndices[c];
        if (idx >= me->mNumVertices) {
          status = ss_fail(err, err_sz, SS_E_MESH,
                           "asset '%s': face %u of mesh %u indexes vertex %u of %u", path, f, m,
                           idx, me->mNumVertices);
          break;
        }
        a->faces[3 * f0 + c] = v0 + (int)idx;
      }
      f0++;
    }
    for (unsigned b = 0; b < me->mNumBones && status == SS_OK; b++) {
      const struct aiBone *bo = me->mBones[b];
      a->bone_name[nb] = ssa_strdup(bo->mName.data);
      a->bone_node[nb] = ssa_asset_node_index(a, bo->mName.data);
      if (a->bone_node[nb] < 0) a->bone_node[nb] = a->part_node[p];
      a->bone_part[nb] = p;
      mat_from_ai(&bo->mOffsetMatrix, a->bone_offset + 16 * nb);
      for (unsigned w = 0; w < bo->mNumWeights; w++) {
        unsigned vi = bo->mWeights[w].mVertexId;
        double wt = bo->mWeights[w].mWeight;
        if (!isfinite(wt)) {
          status = ss_fail(err, err_sz, SS_E_NONFINITE,
                           "asset '%s': bone '%s' has a non-finite weight", path, bo->mName.data);
          break;
        }
        if (vi >= me->mNumVertices || !(wt > 0)) continue;
        coo_v[nw] = v0 + (int)vi;
        a->w_bone[nw] = nb;
        a->w_weight[nw] = wt;
        nw++;
      }
      nb++;
    }
    v0 += (int)me->mNumVertices;
    p++;
  }
  a->nbone_file = nb;
  if (status == SS_OK) {
    /* vertices without weight: rigid on their part's node */
    double *wsum = calloc((size_t)nv, sizeof(double));
    if (!wsum) status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
    for (int i = 0; wsum && i < nw; i++) wsum[coo_v[i]] += a->w_weight[i];
    for (int v = 0; wsum && v < nv; v++)
      if (!(wsum[v] > 0)) rigid_needed[a->vert_part[v]] = 1;
    int *rigid_bone = calloc((size_t)npart, sizeof(int));
    for (int q = 0; rigid_bone && q < npart; q++) {
      rigid_bone[q] = -1;
      if (!rigid_needed[q]) continue;
      rigid_bone[q] = nb;
      a->bone_name[nb] = ssa_strdup(a->node_name[a->part_node[q]]);
      a->bone_node[nb] = a->part_node[q];
      a->bone_part[nb] = q;
      m4_identity(a->bone_offset + 16 * nb);
      nb++;
    }
    for (int v = 0; wsum && rigid_bone && v < nv; v++)
      if (!(wsum[v] > 0)) {
        coo_v[nw] = v;
        a->w_bone[nw] = rigid_bone[a->vert_part[v]];
        a->w_weight[nw] = 1.0;
        wsum[v] = 1.0;
        nw++;
      }
    a->nbone = nb;
    for (int i = 0; i < nb; i++)
      if (!a->bone_name[i] && status == SS_OK)
        status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
    /* COO -> CSR, weights normalised */
    if (wsum && rigid_bone && status == SS_OK) {
      int *cnt = a->w_start;
      for (int i = 0; i < nw; i++) cnt[coo_v[i] + 1]++;
      for (int v = 0; v < nv; v++) cnt[v + 1] += cnt[v];
      int *fill = malloc(sizeof(int) * (size_t)(nv + 1));
      int *wb = malloc(sizeof(int) * (size_t)(nw > 0 ? nw : 1));
      double *ww = malloc(sizeof(double) * (size_t)(nw > 0 ? nw : 1));
      if (!fill || !wb || !ww) {
        status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
      } else {
        memcpy(fill, cnt, sizeof(int) * (size_t)(nv + 1));
        for (int i = 0; i < nw; i++) {
          int at = fill[coo_v[i]]++;
          wb[at] = a->w_bone[i];
          ww[at] = a->w_weight[i] / wsum[coo_v[i]];
        }
        memcpy(a->w_bone, wb, sizeof(int) * (size_t)nw);
        memcpy(a->w_weight, ww, sizeof(double) * (size_t)nw);
      }
      free(fill);
      free(wb);
      free(ww);
    } else if (status == SS_OK) {
      status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
    }
    free(wsum);
    free(rigid_bone);
  }
  SS_FREE_ALL(rigid_needed, part_mesh, part_v0, coo_v);
  for (int q = 0; q < npart && status == SS_OK; q++)
    if (!a->part_name[q])
      status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
  if (status != SS_OK) {
    free(nodes);
    return status;
  }

  /* ---- animations */
  a->nanim = (int)sc->mNumAnimations;
  int nchan = 0, nkey = 0;
  for (int i = 0; i < a->nanim; i++) {
    const struct aiAnimation *an = sc->mAnimations[i];
    nchan += (int)an->mNumChannels;
    for (unsigned c = 0; c < an->mNumChannels; c++) {
      const struct aiNodeAnim *ch = an->mChannels[c];
      nkey += (int)(ch->mNumPositionKeys + ch->mNumRotationKeys + ch->mNumScalingKeys);
    }
  }
  a->anim_name = calloc((size_t)(a->nanim > 0 ? a->nanim : 1), sizeof(char *));
  a->anim_duration = calloc((size_t)(a->nanim > 0 ? a->nanim : 1), sizeof(double));
  a->anim_chan_start = calloc((size_t)a->nanim + 1, sizeof(int));
  a->chan_node = calloc((size_t)(nchan > 0 ? nchan : 1), sizeof(int));
  a->chan_key_start = calloc((size_t)nchan * 4 + 1, sizeof(int));
  a->key_time = calloc((size_t)(nkey > 0 ? nkey : 1), sizeof(double));
  a->key_value = calloc((size_t)(nkey > 0 ? nkey : 1) * 4, sizeof(double));
  a->anim_node_chan = malloc(sizeof(int) * (size_t)(a->nanim > 0 ? a->nanim : 1) * (size_t)a->nnode);
  if (!a->anim_name || !a->anim_duration || !a->anim_chan_start || !a->chan_node ||
      !a->chan_key_start || !a->key_time || !a->key_value || !a->anim_node_chan) {
    free(nodes);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
  }
  int ci = 0, ki = 0;
  for (int i = 0; i < a->nanim; i++) {
    const struct aiAnimation *an = sc->mAnimations[i];
    double tps = an->mTicksPerSecond > 0 ? an->mTicksPerSecond : 25.0;
    if (!(a->anim_name[i] = ssa_strdup(an->mName.data))) {
      free(nodes);
      return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
    }
    a->anim_duration[i] = an->mDuration / tps;
    a->anim_chan_start[i] = ci;
    for (int n = 0; n < a->nnode; n++) a->anim_node_chan[i * a->nnode + n] = -1;
    for (unsigned c = 0; c < an->mNumChannels; c++, ci++) {
      const struct aiNodeAnim *ch = an->mChannels[c];
      int node = ssa_asset_node_index(a, ch->mNodeName.data);
      a->chan_node[ci] = node;
      if (node >= 0 && a->anim_node_chan[i * a->nnode + node] < 0)
        a->anim_node_chan[i * a->nnode + node] = ci;
      a->chan_key_start[4 * ci + 0] = ki;
      for (unsigned q = 0; q < ch->mNumPositionKeys; q++, ki++) {
        a->key_time[ki] = ch->mPositionKeys[q].mTime / tps;
        a->key_value[4 * ki + 0] = ch->mPositionKeys[q].mValue.x;
        a->key_value[4 * ki + 1] = ch->mPositionKeys[q].mValue.y;
        a->key_value[4 * ki + 2] = ch->mPositionKeys[q].mValue.z;
      }
      a->chan_key_start[4 * ci + 1] = ki;
      for (unsigned q = 0; q < ch->mNumRotationKeys; q++, ki++) {
        a->key_time[ki] = ch->mRotationKeys[q].mTime / tps;
        a->key_value[4 * ki + 0] = ch->mRotationKeys[q].mValue.x;
        a->key_value[4 * ki + 1] = ch->mRotationKeys[q].mValue.y;
        a->key_value[4 * ki + 2] = ch->mRotationKeys[q].mValue.z;
        a->key_value[4 * ki + 3] = ch->mRotationKeys[q].mValue.w;
      }
      a->chan_key_start[4 * ci + 2] = ki;
      for (unsigned q = 0; q < ch->mNumScalingKeys; q++, ki++) {
        a->key_time[ki] = ch->mScalingKeys[q].mTime / tps;
        a->key_value[4 * ki + 0] = ch->mScalingKeys[q].mValue.x;
        a->key_value[4 * ki + 1] = ch->mScalingKeys[q].mValue.y;
        a->key_value[4 * ki + 2] = ch->mScalingKeys[q].mValue.z;
      }
      a->chan_key_start[4 * ci + 3] = ki;
    }
  }
  a->anim_chan_start[a->nanim] = ci;
  for (int i = 0; i < ki; i++)
    for (int c = 0; c < 4; c++)
      if (!isfinite(a->key_value[4 * i + c]) || !isfinite(a->key_time[i])) {
        free(nodes);
        return ss_fail(err, err_sz, SS_E_NONFINITE, "asset '%s': an animation key is not finite",
                       path);
      }
  free(nodes);

  /* ---- rest pose */
  double *nw_m = malloc(sizeof(double) * 16 * (size_t)a->nnode);
  double *bm = malloc(sizeof(double) * 16 * (size_t)a->nbone);
  if (!nw_m || !bm) {
    free(nw_m);
    free(bm);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading asset '%s'", path);
  }
  ssa_asset_node_world(a, -1, 0.0, nw_m);
  ssa_asset_skin_matrices(a, nw_m, bm);
  ssa_lbs(a->nvert, a->bind_pos, a->w_start, a->w_bone, a->w_weight, bm, a->rest_pos);
  free(nw_m);
  free(bm);
  for (int i = 0; i < 3 * a->nvert; i++)
    if (!isfinite(a->rest_pos[i]))
      return ss_fail(err, err_sz, SS_E_NONFINITE,
                     "asset '%s': vertex %d is not finite in the rest pose (singular transforms)",
                     path, i / 3);
  return SS_OK;
}

int ssa_asset_load(ssa_asset **out, const char *path, const ssa_asset_opts *opts, char *err,
                   int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  *out = NULL;
  if (!path) return ss_fail(err, err_sz, SS_E_ARG, "no asset path given");
  ssa_asset_opts o = opts ? *opts : ssa_asset_default_opts();
  int st0 = ssa_check_mesh_file(path, &o, err, err_sz); /* before anything opens it */
  if (st0 != SS_OK) return st0;
  struct aiPropertyStore *props = aiCreatePropertyStore();
  if (!props) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading '%s'", path);
  aiSetImportPropertyInteger(props, AI_CONFIG_PP_SBP_REMOVE,
                             aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  if (o.ignore_up_axis) aiSetImportPropertyInteger(props, AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, 1);
  /* in a child: no hang, no bloat; the positions checked finite there, then
     joined (JoinIdenticalVertices would merge a NaN vertex into another) */
  const struct aiScene *sc =
      ssa_safe_import(path, aiProcess_Triangulate | aiProcess_SortByPType,
                      aiProcess_JoinIdenticalVertices, props, &o, &st0, err, err_sz);
  aiReleasePropertyStore(props);
  if (!sc) return st0;
  ssa_asset *a = calloc(1, sizeof *a);
  if (!a) {
    aiReleaseImport(sc);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading '%s'", path);
  }
  int st = (a->path = ssa_strdup(path)) ? SS_OK : SS_E_NOMEM;
  if (st == SS_OK)
    st = load_scene(a, sc, &o, path, err, err_sz);
  else
    ss_fail(err, err_sz, st, "out of memory reading '%s'", path);
  aiReleaseImport(sc);
  if (st != SS_OK) {
    ssa_asset_destroy(a);
    return st;
  }
  *out = a;
  return SS_OK;
}

/* ---------------------------------------------------------------- sampling */

/* Index k with key_time[k] <= t < key_time[k+1] in [lo, hi); -1 before the first key. */
static int find_key(const double *tk, int lo, int hi, double t) {
  if (t < tk[lo]) return -1;
  int a = lo, b = hi - 1;
  while (a < b) {
    int m = (a + b + 1) / 2;
    if (tk[m] <= t)
      a = m;
    else
      b = m - 1;
  }
  return a;
}

static void lerp_keys(const ssa_asset *as, int lo, int hi, double t, int n, double *out) {
  int k = find_key(as->key_time, lo, hi, t);
  if (k < 0) k = lo;
  if (k >= hi - 1 || t <= as->key_time[k]) {
    for (int c = 0; c < n; c++) out[c] = as->key_value[4 * k + c];
    return;
  }
  double t0 = as->key_time[k], t1 = as->key_time[k + 1];
  double u = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
  for (int c = 0; c < n; c++)
    out[c] = (1 - u) * as->key_value[4 * k + c] + u * as->key_value[4 * (k + 1) + c];
}

/* Spherical interpolation from unit quaternion a to b (the short way), u in [0, 1]. */
static void slerp(const double *a, const double *b, double u, double *q) {
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  double s = 1.0;
  if (d < 0) {
    d = -d;
    s = -1.0;
  }
  double wa, wb;
  if (d > 0.9995) {
    wa = 1 - u;
    wb = u;
  } else {
    double th = acos(d), st = sin(th);
    wa = sin((1 - u) * th) / st;
    wb = sin(u * th) / st;
  }
  double n = 0;
  for (int c = 0; c < 4; c++) {
    q[c] = wa * a[c] + wb * s * b[c];
    n += q[c] * q[c];
  }
  n = sqrt(n);
  for (int c = 0; c < 4; c++) q[c] = n > 0 ? q[c] / n : (c == 3);
}

static void slerp_keys(const ssa_asset *as, int lo, int hi, double t, double *q) {
  int k = find_key(as->key_time, lo, hi, t);
  if (k < 0) k = lo;
  const double *a = as->key_value + 4 * k;
  if (k >= hi - 1 || t <= as->key_time[k]) {
    memcpy(q, a, 4 * sizeof(double));
    return;
  }
  const double *b = as->key_value + 4 * (k + 1);
  double t0 = as->key_time[k], t1 = as->key_time[k + 1];
  double u = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
  slerp(a, b, u, q);
}

/* Node i's local translation, rotation and scale in animation anim (>= 0) at
 * t; 0 if the animation has no channel for it (its local matrix holds). */
static int node_trs(const ssa_asset *a, int anim, int i, double t, double tr[3], double q[4],
                    double s[3]) {
  int ch = a->anim_node_chan[anim * a->nnode + i];
  if (ch < 0) return 0;
  const double *rest = a->node_rest_trs + 10 * i;
  const int *ks = a->chan_key_start + 4 * ch;
  if (ks[1] > ks[0])
    lerp_keys(a, ks[0], ks[1], t, 3, tr);
  else
    memcpy(tr, rest, 3 * sizeof(double));
  if (ks[2] > ks[1])
    slerp_keys(a, ks[1], ks[2], t, q);
  else
    memcpy(q, rest + 3, 4 * sizeof(double));
  if (ks[3] > ks[2])
    lerp_keys(a, ks[2], ks[3], t, 3, s);
  else
    memcpy(s, rest + 7, 3 * sizeof(double));
  return 1;
}

void ssa_asset_node_world(const ssa_asset *a, int anim, double t, double *node_world) {
  ssa_asset_node_world_toward_rest(a, anim, t, 0.0, node_world);
}

void ssa_asset_node_world_toward_rest(const ssa_asset *a, int anim, double t, double w,
                                      double *node_world) {
  if (!a || !node_world) return;
  if (anim >= a->nanim) anim = -1;
  for (int i = 0; i < a->nnode; i++) {
    double local[16], tr[3], q[4], s[3];
    if (anim < 0 || !node_trs(a, anim, i, t, tr, q, s)) {
      memcpy(local, a->node_local + 16 * i, sizeof local);
    } else {
      if (w > 0.0) { /* a fraction w of the way to the clip's first pose, in T, R and S */
        double tr0[3], q0[4], s0[3];
        node_trs(a, anim, i, 0.0, tr0, q0, s0);
        const double u = w < 1.0 ? w : 1.0;
        for (int k = 0; k < 3; k++) {
          tr[k] += u * (tr0[k] - tr[k]);
          s[k] += u * (s0[k] - s[k]);
        }
        double qt[4];
        memcpy(qt, q, sizeof qt);
        slerp(qt, q0, u, q);
      }
      m4_from_tqs(tr, q, s, local);
    }
    const double *parent = a->node_parent[i] >= 0 ? node_world + 16 * a->node_parent[i] : a->root_fix;
    m4_mul(parent, local, node_world + 16 * i);
  }
}

void ssa_asset_skin_matrices(const ssa_asset *a, const double *node_world, double *bone_mat) {
  if (!a || !node_world || !bone_mat) return;
  for (int b = 0; b < a->nbone; b++)
    m4_mul(node_world + 16 * a->bone_node[b], a->bone_offset + 16 * b, bone_mat + 16 * b);
}

void ssa_lbs(int nvert, const double *bind_pos, const int *w_start, const int *w_bone,
             const double *w_weight, const double *bone_mat, double *out) {
  for (int v = 0; v < nvert; v++) {
    const double *p = bind_pos + 3 * v;
    double acc[3] = {0, 0, 0};
    for (int k = w_start[v]; k < w_start[v + 1]; k++) {
      double q[3], w = w_weight[k];
      m4_point(bone_mat + 16 * w_bone[k], p, q);
      acc[0] += w * q[0];
      acc[1] += w * q[1];
      acc[2] += w * q[2];
    }
    out[3 * v] = acc[0];
    out[3 * v + 1] = acc[1];
    out[3 * v + 2] = acc[2];
  }
}
