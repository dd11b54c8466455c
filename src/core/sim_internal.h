/* Internal: the inside of ss_sim, shared by its modules.
 *
 *   sim.c            create / destroy / step / reset / accessors
 *   sim_bind.c       anchors at create (copy or closest point), face mask, hinges
 *   sim_pattern.c    sparsity pattern of the unknowns and element-to-slot maps
 *   sim_energy.c     E(x), its gradient, and Hessian assembly over all terms
 *   solver.c         the one solver loop (solver.h); line_search.c its line search
 *   solver_newton.c  projected Newton directions with CHOLMOD (3n x 3n)
 *   solver_qn.c      L-BFGS on the constant L (x) I3 matrix (scalar n x n CHOLMOD)
 *
 * The model (fixed at create) comes first, then the data of a run. Arrays are
 * flat with their shape in a comment. Unknowns ("dofs") are the free skin
 * vertices in increasing vertex order; dof vector entry 3k + c is coordinate c
 * of free vertex dof_vert[k]. */
#ifndef SKIN_SIM_SIM_INTERNAL_H
#define SKIN_SIM_SIM_INTERNAL_H

#include <cholmod.h>

#include "mover.h"
#include "skin_sim/ss_sim.h"

enum ss_vert_kind {
  SS_VERT_FREE = 0,     /* an unknown */
  SS_VERT_PINNED = 1,   /* on the border of the simulated region: follows its anchor */
  SS_VERT_FOLLOWER = 2  /* outside the simulated region: follows its anchor */
};

/* The model of a skin on a body: fixed once built, and shared by every sim
 * created on it (ss_sim_create_from_model); nothing writes it while stepping. */
struct ss_model {
  int refs; /* sims running on it + the creator's reference (ss_model_create) */
  double mu, lam;             /* membrane Lamé parameters (stable form) */
  /* body */
  int nbvert, nbface;
  double *body_rest;          /* (nbvert x 3) */
  ss_topo *btopo;
  /* skin */
  int nvert, nface;
  int *faces;                 /* (nface x 3) */
  double *rest;               /* (nvert x 3) */
  unsigned char *mask;        /* (nface) 1 = simulated face */
  double *dm_inv;             /* (nface x 4) membrane rest data */
  double *rest_area;          /* (nface) 0 for degenerate rest triangles */
  double *vert_area;          /* (nvert) lumped rest area: sum of adjacent areas / 3 */
  double *mass;               /* (nvert) density * vert_area (>= a tiny floor) */
  double *k_vert;             /* (nvert) vertex spring stiffness (0 if not free) */
  double *k_face;             /* (nface) barycenter spring stiffness (0 if none) */
  unsigned char *kind;        /* (nvert) ss_vert_kind */
  int *dof;                   /* (nvert) dof index or -1 */
  int ndof;
  int *dof_vert;              /* (ndof) vertex of each dof */
  int nsimface;               /* faces with a membrane term (masked, >= 1 free vertex) */
  int *simface;               /* (nsimface) those faces */
  int nhinge;
  int *hinge_vert;            /* (nhinge x 4) e0, e1, o0, o1 */
  double *hinge_theta0;       /* (nhinge) */
  double *hinge_weight;       /* (nhinge) k |e|^2 / A_e */
  double edge_len;            /* mean rest edge length of the skin */
  int nanchor;                /* nvert + (barycenters ? nface : 0) */
  int *anchor_face0;          /* (nanchor) bound at create */
  double *anchor_uv0;         /* (nanchor x 2) */
  /* sparsity: block pattern over dofs, upper triangle, CSC; the scalar
   * n x n matrix uses it directly, the 3n x 3n one expands each block. */
  int *bcolp;                 /* (ndof + 1) */
  int *brow;                  /* (nblock) block rows in each block column, sorted */
  int nblock;
  int *colp3;                 /* (3 ndof + 1) column starts of the 3n x 3n matrix */
  int nnz3;                   /* its stored entries */
  int *face_rank;             /* (nface x 9) rank of block (min, max) of corners (a, b) in
                                 column max, -1 if either corner is not free */
  int *hinge_rank;            /* (nhinge x 16) same for hinge corners */
  signed char *orient_sign;   /* (nface) orient.c: rest orientation against the body, +-1, 0 */
  struct ss_membrane_face *mface; /* (nsimface) packed membrane input, in simface order */
  int *grad_ptr;              /* (ndof + 1) CSR: the face_grad slots each dof sums, in */
  int *grad_slot;             /* the order of the sum (springs by face, then membrane by face) */
  int bary_base;              /* first slot of the springs' part of face_grad */
  double *diag_const;         /* (ndof) diagonal of the scalar matrix without inertia */
  /* model_rewrite.py moves the model's fields above this line */
};

struct ss_sim {
  ss_model *m;                /* the model this sim runs on (counted in m->refs) */
  /* ---------------- model: fixed at create */
  ss_sim_settings set;        /* face_mask points to mask below (or NULL) */
  ss_mover *mover;

  /* ---------------- data of a run */
  double *x;                  /* (nvert x 3) skin positions */
  double *x_prev;             /* (nvert x 3) at the start of the substep */
  double *v;                  /* (nvert x 3) velocities */
  double *body_prev;          /* (nbvert x 3) body pose at the end of the last step */
  double *body_sub;           /* (nbvert x 3) body pose of the current substep */
  int *anchor_face;           /* (nanchor) */
  double *anchor_uv;          /* (nanchor x 2) */
  double *anchor_pos;         /* (nanchor x 3) in the current substep pose */
  int nthread;                /* threads the current step uses (OpenMP; 1 without it) */
  int nthread_max;            /* threads made at create (walkers, team) */
  int thread_probe;           /* threads 0: steps into the current probe period (-1: off) */
  double probe_ms[2];         /* threads 0: step times with nthread_max and with 1 thread */
  ss_walker **walkers;        /* (nthread_max) walk scratch, one per thread */
  double *face_energy;        /* (nsimface) membrane energies of one evaluation */
  double *face_grad;          /* their gradients (9 per simulated face), then the
                                 barycenter springs' (3 per face) */
  double *anchor_pull;        /* (nanchor) sum over the last step's substeps of |a* - a0| */
  double *anchor_path;        /* (nanchor) sum of the lengths walked (walk only, else 0) */
  double h;                   /* substep of the current system */
  double slide_frac;          /* share of the way to the skin point an anchor goes this substep */
  double tether_frac;         /* share of the way back home it walks this substep */
  double *mi;                 /* (ndof) inertia weight: mass (1/h^2 + damping/h) */
  double *target;             /* (ndof x 3) inertia target (prediction, damping, gravity) */
  /* solver scratch: dof vectors (ndof x 3) and full position arrays */
  double *xd, *gd, *dir, *xt, *gt;
  double *guess;              /* (ndof x 3) anchors of free vertices in the previous pose */
  double *xfull_t;            /* (nvert x 3) trial positions (fixed vertices in place) */
  /* CHOLMOD */
  cholmod_common cc;
  int cc_started;
  /* Newton: 3n x 3n */
  cholmod_sparse *H;
  cholmod_factor *LH;
  double *h_const;            /* (nnz of H) inertia + springs */
  double h_const_h;           /* h for which h_const was built (0: none) */
  cholmod_dense *nb, *nx, *ny, *ne; /* rhs, solution, workspaces (3n x 1) */
  /* quasi-Newton: n x n, applied to 3 right-hand sides */
  cholmod_sparse *A;
  cholmod_factor *LA;
  double a_h;                 /* h of the current factorisation of A (0: none) */
  cholmod_dense *qb, *qx, *qy, *qe; /* (n x 3) */
  int lb_m;                   /* history size */
  double *lb_s, *lb_y;        /* (m x ndof x 3) ring buffers */
  double *lb_rho, *lb_alpha;  /* (m) */
  int lb_count, lb_head;
  /* per-step counters */
  ss_sim_stats *st;
};

/* ---- sim_bind.c ---- */
/* Anchors of the skin on the body at rest (copy of the body or closest point). */
int ss_sim_bind(ss_sim *sim, const ss_sim_mesh *skin, const double *body_rest, char *err,
                int err_sz);
/* Vertex kinds, dofs, simulated faces, masses, spring stiffnesses, hinges. */
int ss_sim_build_model(ss_sim *sim, char *err, int err_sz);
/* From the settings: Lame parameters, masses and spring stiffnesses (part of
 * ss_sim_build_model; again on ss_sim_set_settings). */
void ss_sim_build_material(ss_sim *sim);

/* ---- orient.c: skin faces resist turning over against the body ---- */
#define SS_ORIENT_S0 0.2 /* signed projected area ratio below which the term acts */
#define SS_ORIENT_MIN_AREA 0.01 /* faces of rest area below this times l^2 are not judged */
#define SS_ORIENT_DEPTH 0.1 /* depth spring of a vertex under the body, per orient (orient.c) */
/* orient_sign from the rest skin and the anchors at rest (after ss_sim_reset). */
int ss_sim_orient_init(ss_sim *sim);
/* The unit body normal skin face f is judged against, in the pose of fr;
 * 0 where the face is not judged (see orient.c). */
int ss_sim_orient_normal(const ss_sim *sim, const ss_frames *fr, int f, double n[3]);
/* Energy at xfull; adds its gradient into g (dofs) if g. 0 when settings orient is 0. */
double ss_sim_orient_energy(const ss_sim *sim, const double *xfull, double *g);
/* Adds its (Gauss-Newton, PSD) Hessian to the 3n x 3n upper-triangular values. */
void ss_sim_orient_hessian(const ss_sim *sim, const double *xfull, double *vals);

/* ---- sim_pattern.c ---- */
int ss_sim_build_pattern(ss_sim *sim, char *err, int err_sz);

/* ---- sim_energy.c ---- */
/* Sets up the inertia weights and targets of a substep of length h from
 * x_prev, v and the settings. */
void ss_sim_energy_begin(ss_sim *sim, double h);
/* The packed layout the energy evaluation runs on (mface, face_grad,
 * grad_ptr, grad_slot), once after the model and the pattern; freed with
 * ss_sim_energy_free. */
int ss_sim_energy_layout(ss_sim *sim, char *err, int err_sz);
void ss_sim_energy_free(ss_sim *sim);
/* Scatters dofs xd into the full positions xfull (fixed vertices untouched). */
void ss_sim_scatter(const ss_sim *sim, const double *xd, double *xfull);
/* E at the full positions xfull; gradient over dofs into g (may be NULL).
 * Returns NaN/Inf if anything is non-finite. */
double ss_sim_energy(const ss_sim *sim, const double *xfull, double *g);
/* Convergence measure of a dof gradient: max over free vertices of
 * |g_v| / (D_v * mean edge length), D the diagonal of the scalar matrix
 * (inertia + springs + rest membrane stiffness): the size of a Jacobi step,
 * in edge lengths (see settings tol). */
double ss_sim_residual(const ss_sim *sim, const double *g);
/* The same measure as a root mean square over free vertices. */
double ss_sim_residual_rms(const ss_sim *sim, const double *g);
/* Adds the Hessian of membrane and hinges at xfull to the values vals of the
 * 3n x 3n upper-triangular matrix H: each element's projected to PSD, or with
 * exact != 0 the membrane's exact (possibly indefinite) Hessian except on
 * nearly collapsed faces (hinges keep their Gauss-Newton Hessian). */
void ss_sim_add_elastic_hessian(const ss_sim *sim, const double *xfull, double *vals, int exact);
/* Values of the constant part (inertia + springs) of H, for the current h. */
void ss_sim_constant_hessian(const ss_sim *sim, double *vals);
/* diag_const from the model (once, at create). */
void ss_sim_diag_const(ss_sim *sim);
/* Values of the scalar n x n matrix: inertia + springs + rest membrane
 * Laplacian scaled by (mu + lam). */
void ss_sim_scalar_matrix(const ss_sim *sim, double *vals);
/* Slot of entry (row 3i+a, col 3j+b) of the 3n matrix from block rank r in
 * block column j (i <= j; a <= b when i == j). */
static inline int ss_sim_slot3(const ss_sim *sim, int j, int rank, int a, int b) {
  return sim->m->colp3[3 * j + b] + 3 * rank + a;
}

/* ---- solvers (solver.h: the one loop, line search and the solvers' hooks).
 * ss_solver_solve minimises E from xd (in/out, dofs) with the solver of the
 * settings; returns SS_OK or SS_E_SOLVER and fills stats (iterations,
 * residual, residual_rms, ...). *nonfinite is 1 if E was not finite at the
 * start (xd unusable), 2 if only trial points were (xd is the last finite
 * iterate). ---- */
int ss_solver_create(ss_sim *sim, char *err, int err_sz);
int ss_solver_solve(ss_sim *sim, double *xd, int *converged, int *stalled, int *nonfinite);
int ss_solver_newton_create(ss_sim *sim, char *err, int err_sz);
int ss_solver_qn_create(ss_sim *sim, char *err, int err_sz);
/* Energy and gradient g at the unknowns xd (scattered into xfull_t), timed
 * into the step's assemble_ms. */
double ss_sim_energy_at(ss_sim *sim, const double *xd, double *g);

#endif
