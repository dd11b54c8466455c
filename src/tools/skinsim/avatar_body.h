/* skinsim: avatars as moving bodies for `skinsim run` — the glue between the
 * avatar layer (URDF + mesh + motion, or a rigged asset with its animation,
 * or the built-in mannequin) and the core's ss_body. */
#ifndef SKINSIM_AVATAR_BODY_H
#define SKINSIM_AVATAR_BODY_H

#include "ss_run.h"

typedef struct avatar_args {
  const char *avatar;       /* "demo" (the built-in mannequin) or NULL */
  const char *urdf, *mesh;  /* a URDF, and optionally its body mesh */
  const char *motion;       /* a CSV file, or a built-in motion name (arms, elbows, twist, all, sweep) */
  const char *asset;        /* a rigged character file */
  const char *anim;         /* its animation: name or index (default 0) */
  const char *region;       /* comma-separated links (or asset nodes) to simulate; NULL: all */
  const char *package_path; /* NAME=DIR,... or search roots, for package:// URIs */
  int avatar_tris;          /* mannequin size (0: 5000) */
  double asset_scale;       /* metres per file unit (<= 0: from the file) */
  int strict_limits;        /* 1: joint values outside the URDF limits are an error, not a
                               warning (they are clamped either way) */
  const char *mesh_up_axis; /* "ignore" (NULL: the default) or "file": Collada up axes of
                               URDF visual meshes */
  double primitive_edge;    /* edge length (m) of tessellated URDF primitives (<= 0: default) */
  /* Hostile mesh files (ssa_asset_opts; <= 0: the defaults 256 MB, 60 s, 4096 MB): */
  double max_file_mb;       /* larger mesh files are refused */
  double import_timeout_s;  /* an import (in a child process) taking longer is stopped */
  double import_mem_mb;     /* address space an import may add */
} avatar_args;

typedef struct avatar_body avatar_body;

/* 1 if args name an avatar at all. */
int avatar_args_given(const avatar_args *args);
/* Loads the avatar and its motion; warnings (joint values outside the
 * limits, Collada up axes) go to stderr, one line each. Fills body (valid until avatar_body_close)
 * and, with --region, *face_mask (owned by the avatar_body). Returns SS_OK
 * or an error with one sentence in err. */
int avatar_body_open(avatar_body **out, const avatar_args *args, ss_body *body,
                     const unsigned char **face_mask, char *err, int err_sz);
void avatar_body_close(avatar_body *ab);
/* Skin faces carried rigidly with their link or bone rather than simulated:
 * the pieces whose vertices all move with one (ss_mesh_rigid_pieces), left
 * out of *face_mask. */
int avatar_body_carried(const avatar_body *ab);
/* What each body vertex moves with (ssa_avatar_rigid_parts), or NULL (none rigid, or
 * no avatar). */
const uint32_t *avatar_body_rigid_parts(const avatar_body *ab);

/* --skin FILE: a skin mesh of its own (any file assimp reads, in the body's frame
 * and units at its rest pose), welded and checked against the body: a vertex
 * farther than max_distance from it is refused with a message naming the file.
 * With body_part (may be NULL) the skin's pieces riding one rigid link are left
 * out of *face_mask (over the skin's faces; NULL when none) and counted in
 * *carried. *skin is valid until skin_file_close. */
typedef struct skin_file skin_file;
int skin_file_open(skin_file **out, const char *path, const ss_body *body, const uint32_t *body_part,
                   double max_distance, ss_sim_mesh *skin, const unsigned char **face_mask,
                   int *carried, char *err, int err_sz);
void skin_file_close(skin_file *sf);

#endif
