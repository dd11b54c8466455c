/* Internal: the inside of ss_sim, shared by its modules.
 *
 *   sim_model.c      model and data: arenas, create / destroy, sims sharing a model
 *   sim.c            step (its stages) / reset / live settings / accessors
 *   sim_bind.c       anchors at create (copy or closest point), face mask, hinges
 *   sim_pattern.c    sparsity pattern of the unknowns and element-to-slot maps
 *   sim_energy.c     E(x), its gradient, and Hessian assembly over all terms
 *   solver.c         the one solver loop (solver.h); line_search.c its line search
 *   solver_newton.c  projected Newton directions with CHOLMOD (3n x 3n)
 *   solver_qn.c      L-BFGS on the constant L (x) I3 matrix (scalar n x n CHOLMOD)
 *
 * The model (fixed once built, shareable) and the data of a run: see "model
 * and data" below. Arrays are flat with their shape in the field lists. Unknowns ("dofs") are the free skin
 * vertices in increasing vertex order; dof vector entry 3k + c is coordinate c
 * of free vertex dof_vert[k]. */
#ifndef SKIN_SIM_SIM_INTERNAL_H
#define SKIN_SIM_SIM_INTERNAL_H

#include <cholmod.h>

#include "mover.h"
#include "par.h"
#include "skin_sim/ss_sim.h"

enum ss_vert_kind {
  SS_VERT_FREE = 0,     /* an unknown */
  SS_VERT_PINNED = 1,   /* on the border of the simulated region: follows its anchor */
  SS_VERT_FOLLOWER = 2  /* outside the simulated region: follows its anchor */
};

/* ---- model and data (MuJoCo's mjModel / mjData split) ----------------------
 *
 * The MODEL of a skin on a body is everything fixed once it is built:
 * topology, rest data, masses and springs, hinges, the sparsity pattern,
 * the packed energy layout and the symbolic analysis of the solver's matrix
 * (below, "symbolic analysis"). Several sims may run on one model (a reference
 * or truth run, a second skin of the same body: ss_sim_create_from_model);
 * nothing writes it while stepping, and ss_sim_set_settings changes its
 * material only when the model is not shared (else it asks for a new sim).
 * The DATA of a run (struct ss_sim) is the state, the anchors, the solver
 * workspaces and the step's counters.
 *
 * Each holds its arrays in ONE arena (one allocation, 64-byte aligned
 * slices) laid out from ONE list of fields below: name, element type, count
 * (elements allocated, evaluated with `m` the model and `sim` the sim), and
 * shape. The list declares the fields, sizes the arena and places them;
 * nothing else allocates, checks or frees them. The model's counts that are
 * only known while it is built (dofs, hinges, blocks of the pattern) are
 * allocated at bounds known before: nvert for dofs, nhinge_max for hinges.
 * Not in the arenas: the body topology (ss_topo), the mover, the walker
 * objects (their pointers are) and the CHOLMOD objects, each with its own
 * create and destroy. */

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

/* The data of a run: counts of the built model `m` and of the sim's own
 * settings (solver, history) and threads. */
#define SS_DATA_ARRAYS(X)                                                                        \
  X(x, double, 3 * (size_t)m->nvert, "(nvert x 3) skin positions")                               \
  X(x_prev, double, 3 * (size_t)m->nvert, "(nvert x 3) at the start of the substep")             \
  X(v, double, 3 * (size_t)m->nvert, "(nvert x 3) velocities")                                   \
  X(xfull_t, double, 3 * (size_t)m->nvert, "(nvert x 3) trial positions (fixed in place)")       \
  X(body_prev, double, 3 * (size_t)m->nbvert, "(nbvert x 3) body pose at the end of the last step") \
  X(body_sub, double, 3 * (size_t)m->nbvert, "(nbvert x 3) body pose of the current substep")    \
  X(anchor_face, int, (size_t)m->nanchor, "(nanchor)")                                           \
  X(anchor_uv, double, 2 * (size_t)m->nanchor, "(nanchor x 2)")                                  \
  X(anchor_pos, double, 3 * (size_t)m->nanchor, "(nanchor x 3) in the current substep pose")     \
  X(anchor_pull, double, (size_t)m->nanchor,                                                     \
    "(nanchor) sum over the last step's substeps of |a* - a0|")                                  \
  X(anchor_path, double, (size_t)m->nanchor, "(nanchor) sum of the lengths walked (walk only)")  \
  X(walkers, ss_walker *, (size_t)sim->nthread_max, "(nthread_max) walk scratch, one per thread") \
  X(face_energy, double, (size_t)m->nface, "(nsimface) per simulated face, in one evaluation: membrane and barycenter spring") \
  X(orient_s, double, (size_t)m->nface, "(nsimface) orient.c: s of each judged face in one evaluation") \
  X(face_grad, double, 9 * (size_t)m->nsimface + 1, "their gradients (9 per simulated face)")   \
  X(mi, double, (size_t)m->ndof, "(ndof) inertia weight: mass (1/h^2 + damping/h)")              \
  X(target, double, 3 * (size_t)m->ndof, "(ndof x 3) inertia target (prediction, damping, gravity)") \
  X(xd, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: the unknowns")                          \
  X(gd, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: gradient at xd")                        \
  X(dir, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: search direction")                     \
  X(xt, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: trial point")                           \
  X(gt, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: gradient at the trial point")           \
  X(guess, double, 3 * (size_t)m->ndof, "(ndof x 3) anchors of free vertices in the previous pose") \
  X(h_const, double, sim->set.solver == SS_SOLVER_NEWTON ? (size_t)m->nnz3 : 0,                  \
    "(nnz of H) Newton: inertia + springs")                                                      \
  X(lb_s, double, SS_SIM_QN_HISTORY(sim) * 3 * (size_t)m->ndof, "(m x ndof x 3) L-BFGS s ring") \
  X(lb_y, double, SS_SIM_QN_HISTORY(sim) * 3 * (size_t)m->ndof, "(m x ndof x 3) L-BFGS y ring") \
  X(lb_rho, double, SS_SIM_QN_HISTORY(sim), "(m)")                                               \
  X(lb_alpha, double, SS_SIM_QN_HISTORY(sim), "(m)")                                               \
  X(skin_n, double, 3 * (size_t)m->ndof, "(ndof x 3) unit skin normal at the start of the solve (0: none)") \
  X(par_part, double,                                                                            \
    SS_PAR_SUMS * (size_t)ss_par_nblocks(3 * m->nvert > m->nface ? 3 * m->nvert : m->nface) + 1,   \
    "par.h: the blocks' partial sums of one pass")                                               \
  X(depth_line, double, 3 * (size_t)m->ndof,                                                    \
    "(ndof x 3) orient.c: each dof's depth, its rate along the search direction and its spring's " \
    "stiffness, 0 where out of reach of a full step (ss_sim_orient_line_step)")                 \
  X(orient_n, double, 4 * ((size_t)m->nface + m->nvert), "orient.c: per simface n, face_c (0: not judged); per dof at 4 nface n, judged")
#define SS_SIM_QN_HISTORY(sim) \
  ((sim)->set.solver == SS_SOLVER_QUASI_NEWTON ? (size_t)(sim)->set.lbfgs_history : 0)

#define SS_ARENA_FIELD(name, type, count, shape) type *name;

struct ss_model {
  int refs;                   /* sims running on it + the creator's reference (ss_model_create) */
  ss_sim_settings set;        /* built with; its model settings (ss_sim_in_model) are every
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

struct ss_sim {
  ss_model *m;                /* the model this sim runs on (counted in m->refs) */
  ss_sim_settings set;        /* this sim's; face_mask points to m->mask (or NULL) */
  void *arena;                /* every array of SS_DATA_ARRAYS */
  size_t arena_bytes;
  ss_mover *mover;            /* body frames and BVH in the current pose */
  struct ss_collider *collider; /* contact scratch (collide.c) */
  int nthread;                /* threads the current step uses (OpenMP; 1 without it) */
  int nthread_max;            /* threads made at create (walkers, team) */
  int isa;                    /* vector instruction set of the kernels (isa.h): the widest the
                                 CPU runs, chosen at create (ss_sim_set_isa); the same bits
                                 from any */
  int thread_probe;           /* threads 0: steps into the current probe period (-1: off) */
  int probe_period;           /* threads 0: steps in the current probe period */
  double probe_ms[2];         /* threads 0: step times with nthread_max and with 1 thread */
  double h;                   /* substep of the current system */
  int measure_anchors;        /* ss_sim_measure_anchors: anchor_pull and anchor_path summed */
  double slide_frac;          /* share of the way to the skin point an anchor goes this substep */
  double tether_frac;         /* share of the way back home it walks this substep */
  /* CHOLMOD */
  cholmod_common cc;
  int cc_started;
  /* Newton: 3n x 3n */
  cholmod_sparse *H;
  cholmod_factor *LH;
  double h_const_h;           /* h for which h_const was built (0: none) */
  cholmod_dense *nb, *nx, *ny, *ne; /* rhs, solution, workspaces (3n x 1) */
  /* quasi-Newton: n x n, applied to 3 right-hand sides */
  cholmod_sparse *A;
  cholmod_factor *LA;
  double a_h;                 /* h of the current factorisation of A (0: none) */
  cholmod_dense *qb, *qx, *qy, *qe; /* (n x 3) */
  /* quasi-Newton on threads: the x and y columns of each solve on one thread
   * (cc, qx_xy, qy_xy, qe_xy) while z is solved on another with its own
   * cholmod_common (cc_z, qx_z, qy_z, qe_z); the factor is shared read-only.
   * Made at create where the sim has threads (solver_qn.c) */
  cholmod_common cc_z;
  int cc_z_started;
  cholmod_dense *qx_xy, *qy_xy, *qe_xy, *qx_z, *qy_z, *qe_z;
  int lb_m;                   /* L-BFGS history size */
  int lb_count, lb_head;
  /* per-step counters */
  ss_sim_stats *st;
  /* over the sim's life (ss_sim_warnings) */
  long long nstep;
  ss_warning warning[SS_NWARNING];
  SS_DATA_ARRAYS(SS_ARENA_FIELD)
};

/* 1 if the setting at this offset of ss_sim_settings is a model setting (young,
 * poisson, density, stiffness, barycenters, bending, orient): every sim on a
 * model has the model's (sim_model.c). */
int ss_sim_in_model(size_t offset);
/* threads 0: the probe's steps (sim.c). After each step of step_ms
 * wall-clock ms, sets the thread count of the next. */
#define SS_PROBE_STEPS 3       /* steps on one thread, then at most as many on all */
#define SS_PROBE_PERIOD 50     /* steps from one probe to the next while all threads pay */
#define SS_PROBE_PERIOD_MAX 1600 /* the longest period, after probes one thread won */
void ss_sim_choose_threads(ss_sim *sim, double step_ms);
/* Sets the vector instruction set of the sim's kernels (isa.h; one the CPU
 * runs): the same bits from any. Chosen at create: the widest. */
void ss_sim_set_isa(ss_sim *sim, int isa);

/* ---- sim_model.c ---- */
/* The model's bvh_rest on the body at rest, built if it is not yet (model
 * building only: the model is read-only once built). */
int ss_sim_model_bvh(ss_model *m, const double *body_rest);

/* ---- sim_bind.c ---- */
/* An orthonormal frame of a triangle with edges e1, e2 from its first corner:
 * t1 along e1, t2 across it in the triangle's plane, n its unit normal (the
 * order of ss_frames' normal). 0 (frame unset) where it is degenerate. */
int ss_sim_face_frame(const double e1[3], const double e2[3], double t1[3], double t2[3],
                      double n[3]);
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
#define SS_ORIENT_MIN_AREA SS_SLIVER_AREA /* faces of rest area below this times l^2 are not judged */
#define SS_ORIENT_DEPTH 0.1 /* depth spring of a vertex under the body, per orient (orient.c) */
/* orient_sign from the rest skin and the anchors at rest (after ss_sim_reset). */
int ss_sim_orient_init(ss_sim *sim);
/* The unit body normal skin face f is judged against, in the pose of fr;
 * 0 where the face is not judged (see orient.c). */
int ss_sim_orient_normal(const ss_sim *sim, const ss_frames *fr, int f, double n[3]);
/* The normals of the faces and free vertices in the current pose and anchors
 * (orient_n), which energy and Hessian read: after every move of either
 * (ss_sim_energy_begin calls it). */
void ss_sim_orient_begin(ss_sim *sim);
/* Energy at xfull; adds its gradient into g (dofs) if g. 0 when settings orient is 0. */
double ss_sim_orient_energy(const ss_sim *sim, const double *xfull, double *g);
/* The first trial step of a quasi-Newton line search along dir from the
 * unknowns xd, where E's slope is `slope` (< 0): the minimum over (0, 1] of
 * the depth springs along the line (exact: one-sided quadratics) plus a
 * quadratic model of every other term whose minimum is the full step (what
 * the constant preconditioner gets right). 1 where no depth spring is in
 * reach or the model does not apply (see orient.c). Writes depth_line. */
double ss_sim_orient_line_step(ss_sim *sim, const double *xd, const double *dir, double slope);
/* Adds its (Gauss-Newton, PSD) Hessian to the 3n x 3n upper-triangular values. */
void ss_sim_orient_hessian(const ss_sim *sim, const double *xfull, double *vals);

/* ---- sim_pattern.c ---- */
int ss_sim_build_pattern(ss_sim *sim, char *err, int err_sz);

/* ---- sim_energy.c ---- */
/* Sets up the inertia weights and targets of a substep of length h from
 * x_prev, v and the settings. */
void ss_sim_energy_begin(ss_sim *sim, double h);
/* The packed layout the energy evaluation runs on (mface, grad_ptr,
 * grad_slot), once after the model and the pattern. */
int ss_sim_energy_layout(ss_sim *sim, char *err, int err_sz);
/* The barycenter springs' stiffness in mface, from k_face: in the layout,
 * and again whenever the material is rebuilt. */
void ss_sim_energy_springs(ss_sim *sim);
/* Scatters dofs xd into the full positions xfull (fixed vertices untouched). */
void ss_sim_scatter(const ss_sim *sim, const double *xd, double *xfull);
/* E at the full positions xfull; gradient over dofs into g (may be NULL).
 * Returns NaN/Inf if anything is non-finite. */
double ss_sim_energy(const ss_sim *sim, const double *xfull, double *g);
/* Convergence measure of a dof gradient: max over free vertices of the size
 * of a Jacobi step in mean edge lengths (see settings tol), the gradient
 * along the skin divided by D_v, the diagonal of the scalar matrix (inertia
 * + springs + rest membrane stiffness), and across it (skin_n, set by
 * ss_sim_normals_begin) by inertia + springs alone (sim_energy.c). */
double ss_sim_residual(const ss_sim *sim, const double *g);
/* The same judged by the scalar matrix's diagonal in every direction (the
 * stiffness along the skin): how far from converged the membrane itself is. */
double ss_sim_residual_along(const ss_sim *sim, const double *g);
/* The same measure as a root mean square over free vertices. */
double ss_sim_residual_rms(const ss_sim *sim, const double *g);
/* Adds the Hessian of membrane and hinges at xfull to the values vals of the
 * 3n x 3n upper-triangular matrix H: each element's projected to PSD, or with
 * exact != 0 the membrane's exact (possibly indefinite) Hessian except on
 * nearly collapsed faces (hinges keep their Gauss-Newton Hessian). */
void ss_sim_add_elastic_hessian(const ss_sim *sim, const double *xfull, double *vals, int exact);
/* Values of the constant part (inertia + springs) of H, for the current h. */
void ss_sim_constant_hessian(const ss_sim *sim, double *vals);
/* The skin's unit vertex normals (skin_n) at the full positions xfull, at
 * the start of each solve: the direction across the membrane, in which only
 * inertia and the anchor springs hold a flat skin (ss_sim_residual). */
void ss_sim_normals_begin(ss_sim *sim, const double *xfull);
/* diag_const and diag_springs from the model (once, at create). */
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
/* The model's symbolic analysis (m->sym_newton / m->sym_qn, with m->cc) for
 * its built pattern, once at model_build (ndof > 0). */
int ss_solver_newton_analyze(ss_model *m, char *err, int err_sz);
int ss_solver_qn_analyze(ss_model *m, char *err, int err_sz);
/* Energy and gradient g at the unknowns xd (scattered into xfull_t), timed
 * into the step's assemble_ms. */
double ss_sim_energy_at(ss_sim *sim, const double *xd, double *g);

#endif
