/* Internal: the model of a skin on a body (MuJoCo's mjModel), everything
 * fixed once built: topology, rest data, masses and springs, hinges, the
 * sparsity pattern, the packed energy layout and the symbolic analysis of
 * the solver's matrix. Built alone, in this order, by sim_model.c:
 *
 *   model_bind.c     anchors bound (copy or closest point), vertex kinds, masses and
 *                    springs, hinges
 *   model_pattern.c  sparsity pattern of the unknowns, element-to-slot maps
 *   model_matrix.c   the packed energy layout, the constant matrices, their diagonal
 *   solver_*.c       the symbolic analysis of the model's solver matrix
 *   orient.c         the rest orientation its term judges against
 *
 * and then read only: a sim (sim_internal.h) holds it as `const ss_model *`.
 * Nothing here knows a sim. */
#ifndef SKIN_SIM_MODEL_H
#define SKIN_SIM_MODEL_H

#include <cholmod.h>
#include <stdatomic.h>

#include "bvh.h"
#include "energy.h"
#include "skin_sim/ss_sim.h"

enum ss_vert_kind {
  SS_VERT_FREE = 0,     /* an unknown */
  SS_VERT_PINNED = 1,   /* on the border of the simulated region: follows its anchor */
  SS_VERT_FOLLOWER = 2  /* outside the simulated region: follows its anchor */
};

/* name, type, count, shape */
#define SS_MODEL_ARRAYS(X)                                                                       \
  X(body_rest, double, 3 * (size_t)m->nbvert, "(nbvert x 3)")                                    \
  X(body_area0, double, (size_t)m->nbface, "(nbface) body face areas at rest (as ss_frames')")   \
  X(faces, int, 3 * (size_t)m->nface, "(nface x 3)")                                             \
  X(rest, double, 3 * (size_t)m->nvert, "(nvert x 3)")                                           \
  X(mask, unsigned char, (size_t)m->nface, "(nface) 1 = simulated face")                         \
  X(dm_inv, double, 4 * (size_t)m->nface, "(nface x 4) membrane rest data")                      \
  X(rest_area, double, (size_t)m->nface, "(nface) 0 for degenerate rest triangles")              \
  X(vert_area, double, (size_t)m->nvert, "(nvert) lumped rest area: sum of adjacent areas / 3")  \
  X(mass, double, (size_t)m->nvert, "(nvert) density * vert_area (>= a tiny floor)")             \
  X(k_vert, double, (size_t)m->nvert, "(nvert) vertex spring stiffness (0 if not free)")         \
  X(k_face, double, (size_t)m->nface, "(nface) barycenter spring stiffness (0 if none)")         \
  X(kind, unsigned char, (size_t)m->nvert, "(nvert) ss_vert_kind")                               \
  X(dof, int, (size_t)m->nvert, "(nvert) dof index or -1")                                       \
  X(dof_vert, int, (size_t)m->nvert, "(ndof) vertex of each dof")                                \
  X(simface, int, (size_t)m->nface, "(nsimface) faces with a membrane term")                     \
  X(hinge_vert, int, 4 * (size_t)m->nhinge_max, "(nhinge x 4) e0, e1, o0, o1")                   \
  X(hinge_theta0, double, (size_t)m->nhinge_max, "(nhinge) rest dihedral angle")                 \
  X(hinge_weight, double, (size_t)m->nhinge_max, "(nhinge) k |e|^2 / A_e")                       \
  X(anchor_face0, int, (size_t)m->nanchor, "(nanchor) bound at create")                          \
  X(anchor_uv0, double, 2 * (size_t)m->nanchor, "(nanchor x 2)")                                 \
  X(bcolp, int, (size_t)m->nvert + 1, "(ndof + 1) block column starts")                          \
  X(brow, int, (size_t)m->nvert + 3 * (size_t)m->nface + 6 * (size_t)m->nhinge_max,              \
    "(nblock) block rows in each block column, sorted")                                          \
  X(colp3, int, 3 * (size_t)m->nvert + 1, "(3 ndof + 1) column starts of the 3n x 3n matrix")    \
  X(face_rank, int, 9 * (size_t)m->nface,                                                        \
    "(nface x 9) rank of block (min, max) of corners (a, b) in column max, -1 if not free")      \
  X(hinge_rank, int, 16 * (size_t)m->nhinge_max, "(nhinge x 16) same for hinge corners")         \
  X(follow_off, double, m->follow_offset ? 3 * (size_t)m->nvert : 0,                              \
    "(nvert x 3) a separate skin's vertices: rest offset from their anchor in the anchor face's " \
    "frame (along e1, across it in the face, along the normal); followers keep it")              \
  X(orient_sign, signed char, (size_t)m->nface,                                                  \
    "(nface) orient.c: rest orientation against the body, +-1, 0")                               \
  X(mface, struct ss_membrane_face, (size_t)m->nface + 1,                                          \
    "(nsimface) packed membrane input, in simface order")                                        \
  X(grad_ptr, int, (size_t)m->nvert + 2, "(ndof + 1) CSR: the face_grad slots each dof sums")    \
  X(grad_slot, int, 3 * (size_t)m->nface + 1,                                                    \
    "in the order of the sum (by simulated face, each corner)")                                   \
  X(diag_const, double, (size_t)m->nvert, "(ndof) diagonal of the scalar matrix without inertia") \
  X(diag_springs, double, (size_t)m->nvert,                                                      \
    "(ndof) its anchor springs' part alone: a flat membrane's stiffness across its surface")


#define SS_ARENA_FIELD(name, type, count, shape) type *name;


struct ss_model {
  atomic_int refs;            /* sims running on it, models derived from it (shape) and the
                                 creator's reference (ss_model_create); sims on other threads
                                 may take and drop theirs */
  ss_model *shape;            /* NULL: the model owns btopo, bvh_rest and the symbolic analysis.
                                 Else a model it was derived from with another material
                                 (ss_sim_set_settings), whose three it borrows, holding a
                                 reference (never a chain: the owner's) */
  ss_sim_settings set;        /* built with; its model settings (scope SS_SCOPE_MODEL) are every
                                 sim's on it. face_mask points to mask (or NULL) */
  void *arena;                /* every array below */
  size_t arena_bytes;
  double mu, lam;             /* membrane Lamé parameters (stable form) */
  /* body */
  int nbvert, nbface;
  ss_topo *btopo;
  ss_bvh *bvh_rest;           /* the body's BVH at rest, or NULL: kept when the skin was bound by
                                 closest point or the model's method is project; every project
                                 sim's mover borrows its tree (ss_bvh_create_on). Never refitted */
  /* skin */
  int nvert, nface;
  int ndof;                   /* free vertices: the unknowns */
  int nsimface;               /* faces with a membrane term (masked, >= 1 free vertex) */
  int nhinge;
  int nhinge_max;             /* bound at allocation: 3 nface / 2 with bending, else 0 */
  double edge_len;            /* mean rest edge length of the skin */
  int nanchor;                /* nvert + (barycenters ? nface : 0) */
  int follow_offset;          /* 1: a separate skin, whose followers keep their height over the
                                 body (follow_off); 0: a copy of the body, on its anchors */
  /* sparsity: block pattern over dofs, upper triangle, CSC; the scalar
   * n x n matrix uses it directly, the 3n x 3n one expands each block. */
  int nblock;
  int nnz3;                   /* stored entries of the 3n x 3n matrix */
  /* Symbolic analysis (fill-reducing ordering and symbolic factor, which
   * depend on the pattern alone) of the matrix of the solver the model was
   * built for (set.solver at model_build): the scalar n x n one (quasi-Newton,
   * solver_qn.c) or the 3n x 3n one (Newton, solver_newton.c); the other is
   * NULL, both are without dofs. Made once with the model's own
   * cholmod_common; each sim on the model factors a copy of its own
   * (cholmod_copy_factor), and a sim with the other solver analyses its
   * matrix itself. Freed by the model's destroy. */
  cholmod_common cc;
  int cc_started;
  cholmod_factor *sym_qn, *sym_newton;
  SS_MODEL_ARRAYS(SS_ARENA_FIELD)
};

/* ---- building a model ---- */
/* The model's bvh_rest on the body at rest, built if it is not yet. */
int ss_sim_model_bvh(ss_model *m, const double *body_rest);

/* ---- model_bind.c ---- */
/* An orthonormal frame of a triangle with edges e1, e2 from its first corner:
 * t1 along e1, t2 across it in the triangle's plane, n its unit normal (the
 * order of ss_frames' normal). 0 (frame unset) where it is degenerate. */
int ss_sim_face_frame(const double e1[3], const double e2[3], double t1[3], double t2[3],
                      double n[3]);
/* Anchors of the skin on the body at rest (copy of the body or closest point). */
int ss_model_bind(ss_model *m, const ss_sim_mesh *skin, const double *body_rest, char *err,
                  int err_sz);
/* Vertex kinds, dofs, simulated faces, masses, spring stiffnesses, hinges. */
int ss_model_build_kinds(ss_model *m, char *err, int err_sz);
/* From the model's settings: Lame parameters, masses and spring stiffnesses
 * (part of ss_model_build_kinds; again on a model derived with another
 * material). */
void ss_model_build_material(ss_model *m);


/* ---- model_pattern.c ---- */
int ss_model_build_pattern(ss_model *m, char *err, int err_sz);
/* Slot of entry (row 3i+a, col 3j+b) of the 3n matrix from block rank r in
 * block column j (i <= j; a <= b when i == j). */
static inline int ss_model_slot3(const ss_model *m, int j, int rank, int a, int b) {
  return m->colp3[3 * j + b] + 3 * rank + a;
}
/* A pair of an element's corners whose block is stored: a's dof i and b's
 * dof j both free, i <= j (the upper triangle: (a, b) and (b, a) meet in
 * one block, counted once; off-diagonal blocks get the (a, b) value, the
 * symmetric (b, a) is implied). */
typedef struct ss_upper_pair {
  int a, b;  /* corners */
  int col;   /* block column: the dof of b */
  int rank;  /* the block's rank in it (elem_rank[n a + b]) */
  int diag;  /* 1: a diagonal block (i == j) */
} ss_upper_pair;
/* The stored pairs of an element of n corners verts with block ranks
 * elem_rank (face_rank, hinge_rank), a then b in order (the order every
 * assembly sums them: the same bits); returns how many (at most n^2). */
static inline int ss_model_upper_pairs(const ss_model *m, const int *verts, int n, const int *elem_rank,
                                       ss_upper_pair *out) {
  int k = 0;
  for (int a = 0; a < n; a++) {
    const int i = m->dof[verts[a]];
    if (i < 0) continue;
    for (int b = 0; b < n; b++) {
      const int j = m->dof[verts[b]];
      if (j < i) continue; /* j < 0 too */
      out[k++] = (ss_upper_pair){a, b, j, elem_rank[n * a + b], i == j};
    }
  }
  return k;
}
/* Adds an element's (3n x 3n, row-major) Hessian he to the 3n x 3n
 * upper-triangular values (model_matrix.c). */
void ss_model_scatter_element(const ss_model *m, const int *verts, int n, const int *elem_rank,
                              const double *he, double *vals);

/* ---- model_matrix.c ---- */
/* The packed layout the energy evaluation runs on (mface, grad_ptr,
 * grad_slot), once after the model and the pattern. */
int ss_model_energy_layout(ss_model *m, char *err, int err_sz);
/* The barycenter springs' stiffness in mface, from k_face: in the layout,
 * and again whenever the material is rebuilt. */
void ss_model_energy_springs(ss_model *m);
/* Values of the constant part of the matrix, inertia weights mi (NULL:
 * none) + anchor springs: the scalar n x n matrix's (scalar != 0, nblock
 * values) or the 3n x 3n one's (nnz3 values). */
void ss_model_constant_terms(const ss_model *m, const double *mi, double *vals, int scalar);
/* diag_const and diag_springs of the model (building it). */
void ss_model_diag_const(ss_model *m);
/* Values of the scalar n x n matrix: inertia weights mi (NULL: none) +
 * springs + rest membrane Laplacian scaled by (mu + lam). */
void ss_model_scalar_matrix(const ss_model *m, const double *mi, double *vals);

/* ---- solver_newton.c, solver_qn.c ---- */
/* The model's symbolic analysis (m->sym_newton / m->sym_qn, with m->cc) for
 * its built pattern, once at model_build (ndof > 0). */
int ss_solver_newton_analyze(ss_model *m, char *err, int err_sz);
int ss_solver_qn_analyze(ss_model *m, char *err, int err_sz);

/* ---- orient.c: skin faces resist turning over against the body ---- */
#define SS_ORIENT_S0 0.2 /* signed projected area ratio below which the term acts */
#define SS_ORIENT_MIN_AREA SS_SLIVER_AREA /* faces of rest area below this times l^2 are not judged */
#define SS_ORIENT_DEPTH 0.1 /* depth spring of a vertex under the body, per orient (orient.c) */
/* orient_sign from the rest skin and the anchors as bound, in the body's
 * frames at rest (the last step of building a model). */
int ss_model_orient_init(ss_model *m, char *err, int err_sz);

#endif
