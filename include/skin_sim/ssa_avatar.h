/* skin_sim avatar layer: kinematic bodies for the skin to slide on.
 *
 * A robot (URDF, read with urdfdom) gives links and joints; forward
 * kinematics turns joint values into link poses. An asset (any file assimp
 * reads: glTF, FBX, Collada, X, OBJ, PLY ...) gives a triangle mesh, bones
 * with weights and inverse bind matrices, a node hierarchy and animation
 * clips. A skin binding (weights and bind matrices) turns the poses of its
 * targets (links or nodes) into vertex positions by linear blend skinning.
 * An avatar puts these together: a body mesh driven by joint values or by an
 * animation clip, with the topology (welded, see ss_mesh.h) the core needs.
 *
 * Conventions. Poses and bone matrices are 4x4 homogeneous matrices stored
 * row-major in 16 doubles (last row 0 0 0 1), mapping a child frame into
 * its parent or world frame. Lengths in metres where the file says so (REP
 * 103); assets are turned Z-up (see ssa_asset_opts). Arrays in the public
 * structs are flat, their shapes written beside them, and read-only to
 * callers. Every _create/_load has a _destroy that accepts NULL.
 * Loading allocates; posing allocates nothing. An object is not safe to pose
 * from two threads at once (it owns its scratch). Functions that can fail
 * return an ss_status (0 ok, negative error); loaders also write one sentence
 * naming the file and the problem into (err, err_sz) (err may be NULL).
 * The layer never prints and never exits. */
#ifndef SKIN_SIM_SSA_AVATAR_H
#define SKIN_SIM_SSA_AVATAR_H

#include <stdint.h>
#include <stdio.h>

#include "ss_common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ================================================================ robot (URDF) */

enum ssa_joint_type {
  SSA_JOINT_FIXED = 0,
  SSA_JOINT_REVOLUTE = 1,    /* rotation about axis by q (rad), clamped to limits */
  SSA_JOINT_CONTINUOUS = 2,  /* rotation about axis by q (rad), no limits */
  SSA_JOINT_PRISMATIC = 3,   /* translation along axis by q (m), clamped to limits */
  SSA_JOINT_UNSUPPORTED = 4  /* floating and planar joints: held at their origin */
};

typedef struct ssa_robot {
  char *name;               /* robot name from the URDF */
  char *path;               /* the URDF file read, or "" for text */
  int root_link;            /* index of the root link */
  int nlink;
  char **link_name;         /* (nlink) */
  int *link_parent;         /* (nlink) parent link, -1 for the root */
  int *link_joint;          /* (nlink) joint from the parent, -1 for the root */
  int *link_order;          /* (nlink) link indices, every parent before its children */
  int njoint;
  char **joint_name;        /* (njoint) */
  int *joint_type;          /* (njoint) ssa_joint_type */
  int *joint_parent_link;   /* (njoint) */
  int *joint_child_link;    /* (njoint) */
  double *joint_origin;     /* (njoint x 16) joint frame in its parent link frame */
  double *joint_axis;       /* (njoint x 3) unit axis in the joint frame */
  int *joint_has_limits;    /* (njoint) 1 for revolute and prismatic joints with limits
                               (lower = upper = 0, urdfdom's default, counts as none) */
  double *joint_lower;      /* (njoint) */
  double *joint_upper;      /* (njoint) */
  int *joint_mimic;         /* (njoint) joint mimicked (value = mult * q[m] + off), or -1 */
  double *joint_mimic_mult; /* (njoint) */
  double *joint_mimic_off;  /* (njoint) */
  int nvisual;
  int *visual_link;         /* (nvisual) link that wears the visual */
  int *visual_is_mesh;      /* (nvisual) 1 for a mesh, 0 for a primitive (box, cylinder, sphere) */
  char **visual_uri;        /* (nvisual) the mesh filename as written in the URDF, or NULL */
  char **visual_path;       /* (nvisual) that file resolved to a readable path, or NULL */
  double *visual_origin;    /* (nvisual x 16) visual frame in its link frame */
  double *visual_scale;     /* (nvisual x 3) mesh scale */
  int *visual_kind;         /* (nvisual) ssa_visual_kind */
  double *visual_size;      /* (nvisual x 3) box: x y z sizes; sphere: radius; cylinder: radius,
                               length (along the visual frame's z), in metres */
} ssa_robot;

/* The geometry of a URDF visual. */
enum ssa_visual_kind {
  SSA_VISUAL_NONE = 0,
  SSA_VISUAL_SPHERE = 1,
  SSA_VISUAL_BOX = 2,
  SSA_VISUAL_CYLINDER = 3,
  SSA_VISUAL_MESH = 4
};

/* Reads a URDF file. package_path resolves package:// mesh URIs: a list of
 * entries separated by ':' or ';', each either NAME=DIR (package NAME is
 * folder DIR; these win) or a search root (package NAME is a folder named
 * NAME, or a folder whose package.xml has <name>NAME</name>, found under it
 * at most 4 levels deep, depth first in name order); ROS_PACKAGE_PATH roots
 * are searched after them. package_path may be NULL. urdfdom's error
 * messages are captured through console_bridge's process-wide output handler
 * (restored afterwards): do not load URDFs from two threads at once. file:// URIs and plain relative
 * names (relative to the URDF's folder) resolve directly. A mesh that cannot
 * be resolved is not an error here (visual_path is NULL) but is one when the
 * visuals become a body. Errors: SS_E_IO (unreadable or invalid URDF),
 * SS_E_ARG (a mimic names an unknown joint, or mimics form a cycle; joints
 * forming a cycle or giving a link two parents; more than
 * SSA_MAX_LINKS links or joints). */
#define SSA_MAX_LINKS 10000 /* links (and joints) of a URDF: loads in seconds */
int ssa_robot_load(ssa_robot **out, const char *urdf_path, const char *package_path,
                   char *err, int err_sz);
/* As ssa_robot_load, from URDF text; base_dir (may be NULL) resolves relative mesh names. */
int ssa_robot_load_string(ssa_robot **out, const char *urdf_xml, const char *base_dir,
                          const char *package_path, char *err, int err_sz);
void ssa_robot_destroy(ssa_robot *robot);

/* Index of the link or joint with this name, or -1. */
int ssa_robot_link_index(const ssa_robot *robot, const char *name);
int ssa_robot_joint_index(const ssa_robot *robot, const char *name);

/* Writes values into q (njoint) for joints given by name, as in
 * sensor_msgs/JointState; other entries of q are left alone. Returns SS_E_ARG
 * naming the first unknown joint, SS_E_NONFINITE for a NaN or Inf value. */
int ssa_robot_set_joints(const ssa_robot *robot, double *q, int n, const char *const *names,
                         const double *values, char *err, int err_sz);

/* The value joint j really takes for raw values q (NULL: all zero): a mimic
 * joint follows its leader (mult * leader + off), then limits clamp. */
double ssa_robot_joint_value(const ssa_robot *robot, const double *q, int j);

/* Joint limits. Counts the joints whose raw value q[j] lies outside their
 * URDF limits (more than 1e-9 beyond; mimic joints are not checked: they
 * follow their leader) and, if any, writes one sentence into (msg, msg_sz)
 * naming the worst one, its value and its limits, e.g. "joint 'l_elbow' of
 * robot 'r' is 143 rad, outside its limits [0, 2.6] rad (degrees? values are
 * radians)". Returns that count (0: all within limits); the FK clamps such
 * values. q NULL: 0. */
int ssa_robot_check_limits(const ssa_robot *robot, const double *q, char *msg, int msg_sz);

/* Forward kinematics: the pose of every link in the root link's frame
 * (link_world, nlink x 16) for joint values q (njoint; NULL: all zero).
 * Limits clamp and mimic joints follow their leaders. */
void ssa_robot_fk(const ssa_robot *robot, const double *q, double *link_world);

/* Resolves a mesh URI as ssa_robot_load does into out (out_sz bytes). Returns
 * SS_OK, or SS_E_IO naming the URI and what was searched. */
int ssa_resolve_uri(const char *uri, const char *base_dir, const char *package_path, char *out,
                    int out_sz, char *err, int err_sz);

/* ================================================================ asset (assimp) */

typedef struct ssa_asset_opts {
  double scale;       /* metres per file unit; <= 0: from the file (FBX UnitScaleFactor), else 1 */
  int z_up;           /* 1: turn the file's up axis (Y unless the file says otherwise) into +Z
                         (Y-up to Z-up is +90 degrees about X: (x,y,z) -> (x,-z,y)); 0: keep */
  int ignore_up_axis; /* 1: take the coordinates as written, ignoring a Collada up_axis (used
                         for URDF visual meshes, whose frame the URDF already gives) */
  /* Hostile files (0 or unset: the default): */
  double max_file_mb;      /* larger mesh files are refused; default 256 MB; negative: no cap */
  double import_timeout_s; /* the import (run in a child process) is stopped after this; 60 s */
  double import_mem_mb;    /* address space the import may add; default 4096 MB */
} ssa_asset_opts;

/* Defaults: scale from the file, z_up 1, ignore_up_axis 0, limits 0 (their defaults). */
ssa_asset_opts ssa_asset_default_opts(void);

typedef struct ssa_asset {
  char *path;
  double root_fix[16];   /* scale and up-axis change applied on top of the file's root */
  int nnode;
  char **node_name;      /* (nnode) in depth-first order: parents before children */
  int *node_parent;      /* (nnode) -1 for the root */
  double *node_local;    /* (nnode x 16) rest transform in the parent node */
  int npart;             /* the file's meshes (triangles only; points and lines dropped) */
  char **part_name;      /* (npart) */
  int *part_node;        /* (npart) the first node (depth-first) that instantiates the mesh;
                            further instances of a mesh are not repeated in the body */
  int nvert;
  int nface;
  double *bind_pos;      /* (nvert x 3) vertices in their mesh's own space, as in the file */
  double *rest_pos;      /* (nvert x 3) posed at rest (no animation), root_fix applied */
  int *faces;            /* (nface x 3) indices into all vertices; meshes appended in order */
  int *vert_part;        /* (nvert) source mesh of each vertex */
  int *vert_src;         /* (nvert) index of the vertex in its source mesh */
  int nbone;             /* the file's bones, plus one rigid bone (on the mesh's node) per
                            mesh with unweighted vertices, e.g. a mesh without bones */
  char **bone_name;      /* (nbone) */
  int *bone_node;        /* (nbone) node driving the bone */
  int *bone_part;        /* (nbone) mesh the bone belongs to */
  double *bone_offset;   /* (nbone x 16) inverse bind matrix: mesh space to bone space */
  int nbone_file;        /* how many of the bones come from the file (the first ones) */
  int *w_start;          /* (nvert + 1) CSR: influences of vertex v are */
  int *w_bone;           /*   w_bone[w_start[v] .. w_start[v+1]-1] */
  double *w_weight;      /*   and w_weight[...] (>= 0, summing to 1) */
  int nanim;
  char **anim_name;      /* (nanim) "" when the file gives none */
  double *anim_duration; /* (nanim) seconds */
  /* Animation channels (internal layout, sampled by ssa_asset_node_world). */
  int *anim_chan_start;  /* (nanim + 1) */
  int *chan_node;        /* per channel: node, -1 if unmatched */
  int *chan_key_start;   /* (nchan x 4) keys of channel c: positions [s[0], s[1]), rotations
                            [s[1], s[2]), scales [s[2], s[3]), s = chan_key_start + 4 c */
  double *key_time;      /* seconds */
  double *key_value;     /* 4 doubles per key: xyz (4th unused) or quaternion xyzw */
  int *anim_node_chan;   /* (nanim x nnode) channel of each node or -1 */
  double *node_rest_trs; /* (nnode x 10) rest local as translation, quaternion xyzw, scale */
} ssa_asset;

/* Loads a mesh or a rigged character: all meshes triangulated and joined
 * (identical vertices merged within a mesh; seams are welded later, by
 * topology), bones and animations. opts may be NULL (defaults). Errors:
 * SS_E_IO (missing or unreadable file, assimp's message), SS_E_MESH (no
 * triangles), SS_E_NONFINITE (NaN or Inf in positions or weights). */
int ssa_asset_load(ssa_asset **out, const char *path, const ssa_asset_opts *opts, char *err,
                   int err_sz);
void ssa_asset_destroy(ssa_asset *asset);

/* Index of the node or animation with this name, or -1. */
int ssa_asset_node_index(const ssa_asset *asset, const char *name);
int ssa_asset_anim_index(const ssa_asset *asset, const char *name);

/* World transforms of all nodes (node_world, nnode x 16, root_fix applied)
 * for animation anim at time t seconds (anim -1: the rest pose). Keys are
 * interpolated (positions and scales linearly, rotations by slerp) and held
 * before the first and after the last key. */
void ssa_asset_node_world(const ssa_asset *asset, int anim, double t, double *node_world);
/* The same a fraction w in [0, 1] of the way from time t back to the clip's
 * pose at time 0, per node: translations and scales linearly, rotations by
 * slerp (so the limbs keep their shape on the way; w 0: as above). */
void ssa_asset_node_world_toward_rest(const ssa_asset *asset, int anim, double t, double w,
                                      double *node_world);

/* Skinning matrices (bone_mat, nbone x 16): node_world[bone_node] x bone_offset. */
void ssa_asset_skin_matrices(const ssa_asset *asset, const double *node_world, double *bone_mat);

/* ================================================================ skinning */

/* Linear blend skinning: out (nvert x 3) = sum_k w_k M[bone_k] p for each
 * vertex p of bind_pos, with bone matrices M (nbone x 16). */
void ssa_lbs(int nvert, const double *bind_pos, const int *w_start, const int *w_bone,
             const double *w_weight, const double *bone_mat, double *out);

typedef struct ssa_autoweight_opts {
  double heat_c;        /* heat weight c in H = c / d^2 (pinocchio: 1) */
  double rigid_ratio;   /* a vertex is rigid (weight 1) when its second-nearest link
                           is farther than rigid_ratio x the nearest (default 2.5) */
  double min_weight;    /* weights below this are dropped before normalising (0.01) */
  int smooth_iters;     /* Laplacian smoothing passes over the weights (2) */
  int visibility;       /* 1: a vertex considers only the segments it sees (pinocchio); 0: all (1) */
} ssa_autoweight_opts;

/* Defaults as documented in the struct. */
ssa_autoweight_opts ssa_autoweight_default_opts(void);

/* Automatic weights by heat diffusion (Baran and Popovic 2007). On the mesh
 * welded at weld_tol (see ss_topo), with the cotangent stiffness L, lumped
 * vertex areas M and H_ii = c / d_i^2 (d_i the distance from vertex i to its
 * nearest visible segment: the line to it crosses no face, see
 * opts.visibility), (L + M H) w_j = M H p_j is solved for each owner j
 * (p_j(i) = 1 where j owns that nearest segment, 1/2 each on a tie) with one
 * CHOLMOD factorisation. Segments: seg (nseg x 6, two end points) owned by
 * seg_owner (nseg, in [0, nowner)). Weights are then clamped to >= 0,
 * smoothed, those below min_weight dropped and normalised to sum 1; a vertex
 * whose second-nearest visible owner is more than rigid_ratio times farther
 * than its nearest gets weight 1 on the nearest. Output in CSR form,
 * allocated here (free with free()): *w_start (nvert + 1), *w_bone,
 * *w_weight; *dominant (nvert, may be NULL) gets each vertex's largest owner. */
int ssa_auto_weights(int nvert, const double *pos, int nface, const int *faces, double weld_tol,
                     int nseg, const double *seg, const int *seg_owner, int nowner,
                     const ssa_autoweight_opts *opts, int **w_start, int **w_bone,
                     double **w_weight, int *dominant, char *err, int err_sz);

/* ================================================================ avatar */

enum ssa_avatar_kind {
  SSA_AVATAR_ROBOT = 0, /* driven by joint values (URDF) */
  SSA_AVATAR_ASSET = 1  /* driven by the asset's own animation clips */
};

enum ssa_weight_source {
  SSA_WEIGHTS_RIGID = 0, /* each URDF visual mesh bound to its link */
  SSA_WEIGHTS_FILE = 1,  /* the file's bones (matched to links by name for URDF avatars) */
  SSA_WEIGHTS_AUTO = 2   /* heat diffusion from the link segments */
};

/* How the Collada (.dae) visual meshes of a URDF treat their <up_axis>. */
enum ssa_up_axis_mode {
  SSA_UP_AXIS_IGNORE = 0, /* coordinates as written, as rviz draws them (its RobotModel clears
                             the rotation assimp puts on the root): the skin overlays rviz */
  SSA_UP_AXIS_FILE = 1    /* honour the file: its up axis becomes the link's +Z (Y_UP: +90
                             degrees about X, (x,y,z) -> (x,-z,y); X_UP: x onto z; Z_UP:
                             as written), for URDFs authored for tools that honour it */
};

/* Receives a warning of the avatar layer (one sentence, no newline); the
 * layer never prints. */
typedef void (*ssa_warn_fn)(void *user, const char *msg);

typedef struct ssa_avatar_opts {
  const char *package_path; /* see ssa_robot_load; may be NULL */
  ssa_asset_opts asset;     /* how body and visual meshes are read */
  double weld_tol;          /* topology welding distance (negative: relative, see ss_topo) */
  int force_auto_weights;   /* 1: compute weights even when the file's bones match links */
  ssa_autoweight_opts autoweight;
  int mesh_up_axis;         /* ssa_up_axis_mode for URDF visual meshes (default IGNORE); with
                               IGNORE, Collada files declaring another up axis than Z get one
                               warning (through warn) per load */
  double primitive_edge;    /* target edge length (m) of tessellated URDF box, cylinder and
                               sphere visuals (default 0.02; see ssa_primitive_mesh) */
  ssa_warn_fn warn;         /* warnings while loading; NULL: dropped */
  void *warn_user;
} ssa_avatar_opts;

/* Defaults: no package path, asset defaults, weld_tol -1, file weights when they match,
 * mesh_up_axis IGNORE, primitive_edge 0.02 m, no warning callback. */
ssa_avatar_opts ssa_avatar_default_opts(void);

typedef struct ssa_avatar {
  int kind;             /* ssa_avatar_kind */
  int weight_source;    /* ssa_weight_source */
  ssa_robot *robot;     /* SSA_AVATAR_ROBOT: the URDF (owned); else NULL */
  ssa_asset *asset;     /* the body mesh file when one was read (owned); else NULL */
  int nvert;
  int nface;
  double *rest_pos;     /* (nvert x 3) body at rest (all joints 0, or no animation) */
  int *faces;           /* (nface x 3) counter-clockwise from outside where the file is */
  int *vert_part;       /* (nvert) source mesh (asset) or URDF visual index */
  int *vert_src;        /* (nvert) vertex index inside that source */
  int *vert_link;       /* (nvert) dominant target: link (robot) or node (asset) */
  int nbone;
  int *bone_target;     /* (nbone) link (robot) or node (asset) that moves the bone */
  double *bone_offset;  /* (nbone x 16) bind: from bind_pos space to the target's frame */
  double *bind_pos;     /* (nvert x 3) */
  int *w_start;         /* (nvert + 1) CSR weights as in ssa_asset */
  int *w_bone;
  double *w_weight;
  int ntarget;          /* nlink or nnode */
  double *target_world; /* (ntarget x 16) the last pose (scratch, read-only) */
  double *bone_mat;     /* (nbone x 16) scratch */
} ssa_avatar;

/* A closed, outward-wound triangle mesh of a URDF primitive in its visual
 * frame (centred on the origin; a cylinder along z), with edges about
 * `edge` metres long (<= 0: 0.02): box faces are regular grids; a sphere is
 * a cube projected by equal angles (the cube's grid mapped through tan, so
 * triangles stay within a factor ~1.5 of each other); a cylinder is a grid
 * on its side and concentric rings on its caps (ring k of 6k vertices). At
 * least 24 segments go around a circle (the volume then falls short by
 * under 2%), at most 512 along any direction; a primitive that would get more
 * than about 200,000 triangles gets longer edges instead.
 * kind: SSA_VISUAL_BOX (size: x y z), SSA_VISUAL_SPHERE (size[0]: radius),
 * SSA_VISUAL_CYLINDER (size[0]: radius, size[1]: length). *pos (nvert x 3)
 * and *faces (nface x 3) are allocated here (free()). Errors: SS_E_ARG (an
 * unknown kind, a size that is not finite and > 0). */
int ssa_primitive_mesh(int kind, const double *size, double edge, double **pos, int *nvert,
                       int **faces, int *nface, char *err, int err_sz);

/* The up axis a Collada file declares in its <asset><up_axis>: 0 X_UP, 1 Y_UP,
 * 2 Z_UP (also when it declares none, Collada's default is Y_UP: 1), -1 for a
 * file that is not Collada (by extension .dae) or cannot be read. */
int ssa_collada_up_axis(const char *path);

/* An avatar from a URDF file. mesh_path NULL: the body is the URDF's visuals,
 * each bound rigidly to its link: meshes (read with opts->mesh_up_axis) and
 * primitives (box, cylinder, sphere, tessellated by ssa_primitive_mesh at
 * opts->primitive_edge), each placed by its <origin>. Otherwise
 * the body is that mesh file, posed with the URDF at zero joint values: its
 * bones bind to links of the same name (a bone whose node is no link binds
 * to the nearest ancestor node that is one); when no bone matches, or some
 * vertex is left without a matched bone, weights are computed automatically
 * (ssa_auto_weights over the link segments: from each link's origin to each
 * child joint's origin; a leaf link continues its parent's direction for the
 * parent's length). opts may be NULL. Errors name the file and the problem:
 * SS_E_IO (unreadable URDF or mesh, unresolved package://), SS_E_MESH (no
 * triangles), SS_E_NONFINITE, SS_E_SOLVER. */
int ssa_avatar_load_urdf(ssa_avatar **out, const char *urdf_path, const char *mesh_path,
                         const ssa_avatar_opts *opts, char *err, int err_sz);
/* As ssa_avatar_load_urdf for a robot already loaded; takes ownership of robot (also on error). */
int ssa_avatar_from_robot(ssa_avatar **out, ssa_robot *robot, const char *mesh_path,
                          const ssa_avatar_opts *opts, char *err, int err_sz);
/* As ssa_avatar_from_robot with a body mesh given as arrays (copied), auto weights. */
int ssa_avatar_from_robot_mesh(ssa_avatar **out, ssa_robot *robot, int nvert, const double *pos,
                               int nface, const int *faces, const ssa_avatar_opts *opts,
                               char *err, int err_sz);
/* An avatar from a rigged character file, driven by its own animation clips. */
/* Sizes outside [SSA_ASSET_SIZE_MIN, SSA_ASSET_SIZE_MAX] metres (the largest extent
 * of the rest pose) get one warning through opts->warn: a file in other units. */
#define SSA_ASSET_SIZE_MIN 0.02
#define SSA_ASSET_SIZE_MAX 20.0
int ssa_avatar_load_asset(ssa_avatar **out, const char *asset_path, const ssa_avatar_opts *opts,
                          char *err, int err_sz);
void ssa_avatar_destroy(ssa_avatar *av);

/* Poses a robot avatar: q (njoint; NULL all zero) -> out (nvert x 3). SS_E_ARG for an asset avatar. */
int ssa_avatar_pose_joints(ssa_avatar *av, const double *q, double *out);
/* As ssa_avatar_pose_joints with the root link placed at root_pose (16, rigid; NULL: identity),
 * e.g. a floating base from TF. */
int ssa_avatar_pose_joints_at(ssa_avatar *av, const double *root_pose, const double *q, double *out);
/* Poses an asset avatar with animation anim (-1: rest) at t seconds. SS_E_ARG for a robot
 * avatar or an anim out of range. */
int ssa_avatar_pose_anim(ssa_avatar *av, int anim, double t, double *out);
/* As ssa_avatar_pose_anim, a fraction w in [0, 1] of the way back to the clip's pose at
 * time 0 in the bones' own motion (ssa_asset_node_world_toward_rest). */
int ssa_avatar_pose_anim_toward_rest(ssa_avatar *av, int anim, double t, double w, double *out);

/* Marks the vertices whose dominant target (vert_link) is one of the named
 * links (robot avatars) or nodes (asset avatars): mask (nvert) gets 1 or 0.
 * Returns how many were marked, or SS_E_ARG naming the first unknown name. */
int ssa_avatar_region_mask(const ssa_avatar *av, int n, const char *const *names,
                           unsigned char *mask, char *err, int err_sz);

/* What each vertex moves with, for ss_mesh_rigid_pieces: part (nvert) gets
 * 1 + the target (link or node) of a vertex whose every weight is on bones
 * of that one target (a URDF's visual mesh bound to its link, a character's
 * vertex skinned to one bone alone), 0 for a vertex blended between targets.
 * Returns the number of vertices with a part, or SS_E_ARG. */
int ssa_avatar_rigid_parts(const ssa_avatar *av, uint32_t *part);

/* ================================================================ the built-in mannequin */

/* The mannequin's URDF (static text, the same as urdf/mannequin.urdf in the
 * package): pelvis root, spine and chest (twist), neck and head, shoulders,
 * elbows, wrists-free forearms, hips and knees. Lengths in metres, Z up,
 * facing +X, arms straight out sideways (a T pose) at zero. */
const char *ssa_mannequin_urdf(void);

/* Generates the mannequin's body: a smooth union of capsules and ellipsoids
 * polygonised (marching tetrahedra, then relaxed onto the surface), closed,
 * welded, counter-clockwise seen from outside, with about target_tris
 * triangles (<= 0: 5000; SS_E_ARG outside [3000, 5000000]: below that the
 * wrists and hands come apart). *pos (nvert x 3) and *faces (nface x 3) are
 * allocated here (free with free()). */
int ssa_mannequin_mesh(int target_tris, double **pos, int *nvert, int **faces, int *nface,
                       char *err, int err_sz);

/* The mannequin as an avatar (URDF + generated body + automatic weights). */
int ssa_avatar_mannequin(ssa_avatar **out, int target_tris, char *err, int err_sz);

/* ================================================================ motions */

/* Scripted motions of the mannequin: "arms" (arms swing down into the
 * torso, pressing the armpits), "elbows" (deep elbow bends), "twist" (torso
 * and neck twist), "all" (the three together, shifted in phase); and one for
 * any robot: "sweep" (every joint that moves on its own swings about zero,
 * 0.6 rad or 3 cm each way, each in a phase of its own, within its limits,
 * eased in over the first second; a period of 4 s). */
int ssa_motion_builtin_count(void);
/* Name of built-in motion i, or NULL. */
const char *ssa_motion_builtin_name(int i);
/* Index of a built-in motion by name, or -1. */
int ssa_motion_builtin_index(const char *name);
/* Period of built-in motion i in seconds (it repeats after it). */
double ssa_motion_builtin_period(int i);
/* How many of the joints built-in motion i moves the robot has (0: the
 * motion would not move it at all). */
int ssa_motion_builtin_coverage(int i, const ssa_robot *robot);
/* Joint values of built-in motion i at time t for robot (normally the
 * mannequin; joints it does not have are ignored): q (njoint) is filled, all
 * other joints zero. Returns SS_E_ARG for an unknown motion. */
int ssa_motion_builtin_eval(int i, double t, const ssa_robot *robot, double *q);

/* A motion table: joint values over time. CSV format: one header row
 * "time,<joint>,<joint>,..." (the first column must be named time), then one row
 * per sample: time in seconds from the motion's start (strictly increasing,
 * each in [-SSA_MOTION_MAX_S, SSA_MOTION_MAX_S]) and one value per joint
 * (radians or metres). Commas separate; blank lines and lines starting with
 * '#' are skipped; spaces around fields are ignored. */
#define SSA_MOTION_MAX_S 1e6 /* s (11.6 days): a bound on a motion's times, so that its
                                frames at any rate fit in an int; past it, absolute
                                stamps (seconds since 1970) or milliseconds */
typedef struct ssa_motion {
  int njoint;
  char **joint_name; /* (njoint) */
  int nframe;
  double *time;      /* (nframe) */
  double *value;     /* (nframe x njoint) */
} ssa_motion;

/* Reads a CSV motion. Errors: SS_E_IO (unreadable), SS_E_ARG (a first column
 * not named time, a row with the wrong number of columns, a value that is not a number, times not
 * increasing, a time past SSA_MOTION_MAX_S, no rows), naming the file and line. */
int ssa_motion_read_csv(ssa_motion **out, const char *path, char *err, int err_sz);
/* Writes a motion as CSV (%.17g, so it reads back bit for bit). */
int ssa_motion_write_csv(const ssa_motion *motion, const char *path, char *err, int err_sz);
/* Samples a built-in motion into a table with nframe frames over [0, duration]. */
int ssa_motion_from_builtin(ssa_motion **out, int i, const ssa_robot *robot, double duration,
                            int nframe, char *err, int err_sz);
void ssa_motion_destroy(ssa_motion *motion);

/* Maps the motion's joint names to robot joints: map (motion->njoint) gets
 * the robot joint index of each column. SS_E_ARG naming the first unknown joint. */
int ssa_motion_bind(const ssa_motion *motion, const ssa_robot *robot, int *map, char *err,
                    int err_sz);
/* Joint values at time t (clamped to the table's range, linear between
 * frames) written into q (robot njoint) through map; other entries untouched. */
void ssa_motion_sample(const ssa_motion *motion, const int *map, double t, double *q);
/* Joint values a fraction w in [0, 1] of the way from q to q_rest (njoint
 * each) into out: linear per joint, a continuous joint the short way round
 * (less than half a turn). out may be q. */
void ssa_joints_toward(const ssa_robot *robot, const double *q, const double *q_rest, double w,
                       double *out);
/* Joint limits over a whole table bound with map: counts the values (frames x
 * columns) outside their joint's URDF limits and, if any, writes one sentence
 * naming the worst joint, its value and its limits and how many values of how
 * many joints are outside into (msg, msg_sz). Returns that count (0: none). */
int ssa_motion_check_limits(const ssa_motion *motion, const int *map, const ssa_robot *robot,
                            char *msg, int msg_sz);

#ifdef __cplusplus
}
#endif
#endif
